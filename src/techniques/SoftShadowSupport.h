// What the PCSS-family techniques (pcss, savsm) share: their kernel and blocker-search parameters and the
// uniforms of shaders/common/SoftShadowKernels.glsl.
#pragma once

#include "techniques/Technique.h"

class vtkShaderProgram;

namespace sl
{

struct FrameResources;

// blocker_search, max_grid_taps, poisson_samples, receiver_plane_bias.
std::vector<ParameterSpec> softShadowParameters();
// lightSizeWorld, lightNearDepth, shadowTexelTangent, shadowWindowMin, poissonDisk.
void setSoftShadowUniforms(vtkShaderProgram* program, const FrameResources& frame);

} // namespace sl
