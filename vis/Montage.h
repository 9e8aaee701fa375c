// Montages (`shadowlab montage`, the lessons): one buffer of several runs side by side on ONE colour scale, so that
// equal colours mean equal values in every panel. Each panel shows its values 1:1 (canvas pixel = buffer pixel,
// row 0 at the bottom), with its label lines under it, wrapped to the panel's width so that no two labels touch;
// one colour key on the right serves every panel, and a title band on top names the buffer, the range of the
// values over all panels (and the scale and share of pixels beyond it where the scale is narrower), then what
// every panel shares (MontageOptions::commonLines) once.
//
// Colour maps (vis/ColorMap.h), by the buffer's kind, over the pixels with a value of ALL panels:
//  - Continuous: viridis (perceptually uniform), from the 0.5th to the 99.5th percentile
//    (HeatMapOptions::robustRange);
//  - Signed: ColorBrewer RdBu, blue - white - red, centred on 0 (white) and symmetric: [-m, m] with m the 99.5th
//    percentile of |value|. RdBu is one of ColorBrewer's colour-blind-safe schemes: its two arms differ in hue along
//    the blue-yellow axis that deuteranopes and protanopes keep, and in lightness, which everybody sees;
//  - Categorical: the Tableau 10 palette by class id, the key listing the classes by label (no numeric range).
// No surface (mask 0, NaN, inf): kInvalidPixelColor; not applicable (mask kNotApplicablePixel, e.g. depth_margin
// where no shadow test ran): kNotApplicableColor; both with a swatch in the key. No OpenGL (text through FreeType,
// as vis/HeatMap.h).
#pragma once

#include "core/Image.h"
#include "core/NamedImage.h"
#include "vis/ColorMap.h"
#include "vis/HeatMap.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace sl
{

struct MontagePanel
{
  ImageF values;        // 1 component
  ImageU8 validMask;    // same size, 1 component: 0 = no surface, kNotApplicablePixel = the quantity does not apply,
                        // other = the pixel has a value; empty = every pixel has one
  std::vector<std::string> labels; // lines drawn under the panel, top to bottom
};

struct MontageOptions
{
  std::string title; // the buffer's name
  std::string unit;  // shown after the title in brackets when non-empty
  BufferKind kind = BufferKind::Continuous;
  std::vector<std::string> categoryLabels; // Categorical: the label of class id 0..n-1
  // Continuous and Signed: end the scale at this quantile (0 < q <= 1) of the valid values over all panels
  // (Continuous: [min, quantile q]; Signed: +-(quantile q of |value|)); values beyond take the end colours and the
  // title says so. Unset: the robust scale (0.5th to 99.5th percentile; Signed: 99.5th of |value|).
  std::optional<double> clipQuantile;
  // What every panel shares (montageCommonLabels), drawn once under the title, wrapped to the montage's width.
  std::vector<std::string> commonLines;
  // Signed only: a symmetric log scale (HeatMapOptions::signedLogLinearWidth) linear within the quantile q
  // (0 < q < 1) of |value| over all panels, for buffers whose values near 0 matter and span decades.
  std::optional<double> signedLogLinearQuantile;
};

// A line of text on the montage canvas and its box (measureText's, row 0 at the bottom).
struct MontageTextBox
{
  std::string text;
  int left = 0;
  int bottom = 0;
  int width = 0;
  int height = 0;
};

// The valid values' range over every panel (nullopt when no panel has a valid pixel).
std::optional<ValueRange> montageValueRange(const std::vector<MontagePanel>& panels);

// Where everything goes on the canvas (row 0 at the bottom, like Image). Layout, bottom to top: a band of label
// lines (the most any panel has after wrapping), the row of panels (bottom-aligned, left to right, `paddingPx` apart
// and from the edges, each column as wide as its values, or kMinLabelChars characters when narrower), then the
// title band; the colour key fills the right margin beside the panel row. Label lines are wrapped to their column
// (wrapText), lineGapPx apart. fontPx = heatMapFontPx(tallest panel).
struct MontageLayout
{
  int width = 0;
  int height = 0;
  int fontPx = 0;
  int paddingPx = 0;
  std::vector<int> panelLeft; // canvas column of each panel's values' pixel x = 0
  int panelBottom = 0;        // canvas row of every panel's values' pixel y = 0
  int keyLeft = 0;
  int keyBottom = 0;
  int keyHeight = 0;
  // The values at the two ends of the colour map (Continuous: the valid range over all panels, widened as
  // colorMapRange does when it is a single value; Signed: symmetric about 0; both clipped by clipQuantile when it
  // is set). Categorical: the valid range.
  ValueRange colorRange;
  std::optional<ValueRange> validRange; // over all panels
  HeatMapScale scale;                   // colorRange, validRange and the pixel counts behind them
  double signedLogLinearWidth = 0.0;    // from signedLogLinearQuantile; 0: linear
  int lineGapPx = 0;
  std::vector<std::vector<MontageTextBox>> labelBoxes; // per panel, its wrapped label lines top to bottom
  std::vector<MontageTextBox> titleBoxes;              // the title band's lines, top to bottom
};

// The narrowest column labels wrap to, in characters of the label font.
inline constexpr int kMinLabelChars = 10;


// Throws InputError when there are no panels or a panel is not a non-empty 1-component image with a mask of its
// size (naming the panel by its first label).
MontageLayout montageLayout(const std::vector<MontagePanel>& panels, const MontageOptions& options);

// The montage as an RGB image (row 0 at the bottom), laid out by montageLayout.
ImageU8 renderMontage(const std::vector<MontagePanel>& panels, const MontageOptions& options);

// The label lines of panels made from runs, from each run's stats.json document (render or reference output,
// or any document with the same keys): the run's name and its technique ("reference" for a ray-traced reference;
// the name alone when every run is of one technique, which montageCommonLabels then names once); the parameters
// whose values differ between the runs that have them ("key=value", a line each, on the runs that have the key; a
// key of one technique only is left to the technique's name); the scene and resolution when they differ;
// "GPU <ms> ms" (total_gpu_ms) when present; and "RMSE <value>" (error/covered/rmse, bench-run and lesson runs) when
// the run was compared against a reference.
std::vector<std::vector<std::string>> montageRunLabels(
  const std::vector<std::string>& runNames, const std::vector<nlohmann::json>& stats);

// What the runs share, for the montage's title band (MontageOptions::commonLines): "technique <name>" when there is
// one, every parameter all runs hold with one value ("key=value"), the scene and the resolution when they are one.
std::vector<std::string> montageCommonLabels(const std::vector<nlohmann::json>& stats);

} // namespace sl
