// How a frame's buffer is drawn as a heat map, written once for every place that draws one: `render`'s
// heatmap_<buffer>.png (output/OutputWriter.cpp), the montages (vis/Montage.h, lessons/RunMontage.h) and the
// viewer (`shadowlab view`, src/cli/ViewerSession.cpp).
#pragma once

#include "core/NamedImage.h"
#include "vis/HeatMap.h"

#include <vector>

namespace sl
{

// The colour map by the buffer's kind: viridis (perceptually uniform) for magnitudes and bit counts, the diverging
// map centred on 0 for signed values, the categorical palette with the buffer's labels for classes. `visibility`
// and `coverage` keep the fixed scale [0, 1], a bit mask the scale [0, its bit count]; other continuous and signed
// buffers get the robust scale (HeatMapOptions::robustRange: 0.5th to 99.5th percentile of the pixels with a
// value, signed ones symmetric about 0), and the title gives their true range and the share of pixels beyond the scale.
HeatMapOptions bufferHeatMapOptions(const NamedImage& buffer, const ImageU8* validMask);
// The colour map alone, by the buffer's kind (also the montage's, vis/Montage.h).
ColorMapKind colorMapFor(BufferKind kind);

// Whether the buffer gets a heat map: 1-component buffers and bit masks, except summed-area tables (a texel of a
// wrapped prefix sum means nothing by itself; only box differences of four texels do).
bool drawsHeatMap(const NamedImage& buffer);
// The one component a heat map shows: a BitMask buffer's count of set bits over all its components (16 bits per
// component, each holding an integer 0 .. 65535), any other buffer's own values.
ImageF heatMapValues(const NamedImage& buffer);

// The pixels a surface covers (coverage > 0.5), 1 component: the valid mask of a frame's heat maps.
ImageU8 coverageMask(const NamedImage& coverage);
// The mask of `buffer`'s heat map in a frame whose buffers are `frameBuffers`: coverageMask (every pixel 1 when the
// frame has no coverage), and for a buffer declared on BufferDomain::ShadowTested the covered pixels whose
// shadow_tested is 0 set to kNotApplicablePixel. A frame without shadow_tested (a run written before it existed)
// leaves them 1.
ImageU8 bufferValueMask(const NamedImage& buffer, const std::vector<NamedImage>& frameBuffers);

} // namespace sl
