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
  return std::isfinite(panel.values.at(x, y)) &&
    (panel.validMask.empty() || (panel.validMask.at(x, y) != 0 && panel.validMask.at(x, y) != kNotApplicablePixel));
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

HeatMapOptions montageHeatMapOptions(const MontageOptions& options)
{
  HeatMapOptions heatMap;
  heatMap.title = options.title;
  heatMap.unit = options.unit;
  heatMap.colorMap = colorMapFor(options.kind);
  heatMap.categoryLabels = options.categoryLabels;
  heatMap.robustRange = true;
  if (options.title == "visibility" || options.title == "coverage")
  {
    // As their heat maps (vis/BufferHeatMap.h): a fraction of the light, on its own fixed scale.
    heatMap.rangeMin = 0.0;
    heatMap.rangeMax = 1.0;
  }
  return heatMap;
}

// The heat map's key over all panels (one scale).
ColorKey makeKey(const MontageOptions& options, const MontageLayout& layout)
{
  HeatMapOptions heatMap = montageHeatMapOptions(options);
  heatMap.signedLogLinearWidth = layout.signedLogLinearWidth;
  return heatMapColorKey(ColorMap(heatMap.colorMap), layout.scale, heatMap, layout.fontPx);
}

// The title band's lines before wrapping: the heat map's title lines, the first saying how many panels share the
// scale (and the clip quantile when one was asked for), then the common lines as one text.
std::vector<std::string> montageTitleLines(
  const MontageOptions& options, const MontageLayout& layout, std::size_t panelCount)
{
  HeatMapOptions heatMap = montageHeatMapOptions(options);
  heatMap.signedLogLinearWidth = layout.signedLogLinearWidth;
  std::vector<std::string> lines = heatMapTitleLines(heatMap, layout.scale);
  if (lines.empty())
    lines.emplace_back();
  std::string& first = lines.front();
  first += format(first == "no pixel with a value" ? "" : ", ", "one scale for ", panelCount,
    panelCount == 1 ? " panel" : " panels");
  if (options.clipQuantile && options.kind != BufferKind::Categorical)
    first += format(", clipped at the ", formatThreeSignificant(100.0 * *options.clipQuantile), "th percentile",
      options.kind == BufferKind::Signed ? " of |value|" : "");
  return lines;
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
  HeatMapOptions heatMap = montageHeatMapOptions(options);
  // One range for every panel: what makes the panels comparable (colorMapRange centres Signed buffers on 0).
  if (options.clipQuantile && options.kind != BufferKind::Categorical)
  {
    if (!(*options.clipQuantile > 0.0 && *options.clipQuantile <= 1.0))
      throw InputError(format("montage '", options.title, "': clip quantile ", *options.clipQuantile, " is not in (0, 1]"));
    const std::optional<ValueRange> validRange = montageValueRange(panels);
    if (validRange)
    {
      const double clipped = valueQuantile(panels, *options.clipQuantile, options.kind == BufferKind::Signed);
      if (options.kind == BufferKind::Signed)
        heatMap.rangeMax = clipped; // mirrored to -clipped
      else
      {
        heatMap.rangeMin = validRange->min;
        heatMap.rangeMax = clipped;
      }
    }
  }
  std::vector<MaskedValues> images;
  for (const MontagePanel& panel : panels)
    images.emplace_back(&panel.values, validMaskOf(panel));
  layout.scale = heatMapScale(images, heatMap);
  if (options.signedLogLinearQuantile && options.kind == BufferKind::Signed && layout.scale.validRange)
  {
    if (!(*options.signedLogLinearQuantile > 0.0 && *options.signedLogLinearQuantile < 1.0))
      throw InputError(format("montage '", options.title, "': log scale quantile ", *options.signedLogLinearQuantile,
        " is not in (0, 1)"));
    layout.signedLogLinearWidth = valueQuantile(panels, *options.signedLogLinearQuantile, true);
    // All but a few values 0: a linear scale shows them as well.
    if (!(layout.signedLogLinearWidth > 0.0) || layout.signedLogLinearWidth >= layout.scale.colorRange.max)
      layout.signedLogLinearWidth = 0.0;
  }
  layout.validRange = layout.scale.validRange;
  layout.colorRange = layout.scale.colorRange;

  int tallest = 0;
  for (const MontagePanel& panel : panels)
    tallest = std::max(tallest, panel.values.height);
  layout.fontPx = heatMapFontPx(tallest);
  layout.paddingPx = std::max(3, layout.fontPx / 2);
  layout.lineGapPx = std::max(2, layout.fontPx / 6);
  const int lineHeight = measureText("0", layout.fontPx).height;
  const int linePitch = lineHeight + layout.lineGapPx;
  const int minColumnWidth = measureText(std::string(kMinLabelChars, 'M'), layout.fontPx).width;

  // Columns: each panel's width (at least kMinLabelChars), its labels wrapped to it.
  std::vector<std::vector<std::string>> wrapped(panels.size());
  std::vector<int> columnWidth(panels.size());
  std::size_t labelLines = 0;
  for (std::size_t p = 0; p < panels.size(); ++p)
  {
    columnWidth[p] = std::max(panels[p].values.width, minColumnWidth);
    for (const std::string& label : panels[p].labels)
      for (std::string& line : wrapText(label, columnWidth[p], layout.fontPx))
        wrapped[p].push_back(std::move(line));
    labelLines = std::max(labelLines, wrapped[p].size());
  }
  const int labelBand = labelLines > 0 ? static_cast<int>(labelLines) * linePitch + layout.paddingPx : 0;

  const ColorKey key = makeKey(options, layout);
  int left = layout.paddingPx;
  for (std::size_t p = 0; p < panels.size(); ++p)
  {
    layout.panelLeft.push_back(left);
    left += columnWidth[p] + layout.paddingPx;
  }
  layout.panelBottom = layout.paddingPx + labelBand;
  layout.keyLeft = left;
  layout.keyBottom = layout.panelBottom;
  layout.keyHeight = std::max(tallest, key.minHeight());
  for (std::size_t p = 0; p < panels.size(); ++p)
  {
    int lineBottom = layout.panelBottom - layout.paddingPx / 2 - linePitch + layout.lineGapPx;
    std::vector<MontageTextBox> boxes;
    for (const std::string& line : wrapped[p])
    {
      boxes.push_back({ line, layout.panelLeft[p], lineBottom, measureText(line, layout.fontPx).width, lineHeight });
      lineBottom -= linePitch;
    }
    layout.labelBoxes.push_back(std::move(boxes));
  }

  // The title band: the title lines as they are (the canvas widens for them), the common lines wrapped to the
  // width of the panels and the key.
  std::vector<std::string> titleLines = montageTitleLines(options, layout, panels.size());
  const int wrapWidth = std::max(layout.keyLeft + key.width() - 2 * layout.paddingPx, minColumnWidth);
  std::string common;
  for (const std::string& item : options.commonLines)
    common += (common.empty() ? "" : ", ") + item;
  if (!common.empty())
    for (std::string& line : wrapText("shared: " + common, wrapWidth, layout.fontPx))
      titleLines.push_back(std::move(line));
  int titleWidth = 0;
  for (const std::string& line : titleLines)
    titleWidth = std::max(titleWidth, measureText(line, layout.fontPx).width);
  layout.width = std::max(layout.keyLeft + key.width(), titleWidth + 2 * layout.paddingPx);
  const int titleBand = static_cast<int>(titleLines.size()) * linePitch + layout.paddingPx;
  layout.height = layout.panelBottom + layout.keyHeight + titleBand + layout.paddingPx;
  int lineBottom = layout.height - layout.paddingPx - lineHeight;
  for (const std::string& line : titleLines)
  {
    layout.titleBoxes.push_back(
      { line, layout.paddingPx, lineBottom, measureText(line, layout.fontPx).width, lineHeight });
    lineBottom -= linePitch;
  }
  return layout;
}

ImageU8 renderMontage(const std::vector<MontagePanel>& panels, const MontageOptions& options)
{
  const MontageLayout layout = montageLayout(panels, options);
  ImageU8 canvas(layout.width, layout.height, 3, 255); // white margins
  const ColorMap colorMap(colorMapFor(options.kind));
  for (std::size_t p = 0; p < panels.size(); ++p)
  {
    const MontagePanel& panel = panels[p];
    paintHeatMapValues(canvas, layout.panelLeft[p], layout.panelBottom, panel.values, validMaskOf(panel), colorMap,
      layout.colorRange, layout.signedLogLinearWidth);
    for (const MontageTextBox& box : layout.labelBoxes[p])
      drawText(canvas, box.text, layout.fontPx, box.left, box.bottom);
  }
  makeKey(options, layout).draw(canvas, layout.keyLeft, layout.keyBottom, layout.keyHeight);
  for (const MontageTextBox& box : layout.titleBoxes)
    drawText(canvas, box.text, layout.fontPx, box.left, box.bottom);
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
  const bool techniquesDiffer = differs([&](const nlohmann::json& d) { return valueAt(d, "technique"); }) ||
    differs([&](const nlohmann::json& d) { return valueAt(d, "command"); });
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
    // One technique throughout: it is in the title band's common line (montageCommonLabels).
    lines.push_back(runNames[r] == techniqueName || !techniquesDiffer ? runNames[r] : runNames[r] + ": " + techniqueName);
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

std::vector<std::string> montageCommonLabels(const std::vector<nlohmann::json>& stats)
{
  std::vector<std::string> common;
  if (stats.empty())
    return common;
  const auto valueAt = [](const nlohmann::json& document, const char* key) {
    return document.is_object() && document.contains(key) ? document[key] : nlohmann::json();
  };
  const auto shared = [&](const char* key) {
    const nlohmann::json first = valueAt(stats.front(), key);
    for (const nlohmann::json& document : stats)
      if (valueAt(document, key) != first)
        return nlohmann::json();
    return first;
  };
  const nlohmann::json technique = shared("technique");
  if (technique.is_string())
    common.push_back("technique " + technique.get<std::string>());
  // The parameters every run holds with one value (a parameter some run lacks is no common ground).
  const nlohmann::json firstParameters = valueAt(stats.front(), "parameters");
  if (firstParameters.is_object())
    for (const auto& [key, value] : firstParameters.items())
    {
      bool everywhere = true;
      for (const nlohmann::json& document : stats)
      {
        const nlohmann::json parameters = valueAt(document, "parameters");
        everywhere = everywhere && parameters.is_object() && parameters.contains(key) && parameters[key] == value;
      }
      if (everywhere)
        common.push_back(key + "=" + jsonValueText(value));
    }
  const nlohmann::json scene = shared("scene");
  if (scene.is_string())
  {
    const std::filesystem::path path = scene.get<std::string>();
    common.push_back("scene " +
      (path.filename() == "scene.json" && path.has_parent_path() ? path.parent_path().filename().string()
                                                                 : path.filename().string()));
  }
  const nlohmann::json resolution = shared("resolution");
  if (resolution.is_array() && resolution.size() == 2)
    common.push_back(format(jsonValueText(resolution[0]), "x", jsonValueText(resolution[1])));
  return common;
}

} // namespace sl
