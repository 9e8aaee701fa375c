#include "techniques/SoftShadowSupport.h"

#include "passes/FrameResources.h"
#include "techniques/SamplingPatterns.h"

#include <vtkShaderProgram.h>

namespace sl
{

std::vector<ParameterSpec> softShadowParameters()
{
  return {
    { "blocker_search", 0, 0, 1, "", "grid: every texel of the search kernel w_i (brute force); poisson: rotated Poisson taps", { "grid", "poisson" }, true },
    { "max_grid_taps", 32, 1, 256, "taps per axis", "grid kernels wider than this are sampled on a regular sub-grid of this size (the paper's 30x30 banding limit)", {}, true },
    { "poisson_samples", 32, 1, maxPoissonSamples, "taps", "taps per step for the poisson variants", {}, true },
    { "receiver_plane_bias", 1, 0, 1, "", "on: each tap compares against the receiver's tangent plane (Isidoro 2006), so sloped receivers do not shadow themselves across wide kernels; off: one depth per pixel", { "off", "on" }, true },
  };
}

void setSoftShadowUniforms(vtkShaderProgram* program, const FrameResources& frame)
{
  const LightView& view = frame.lightView;
  const double lightSize = frame.light->type == LightType::Area ? frame.light->size : 0.0;
  program->SetUniformf("lightSizeWorld", static_cast<float>(lightSize));
  program->SetUniformf("lightNearDepth", static_cast<float>(view.nearDepth));
  const float texelTangent[2] = { static_cast<float>((view.window.y - view.window.x) / view.resolution),
    static_cast<float>((view.window.w - view.window.z) / view.resolution) };
  program->SetUniform2f("shadowTexelTangent", texelTangent);
  const float windowMin[2] = { static_cast<float>(view.window.x), static_cast<float>(view.window.z) };
  program->SetUniform2f("shadowWindowMin", windowMin);
  setPoissonDiskUniform(program);
}

ShaderDefines poissonDiskDefines()
{
  return { { "MAX_POISSON_SAMPLES", std::to_string(maxPoissonSamples) } };
}

void setPoissonDiskUniform(vtkShaderProgram* program)
{
  if (program->IsUniformUsed("poissonDisk"))
  {
    program->SetUniform2fv("poissonDisk", maxPoissonSamples, poissonDiskFloats().data());
  }
}

} // namespace sl
