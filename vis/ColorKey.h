// The key drawn beside a heat map: a vertical colour bar with tick labels for continuous colour maps, or a
// list of colour swatches with labels for categorical ones. It fills a panel of width() pixels and any height
// of at least minHeight(); all sizes scale with the font size.
#pragma once

#include "core/Image.h"
#include "vis/ColorMap.h"

#include <string>
#include <vector>

namespace sl
{

// A value with 3 significant digits, as printf's %.3g: 0.03125 -> "0.0312", 1500 -> "1.5e+03", 2 -> "2".
std::string formatThreeSignificant(double value);

class ColorKey
{
public:
  // A bar from valueMin (bottom) to valueMax (top), valueMin < valueMax, with ticks at both ends and in the
  // middle (and at the quarters when the bar is tall enough), labelled with at least 3 significant digits and as
  // many more as make the five labels differ (vis/NumberText.h distinctTickLabels). An open end
  // (pixels lie beyond it, drawn in its colour) is labelled "<=" or ">=" its value. signedLogLinearWidth > 0: the
  // bar is a symmetric log scale (vis/HeatMap.h colorMapPosition) and the ticks give the values drawn there.
  static ColorKey continuous(const ColorMap& colorMap, double valueMin, double valueMax, int fontPx,
    bool openBelow = false, bool openAbove = false, double signedLogLinearWidth = 0.0);

  // One swatch per class id firstId .. firstId + count - 1, top to bottom, each labelled "<id>: <label>" with
  // labels[id] where 0 <= id < labels.size(), else "<id>". Swatch colours are ColorMap::categoryColor(id).
  // Long lists are cut at kMaxCategoryRows rows, the last one saying "+N more".
  static ColorKey categorical(
    long long firstId, long long count, const std::vector<std::string>& labels, int fontPx);
  static constexpr int kMaxCategoryRows = 32;

  // A row under the bar or the classes: a swatch of `color` labelled `label` (pixels drawn outside the scale:
  // "not tested / n.a.", "no surface"). Widens the key and raises minHeight() to fit.
  void addSwatch(const RgbColor& color, const std::string& label);

  // The continuous bar's five tick labels, bottom to top (the quarters' drawn only on a tall bar); empty for a
  // categorical key.
  std::vector<std::string> tickLabels() const;

  int width() const { return width_; }
  int minHeight() const { return minHeight_; }

  // Draws the key into the panel whose bottom-left canvas pixel is (left, bottom); height >= minHeight().
  void draw(ImageU8& canvas, int left, int bottom, int height) const;

private:
  struct Category
  {
    long long id;
    std::string label;
  };
  struct Swatch
  {
    RgbColor color;
    std::string label;
  };
  struct Tick
  {
    double fraction; // 0 = bottom of the bar, 1 = top
    std::string label;
  };

  explicit ColorKey(int fontPx);
  void drawBar(ImageU8& canvas, int left, int bottom, int height) const;
  void drawCategories(ImageU8& canvas, int left, int bottom, int height) const;
  int tickRow(double fraction, int barBottom, int barHeight) const;
  int rowHeight() const { return lineHeightPx_ + labelGapPx_; }
  int swatchBlockHeight() const;
  void drawSwatchRow(ImageU8& canvas, int left, int rowBottom, const RgbColor& color, const std::string& label) const;

  bool isCategorical_ = false;
  ColorMap colorMap_{ ColorMapKind::Viridis };
  std::vector<Tick> ticks_;          // continuous
  std::vector<Category> categories_; // categorical
  std::string moreCategoriesLabel_;  // "+N more", empty when every category fits
  std::vector<Swatch> swatches_;     // under the bar or the classes

  int fontPx_;
  int lineHeightPx_;
  int paddingPx_;
  int swatchPx_; // bar width, and side of a category swatch
  int tickLengthPx_;
  int labelGapPx_;
  int lineWidthPx_; // outlines and tick marks
  int width_ = 0;
  int minHeight_ = 0;
};

} // namespace sl
