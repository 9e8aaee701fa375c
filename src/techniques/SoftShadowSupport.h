// What the PCSS-family techniques (pcss, savsm) share: their kernel and blocker-search parameters and the
// uniforms of shaders/common/SoftShadowKernels.glsl.
#pragma once

#include "gl/ShaderLibrary.h"
#include "techniques/Technique.h"

class vtkShaderProgram;

namespace sl
{

struct FrameResources;

// The rotated Poisson disk of every filtering technique (pcf too): MAX_POISSON_SAMPLES for the shaders, and the
// `poissonDisk` uniform (set where the program uses it).
ShaderDefines poissonDiskDefines();
void setPoissonDiskUniform(vtkShaderProgram* program);

// blocker_search, max_grid_taps, poisson_samples, receiver_plane_bias.
std::vector<ParameterSpec> softShadowParameters();
// lightSizeWorld, lightNearDepth, shadowTexelTangent, shadowWindowMin, poissonDisk.
void setSoftShadowUniforms(vtkShaderProgram* program, const FrameResources& frame);

} // namespace sl
