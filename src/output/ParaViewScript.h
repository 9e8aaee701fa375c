// open_in_paraview.py: a ParaView Python script written beside buffers.vti that opens the frame's buffers with the
// colour maps and ranges of its heat maps (heatmap_<buffer>.png), so what ParaView shows is what the PNGs show.
// Run it with `paraview --script=open_in_paraview.py` (the GUI) or `pvpython open_in_paraview.py --buffer NAME
// --screenshot FILE` (docs/outputs.md). Pixels without a value show the heat maps' greys; bit masks (drawn as bit
// counts) are left to their PNG. The colour maps are written as explicit control points, not preset names, so
// the script does not depend on the presets of a ParaView version.
#pragma once

#include "core/NamedImage.h"
#include "vis/HeatMap.h"

#include <string>
#include <vector>

namespace sl
{

// A heat map as OutputWriter drew it: the buffer, the file that holds it, the array that marks its pixels with a value
// ("coverage", "shadow_tested", or "" for every pixel), and the options and scale it was drawn with.
struct DrawnHeatMap
{
  const NamedImage* buffer = nullptr;
  std::string file; // "buffers.vti" or "light_space.vti"
  std::string appliesWhere;
  HeatMapOptions options;
  HeatMapScale scale;
};

// The script's text for the heat maps drawn into a directory holding buffers.vti and, for light-space ones,
// light_space.vti: each with its heat map's colour map and scale. Bit masks (drawn as bit counts) are left out; the
// first shown is `visibility` when present; the screenshot is `imageSize` pixels (the frame's).
std::string paraViewScript(const std::vector<DrawnHeatMap>& heatMaps, glm::ivec2 imageSize);

// The bench's open_in_paraview.py, beside bench.csv: a spreadsheet of every configuration and a chart of one column
// against another (default: RMSE against median frame GPU ms, both axes logarithmic, as speed_vs_error_*.png).
std::string benchParaViewScript();

} // namespace sl
