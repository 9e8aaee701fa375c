#include "vis/ColorKey.h"

#include "core/Error.h"
#include "vis/Canvas.h"
#include "vis/NumberText.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace sl
{

std::string formatThreeSignificant(double value)
{
  char text[32];
  std::snprintf(text, sizeof(text), "%.3g", value);
  return text;
}

ColorKey::ColorKey(int fontPx)
  : fontPx_(fontPx)
  , lineHeightPx_(measureText("0", fontPx).height)
  , paddingPx_(std::max(3, fontPx / 2))
  , swatchPx_(std::max(8, fontPx))
  , tickLengthPx_(std::max(3, fontPx / 3))
  , labelGapPx_(std::max(2, fontPx / 4))
  , lineWidthPx_(std::max(1, fontPx / 16))
{
}

ColorKey ColorKey::continuous(const ColorMap& colorMap, double valueMin, double valueMax, int fontPx,
  bool openBelow, bool openAbove, double signedLogLinearWidth)
{
  SL_CHECK_MSG(valueMin < valueMax, "colour bar range [", valueMin, ", ", valueMax, "]");
  ColorKey key(fontPx);
  key.colorMap_ = colorMap;
  // Every tick's value first, then labels with the digits to tell them apart (distinctTickLabels): a narrow
  // range reads 3.475, 3.473, 3.471 rather than 3.48, 3.47, 3.47.
  const std::vector<double> fractions = { 0.0, 0.25, 0.5, 0.75, 1.0 };
  std::vector<double> values;
  for (const double fraction : fractions)
  {
    values.push_back(signedLogLinearWidth > 0.0
        ? std::copysign(signedLogLinearWidth *
              std::expm1(std::abs(2.0 * fraction - 1.0) *
                std::log1p(std::max(std::abs(valueMin), std::abs(valueMax)) / signedLogLinearWidth)),
            2.0 * fraction - 1.0)
        : valueMin + fraction * (valueMax - valueMin));
  }
  const std::vector<std::string> labels = distinctTickLabels(values);
  int labelWidth = 0;
  for (std::size_t i = 0; i < fractions.size(); ++i)
  {
    const double fraction = fractions[i];
    const std::string prefix = fraction == 0.0 && openBelow ? "<=" : fraction == 1.0 && openAbove ? ">=" : "";
    key.ticks_.push_back({ fraction, prefix + labels[i] });
    labelWidth = std::max(labelWidth, measureText(key.ticks_.back().label, fontPx).width);
  }
  key.width_ =
    key.paddingPx_ + key.swatchPx_ + key.tickLengthPx_ + key.labelGapPx_ + labelWidth + key.paddingPx_;
  // A bar of 3 line heights keeps the min, middle and max labels apart; half a line above and below leaves
  // room for the end labels, which are centred on their ticks.
  key.minHeight_ = 4 * key.lineHeightPx_;
  return key;
}

ColorKey ColorKey::categorical(
  long long firstId, long long count, const std::vector<std::string>& labels, int fontPx)
{
  ColorKey key(fontPx);
  key.isCategorical_ = true;
  const long long shownCount = count > kMaxCategoryRows ? kMaxCategoryRows - 1 : std::max(count, 0LL);
  if (shownCount < count)
    key.moreCategoriesLabel_ = format("+", count - shownCount, " more");
  int labelWidth = measureText(key.moreCategoriesLabel_, fontPx).width;
  for (long long id = firstId; id < firstId + shownCount; ++id)
  {
    const bool hasLabel = id >= 0 && id < static_cast<long long>(labels.size());
    const std::string label = hasLabel ? labels[static_cast<std::size_t>(id)] : std::string();
    key.categories_.push_back({ id, label.empty() ? format(id) : format(id, ": ", label) });
    labelWidth = std::max(labelWidth, measureText(key.categories_.back().label, fontPx).width);
  }
  const int rowCount = static_cast<int>(key.categories_.size()) + (key.moreCategoriesLabel_.empty() ? 0 : 1);
  key.width_ = key.paddingPx_ + key.swatchPx_ + key.labelGapPx_ + labelWidth + key.paddingPx_;
  key.minHeight_ = key.paddingPx_ + rowCount * (key.lineHeightPx_ + key.labelGapPx_);
  return key;
}

std::vector<std::string> ColorKey::tickLabels() const
{
  std::vector<std::string> labels;
  for (const Tick& tick : ticks_)
    labels.push_back(tick.label);
  return labels;
}

void ColorKey::addSwatch(const RgbColor& color, const std::string& label)
{
  swatches_.push_back({ color, label });
  width_ = std::max(width_, paddingPx_ + swatchPx_ + labelGapPx_ + measureText(label, fontPx_).width + paddingPx_);
  minHeight_ += rowHeight() + (swatches_.size() == 1 ? paddingPx_ : 0);
}

int ColorKey::swatchBlockHeight() const
{
  return swatches_.empty() ? 0 : paddingPx_ + static_cast<int>(swatches_.size()) * rowHeight();
}

void ColorKey::drawSwatchRow(
  ImageU8& canvas, int left, int rowBottom, const RgbColor& color, const std::string& label) const
{
  const int swatchLeft = left + paddingPx_;
  const int swatchSide = std::min(swatchPx_, lineHeightPx_);
  const int swatchBottom = rowBottom + (lineHeightPx_ - swatchSide) / 2;
  fillRect(canvas, swatchLeft, swatchBottom, swatchSide, swatchSide, color);
  strokeRect(canvas, swatchLeft, swatchBottom, swatchSide, swatchSide, kBlack, lineWidthPx_);
  drawText(canvas, label, fontPx_, swatchLeft + swatchPx_ + labelGapPx_, rowBottom);
}

void ColorKey::draw(ImageU8& canvas, int left, int bottom, int height) const
{
  SL_CHECK_MSG(height >= minHeight_, "colour key height ", height, " < ", minHeight_);
  // The swatches take the bottom rows; the bar or the classes the rest.
  const int block = swatchBlockHeight();
  int rowBottom = bottom + block - paddingPx_ - rowHeight();
  for (const Swatch& swatch : swatches_)
  {
    drawSwatchRow(canvas, left, rowBottom + labelGapPx_, swatch.color, swatch.label);
    rowBottom -= rowHeight();
  }
  if (isCategorical_)
    drawCategories(canvas, left, bottom + block, height - block);
  else
    drawBar(canvas, left, bottom + block, height - block);
}

int ColorKey::tickRow(double fraction, int barBottom, int barHeight) const
{
  return barBottom + static_cast<int>(std::lround(fraction * (barHeight - 1)));
}

void ColorKey::drawBar(ImageU8& canvas, int left, int bottom, int height) const
{
  const int halfLine = (lineHeightPx_ + 1) / 2;
  const int barLeft = left + paddingPx_;
  const int barBottom = bottom + halfLine;
  const int barHeight = height - 2 * halfLine;
  // Bottom row = map(0) = valueMin, top row = map(1) = valueMax, the same rows the end ticks point at.
  for (int row = 0; row < barHeight; ++row)
    fillRect(canvas, barLeft, barBottom + row, swatchPx_, 1, colorMap_.map(row / double(barHeight - 1)));
  strokeRect(canvas, barLeft - lineWidthPx_, barBottom - lineWidthPx_, swatchPx_ + 2 * lineWidthPx_,
    barHeight + 2 * lineWidthPx_, kBlack, lineWidthPx_);

  // Quarter ticks only where their labels cannot touch (two line heights apart).
  const bool drawQuarterTicks = barHeight >= 8 * lineHeightPx_;
  const int tickLeft = barLeft + swatchPx_ + lineWidthPx_;
  for (const Tick& tick : ticks_)
  {
    const bool isQuarter = tick.fraction == 0.25 || tick.fraction == 0.75;
    if (isQuarter && !drawQuarterTicks)
      continue;
    const int row = tickRow(tick.fraction, barBottom, barHeight);
    fillRect(canvas, tickLeft, row - lineWidthPx_ / 2, tickLengthPx_, lineWidthPx_, kBlack);
    drawText(canvas, tick.label, fontPx_, tickLeft + tickLengthPx_ + labelGapPx_, row - lineHeightPx_ / 2);
  }
}

void ColorKey::drawCategories(ImageU8& canvas, int left, int bottom, int height) const
{
  const int rowHeight = lineHeightPx_ + labelGapPx_;
  const int swatchLeft = left + paddingPx_;
  const int labelLeft = swatchLeft + swatchPx_ + labelGapPx_;
  const int swatchSide = std::min(swatchPx_, lineHeightPx_);
  int rowBottom = bottom + height - paddingPx_ / 2 - rowHeight;
  for (const Category& category : categories_)
  {
    const int swatchBottom = rowBottom + (lineHeightPx_ - swatchSide) / 2;
    fillRect(canvas, swatchLeft, swatchBottom, swatchSide, swatchSide, ColorMap::categoryColor(category.id));
    strokeRect(canvas, swatchLeft, swatchBottom, swatchSide, swatchSide, kBlack, lineWidthPx_);
    drawText(canvas, category.label, fontPx_, labelLeft, rowBottom);
    rowBottom -= rowHeight;
  }
  drawText(canvas, moreCategoriesLabel_, fontPx_, labelLeft, rowBottom);
}

} // namespace sl
