// The shadow map's sampling error at every visible receiver (survey §3), published beside the technique's buffers
// by every frame that renders one shadow map: texel_ratio_s and texel_ratio_t (Eq. 2 per map axis), and Eq. 1's
// perspective_factor and projection_factor (ShadowMapMath.h samplingError). Evaluated in double from the frame's
// G-buffer and its light matrix, so a warped or partitioned map's matrix gives its own error exactly.
#pragma once

#include "core/NamedImage.h"
#include "frame/TechniqueDescriptor.h"

#include <string>
#include <vector>

namespace sl
{

struct FrameResources;
struct FrameResult;

// The four buffers' declarations (name, unit, meaning), as `list` and the docs show them.
const std::vector<BufferSpec>& samplingErrorBufferSpecs();

// The four buffers for the frame's light view, from result's position, normal, coverage and receives_shadows
// buffers; 0 at pixels the map does not test (uncovered, not receiving, out of the light's reach, or grazing).
// Empty for a frame with sub-lights (one light view each: their errors differ). With views that partition the pixels
// (FrameResources::partitions), each pixel's error is that of the view `viewIndex` names (its primary view); null
// otherwise.
std::vector<NamedImage> samplingErrorBuffers(
  const FrameResources& frame, const FrameResult& result, const ImageF* viewIndex = nullptr);

} // namespace sl
