// open_in_paraview.py: a ParaView Python script written beside buffers.vti that opens the frame's buffers with the
// colour maps and ranges of its heat maps (heatmap_<buffer>.png), so what ParaView shows is what the PNGs show.
// Run it with `paraview --script=open_in_paraview.py` (the GUI) or `pvpython open_in_paraview.py --buffer NAME
// --screenshot FILE` (docs/outputs.md). Pixels without a value show the heat maps' greys; bit masks (drawn as bit
// counts) are left to their PNG. The colour maps are written as explicit control points, not preset names, so
// the script does not depend on the presets of a ParaView version.
#pragma once

#include "core/Image.h"
#include "core/NamedImage.h"

#include <string>
#include <vector>

namespace sl
{

// The script's text for a directory holding buffers.vti (the frame's buffers, each over the pixels its heat map
// gives a value, vis/BufferHeatMap.h bufferValueMask) and, when `lightSpace` is not empty, light_space.vti. Only
// scalar buffers are listed (as the heat maps); the first shown is `visibility` when present.
std::string paraViewScript(const std::vector<NamedImage>& buffers, const std::vector<NamedImage>& lightSpace);

// The bench's open_in_paraview.py, beside bench.csv: a spreadsheet of every configuration and a chart of one column
// against another (default: RMSE against median frame GPU ms, both axes logarithmic, as speed_vs_error_*.png).
std::string benchParaViewScript();

} // namespace sl
