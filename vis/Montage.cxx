#include "vis/Montage.h"

#include "core/Error.h"
#include "vis/BufferHeatMap.h"
#include "vis/Canvas.h"
#include "vis/ColorKey.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <optional>
#include <set>

namespace sl
{

namespace
{

// The panel's mask as the heat map functions take it (null: every pixel valid).
const ImageU8* validMaskOf(const MontagePanel& panel)
{
  return panel.validMask.empty() ? nullptr : &panel.validMask;
}

bool isValidPixel(const MontagePanel& panel, int x, int y)
{
  return std::isfinite(panel.values.at(x, y)) && (panel.validMask.empty() || panel.validMask.at(x, y) != 0);
}

std::string panelName(const MontagePanel& panel, std::size_t index)
{
  return panel.labels.empty() ? format("panel ", index + 1) : panel.labels.front();
}

void checkPanels(const std::vector<MontagePanel>& panels)
{
  if (panels.empty())
    throw InputError("montage: no panels");
  for (std::size_t i = 0; i < panels.size(); ++i)
  {
    const MontagePanel& panel = panels[i];
    if (panel.values.empty() || panel.values.components != 1)
      throw InputError(format("montage: ", panelName(panel, i), ": a ", panel.values.width, "x", panel.values.height,
        "x", panel.values.components, " image (a montage shows 1-component images)"));
    const bool maskFits = panel.validMask.empty() ||
      (panel.validMask.width == panel.values.width && panel.validMask.height == panel.values.height &&
        panel.validMask.components == 1);
    if (!maskFits)
      throw InputError(format("montage: ", panelName(panel, i), ": its mask is ", panel.validMask.width, "x",
        panel.validMask.height, ", its values ", panel.values.width, "x", panel.values.height));
  }
}

// The heat map's key over all panels (one scale).
ColorKey makeKey(const MontageOptions& options, const MontageLayout& layout)
{
  HeatMapOptions heatMap;
  heatMap.colorMap = colorMapFor(options.kind);
  heatMap.categoryLabels = options.categoryLabels;
  return heatMapColorKey(ColorMap(heatMap.colorMap), layout.validRange, layout.colorRange, heatMap, layout.fontPx);
}

std::string montageTitle(const MontageOptions& options, const std::optional<ValueRange>& validRange,
  std::size_t panelCount)
{
  HeatMapOptions heatMap;
  heatMap.title = options.title;
  heatMap.unit = options.unit;
  std::string title = heatMapTitle(heatMap, validRange) + format(", one scale for ", panelCount, " panels");
  if (options.clipQuantile && options.kind != BufferKind::Categorical)
    title += format(", clipped at the ", formatThreeSignificant(100.0 * *options.clipQuantile), "th percentile",
      options.kind == BufferKind::Signed ? " of |value|" : "");
  return title;
}

// The value at quantile q of the valid values (Signed: of their magnitudes) over every panel.
double valueQuantile(const std::vector<MontagePanel>& panels, double q, bool magnitudes)
{
  std::vector<double> values;
  for (const MontagePanel& panel : panels)
    for (int y = 0; y < panel.values.height; ++y)
      for (int x = 0; x < panel.values.width; ++x)
        if (isValidPixel(panel, x, y))
          values.push_back(magnitudes ? std::abs(double(panel.values.at(x, y))) : double(panel.values.at(x, y)));
  SL_CHECK(!values.empty());
  const auto at = values.begin() + static_cast<std::ptrdiff_t>(q * static_cast<double>(values.size() - 1));
  std::nth_element(values.begin(), at, values.end());
  return *at;
}

// A number for a label: 3 significant digits, as the colour key's ticks.
std::string labelNumber(double value)
{
  return formatThreeSignificant(value);
}

std::string jsonValueText(const nlohmann::json& value)
{
  if (value.is_string())
    return value.get<std::string>();
  if (value.is_number_float())
  {
    char text[32];
    std::snprintf(text, sizeof(text), "%.6g", value.get<double>());
    return text;
  }
  return value.dump();
}

} // namespace

std::optional<ValueRange> montageValueRange(const std::vector<MontagePanel>& panels)
{
  std::optional<ValueRange> range;
  for (const MontagePanel& panel : panels)
  {
    const std::optional<ValueRange> panelRange = validValueRange(panel.values, validMaskOf(panel));
    if (!panelRange)
      continue;
    if (!range)
      range = panelRange;
    range->min = std::min(range->min, panelRange->min);
    range->max = std::max(range->max, panelRange->max);
  }
  return range;
}

MontageLayout montageLayout(const std::vector<MontagePanel>& panels, const MontageOptions& options)
{
  checkPanels(panels);
  MontageLayout layout;
  layout.validRange = montageValueRange(panels);
  HeatMapOptions heatMap;
  heatMap.title = options.title;
  heatMap.colorMap = colorMapFor(options.kind);
  // One range for every panel: what makes the panels comparable (colorMapRange centres Signed buffers on 0).
  if (options.clipQuantile && options.kind != BufferKind::Categorical)
  {
    if (!(*options.clipQuantile > 0.0 && *options.clipQuantile <= 1.0))
      throw InputError(format("montage '", options.title, "': clip quantile ", *options.clipQuantile, " is not in (0, 1]"));
    if (layout.validRange)
    {
      const double clipped = valueQuantile(panels, *options.clipQuantile, options.kind == BufferKind::Signed);
      if (options.kind == BufferKind::Signed)
        heatMap.rangeMax = clipped; // mirrored to -clipped
      else
      {
        heatMap.rangeMin = layout.validRange->min;
        heatMap.rangeMax = clipped;
      }
    }
  }
  layout.colorRange = options.kind == BufferKind::Categorical && layout.validRange
    ? *layout.validRange
    : colorMapRange(layout.validRange, heatMap);

  int tallest = 0;
  std::size_t labelLines = 0;
  for (const MontagePanel& panel : panels)
  {
    tallest = std::max(tallest, panel.values.height);
    labelLines = std::max(labelLines, panel.labels.size());
  }
  layout.fontPx = heatMapFontPx(tallest);
  layout.paddingPx = std::max(3, layout.fontPx / 2);
  const int lineHeight = measureText("0", layout.fontPx).height;
  const int labelBand = static_cast<int>(labelLines) * lineHeight + (labelLines > 0 ? layout.paddingPx : 0);

  const ColorKey key = makeKey(options, layout);
  int left = layout.paddingPx;
  for (const MontagePanel& panel : panels)
  {
    int columnWidth = panel.values.width;
    for (const std::string& line : panel.labels)
      columnWidth = std::max(columnWidth, measureText(line, layout.fontPx).width);
    layout.panelLeft.push_back(left);
    left += columnWidth + layout.paddingPx;
  }
  layout.panelBottom = layout.paddingPx + labelBand;
  layout.keyLeft = left;
  layout.keyBottom = layout.panelBottom;
  layout.keyHeight = std::max(tallest, key.minHeight());

  const TextSize titleSize = measureText(montageTitle(options, layout.validRange, panels.size()), layout.fontPx);
  layout.width = std::max(layout.keyLeft + key.width(), titleSize.width + 2 * layout.paddingPx);
  layout.height = layout.panelBottom + layout.keyHeight + titleSize.height + 2 * layout.paddingPx;
  return layout;
}

ImageU8 renderMontage(const std::vector<MontagePanel>& panels, const MontageOptions& options)
{
  const MontageLayout layout = montageLayout(panels, options);
  ImageU8 canvas(layout.width, layout.height, 3, 255); // white margins
  const ColorMap colorMap(colorMapFor(options.kind));
  const int lineHeight = measureText("0", layout.fontPx).height;
  for (std::size_t p = 0; p < panels.size(); ++p)
  {
    const MontagePanel& panel = panels[p];
    const int left = layout.panelLeft[p];
    paintHeatMapValues(canvas, left, layout.panelBottom, panel.values, validMaskOf(panel), colorMap, layout.colorRange);
    // Label lines top to bottom under the panel.
    int lineBottom = layout.panelBottom - layout.paddingPx / 2 - lineHeight;
    for (const std::string& line : panel.labels)
    {
      drawText(canvas, line, layout.fontPx, left, lineBottom);
      lineBottom -= lineHeight;
    }
  }
  makeKey(options, layout).draw(canvas, layout.keyLeft, layout.keyBottom, layout.keyHeight);
  drawText(canvas, montageTitle(options, layout.validRange, panels.size()), layout.fontPx, layout.paddingPx,
    layout.panelBottom + layout.keyHeight + layout.paddingPx);
  return canvas;
}

std::vector<std::vector<std::string>> montageRunLabels(
  const std::vector<std::string>& runNames, const std::vector<nlohmann::json>& stats)
{
  SL_CHECK(runNames.size() == stats.size());
  const auto valueAt = [](const nlohmann::json& document, const char* key) {
    return document.is_object() && document.contains(key) ? document[key] : nlohmann::json();
  };
  // A parameter is labelled when the runs that have it hold two or more values of it (a key of one technique
  // only, or one value throughout, says nothing the technique's name does not).
  std::set<std::string> parameterKeys;
  for (const nlohmann::json& document : stats)
  {
    const nlohmann::json parameters = valueAt(document, "parameters");
    if (parameters.is_object())
      for (const auto& [key, value] : parameters.items())
        parameterKeys.insert(key);
  }
  const auto differs = [&](const std::function<nlohmann::json(const nlohmann::json&)>& get) {
    for (const nlohmann::json& document : stats)
      if (get(document) != get(stats.front()))
        return true;
    return false;
  };
  std::vector<std::string> differingKeys;
  for (const std::string& key : parameterKeys)
  {
    std::set<std::string> values;
    for (const nlohmann::json& document : stats)
    {
      const nlohmann::json parameters = valueAt(document, "parameters");
      if (parameters.is_object() && parameters.contains(key))
        values.insert(parameters[key].dump());
    }
    if (values.size() > 1)
      differingKeys.push_back(key);
  }
  const bool scenesDiffer = differs([&](const nlohmann::json& d) { return valueAt(d, "scene"); });
  const bool resolutionsDiffer = differs([&](const nlohmann::json& d) { return valueAt(d, "resolution"); });

  std::vector<std::vector<std::string>> labels;
  for (std::size_t r = 0; r < stats.size(); ++r)
  {
    const nlohmann::json& document = stats[r];
    std::vector<std::string> lines;
    const nlohmann::json technique = valueAt(document, "technique");
    const std::string techniqueName = technique.is_string() ? technique.get<std::string>()
      : valueAt(document, "command") == "reference"        ? std::string("reference")
                                                           : std::string("?");
    lines.push_back(runNames[r] == techniqueName ? techniqueName : runNames[r] + ": " + techniqueName);
    const nlohmann::json parameters = valueAt(document, "parameters");
    for (const std::string& key : differingKeys)
      if (parameters.is_object() && parameters.contains(key))
        lines.push_back(key + "=" + jsonValueText(parameters[key]));
    if (scenesDiffer && valueAt(document, "scene").is_string())
    {
      // datasets/<name>/scene.json -> <name>; another file -> its name.
      const std::filesystem::path scene = valueAt(document, "scene").get<std::string>();
      lines.push_back("scene " +
        (scene.filename() == "scene.json" && scene.has_parent_path() ? scene.parent_path().filename().string()
                                                                      : scene.filename().string()));
    }
    const nlohmann::json resolution = valueAt(document, "resolution");
    if (resolutionsDiffer && resolution.is_array() && resolution.size() == 2)
      lines.push_back(format(jsonValueText(resolution[0]), "x", jsonValueText(resolution[1])));
    const nlohmann::json gpuMs = valueAt(document, "total_gpu_ms");
    if (gpuMs.is_number())
      lines.push_back("GPU " + labelNumber(gpuMs.get<double>()) + " ms");
    const nlohmann::json error = valueAt(document, "error");
    if (error.is_object() && error.contains("covered") && error["covered"].is_object() &&
      error["covered"].contains("rmse") && error["covered"]["rmse"].is_number())
      lines.push_back("RMSE " + labelNumber(error["covered"]["rmse"].get<double>()));
    labels.push_back(std::move(lines));
  }
  return labels;
}

} // namespace sl
