// Colour maps for heat maps: a sequential map (viridis), a diverging blue-white-red map and a
// categorical palette. Colours are sRGB-encoded components in [0, 1], as written to 8-bit images.
#pragma once

#include <array>

namespace sl
{

using RgbColor = std::array<double, 3>;

enum class ColorMapKind
{
  Viridis,    // sequential, perceptually uniform
  Diverging,  // blue - white - red; heat maps centre it on value 0
  Categorical // distinct colours for small integer class ids
};

class ColorMap
{
public:
  explicit ColorMap(ColorMapKind kind)
    : kind_(kind)
  {
  }

  ColorMapKind kind() const { return kind_; }

  // The colour at t in [0, 1]; t outside is clamped, NaN reads as 0. Viridis and Diverging interpolate
  // linearly between their control points (Diverging is pure white at t = 0.5); Categorical returns the
  // palette entry nearest to t * (paletteSize - 1), without blending.
  RgbColor map(double t) const;

  // The colour of class id `categoryId`; the palette (10 colours) repeats for ids outside 0..9.
  static RgbColor categoryColor(long long categoryId);

private:
  ColorMapKind kind_;
};

} // namespace sl
