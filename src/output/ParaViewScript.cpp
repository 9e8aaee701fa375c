#include "output/ParaViewScript.h"


#include <nlohmann/json.hpp>

#include <cmath>
#include <sstream>

namespace sl
{
namespace
{

// Control points per continuous colour map: the heat maps' maps are piecewise linear with fewer segments (ColorMap),
// so 65 points in ParaView's RGB interpolation reproduce them to well under one 8-bit step.
constexpr int kParaViewColorPoints = 65;

nlohmann::json colorMapPoints(const ColorMap& colorMap, const ValueRange& range)
{
  nlohmann::json points = nlohmann::json::array();
  for (int i = 0; i < kParaViewColorPoints; ++i)
  {
    const double t = static_cast<double>(i) / (kParaViewColorPoints - 1);
    const RgbColor color = colorMap.map(t);
    points.push_back(range.min + t * (range.max - range.min));
    points.push_back(color[0]);
    points.push_back(color[1]);
    points.push_back(color[2]);
  }
  return points;
}

// One entry of the script's BUFFERS table: where the buffer is and how its heat map drew it.
nlohmann::json bufferEntry(const DrawnHeatMap& drawn)
{
  const HeatMapOptions& options = drawn.options;
  nlohmann::json entry;
  entry["file"] = drawn.file;
  entry["unit"] = drawn.buffer->unit;
  entry["applies_where"] = drawn.appliesWhere;
  if (options.colorMap == ColorMapKind::Categorical)
  {
    // The classes the heat map's key lists (heatMapColorKey): the labels' ids, or the valid ids' span.
    nlohmann::json categories = nlohmann::json::array();
    long long first = 0;
    long long last = -1;
    if (!options.categoryLabels.empty())
    {
      last = static_cast<long long>(options.categoryLabels.size()) - 1;
    }
    else if (drawn.scale.validRange)
    {
      first = std::llround(drawn.scale.validRange->min);
      last = std::llround(drawn.scale.validRange->max);
    }
    for (long long id = first; id <= last && id - first < 256; ++id)
    {
      const RgbColor color = ColorMap::categoryColor(id);
      const std::string label = options.categoryLabels.empty() ? std::to_string(id)
                                                               : options.categoryLabels[static_cast<std::size_t>(id)];
      categories.push_back({ { "id", id }, { "label", label }, { "rgb", { color[0], color[1], color[2] } } });
    }
    entry["kind"] = "categorical";
    entry["categories"] = categories;
    return entry;
  }
  const ValueRange& range = drawn.scale.colorRange;
  entry["kind"] = options.colorMap == ColorMapKind::Diverging ? "diverging" : "sequential";
  entry["range"] = { range.min, range.max };
  entry["rgb_points"] = colorMapPoints(ColorMap(options.colorMap), range);
  return entry;
}

// The script's fixed part: reads BUFFERS (written above it) and shows one buffer.
constexpr const char* kScriptBody = R"PY(

INVALID_GREY = [0.25, 0.25, 0.25]  # the heat maps' colour where no surface is (vis/HeatMap.h kInvalidPixelColor)
NOT_APPLICABLE_GREY = [0.66, 0.66, 0.66]  # where the quantity does not apply (kNotApplicableColor)


def _here():
    try:
        return os.path.dirname(os.path.abspath(__file__))
    except NameError:  # paraview --script= may run it without __file__
        return os.getcwd()


def _pixels_where(image, array):
    """The pixels whose `array` is at least 0.5 (coverage, shadow_tested)."""
    selected = Threshold(Input=image, Scalars=["POINTS", array])
    if hasattr(selected, "LowerThreshold"):
        selected.LowerThreshold = 0.5
        selected.UpperThreshold = 1.0e30
    else:
        selected.ThresholdRange = [0.5, 1.0e30]
    return selected


def _unlit(display):
    """Colours as the heat maps draw them: ParaView's light kit would darken every one."""
    display.Ambient = 1.0
    display.Diffuse = 0.0
    display.Specular = 0.0


def show_buffer(name, view=None, legend=True):
    """Shows buffer `name` in `view` (the active render view by default) as its heat map draws it."""
    if name not in BUFFERS:
        raise SystemExit("open_in_paraview.py: no scalar buffer %r; buffers: %s" % (name, ", ".join(sorted(BUFFERS))))
    spec = BUFFERS[name]
    view = view or GetActiveViewOrCreate("RenderView")
    image = OpenDataFile(os.path.join(_here(), spec["file"]))
    source = image
    if spec["applies_where"]:
        # Pixels without a value are not drawn: the background shows "no surface" in the heat maps' dark grey, and
        # for a quantity defined on shadow-tested pixels only, the covered surface behind it shows light grey.
        source = _pixels_where(image, spec["applies_where"])
        if spec["applies_where"] != "coverage":
            surface = Show(_pixels_where(image, "coverage"), view)
            surface.ColorArrayName = [None, ""]
            surface.AmbientColor = NOT_APPLICABLE_GREY
            surface.DiffuseColor = NOT_APPLICABLE_GREY
            _unlit(surface)
            surface.Position = [0.0, 0.0, -1.0]
    display = Show(source, view)
    _unlit(display)
    ColorBy(display, ("POINTS", name))
    lut = GetColorTransferFunction(name)
    lut.AutomaticRescaleRangeMode = "Never"
    if spec["kind"] == "categorical":
        lut.InterpretValuesAsCategories = 1
        annotations = []
        colors = []
        for category in spec["categories"]:
            annotations += [str(category["id"]), category["label"]]
            colors += category["rgb"]
        lut.Annotations = annotations
        lut.IndexedColors = colors
    else:
        lut.ColorSpace = "RGB"
        lut.RGBPoints = spec["rgb_points"]
        lut.RescaleTransferFunction(spec["range"][0], spec["range"][1])
    display.SetScalarBarVisibility(view, legend)
    if legend:
        bar = GetScalarBar(lut, view)
        bar.Title = name + (" [%s]" % spec["unit"] if spec["unit"] else "")
        bar.ComponentTitle = ""
    return display


def fit_view_to_image(view, width, height):
    """One pixel per buffer pixel: a parallel camera over the image plane, the view `width` x `height`."""
    view.ViewSize = [width, height]
    view.CameraParallelProjection = 1
    view.CameraPosition = [0.5 * (width - 1), 0.5 * (height - 1), 1000.0]
    view.CameraFocalPoint = [0.5 * (width - 1), 0.5 * (height - 1), 0.0]
    view.CameraViewUp = [0.0, 1.0, 0.0]
    view.CameraParallelScale = 0.5 * height
    view.OrientationAxesVisibility = 0
    if hasattr(view, "UseColorPaletteForBackground"):
        view.UseColorPaletteForBackground = 0
    view.Background = INVALID_GREY


def main(argv):
    parser = argparse.ArgumentParser(description="Open this ShadowLab output in ParaView.")
    parser.add_argument("--buffer", default=DEFAULT_BUFFER, help="the buffer to colour by (default %(default)s)")
    parser.add_argument("--screenshot", help="save the view as this PNG (one pixel per buffer pixel) and exit")
    parser.add_argument("--no-legend", action="store_true", help="leave the colour legend out")
    arguments, _ = parser.parse_known_args(argv)
    view = GetActiveViewOrCreate("RenderView")
    show_buffer(arguments.buffer, view, legend=not arguments.no_legend)
    Render(view)  # the first render resets the camera: fit it afterwards
    fit_view_to_image(view, IMAGE_SIZE[0], IMAGE_SIZE[1])
    Render(view)
    if arguments.screenshot:
        SaveScreenshot(arguments.screenshot, view, ImageResolution=IMAGE_SIZE)


main(sys.argv[1:])
)PY";

constexpr const char* kBenchScript = R"PY(# Generated by ShadowLab's bench: opens bench.csv in ParaView, a spreadsheet of every configuration beside a chart
# of one column against another (default: RMSE against the median frame GPU ms, both axes logarithmic).
#   paraview --script=open_in_paraview.py
#   pvpython open_in_paraview.py --x frame_wall_ms --y penumbra_rmse --screenshot chart.png
import argparse
import os
import sys

from paraview.simple import *


def _here():
    try:
        return os.path.dirname(os.path.abspath(__file__))
    except NameError:  # paraview --script= may run it without __file__
        return os.getcwd()


def main(argv):
    parser = argparse.ArgumentParser(description="Open this ShadowLab bench in ParaView.")
    parser.add_argument("--x", default="frame_gpu_ms", help="bench.csv column on the horizontal axis (%(default)s)")
    parser.add_argument("--y", default="rmse", help="bench.csv column on the vertical axis (%(default)s)")
    parser.add_argument("--linear", action="store_true", help="linear axes instead of logarithmic")
    parser.add_argument("--screenshot", help="save the chart as this PNG and exit")
    arguments, _ = parser.parse_known_args(argv)
    path = os.path.join(_here(), "bench.csv")
    with open(path) as csv:
        columns = csv.readline().strip().split(",")
    for column in (arguments.x, arguments.y):
        if column not in columns:
            raise SystemExit("open_in_paraview.py: bench.csv has no column %r" % column)
    table = CSVReader(FileName=[path])
    if not arguments.screenshot:
        spreadsheet = CreateView("SpreadSheetView")
        Show(table, spreadsheet)
    try:
        chart = CreateView("XYPointChartView")  # points only, no lines between unrelated configurations
    except Exception:
        chart = CreateView("XYChartView")
    display = Show(table, chart)
    display.UseIndexForXAxis = 0
    display.XArrayName = arguments.x
    display.SeriesVisibility = [arguments.y]
    display.SeriesMarkerStyle = [arguments.y, "4"]  # circles
    if hasattr(display, "SeriesMarkerSize"):
        display.SeriesMarkerSize = [arguments.y, "10"]
    chart.LeftAxisTitle = arguments.y
    chart.BottomAxisTitle = arguments.x
    chart.LeftAxisLogScale = 0 if arguments.linear else 1
    chart.BottomAxisLogScale = 0 if arguments.linear else 1
    chart.ViewSize = [800, 600]
    Render(chart)
    if arguments.screenshot:
        SaveScreenshot(arguments.screenshot, chart, ImageResolution=[800, 600])


main(sys.argv[1:])
)PY";

} // namespace

std::string benchParaViewScript()
{
  return kBenchScript;
}

std::string paraViewScript(const std::vector<DrawnHeatMap>& heatMaps, glm::ivec2 imageSize)
{
  nlohmann::json table = nlohmann::json::object();
  std::string defaultBuffer;
  for (const DrawnHeatMap& drawn : heatMaps)
  {
    // A bit mask's heat map counts its set bits, which ParaView would have to compute: left to the PNG.
    const NamedImage& named = *drawn.buffer;
    if (named.kind == BufferKind::BitMask || table.contains(named.name))
    {
      continue;
    }
    table[named.name] = bufferEntry(drawn);
    if (drawn.file == "buffers.vti" && (defaultBuffer.empty() || named.name == "visibility"))
    {
      defaultBuffer = named.name;
    }
  }
  std::ostringstream script;
  script << "# Generated by ShadowLab: opens this directory's buffers in ParaView with the colour maps and ranges of its\n"
            "# heat maps (heatmap_<buffer>.png).\n"
            "#   paraview --script=open_in_paraview.py\n"
            "#   pvpython open_in_paraview.py --buffer depth_margin --screenshot depth_margin.png\n"
            "# In a ParaView Python shell after running it: show_buffer('texel_ratio').\n"
            "import argparse\nimport json\nimport os\nimport sys\n\nfrom paraview.simple import *\n\n";
  // The table as JSON in a raw string; a quote inside a label becomes the JSON escape \u0027, so no text can close
  // the string early.
  // One buffer per line: a person can find a buffer's range in the file.
  std::string tableText = "{";
  for (auto entry = table.begin(); entry != table.end(); ++entry)
  {
    tableText += (entry == table.begin() ? "\n " : ",\n ") + nlohmann::json(entry.key()).dump() + ": " + entry.value().dump();
  }
  tableText += "\n}";
  for (std::size_t at = tableText.find('\''); at != std::string::npos; at = tableText.find('\'', at))
  {
    tableText.replace(at, 1, "\\u0027");
  }
  script << "BUFFERS = json.loads(r'''" << tableText << "''')\n";
  script << "DEFAULT_BUFFER = " << nlohmann::json(defaultBuffer).dump() << "\n";
  script << "IMAGE_SIZE = [" << imageSize.x << ", " << imageSize.y << "]\n";
  script << kScriptBody;
  return script.str();
}

} // namespace sl
