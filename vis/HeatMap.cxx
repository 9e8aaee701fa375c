#include "vis/HeatMap.h"

#include "core/Error.h"
#include "io/ImageIO.h"
#include "vis/Canvas.h"
#include "vis/ColorKey.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace sl
{

namespace
{

bool hasValueMark(const ImageU8* validMask, int x, int y)
{
  return validMask == nullptr || (validMask->at(x, y) != 0 && validMask->at(x, y) != kNotApplicablePixel);
}

bool isValidPixel(const ImageF& values, const ImageU8* validMask, int x, int y)
{
  return std::isfinite(values.at(x, y)) && hasValueMark(validMask, x, y);
}

bool isNotApplicablePixel(const ImageU8* validMask, int x, int y)
{
  return validMask != nullptr && validMask->at(x, y) == kNotApplicablePixel;
}

// The value at quantile q (0..1) of `values` (reordered): the element of rank floor(q (n - 1)), so that at most
// a share 1 - q of them lies above it.
double quantileOf(std::vector<double>& values, double q)
{
  const auto at = values.begin() + static_cast<std::ptrdiff_t>(q * static_cast<double>(values.size() - 1));
  std::nth_element(values.begin(), at, values.end());
  return *at;
}


// Class id of a categorical value: the nearest integer (clamped so that the conversion cannot overflow).
long long categoryId(double value)
{
  return std::llround(std::clamp(value, -1e15, 1e15));
}

double explicitBound(const std::optional<double>& bound, const char* name, const HeatMapOptions& options)
{
  if (!std::isfinite(*bound))
    throw InputError(format("heat map '", options.title, "': ", name, " ", *bound, " is not finite"));
  return *bound;
}

// The symmetric log scale's linear width, where it applies (diverging maps only).
double symlogWidthOf(const HeatMapOptions& options)
{
  return options.colorMap == ColorMapKind::Diverging ? std::max(options.signedLogLinearWidth, 0.0) : 0.0;
}

} // namespace

double colorMapPosition(double value, const ValueRange& colorRange, double signedLogLinearWidth)
{
  if (signedLogLinearWidth <= 0.0)
    return (value - colorRange.min) / (colorRange.max - colorRange.min);
  const double magnitude = std::max(std::abs(colorRange.min), std::abs(colorRange.max));
  const double scaled =
    std::log1p(std::abs(value) / signedLogLinearWidth) / std::log1p(magnitude / signedLogLinearWidth);
  return 0.5 + 0.5 * std::copysign(scaled, value);
}

double colorMapValueAt(double t, const ValueRange& colorRange, double signedLogLinearWidth)
{
  if (signedLogLinearWidth <= 0.0)
    return colorRange.min + t * (colorRange.max - colorRange.min);
  const double magnitude = std::max(std::abs(colorRange.min), std::abs(colorRange.max));
  const double scaled = 2.0 * t - 1.0;
  return std::copysign(
    signedLogLinearWidth * std::expm1(std::abs(scaled) * std::log1p(magnitude / signedLogLinearWidth)), scaled);
}

void paintHeatMapValues(ImageU8& canvas, int left, int bottom, const ImageF& values, const ImageU8* validMask,
  const ColorMap& colorMap, const ValueRange& colorRange, double signedLogLinearWidth)
{
  for (int y = 0; y < values.height; ++y)
    for (int x = 0; x < values.width; ++x)
    {
      RgbColor color = isNotApplicablePixel(validMask, x, y) ? kNotApplicableColor : kInvalidPixelColor;
      if (isValidPixel(values, validMask, x, y))
      {
        const double value = values.at(x, y);
        color = colorMap.kind() == ColorMapKind::Categorical
                  ? ColorMap::categoryColor(categoryId(value))
                  : colorMap.map(colorMapPosition(value, colorRange, signedLogLinearWidth));
      }
      fillRect(canvas, left + x, bottom + y, 1, 1, color);
    }
}

ColorKey heatMapColorKey(const ColorMap& colorMap, const std::optional<ValueRange>& validRange,
  const ValueRange& colorRange, const HeatMapOptions& options, int fontPx)
{
  if (colorMap.kind() != ColorMapKind::Categorical)
    return ColorKey::continuous(colorMap, colorRange.min, colorRange.max, fontPx);
  if (!options.categoryLabels.empty())
  {
    const auto labelCount = static_cast<long long>(options.categoryLabels.size());
    return ColorKey::categorical(0, labelCount, options.categoryLabels, fontPx);
  }
  if (!validRange)
    return ColorKey::categorical(0, 0, {}, fontPx);
  const long long firstId = categoryId(validRange->min);
  return ColorKey::categorical(firstId, categoryId(validRange->max) - firstId + 1, {}, fontPx);
}

std::optional<ValueRange> validValueRange(const ImageF& values, const ImageU8* validMask)
{
  std::optional<ValueRange> range;
  for (int y = 0; y < values.height; ++y)
    for (int x = 0; x < values.width; ++x)
    {
      if (!isValidPixel(values, validMask, x, y))
        continue;
      const double value = values.at(x, y);
      if (!range)
        range = ValueRange{ value, value };
      range->min = std::min(range->min, value);
      range->max = std::max(range->max, value);
    }
  return range;
}

ValueRange colorMapRange(const std::optional<ValueRange>& validRange, const HeatMapOptions& options)
{
  const bool isDiverging = options.colorMap == ColorMapKind::Diverging;
  ValueRange range = validRange.value_or(isDiverging ? ValueRange{ -1.0, 1.0 } : ValueRange{ 0.0, 1.0 });
  if (isDiverging && !options.rangeMin && !options.rangeMax)
  {
    const double magnitude = std::max(std::abs(range.min), std::abs(range.max));
    range = { -magnitude, magnitude };
  }
  if (options.rangeMin)
    range.min = explicitBound(options.rangeMin, "rangeMin", options);
  if (options.rangeMax)
    range.max = explicitBound(options.rangeMax, "rangeMax", options);
  if (isDiverging && options.rangeMin.has_value() != options.rangeMax.has_value())
  {
    // One explicit bound: mirror it, so that 0 stays white.
    const double magnitude = std::abs(options.rangeMin ? range.min : range.max);
    range = { -magnitude, magnitude };
  }
  if (range.min > range.max)
    throw InputError(format("heat map '", options.title, "': rangeMin ", range.min, " > rangeMax ", range.max));
  if (range.min == range.max)
  {
    const double halfWidth = range.min == 0.0 ? 1.0 : 0.01 * std::abs(range.min);
    range = { range.min - halfWidth, range.max + halfWidth };
  }
  return range;
}

HeatMapScale heatMapScale(const std::vector<MaskedValues>& images, const HeatMapOptions& options)
{
  HeatMapScale scale;
  std::vector<double> values;
  for (const auto& [image, mask] : images)
    for (int y = 0; y < image->height; ++y)
      for (int x = 0; x < image->width; ++x)
      {
        if (isNotApplicablePixel(mask, x, y))
          ++scale.notApplicablePixels;
        else if (!isValidPixel(*image, mask, x, y))
          ++scale.noSurfacePixels;
        else
          values.push_back(image->at(x, y));
      }
  scale.valuePixels = values.size();
  if (!values.empty())
  {
    const auto [minimum, maximum] = std::minmax_element(values.begin(), values.end());
    scale.validRange = ValueRange{ *minimum, *maximum };
  }
  if (options.colorMap == ColorMapKind::Categorical)
  {
    scale.colorRange = scale.validRange.value_or(ValueRange{ 0.0, 1.0 });
    return scale;
  }
  HeatMapOptions bounds = options;
  if (options.robustRange && !options.rangeMin && !options.rangeMax && scale.validRange)
  {
    if (options.colorMap == ColorMapKind::Diverging)
    {
      std::vector<double> magnitudes(values.size());
      std::transform(values.begin(), values.end(), magnitudes.begin(), [](double v) { return std::abs(v); });
      const double magnitude = quantileOf(magnitudes, 1.0 - kRobustTail);
      bounds.rangeMax = magnitude > 0.0 ? magnitude
                                        : std::max(std::abs(scale.validRange->min), std::abs(scale.validRange->max));
    }
    else
    {
      std::vector<double> sorted = values;
      const double low = quantileOf(sorted, kRobustTail);
      const double high = quantileOf(sorted, 1.0 - kRobustTail);
      // All but the tails equal: the percentiles would leave no scale, so the tails get it.
      bounds.rangeMin = low < high ? low : scale.validRange->min;
      bounds.rangeMax = low < high ? high : scale.validRange->max;
    }
  }
  scale.colorRange = colorMapRange(scale.validRange, bounds);
  for (const double value : values)
  {
    scale.clippedBelow = scale.clippedBelow || value < scale.colorRange.min;
    scale.clippedAbove = scale.clippedAbove || value > scale.colorRange.max;
    scale.clippedPixels += value < scale.colorRange.min || value > scale.colorRange.max ? 1 : 0;
  }
  return scale;
}

std::vector<std::string> heatMapTitleLines(const HeatMapOptions& options, const HeatMapScale& scale)
{
  std::vector<std::string> lines;
  std::string name = options.title;
  if (!options.unit.empty())
    name += format(name.empty() ? "" : " ", "[", options.unit, "]");
  if (!name.empty())
    lines.push_back(name);
  if (!scale.validRange)
  {
    lines.push_back("no pixel with a value");
    return lines;
  }
  if (options.colorMap == ColorMapKind::Categorical)
    return lines;
  std::string numbers = format("values [", formatThreeSignificant(scale.validRange->min), ", ",
    formatThreeSignificant(scale.validRange->max), "]");
  if (scale.clippedPixels > 0)
  {
    char percent[32];
    std::snprintf(percent, sizeof(percent), "%.2g", scale.clippedPercent());
    numbers += format("; scale [", formatThreeSignificant(scale.colorRange.min), ", ",
      formatThreeSignificant(scale.colorRange.max), "], ", percent, "% of pixels beyond");
  }
  if (symlogWidthOf(options) > 0.0)
    numbers += format("; log scale, linear within +-", formatThreeSignificant(options.signedLogLinearWidth));
  lines.push_back(numbers);
  return lines;
}

ColorKey heatMapColorKey(const ColorMap& colorMap, const HeatMapScale& scale, const HeatMapOptions& options, int fontPx)
{
  ColorKey key = colorMap.kind() == ColorMapKind::Categorical
    ? heatMapColorKey(colorMap, scale.validRange, scale.colorRange, options, fontPx)
    : ColorKey::continuous(colorMap, scale.colorRange.min, scale.colorRange.max, fontPx, scale.clippedBelow,
        scale.clippedAbove, symlogWidthOf(options));
  if (scale.notApplicablePixels > 0)
    key.addSwatch(kNotApplicableColor, "not tested / n.a.");
  if (scale.noSurfacePixels > 0)
    key.addSwatch(kInvalidPixelColor, "no surface");
  return key;
}

std::string heatMapTitle(const HeatMapOptions& options, const std::optional<ValueRange>& validRange)
{
  std::string title = options.title;
  if (!options.unit.empty())
    title += format(title.empty() ? "" : " ", "[", options.unit, "]");
  if (!title.empty())
    title += "  ";
  if (!validRange)
    return title + "no valid pixels";
  return title + format("range [", formatThreeSignificant(validRange->min), ", ",
                   formatThreeSignificant(validRange->max), "]");
}

int heatMapFontPx(int imageHeight)
{
  return std::clamp(imageHeight / 32, 12, 96);
}

ImageU8 renderHeatMap(const ImageF& values, const ImageU8* validMask, const HeatMapOptions& options,
  HeatMapScale* drawnScale)
{
  SL_CHECK_MSG(values.components == 1 && !values.empty(), "heat map of a ", values.width, "x", values.height,
    "x", values.components, " image");
  const bool maskMatchesValues =
    validMask == nullptr ||
    (validMask->width == values.width && validMask->height == values.height && validMask->components == 1);
  SL_CHECK_MSG(maskMatchesValues, "valid mask ", validMask->width, "x", validMask->height, "x",
    validMask->components, " for values ", values.width, "x", values.height);

  const HeatMapScale scale = heatMapScale({ { &values, validMask } }, options);
  if (drawnScale)
  {
    *drawnScale = scale;
  }
  const ColorMap colorMap(options.colorMap);
  const int fontPx = heatMapFontPx(values.height);
  const ColorKey colorKey = heatMapColorKey(colorMap, scale, options, fontPx);
  const int lineHeight = measureText("0", fontPx).height;
  const int paddingPx = std::max(3, fontPx / 2);
  // The title lines wrap at spaces to the width of the values and the key (or of their widest word): the numbers
  // line must not widen a small map.
  const std::vector<std::string> unwrapped = heatMapTitleLines(options, scale);
  int wrapWidth = values.width + colorKey.width() - 2 * paddingPx;
  for (const std::string& line : unwrapped)
    for (std::size_t start = 0; start < line.size();)
    {
      const std::size_t space = std::min(line.find(' ', start), line.size());
      wrapWidth = std::max(wrapWidth, measureText(line.substr(start, space - start), fontPx).width);
      start = space + 1;
    }
  std::vector<std::string> titleLines;
  for (const std::string& line : unwrapped)
    for (std::string& wrapped : wrapText(line, wrapWidth, fontPx))
      titleLines.push_back(std::move(wrapped));
  int titleWidth = 0;
  for (const std::string& line : titleLines)
    titleWidth = std::max(titleWidth, measureText(line, fontPx).width);

  // Layout, bottom to top: [values | colour key] (as tall as the taller of the two), then the title band.
  const int keyLeft = values.width;
  const int bodyHeight = std::max(values.height, colorKey.minHeight());
  const int titleBandHeight = static_cast<int>(titleLines.size()) * lineHeight + 2 * paddingPx;
  const int canvasWidth = std::max(keyLeft + colorKey.width(), titleWidth + 2 * paddingPx);
  ImageU8 canvas(canvasWidth, bodyHeight + titleBandHeight, 3, 255); // white margins

  paintHeatMapValues(canvas, 0, 0, values, validMask, colorMap, scale.colorRange, symlogWidthOf(options));
  colorKey.draw(canvas, keyLeft, 0, bodyHeight);
  int lineBottom = bodyHeight + titleBandHeight - paddingPx - lineHeight;
  for (const std::string& line : titleLines)
  {
    drawText(canvas, line, fontPx, paddingPx, lineBottom);
    lineBottom -= lineHeight;
  }
  return canvas;
}

HeatMapScale writeHeatMapPng(const ImageF& values, const ImageU8* validMask, const HeatMapOptions& options,
  const std::filesystem::path& pngPath)
{
  HeatMapScale scale;
  const ImageU8 canvas = renderHeatMap(values, validMask, options, &scale);

  // writePng checks every step of the write (a full disk or a file-size limit is an InputError naming
  // the file, never a truncated PNG that passes as written).
  writePng(pngPath, canvas);
  return scale;
}

} // namespace sl
