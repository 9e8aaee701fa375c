// The per-pixel preamble of the back-projection methods (gbp06, gbp07, yfgl09), in double precision: the CPU
// mirror of shaders/common/ContourKernel.glsl.
// Kernel of Eq. 1 (Yang et al. 2009) with the near plane, shrunk `kernel_refinements` times to the minimum
// depth inside it (MSSM kernels, Schwarz and Stamminger 2007); lit / umbra from the same range (Alg. 1 step 5).
#pragma once

#include "frame/ProbeRecord.h"
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

// (min, max) depth over an inclusive sample rectangle inside the map, at least 2 x 2 samples; `nodes` (null
// unless a probe records) receives the structure's nodes the query read.
using DepthRangeQuery = std::function<glm::dvec2(glm::ivec2 lo, glm::ivec2 hi, std::vector<HsmQueryNode>* nodes)>;

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
  // Light-centre status f(O): the receiver's own map position inside the reconstructed occluder. `recorder`
  // (optional): the cell's four samples (role "light centre cell"), f(O) and, when set, the whole light as a
  // ProbeLightPolygon (f(O) A of the radial integration).
  bool centreOccluded(const ShadowMapInputs& inputs, ProbeRecorder* recorder = nullptr);
  // Signed occluded light area of one contour edge (back-projection + radial integration). `recorder`
  // (optional): the edge, its back-projection (light coordinates) and that area as a ProbeContourEdge.
  double edgeArea(const glm::dvec2& a, double depthA, const glm::dvec2& b, double depthB,
    ProbeRecorder* recorder = nullptr) const;
  // The back-projection from this receiver onto the light plane (light coordinates) of a point at `depth` seen
  // at shadow-map position `texels`.
  glm::dvec2 backProjectToLight(const glm::dvec2& texels, double depth) const;
  // For a probe: every sample of `samples` (inside the map) as a ProbeTexel of `role`, with its tap comparison
  // depth and whether it occludes (the statuses marching squares reads). Changes nothing of the receiver.
  void recordSamples(const ShadowMapInputs& inputs, const TexelRectangle& samples, ProbeRecorder& recorder,
    const std::string& role) const;
};

// A kernel's texels plus one ring, clamped to the map (ContourKernel.glsl's ringed).
TexelRectangle ringed(const TexelRectangle& kernel, int mapSize);

// The `gap_filling` choices of the micropatch back-projections (gbp06, ss08).
enum class GapFilling
{
  Off,
  LeftBottom, // GBP06's rule as SS08 §3 gives it
  RightTop    // the mirror convention
};
GapFilling gapFillingOf(const ParameterValues& values);
const char* gapFillingName(GapFilling gapFilling); // the choice's name

// The back-projection techniques' receiver parameters, typed (parsed once, by from()): part of gbp06's, gbp07's and
// yfgl09's settings.
struct ContourReceiverSettings
{
  BiasSettings bias;
  bool receiverPlaneBias{};
  int kernelRefinements{}; // times Eq. 1's kernel is shrunk to the minimum occluder depth inside it

  static ContourReceiverSettings from(const ParameterValues& values);
};

// `recorder` (optional, `shadowlab probe`): the receiver (group "receiver"), each kernel of Eq. 1 with its
// search depth (ProbeKernel "blocker search"), the range queries' nodes (ProbeNode, decision "query: ..."), the
// final kernel and its ring, and the lit / umbra / penumbra decision with its depth ranges and margins.
ContourReceiver prepareContourReceiver(const ShadowMapInputs& inputs, const ContourReceiverSettings& settings,
  const DepthRangeQuery& range, int x, int y, ProbeRecorder* recorder = nullptr);
// The same with the ranges of a min-max structure built from inputs.shadowMapLinear.
ContourReceiver prepareContourReceiver(const ShadowMapInputs& inputs, const ContourReceiverSettings& settings,
  const HierarchicalShadowMap& structure, int x, int y, ProbeRecorder* recorder = nullptr);

// The `structure` a probe names an HSM / MSSM node with: "hsm" for the mip-map (and the YSM's mip-map levels),
// "mssm" for N-buffers, the YSM's MSSM part and the dual-grid MSSM.
std::string probeStructureName(const char* part);
// A probe's ProbeNode for a node a range query read, with `decision`.
ProbeNode probeNodeOf(const HsmQueryNode& node, std::string decision);
// The label of a BackprojectionClass ("lit", "penumbra over the loop budget", ...), as the buffer's categories.
std::string backprojectionClassLabel(BackprojectionClass classification);

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

// For probes of gbp06 and gbp07: the `classification` buffer's code, with its label.
void recordClassification(ProbeRecorder& recorder, BackprojectionClass classification);
// The source line of a visibility decided without integration (lit: 1, umbra: 0), or of the integration.
const char* decisionSourceOf(BackprojectionClass classification);
// The tests' ambiguity rule for gbp06 and gbp07 beyond the sample's own margins (probeOutcome): a kernel edge
// within 1e-4 texel of a texel centre, a lit / umbra test within 1e-5 (relative) of its boundary; and the loop
// cap: a pixel the GPU flagged cut short (classification OverLoopBudget) is not exact, and where only the twin's
// estimate (its loop budget) says over, the GPU's class differs from the twin's.
void noteBackprojectionAmbiguity(std::string& ambiguity, const BackprojectionPixel& pixel, const FrameResult& frame,
  glm::ivec2 at);

} // namespace sl
