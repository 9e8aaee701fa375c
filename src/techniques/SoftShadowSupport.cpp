#include "techniques/SoftShadowSupport.h"

#include "core/Error.h"
#include "passes/FrameResources.h"
#include "passes/PassUtilities.h"
#include "techniques/SamplingPatterns.h"

#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>

#include <algorithm>

namespace sl
{

std::vector<ParameterSpec> softShadowParameters()
{
  return {
    { "blocker_search", 0, 0, 1, "", "grid: every texel of the search kernel w_i (brute force); poisson: rotated Poisson taps", { "grid", "poisson" }, true },
    // At most 160: the blocker search and the filter, two grids of max_grid_taps^2 taps plus a row iteration
    // each, stay at 2 (160^2 + 160) = 51520 loop iterations, under the 65535 that llvmpipe allows one invocation
    // (it cut 256 x 256 grids short at 2048^2 maps without a trace, issue 13); 160 still covers every texel of
    // the widest kernels the 512^2 benches reach (147 texels).
    { "max_grid_taps", 32, 1, softShadowMaxGridTaps, "taps per axis", "grid kernels wider than this are sampled on a regular sub-grid of this size (the paper's 30x30 banding limit); at most 160, so that both grids stay under GLs' caps on loop iterations (llvmpipe: 65535)", {}, true },
    { "poisson_samples", 32, 1, maxPoissonSamples, "taps", "taps per step for the poisson variants", {}, true },
    receiverPlaneBiasParameter(),
  };
}

ParameterSpec receiverPlaneBiasParameter()
{
  return { "receiver_plane_bias", 1, 0, 1, "", "on: each tap compares against the receiver's tangent plane (Isidoro 2006), so sloped receivers do not shadow themselves across wide kernels; off: one depth per pixel", { "off", "on" }, true };
}

ParameterSpec subLightsParameter()
{
  return { "sublights", 1, 1, 4, "per side", "multi-view shadow maps (Yang et al. 2009 §5): the light split into S x S sub-lights, each with its own focused shadow map and MSSM, visibilities averaged", {}, true };
}

TapPattern tapPatternOf(const ParameterValues& values, const std::string& name)
{
  return choiceOf<TapPattern>(values, name, { { "grid", TapPattern::Grid }, { "poisson", TapPattern::Poisson } });
}

bool receiverPlaneBiasOf(const ParameterValues& values)
{
  return values.choice("receiver_plane_bias") == "on";
}

SoftShadowSettings SoftShadowSettings::from(const ParameterValues& values)
{
  SoftShadowSettings settings;
  settings.blockerSearch = tapPatternOf(values, "blocker_search");
  settings.maxGridTaps = values.getInt("max_grid_taps");
  settings.poissonSamples = values.getInt("poisson_samples");
  settings.receiverPlaneBias = receiverPlaneBiasOf(values);
  return settings;
}

glm::dvec2 SoftShadowGeometry::kernelHalfTexels(double planeDepthValue) const
{
  const double halfTangent = 0.5 * lightSize * (d - planeDepthValue) / (planeDepthValue * d);
  return glm::dvec2(std::max(halfTangent, 0.0)) / texelTangent;
}

std::optional<double> SoftShadowGeometry::planeDepth(const glm::dvec2& tapTexels) const
{
  if (!usePlane)
  {
    return std::nullopt;
  }
  const glm::dvec3 ray(windowMin + tapTexels * texelTangent, -1.0);
  const double depth = 1.0 / glm::dot(plane, ray);
  return depth > 0.0 ? std::optional<double>(depth) : std::nullopt;
}

double SoftShadowGeometry::tapComparisonDepth(const glm::dvec2& tapTexels, double bias) const
{
  const std::optional<double> depth = planeDepth(tapTexels);
  return depth ? std::clamp(*depth, 0.5 * d, 2.0 * d) - bias : d - bias;
}

glm::dvec2 SoftShadowGeometry::comparisonDepthRange(glm::ivec2 lo, glm::ivec2 hi, double bias) const
{
  // 1 / (linear in the tap) per receiver plane: extremes at the rectangle's corners, unless the plane turns
  // away inside it (then the clamp range).
  glm::dvec2 range(d - bias);
  if (usePlane)
  {
    for (int corner = 0; corner < 4; ++corner)
    {
      const glm::dvec2 position((corner & 1) == 0 ? lo.x : hi.x + 1, (corner >> 1) == 0 ? lo.y : hi.y + 1);
      const std::optional<double> depth = planeDepth(position);
      if (!depth)
      {
        return glm::dvec2(0.5 * d, 2.0 * d) - bias;
      }
      const double comparison = std::clamp(*depth, 0.5 * d, 2.0 * d) - bias;
      range = glm::dvec2(std::min(range.x, comparison), std::max(range.y, comparison));
    }
  }
  return range;
}

double SoftShadowGeometry::clampedPlaneDepth(const glm::dvec2& texels) const
{
  const glm::dvec3 ray(windowMin + texels * texelTangent, -1.0);
  const double depth = 1.0 / glm::dot(plane, ray);
  return depth > 0.0 ? std::clamp(depth, 0.5 * d, 2.0 * d) : 0.5 * d;
}

SoftShadowGeometry softShadowGeometry(const ShadowMapInputs& inputs, const ShadowLookup& lookup,
  bool receiverPlaneBias, int x, int y)
{
  const LightView& view = inputs.lightView;
  SoftShadowGeometry geometry;
  geometry.lightSize = inputs.light->type == LightType::Area ? inputs.light->size : 0.0;
  geometry.nearDepth = view.nearDepth;
  geometry.texelTangent = glm::dvec2((view.window.y - view.window.x) / view.resolution, (view.window.w - view.window.z) / view.resolution);
  geometry.windowMin = glm::dvec2(view.window.x, view.window.z);
  geometry.mapSize = inputs.shadowMapLinear.width;
  geometry.d = lookup.sm.depthLin;
  // setReceiverPlane(): the tangent plane in light view space, scaled so dot(plane, X) = 1 on it.
  const glm::dvec3 pWs(inputs.position.at(x, y, 0), inputs.position.at(x, y, 1), inputs.position.at(x, y, 2));
  const glm::dvec3 nWs(inputs.normal.at(x, y, 0), inputs.normal.at(x, y, 1), inputs.normal.at(x, y, 2));
  const glm::dvec3 nLs = glm::dmat3(view.viewFromWorld) * nWs;
  const glm::dvec3 pLs = glm::dvec3(view.viewFromWorld * glm::dvec4(pWs, 1.0));
  const double planeOffset = glm::dot(nLs, pLs);
  geometry.hasPlane = std::abs(planeOffset) > 1e-12;
  geometry.usePlane = receiverPlaneBias && geometry.hasPlane;
  geometry.plane = geometry.hasPlane ? nLs / planeOffset : glm::dvec3(0.0);
  return geometry;
}

TexelRectangle kernelRectangle(const glm::dvec2& uvTexels, const glm::dvec2& halfTexels, int mapSize, double* edgeMargin)
{
  TexelRectangle rectangle;
  for (int axis = 0; axis < 2; ++axis)
  {
    const double low = uvTexels[axis] - halfTexels[axis] - 0.5;
    const double high = uvTexels[axis] + halfTexels[axis] - 0.5;
    if (edgeMargin)
    {
      *edgeMargin = std::min({ *edgeMargin, std::abs(low - std::round(low)), std::abs(high - std::round(high)) });
    }
    double first = std::ceil(low);
    double last = std::floor(high);
    if (last < first)
    {
      first = std::floor(uvTexels[axis]);
      last = first;
    }
    rectangle.lo[axis] = static_cast<int>(std::clamp(first, 0.0, mapSize - 1.0));
    rectangle.hi[axis] = static_cast<int>(std::clamp(last, 0.0, mapSize - 1.0));
  }
  return rectangle;
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
