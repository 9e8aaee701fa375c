// A named per-pixel (or per-texel) image with what a reader needs to interpret it: unit, documentation, and how
// to colour it. Buffers of a frame, light-space exports and arrays read back from a .vti are NamedImages.
#pragma once

#include "core/Image.h"

#include <algorithm>
#include <string>
#include <vector>

namespace sl
{

enum class BufferKind
{
  Continuous,  // heat map with a sequential colour map
  Signed,      // diverging colour map about 0
  Categorical, // integer classes with labels
  BitMask,     // bits of a mask, 16 per float component (light_sample_mask): drawn as the count of set bits
  SummedArea   // a summed-area table (sat_z): a texel holds a sum over a rectangle, wrapping mod 2^32 in fixed
               // point, so one texel's value says nothing by itself; no heat map (docs/outputs.md)
};

// The pixels a buffer has a value at. Heat maps and montages draw the others in kNotApplicableColor
// (vis/HeatMap.h), never in a colour of the scale: a 0 written where no shadow test ran is not a margin of 0.
enum class BufferDomain
{
  Covered,     // every pixel a surface covers (coverage > 0.5)
  ShadowTested // the covered pixels that reach a shadow test: the frame's shadow_tested buffer is 1 (the surface
               // receives shadows and the light can reach it); 0 is written elsewhere and means nothing
};

struct NamedImage
{
  std::string name;
  ImageF image;
  std::string unit;
  std::string doc;
  BufferKind kind = BufferKind::Continuous;
  std::vector<std::string> categoryLabels;
  BufferDomain domain = BufferDomain::Covered;
};

// The image called `name` in `images`, or nullptr.
inline const NamedImage* findNamed(const std::vector<NamedImage>& images, const std::string& name)
{
  const auto found =
    std::find_if(images.begin(), images.end(), [&](const NamedImage& named) { return named.name == name; });
  return found == images.end() ? nullptr : &*found;
}

} // namespace sl
