#include "vis/HeatMap.h"

#include "core/Error.h"
#include "io/ImageIO.h"
#include "vis/Canvas.h"
#include "vis/ColorKey.h"

#include <algorithm>
#include <cmath>

namespace sl
{

namespace
{

bool isValidPixel(const ImageF& values, const ImageU8* validMask, int x, int y)
{
  return std::isfinite(values.at(x, y)) && (validMask == nullptr || validMask->at(x, y) != 0);
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

} // namespace

void paintHeatMapValues(ImageU8& canvas, int left, int bottom, const ImageF& values, const ImageU8* validMask,
  const ColorMap& colorMap, const ValueRange& colorRange)
{
  const double rangeWidth = colorRange.max - colorRange.min;
  for (int y = 0; y < values.height; ++y)
    for (int x = 0; x < values.width; ++x)
    {
      RgbColor color = kInvalidPixelColor;
      if (isValidPixel(values, validMask, x, y))
      {
        const double value = values.at(x, y);
        color = colorMap.kind() == ColorMapKind::Categorical
                  ? ColorMap::categoryColor(categoryId(value))
                  : colorMap.map((value - colorRange.min) / rangeWidth);
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

ImageU8 renderHeatMap(const ImageF& values, const ImageU8* validMask, const HeatMapOptions& options)
{
  SL_CHECK_MSG(values.components == 1 && !values.empty(), "heat map of a ", values.width, "x", values.height,
    "x", values.components, " image");
  const bool maskMatchesValues =
    validMask == nullptr ||
    (validMask->width == values.width && validMask->height == values.height && validMask->components == 1);
  SL_CHECK_MSG(maskMatchesValues, "valid mask ", validMask->width, "x", validMask->height, "x",
    validMask->components, " for values ", values.width, "x", values.height);

  const std::optional<ValueRange> validRange = validValueRange(values, validMask);
  const ValueRange colorRange = colorMapRange(validRange, options);
  const ColorMap colorMap(options.colorMap);
  const int fontPx = heatMapFontPx(values.height);
  const ColorKey colorKey = heatMapColorKey(colorMap, validRange, colorRange, options, fontPx);
  const std::string title = heatMapTitle(options, validRange);
  const TextSize titleSize = measureText(title, fontPx);
  const int paddingPx = std::max(3, fontPx / 2);

  // Layout, bottom to top: [values | colour key] (as tall as the taller of the two), then the title band.
  const int keyLeft = values.width;
  const int bodyHeight = std::max(values.height, colorKey.minHeight());
  const int titleBandHeight = titleSize.height + 2 * paddingPx;
  const int canvasWidth = std::max(keyLeft + colorKey.width(), titleSize.width + 2 * paddingPx);
  ImageU8 canvas(canvasWidth, bodyHeight + titleBandHeight, 3, 255); // white margins

  paintHeatMapValues(canvas, 0, 0, values, validMask, colorMap, colorRange);
  colorKey.draw(canvas, keyLeft, 0, bodyHeight);
  drawText(canvas, title, fontPx, paddingPx, bodyHeight + paddingPx);
  return canvas;
}

void writeHeatMapPng(const ImageF& values, const ImageU8* validMask, const HeatMapOptions& options,
  const std::filesystem::path& pngPath)
{
  const ImageU8 canvas = renderHeatMap(values, validMask, options);

  // writePng checks every step of the write (a full disk or a file-size limit is an InputError naming
  // the file, never a truncated PNG that passes as written).
  writePng(pngPath, canvas);
}

} // namespace sl
