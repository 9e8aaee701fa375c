// Heat maps of per-pixel instrumentation buffers: one scalar buffer becomes an 8-bit RGB image a researcher can
// read without any other tool. The values are drawn 1:1 with their bottom-left pixel at the canvas' bottom-left
// corner (canvas.at(x, y) shows values.at(x, y)); a colour key fills a margin on the right and a title line
// "<title> [<unit>]  range [<min>, <max>]" a band on top. Text scales with the image height (heatMapFontPx).
// No OpenGL: text is rasterised by VTK's FreeType text renderer, so this works without a graphics context
// (link VTK::RenderingFreeType and run vtk_module_autoinit).
#pragma once

#include "core/Image.h"
#include "vis/ColorKey.h"
#include "vis/ColorMap.h"

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace sl
{

struct HeatMapOptions
{
  std::string title; // buffer name, e.g. "kernel_texels"
  std::string unit;  // optional, e.g. "texels"; shown after the title in brackets when non-empty
  ColorMapKind colorMap = ColorMapKind::Viridis;
  // The values at the two ends of the colour map. Default: min/max over the valid pixels; for Diverging,
  // symmetric about 0 (a single explicit bound is mirrored). Categorical colours do not use it.
  std::optional<double> rangeMin, rangeMax;
  // Categorical only: label of class id 0..n-1; the key then lists exactly these classes. Without labels it
  // lists the ids from the smallest to the largest valid value.
  std::vector<std::string> categoryLabels;
};

// Invalid pixels (mask 0) and non-finite values: a neutral dark grey, outside every colour map.
inline constexpr RgbColor kInvalidPixelColor{ 0.25, 0.25, 0.25 };

struct ValueRange
{
  double min = 0.0;
  double max = 0.0;
};

// Min and max over the valid pixels (validMask nonzero, or all when null) with finite values; nullopt when there
// are none.
std::optional<ValueRange> validValueRange(const ImageF& values, const ImageU8* validMask);

// The values mapped to t = 0 and t = 1 of the colour map (see HeatMapOptions::rangeMin). Never empty: a single
// value c is widened to c -/+ 1% (or -/+ 1 for 0), so a constant image shows the colour map's middle colour and
// the key keeps a scale. Throws InputError when an explicit bound is not finite or rangeMin > rangeMax.
ValueRange colorMapRange(const std::optional<ValueRange>& validRange, const HeatMapOptions& options);

// Paints `values` 1:1 with values.at(0, 0) at canvas pixel (left, bottom): a valid pixel (validMask nonzero, or
// all when null, and a finite value) in `colorMap` over `colorRange` (categorical: its class id's colour, the
// nearest integer), the others kInvalidPixelColor; what falls outside the canvas is clipped.
void paintHeatMapValues(ImageU8& canvas, int left, int bottom, const ImageF& values, const ImageU8* validMask,
  const ColorMap& colorMap, const ValueRange& colorRange);

// The colour key beside a heat map drawn with `colorMap` over `colorRange`: a continuous scale, or for a categorical
// map the classes of options.categoryLabels, or without labels the ids from the smallest to the largest valid value.
ColorKey heatMapColorKey(const ColorMap& colorMap, const std::optional<ValueRange>& validRange,
  const ValueRange& colorRange, const HeatMapOptions& options, int fontPx);

// "<title> [<unit>]  range [<min>, <max>]" with the range of the valid values, 3 significant digits;
// "... no valid pixels" when there are none.
std::string heatMapTitle(const HeatMapOptions& options, const std::optional<ValueRange>& validRange);

// Font size in pixels for an image `imageHeight` pixels tall: 1/32 of it, clamped to [12, 96].
int heatMapFontPx(int imageHeight);

// The heat map as an RGB image (3 components, row 0 = bottom, like Image). values: 1 component;
// validMask: same size, 1 component, nonzero = pixel has data; null = all valid. Categorical colours the value
// rounded to the nearest integer class id.
ImageU8 renderHeatMap(const ImageF& values, const ImageU8* validMask, const HeatMapOptions& options);

// renderHeatMap written as an 8-bit RGB PNG (top row of the PNG = top row of the image). Throws InputError
// naming the path when it cannot be written.
void writeHeatMapPng(const ImageF& values, const ImageU8* validMask, const HeatMapOptions& options,
  const std::filesystem::path& pngPath);

} // namespace sl
