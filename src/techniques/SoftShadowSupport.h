// What the PCSS-family techniques (pcss, savsm) share: their kernel and blocker-search parameters and the
// uniforms of shaders/common/SoftShadowKernels.glsl.
#pragma once

#include "gl/ShaderLibrary.h"
#include "lightspace/LightSamples.h" // splitIntoSubLights, for the techniques with `sublights`
#include "techniques/ShadowMapReference.h"
#include "frame/TechniqueDescriptor.h"

#include <optional>

class vtkShaderProgram;
class vtkTextureObject;

namespace sl
{

struct FrameResources;

// The rotated Poisson disk of every filtering technique (pcf too): MAX_POISSON_SAMPLES for the shaders, and the
// `poissonDisk` uniform (set where the program uses it).
ShaderDefines poissonDiskDefines();
void setPoissonDiskUniform(vtkShaderProgram* program);

// The loop iterations a GL may allow one shader invocation (llvmpipe's gallivm loop limiter counts every loop
// iteration of an invocation against 65535); the techniques' parameter ranges keep their loops under it.
inline constexpr int glLoopIterationCap = 65535;
// The largest max_grid_taps: the blocker search and the filter grids, (taps^2 + taps) loop iterations each,
// must fit under glLoopIterationCap together (2 (160^2 + 160) = 51520).
inline constexpr int softShadowMaxGridTaps = 160;
static_assert(2 * (softShadowMaxGridTaps * softShadowMaxGridTaps + softShadowMaxGridTaps) < glLoopIterationCap);

// blocker_search, max_grid_taps, poisson_samples, receiver_plane_bias.
std::vector<ParameterSpec> softShadowParameters();
ParameterSpec receiverPlaneBiasParameter();
// `sublights` (TechniqueDescriptor::hasSubLights): multi-view shadow maps, Yang et al. 2009 §5.
ParameterSpec subLightsParameter();

enum class TapPattern
{
  Grid,   // every texel of the kernel (sub-sampled beyond max_grid_taps per axis)
  Poisson // rotated Poisson taps
};

// softShadowParameters(), typed (parsed once, by from()): part of the soft-shadow techniques' settings.
struct SoftShadowSettings
{
  TapPattern blockerSearch{};
  int maxGridTaps{};
  int poissonSamples{};
  bool receiverPlaneBias{};

  static SoftShadowSettings from(const ParameterValues& values);
};
// receiverPlaneBiasParameter(), typed, for the techniques that declare it alone (subLightsParameter():
// TechniqueDescriptor::subLightsPerSide).
bool receiverPlaneBiasOf(const ParameterValues& values);
TapPattern tapPatternOf(const ParameterValues& values, const std::string& name); // a {grid, poisson} choice
// lightSizeWorld, lightNearDepth, shadowTexelTangent, shadowWindowMin, poissonDisk.
void setSoftShadowUniforms(vtkShaderProgram* program, const FrameResources& frame);

// CPU mirror (double precision) of shaders/common/SoftShadowKernels.glsl at one receiver.
struct SoftShadowGeometry
{
  double lightSize = 0.0; // area light side or diameter; 0 for point and spot lights
  double nearDepth = 0.0;
  glm::dvec2 texelTangent{ 0.0 };
  glm::dvec2 windowMin{ 0.0 };
  int mapSize = 0;
  double d = 0.0; // the receiver's depth
  bool hasPlane = false;   // the receiver's tangent plane does not pass through the light (setReceiverPlane)
  bool usePlane = false;   // receiver_plane_bias and hasPlane: the taps compare against the plane
  glm::dvec3 plane{ 0.0 }; // dot(plane, X) = 1 on the receiver's tangent plane (when hasPlane)

  // kernelHalfTexels(d, planeDepth).
  glm::dvec2 kernelHalfTexels(double planeDepth) const;
  // The receiver plane's depth along a tap's ray (nullopt without a plane, or where it faces away).
  std::optional<double> planeDepth(const glm::dvec2& tapTexels) const;
  // tapComparisonDepth(tap, d, bias).
  double tapComparisonDepth(const glm::dvec2& tapTexels, double bias) const;
  // comparisonDepthRange(lo, hi, d, bias): lowest and highest comparison depth of the texels [lo, hi].
  glm::dvec2 comparisonDepthRange(glm::ivec2 lo, glm::ivec2 hi, double bias) const;
  // The tangent plane's depth along the ray through `texels`, clamped to [0.5 d, 2 d] (0.5 d where it turns away),
  // whether or not the taps use it: clampedPlaneDepth of Ss08Visibility.glsl. Needs hasPlane.
  double clampedPlaneDepth(const glm::dvec2& texels) const;
};
SoftShadowGeometry softShadowGeometry(const ShadowMapInputs& inputs, const ShadowLookup& lookup,
  bool receiverPlaneBias, int x, int y);

// kernelRectangle(): the inclusive texels whose centres lie in [uv - h, uv + h] (at least the one holding
// uv), clamped to the map. `edgeMargin` (optional) is lowered to the kernel edges' distance to texel centres.
struct TexelRectangle
{
  glm::ivec2 lo{ 0 };
  glm::ivec2 hi{ 0 };
  double area() const { return static_cast<double>(hi.x - lo.x + 1) * (hi.y - lo.y + 1); }
};
TexelRectangle kernelRectangle(const glm::dvec2& uvTexels, const glm::dvec2& halfTexels, int mapSize,
  double* edgeMargin = nullptr);

} // namespace sl
