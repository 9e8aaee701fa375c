// The per-pixel preamble of the back-projection methods (gbp06, gbp07, yfgl09), in double precision: the CPU
// mirror of shaders/common/ContourKernel.glsl.
// Kernel of Eq. 1 (Yang et al. 2009) with the near plane, shrunk `kernel_refinements` times to the minimum
// depth inside it (MSSM kernels, Schwarz and Stamminger 2007); lit / umbra from the same range (Alg. 1 step 5).
#pragma once

#include "lightspace/HierarchicalShadowMap.h"
#include "techniques/ShadowMapReference.h"
#include "techniques/SoftShadowSupport.h"
#include "frame/TechniqueDescriptor.h"

#include <glm/glm.hpp>

#include <array>
#include <functional>
#include <string>
#include <vector>

namespace sl
{

// How a pixel was decided: the CPU twins' classification and, as categories, gbp06's and gbp07's
// `classification` buffer (backprojectionClassificationBuffer); the codes of the kernel's decision too
// (contourKernelShaderConstants). The one declaration of these codes: the shaders' are generated from it.
enum class BackprojectionClass
{
  NotTested = 0,
  Lit = 1,
  Umbra = 2,
  Penumbra = 3,
  OverLoopBudget = 4 // penumbra past the technique's loop budget (gbp06LoopBudget, gbp07LoopBudgetCells)
};

// The `classification` buffer of gbp06 and gbp07: BackprojectionClass as categories, code = the enumerator's
// value, identifier = its name in upper case (the shaders write CLASSIFICATION_OVER_LOOP_BUDGET, ...).
BufferSpec backprojectionClassificationBuffer(const std::string& doc, SubLightCombine combine);
// The kernel decisions of shaders/common/ContourKernel.glsl, KERNEL_LIT, KERNEL_UMBRA and KERNEL_PENUMBRA: the
// BackprojectionClass codes ContourReceiver::classification takes. Shader constants of every technique whose
// shader includes the snippet.
std::vector<ShaderConstant> contourKernelShaderConstants();

// (min, max) depth over an inclusive sample rectangle inside the map, at least 2 x 2 samples.
using DepthRangeQuery = std::function<glm::dvec2(glm::ivec2 lo, glm::ivec2 hi)>;

struct ContourReceiver
{
  ShadowLookup lookup;
  SoftShadowGeometry geometry;
  double bias = 0.0;
  TexelRectangle kernel;  // the texels of Eq. 1's kernel
  TexelRectangle samples; // plus one ring, clamped to the map: the corners of the kernel's dual cells
  double kernelTexels = 0.0; // 2 max(half extent)
  BackprojectionClass classification = BackprojectionClass::NotTested;
  double kernelEdgeMargin = 1e300;
  double decisionMargin = 1e300; // the lit / umbra tests, relative to d
  glm::dvec2 receiverXy{ 0.0 }; // light view x, y of the receiver
  double lightHalfSize = 0.0;

  // Dual cells examined: [kernel.lo - 1, kernel.hi] per axis.
  glm::ivec2 firstCell() const { return kernel.lo - 1; }
  glm::ivec2 lastCell() const { return kernel.hi; }
  // Whether the sample (i, j) (possibly outside the map, which never occludes) hides the light centre from
  // this receiver, and its depth (0 outside). Records the comparison's margin in lookup.sample.
  bool occludes(const ShadowMapInputs& inputs, glm::ivec2 sample, double& depth);
  // Light-centre status f(O): the receiver's own map position inside the reconstructed occluder.
  bool centreOccluded(const ShadowMapInputs& inputs);
  // Signed occluded light area of one contour edge (back-projection + radial integration).
  double edgeArea(const glm::dvec2& a, double depthA, const glm::dvec2& b, double depthB) const;
};

// A kernel's texels plus one ring, clamped to the map (ContourKernel.glsl's ringed).
TexelRectangle ringed(const TexelRectangle& kernel, int mapSize);

ContourReceiver prepareContourReceiver(const ShadowMapInputs& inputs, const ParameterValues& values,
  const DepthRangeQuery& range, int x, int y);
// The same with the ranges of a min-max structure built from inputs.shadowMapLinear.
ContourReceiver prepareContourReceiver(const ShadowMapInputs& inputs, const ParameterValues& values,
  const HierarchicalShadowMap& structure, int x, int y);

// What the CPU twins of gbp06 and gbp07 report for every pixel: the preamble's outcome and margins.
struct BackprojectionPixel
{
  ReferenceSample sample;
  BackprojectionClass classification = BackprojectionClass::NotTested;
  double kernelTexels = 0.0;
  double kernelEdgeMargin = 1e300;
  double decisionMargin = 1e300; // the lit / umbra tests against the structure's range, relative to d
};
// Copies the receiver's sample, kernel width and margins into `pixel`, with its final class.
void recordReceiver(const ContourReceiver& receiver, BackprojectionClass classification, BackprojectionPixel& pixel);

} // namespace sl
