// Heat maps of per-pixel instrumentation buffers: one scalar buffer becomes an 8-bit RGB image a researcher can
// read without any other tool. The values are drawn 1:1 with their bottom-left pixel at the canvas' bottom-left
// corner (canvas.at(x, y) shows values.at(x, y)); a colour key fills a margin on the right and title lines a band
// on top: "<title> [<unit>]", then the values' range and, where the scale is narrower, the scale and the share of
// pixels beyond it (drawn in the end colours). Pixels without a value are never drawn in a colour of the scale:
// no surface (or NaN) in kInvalidPixelColor, a surface the quantity does not apply to (kNotApplicablePixel, e.g. a
// face turned from the light in depth_margin) in kNotApplicableColor; both have a swatch in the key when present.
// Text scales with the image height (heatMapFontPx). No OpenGL: text is rasterised by VTK's FreeType text
// renderer, so this works without a graphics context (link VTK::RenderingFreeType and run vtk_module_autoinit).
#pragma once

#include "core/Image.h"
#include "vis/ColorKey.h"
#include "vis/ColorMap.h"

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
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
  // Viridis and Diverging without explicit bounds: end the scale at robust percentiles of the pixels with a value
  // (heatMapScale: the 0.5th and 99.5th, for Diverging the 99.5th of |value|) instead of at their min and max, so
  // that a few extreme pixels cannot flatten the rest and at most 2 % of them saturate.
  bool robustRange = false;
  // Diverging only, > 0: a symmetric log scale, linear within +-signedLogLinearWidth and logarithmic in |value|
  // beyond (colorMapPosition), for signed buffers whose values near 0 matter and span decades (depth_margin, where
  // acne lies within a bias of 0 and shadowed pixels a caster's distance away). 0: linear.
  double signedLogLinearWidth = 0.0;
};

// The share of the pixels with a value that a robust scale (HeatMapOptions::robustRange) leaves beyond each of its
// ends: its ends are the 0.5th and 99.5th percentiles, so that at most 1 % lie beyond the scale, and the pixels
// drawn in an end colour (those beyond, those at an end, and those within an 8-bit step of it) stay under 2 %.
inline constexpr double kRobustTail = 0.005;

// The mask value of a surface pixel the quantity does not apply to (a buffer's BufferDomain, core/NamedImage.h):
// drawn in kNotApplicableColor and left out of every range. Mask 0: no surface. Any other nonzero value: a pixel
// with a value.
inline constexpr std::uint8_t kNotApplicablePixel = 2;

// No surface (mask 0) and non-finite values: a neutral dark grey, outside every colour map.
inline constexpr RgbColor kInvalidPixelColor{ 0.25, 0.25, 0.25 };
// A surface the quantity does not apply to ("not tested / n.a." in the key): a neutral light grey, distinct from
// the diverging map's white (0 = "at the threshold"), from kInvalidPixelColor and from Tableau 10's grey (#7f7f7f).
inline constexpr RgbColor kNotApplicableColor{ 0.66, 0.66, 0.66 };

struct ValueRange
{
  double min = 0.0;
  double max = 0.0;
};

// Min and max over the valid pixels (validMask nonzero and not kNotApplicablePixel, or all when null) with finite
// values; nullopt when there are none.
std::optional<ValueRange> validValueRange(const ImageF& values, const ImageU8* validMask);

// The values mapped to t = 0 and t = 1 of the colour map (see HeatMapOptions::rangeMin). Never empty: a single
// value c is widened to c -/+ 1% (or -/+ 1 for 0), so a constant image shows the colour map's middle colour and
// the key keeps a scale. Throws InputError when an explicit bound is not finite or rangeMin > rangeMax.
ValueRange colorMapRange(const std::optional<ValueRange>& validRange, const HeatMapOptions& options);

// One colour scale over one or several images (a montage's panels), each with its mask (null: every pixel has a
// value) and what it says about their pixels.
using MaskedValues = std::pair<const ImageF*, const ImageU8*>;
struct HeatMapScale
{
  std::optional<ValueRange> validRange; // min and max of the pixels with a value
  ValueRange colorRange;                // the values at t = 0 and t = 1 of the colour map
  std::size_t valuePixels = 0;          // pixels with a finite value
  std::size_t clippedPixels = 0;        // of those, the ones beyond colorRange (drawn in its end colours)
  std::size_t notApplicablePixels = 0;  // mask kNotApplicablePixel
  std::size_t noSurfacePixels = 0;      // mask 0 or a non-finite value
  bool clippedBelow = false;            // some pixel lies below colorRange.min
  bool clippedAbove = false;
  double clippedPercent() const { return valuePixels ? 100.0 * double(clippedPixels) / double(valuePixels) : 0.0; }
};

// The scale of `images`: colorMapRange over their valid range, except that with options.robustRange (and no
// explicit bound) Viridis ends at the kRobustTail and 1 - kRobustTail quantiles (rank floor(q (n - 1)); their min
// and max when those two are equal) and Diverging at +-(1 - kRobustTail quantile of |value|) (the largest |value|
// when that is 0). Categorical: the valid range.
HeatMapScale heatMapScale(const std::vector<MaskedValues>& images, const HeatMapOptions& options);

// The title band's lines: "<title> [<unit>]", then for continuous and diverging maps "values [<min>, <max>]",
// followed where the scale is narrower by "; scale [<lo>, <hi>], <p>% of pixels beyond" (3 significant digits);
// "no pixel with a value" when there is none. Categorical maps give no numbers: the key names the classes.
std::vector<std::string> heatMapTitleLines(const HeatMapOptions& options, const HeatMapScale& scale);

// Where `value` falls on the colour map drawn over `colorRange`, t in [0, 1] before clamping: linear, or with
// signedLogLinearWidth c > 0 (colorRange [-m, m]) 0.5 + 0.5 sign(v) log(1 + |v| / c) / log(1 + m / c).
double colorMapPosition(double value, const ValueRange& colorRange, double signedLogLinearWidth = 0.0);
// Its inverse for t in [0, 1]: the value drawn at t (the colour key's tick labels).
double colorMapValueAt(double t, const ValueRange& colorRange, double signedLogLinearWidth = 0.0);

// Paints `values` 1:1 with values.at(0, 0) at canvas pixel (left, bottom): a valid pixel (validMask nonzero and not
// kNotApplicablePixel, or all when null, and a finite value) in `colorMap` over `colorRange` (categorical: its class
// id's colour, the nearest integer), kNotApplicablePixel in kNotApplicableColor, the others kInvalidPixelColor;
// what falls outside the canvas is clipped.
void paintHeatMapValues(ImageU8& canvas, int left, int bottom, const ImageF& values, const ImageU8* validMask,
  const ColorMap& colorMap, const ValueRange& colorRange, double signedLogLinearWidth = 0.0);

// The colour key beside a heat map drawn with `colorMap` over `colorRange`: a continuous scale, or for a categorical
// map the classes of options.categoryLabels, or without labels the ids from the smallest to the largest valid value.
ColorKey heatMapColorKey(const ColorMap& colorMap, const std::optional<ValueRange>& validRange,
  const ValueRange& colorRange, const HeatMapOptions& options, int fontPx);
// The same for `scale`, with open ends ("<= lo", ">= hi") where pixels lie beyond the scale, and swatches for
// "not tested / n.a." and "no surface" where `scale` counts such pixels.
ColorKey heatMapColorKey(
  const ColorMap& colorMap, const HeatMapScale& scale, const HeatMapOptions& options, int fontPx);

// "<title> [<unit>]  range [<min>, <max>]" with the range of the valid values, 3 significant digits;
// "... no valid pixels" when there are none.
std::string heatMapTitle(const HeatMapOptions& options, const std::optional<ValueRange>& validRange);

// Font size in pixels for an image `imageHeight` pixels tall: 1/32 of it, clamped to [12, 96].
int heatMapFontPx(int imageHeight);

// The heat map as an RGB image (3 components, row 0 = bottom, like Image). values: 1 component;
// validMask: same size, 1 component, 0 = no surface, kNotApplicablePixel = not applicable, other = pixel has a
// value; null = all valid. Categorical colours the value
// rounded to the nearest integer class id.
// `drawnScale` (optional): the scale it drew with, for a consumer that must match it (output/ParaViewScript.h).
ImageU8 renderHeatMap(const ImageF& values, const ImageU8* validMask, const HeatMapOptions& options,
  HeatMapScale* drawnScale = nullptr);

// renderHeatMap written as an 8-bit RGB PNG (top row of the PNG = top row of the image). Throws InputError
// naming the path when it cannot be written. Returns the scale it drew with.
HeatMapScale writeHeatMapPng(const ImageF& values, const ImageU8* validMask, const HeatMapOptions& options,
  const std::filesystem::path& pngPath);

} // namespace sl
