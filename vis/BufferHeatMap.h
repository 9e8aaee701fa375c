// How a frame's buffer is drawn as a heat map, written once for every place that draws one: `render`'s
// heatmap_<buffer>.png (output/OutputWriter.cpp) and the viewer (`shadowlab view`, src/cli/ViewerSession.cpp).
#pragma once

#include "core/NamedImage.h"
#include "vis/HeatMap.h"

namespace sl
{

// The colour map by the buffer's kind: viridis (perceptually uniform) for magnitudes, the diverging map centred
// on 0 for signed values, the categorical palette with the buffer's labels for classes. `visibility` and
// `coverage` keep the fixed scale [0, 1]; a continuous buffer whose few extreme values would flatten the scale
// (texel_ratio where a surface runs parallel to the light) is clipped at its 99th percentile over the valid pixels
// (validMask nonzero, or all when null) when the maximum lies more than 4 times as far from the minimum as the
// percentile does. The title keeps the true range either way.
HeatMapOptions bufferHeatMapOptions(const NamedImage& buffer, const ImageU8* validMask);
// The colour map alone, by the buffer's kind (also the montage's, vis/Montage.h).
ColorMapKind colorMapFor(BufferKind kind);

// The pixels a surface covers (coverage > 0.5), 1 component: the valid mask of a frame's heat maps.
ImageU8 coverageMask(const NamedImage& coverage);

} // namespace sl
