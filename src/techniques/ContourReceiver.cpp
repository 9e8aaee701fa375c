#include "techniques/ContourReceiver.h"

#include "core/Error.h"
#include "techniques/ProbeSupport.h"
#include "techniques/ContourBackprojection.h"
#include "techniques/ShadowMapParameters.h"

#include <algorithm>
#include <cmath>
#include <iterator>

namespace sl
{

namespace
{

// In code order (checked where it is read).
const Category<BackprojectionClass> backprojectionCategories[] = {
  { BackprojectionClass::NotTested, "NOT_TESTED", "not tested" },
  { BackprojectionClass::Lit, "LIT", "lit" },
  { BackprojectionClass::Umbra, "UMBRA", "umbra" },
  { BackprojectionClass::Penumbra, "PENUMBRA", "penumbra" },
  // A pixel a GL's loop cap cut short (gbp06's and gbp07's shaders detect it, so GLs without a cap flag
  // nothing): counted as cut short. The twins can only estimate it, by their loop budgets.
  { BackprojectionClass::OverLoopBudget, "OVER_LOOP_BUDGET", "penumbra over the loop budget", true },
};

} // namespace

BufferSpec backprojectionClassificationBuffer(const std::string& doc, SubLightCombine combine)
{
  return categoricalBuffer("classification", doc, backprojectionCategories, combine);
}

std::vector<ShaderConstant> contourKernelShaderConstants()
{
  const auto code = [](BackprojectionClass value) { return static_cast<int>(value); };
  return {
    { "KERNEL_LIT", code(BackprojectionClass::Lit), "ContourKernel.decision: no sample of the ring can occlude" },
    { "KERNEL_UMBRA", code(BackprojectionClass::Umbra), "ContourKernel.decision: every sample of the ring occludes" },
    { "KERNEL_PENUMBRA", code(BackprojectionClass::Penumbra), "ContourKernel.decision: neither; the technique integrates" },
  };
}

std::string backprojectionClassLabel(BackprojectionClass classification)
{
  const std::size_t code = static_cast<std::size_t>(classification);
  SL_CHECK(code < std::size(backprojectionCategories));
  return backprojectionCategories[code].label;
}

std::string probeStructureName(const char* part)
{
  return std::string(part) == "mip-map" ? "hsm" : "mssm";
}

ProbeNode probeNodeOf(const HsmQueryNode& node, std::string decision)
{
  return { probeStructureName(node.part), node.level, node.lo, node.hi, node.range.x, node.range.y,
    std::move(decision) };
}

namespace
{

// A texel rectangle as a ProbeKernel (texel i spans [i, i + 1]).
ProbeKernel probeKernelOf(const TexelRectangle& rectangle, std::string role, std::string label, std::string source)
{
  return { std::move(role), glm::dvec2(rectangle.lo), glm::dvec2(rectangle.hi + 1), std::move(label), std::move(source) };
}

const char* const eq1Source = "Eq. 1, YFGL09 (Yang et al. 2009)";
const char* const mssmKernelSource = "Eq. 1 with z_occ_min, YFGL09; MSSM range query (Schwarz & Stamminger 2007)";
const char* const decisionSource = "Alg. 1 step 5, YFGL09: remove fully lit or fully occluded pixels [GBP06]";

} // namespace

TexelRectangle ringed(const TexelRectangle& kernel, int mapSize)
{
  return { glm::max(kernel.lo - 1, glm::ivec2(0)), glm::min(kernel.hi + 1, glm::ivec2(mapSize - 1)) };
}

GapFilling gapFillingOf(const ParameterValues& values)
{
  return choiceOf<GapFilling>(values, "gap_filling",
    { { "off", GapFilling::Off }, { "left_bottom", GapFilling::LeftBottom }, { "right_top", GapFilling::RightTop } });
}

const char* gapFillingName(GapFilling gapFilling)
{
  return gapFilling == GapFilling::LeftBottom ? "left_bottom" : gapFilling == GapFilling::RightTop ? "right_top" : "off";
}

ContourReceiverSettings ContourReceiverSettings::from(const ParameterValues& values)
{
  ContourReceiverSettings settings;
  settings.bias = biasSettings(values);
  settings.receiverPlaneBias = receiverPlaneBiasOf(values);
  settings.kernelRefinements = values.getInt("kernel_refinements");
  return settings;
}

ContourReceiver prepareContourReceiver(const ShadowMapInputs& inputs, const ContourReceiverSettings& settings,
  const DepthRangeQuery& range, int x, int y, ProbeRecorder* recorder)
{
  ContourReceiver receiver;
  receiver.lookup = prepareShadowLookup(inputs, settings.bias, x, y, recorder);
  if (!receiver.lookup.sample.evaluated)
  {
    return receiver;
  }
  // A probe's view of each kernel: its search depth, Eq. 1's half extent and texels, and the range query's
  // nodes, recorded when the next query shows what the range was used for.
  std::vector<HsmQueryNode> queryNodes;
  std::vector<HsmQueryNode>* const nodes = recorder ? &queryNodes : nullptr;
  int iteration = 0;
  const auto recordKernel = [&](double planeDepth, const glm::dvec2& half) {
    if (!recorder)
    {
      return;
    }
    recorder->beginGroup(iteration == 0 ? std::string("kernel at the near plane (Eq. 1)")
                                        : "kernel refinement " + std::to_string(iteration) + " (Eq. 1 with z_occ_min)");
    recorder->quantity("search_depth", planeDepth, "linear depth",
      iteration == 0 ? "Eq. 1, YFGL09: the shadow map's near plane" : mssmKernelSource);
    recorder->quantity("kernel_half_texels", half, "texels", eq1Source);
    recorder->quantity("kernel_half_world", 0.5 * receiver.geometry.lightSize * (receiver.geometry.d - planeDepth) / receiver.geometry.d,
      "world units", "Eq. 1, YFGL09: the light's cone from the receiver cut at the search depth, w_l (d - z) / 2d");
    recorder->quantity("searched_samples", glm::dvec2(receiver.samples.hi - receiver.samples.lo + 1), "texels",
      "ShadowLab: the kernel's texels plus one ring (ContourKernel.glsl ringed)");
    recorder->kernel(probeKernelOf(receiver.kernel, "blocker search",
      iteration == 0 ? "near plane" : "refinement " + std::to_string(iteration), eq1Source));
  };
  const auto recordQuery = [&](const glm::dvec2& depthRange, const std::string& decision) {
    if (!recorder)
    {
      return;
    }
    recorder->quantity("occluder_depth_range", depthRange, "linear depth",
      "MSSM / HSM range over the searched samples (Schwarz & Stamminger 2007)");
    recorder->quantity("range_query_nodes", static_cast<double>(queryNodes.size()), "count",
      "ShadowLab: nodes the range query read (HierarchicalShadowMap::range)");
    for (const HsmQueryNode& node : queryNodes)
    {
      recorder->node(probeNodeOf(node, decision));
    }
    queryNodes.clear();
  };
  receiver.geometry = softShadowGeometry(inputs, receiver.lookup, settings.receiverPlaneBias, x, y);
  receiver.bias = receiver.lookup.sample.bias;
  const SoftShadowGeometry& geometry = receiver.geometry;
  const double d = geometry.d;
  const int size = geometry.mapSize;
  const glm::dvec2 uv = receiver.lookup.sm.uvTexels;
  // Eq. 1 with the map's near plane, then with the minimum depth found inside the kernel.
  double planeDepth = geometry.nearDepth;
  glm::dvec2 half = geometry.kernelHalfTexels(planeDepth);
  receiver.kernel = kernelRectangle(uv, half, size, &receiver.kernelEdgeMargin);
  receiver.samples = ringed(receiver.kernel, size); // the samples whose dual cells can hold edges
  recordKernel(planeDepth, half);
  glm::dvec2 depthRange = range(receiver.samples.lo, receiver.samples.hi, nodes);
  for (int refinement = 0; refinement < settings.kernelRefinements; ++refinement)
  {
    recordQuery(depthRange, "query: z_occ_min for refinement " + std::to_string(refinement + 1));
    ++iteration;
    planeDepth = std::clamp(depthRange.x, geometry.nearDepth, d);
    half = geometry.kernelHalfTexels(planeDepth);
    receiver.kernel = kernelRectangle(uv, half, size, &receiver.kernelEdgeMargin);
    receiver.samples = ringed(receiver.kernel, size); // the samples whose dual cells can hold edges
    recordKernel(planeDepth, half);
    depthRange = range(receiver.samples.lo, receiver.samples.hi, nodes);
  }
  receiver.kernelTexels = 2.0 * std::max(half.x, half.y);
  receiver.lightHalfSize = 0.5 * geometry.lightSize;
  receiver.receiverXy = (geometry.windowMin + uv * geometry.texelTangent) * d;
  const glm::dvec2 comparison = geometry.comparisonDepthRange(receiver.samples.lo, receiver.samples.hi, receiver.bias);
  receiver.decisionMargin =
    std::min(std::abs(depthRange.x - comparison.y), std::abs(depthRange.y - comparison.x)) / d;
  // Umbra only when the ring lies inside the map: beyond it the contour method sees non-occluders.
  const bool ringInsideMap = receiver.samples.lo == receiver.kernel.lo - 1 && receiver.samples.hi == receiver.kernel.hi + 1;
  if (depthRange.x >= comparison.y)
  {
    receiver.classification = BackprojectionClass::Lit;
    receiver.lookup.sample.visibility = 1.0;
  }
  else if (ringInsideMap && depthRange.y < comparison.x)
  {
    receiver.classification = BackprojectionClass::Umbra;
    receiver.lookup.sample.visibility = 0.0;
  }
  else
  {
    receiver.classification = BackprojectionClass::Penumbra;
  }
  if (recorder)
  {
    const std::string label = backprojectionClassLabel(receiver.classification);
    recordQuery(depthRange, "query: decides " + label);
    recorder->beginGroup("lit / umbra / penumbra (Alg. 1 step 5)");
    recorder->quantity("kernel_texels", receiver.kernelTexels, "texels", eq1Source);
    recorder->quantity("kernel_world_size", geometry.lightSize * (d - planeDepth) / d, "world units",
      "Eq. 1, YFGL09: the light's cone from the receiver cut at the last search depth, w_l (d - z) / d");
    recorder->quantity("comparison_depth_range", comparison, "linear depth",
      "ShadowLab: the receiver's comparison depths (receiver plane, bias) over the searched samples");
    recorder->quantity("ring_inside_map", ringInsideMap ? 1.0 : 0.0, "",
      "ShadowLab: umbra only when the ring lies inside the map (outside samples never occlude)");
    recorder->category("kernel_decision", label, decisionSource);
    recorder->quantity("decision_margin", receiver.decisionMargin, "relative depth",
      "ShadowLab: distance of the lit / umbra tests to their boundary, / d (tests: ambiguous under 1e-5)");
    recorder->quantity("kernel_edge_margin", receiver.kernelEdgeMargin, "texels",
      "ShadowLab: kernel edges' distance to texel centres (tests: ambiguous under 1e-4)");
    recorder->quantity("light_half_size", receiver.lightHalfSize, "world units", "GBP07: the square light [-h, h]^2");
    recorder->quantity("receiver_light_xy", receiver.receiverXy, "world units",
      "GBP07: the receiver in light coordinates (light view x, y)");
    recorder->kernel(probeKernelOf(receiver.kernel, "kernel", label, eq1Source));
    recorder->kernel(probeKernelOf(receiver.samples, "searched samples", "kernel + one ring",
      "ShadowLab: the samples whose dual cells can hold edges (ContourKernel.glsl ringed)"));
  }
  return receiver;
}

ContourReceiver prepareContourReceiver(const ShadowMapInputs& inputs, const ContourReceiverSettings& settings,
  const HierarchicalShadowMap& structure, int x, int y, ProbeRecorder* recorder)
{
  return prepareContourReceiver(inputs, settings,
    [&](glm::ivec2 lo, glm::ivec2 hi, std::vector<HsmQueryNode>* nodes) { return structure.range(lo, hi, nullptr, nodes); },
    x, y, recorder);
}

void recordReceiver(const ContourReceiver& receiver, BackprojectionClass classification, BackprojectionPixel& pixel)
{
  pixel.sample = receiver.lookup.sample;
  pixel.classification = classification;
  pixel.kernelTexels = receiver.kernelTexels;
  pixel.kernelEdgeMargin = receiver.kernelEdgeMargin;
  pixel.decisionMargin = receiver.decisionMargin;
}

void recordClassification(ProbeRecorder& recorder, BackprojectionClass classification)
{
  recorder.category("classification", static_cast<int>(classification), backprojectionClassLabel(classification),
    "Alg. 1 step 5, YFGL09 (lit / umbra / penumbra); ShadowLab: the classification buffer's code (BackprojectionClass)");
}

const char* decisionSourceOf(BackprojectionClass classification)
{
  return classification == BackprojectionClass::Lit ? "Alg. 1 step 5, YFGL09: no searched sample can occlude, V = 1"
    : classification == BackprojectionClass::Umbra ? "Alg. 1 step 5, YFGL09: every searched sample occludes, V = 0"
    : "ShadowLab: not tested (facing away or outside the light's reach)";
}

void noteBackprojectionAmbiguity(std::string& ambiguity, const BackprojectionPixel& pixel, const FrameResult& frame,
  glm::ivec2 at)
{
  if (!pixel.sample.evaluated)
  {
    return;
  }
  noteAmbiguity(ambiguity, "kernel edge from a texel centre (texels)", pixel.kernelEdgeMargin, 1e-4);
  noteAmbiguity(ambiguity, "lit / umbra test from its boundary (relative)", pixel.decisionMargin, 1e-5);
  const auto overBudget = static_cast<double>(BackprojectionClass::OverLoopBudget);
  const bool gpuCut = bufferValue(frame, "classification", at) == overBudget;
  if (gpuCut)
  {
    ambiguity += std::string(ambiguity.empty() ? "" : ", ") +
      "the GPU's loop cap cut this pixel short (classification " + backprojectionClassLabel(BackprojectionClass::OverLoopBudget) +
      "): its visibility is not exact";
  }
  else if (pixel.classification == BackprojectionClass::OverLoopBudget)
  {
    ambiguity += std::string(ambiguity.empty() ? "" : ", ") +
      "the twin's loop-budget estimate says over budget where the GPU finished: the classification differs, "
      "the visibility is exact";
  }
}

bool ContourReceiver::occludes(const ShadowMapInputs& inputs, glm::ivec2 sample, double& depth)
{
  const int size = geometry.mapSize;
  depth = 0.0;
  if (sample.x < 0 || sample.y < 0 || sample.x >= size || sample.y >= size)
  {
    return false;
  }
  depth = inputs.shadowMapLinear.at(sample.x, sample.y);
  const double compared = geometry.tapComparisonDepth(glm::dvec2(sample) + 0.5, bias);
  lookup.sample.noteDepthComparison(compared, depth);
  return depth < compared;
}

bool ContourReceiver::centreOccluded(const ShadowMapInputs& inputs, ProbeRecorder* recorder)
{
  const glm::dvec2 uv = lookup.sm.uvTexels;
  const glm::ivec2 cell(static_cast<int>(std::floor(uv.x - 0.5)), static_cast<int>(std::floor(uv.y - 0.5)));
  const std::array<glm::ivec2, 4> offsets = { glm::ivec2(0, 0), glm::ivec2(1, 0), glm::ivec2(1, 1), glm::ivec2(0, 1) };
  std::array<bool, 4> occluding{};
  for (std::size_t k = 0; k < 4; ++k)
  {
    double depth = 0.0;
    occluding[k] = occludes(inputs, cell + offsets[k], depth);
  }
  const bool inside = insideReconstructedOccluder(occluding, glm::dvec2(cell) + 0.5, uv);
  if (recorder)
  {
    recordSamples(inputs, { glm::max(cell, glm::ivec2(0)), glm::min(cell + 1, glm::ivec2(geometry.mapSize - 1)) },
      *recorder, "light centre cell");
    recorder->quantity("light_centre_occluded", inside ? 1.0 : 0.0, "",
      "GBP07 radial integration: f(O), the receiver's own map position inside the reconstructed occluder");
    if (inside)
    {
      const double h = lightHalfSize;
      recorder->lightPolygon({ "light centre occluded: f(O) A", { { -h, -h }, { h, -h }, { h, h }, { -h, h } }, 4.0 * h * h });
    }
  }
  return inside;
}

double ContourReceiver::edgeArea(const glm::dvec2& a, double depthA, const glm::dvec2& b, double depthB,
  ProbeRecorder* recorder) const
{
  const glm::dvec2 backA = backProjectToLight(a, depthA);
  const glm::dvec2 backB = backProjectToLight(b, depthB);
  const double area = radialEdgeArea(backA, backB, lightHalfSize);
  if (recorder)
  {
    recorder->contourEdge({ a, b, backA, backB, area });
  }
  return area;
}

glm::dvec2 ContourReceiver::backProjectToLight(const glm::dvec2& texels, double depth) const
{
  return backProject(geometry.windowMin + texels * geometry.texelTangent, depth, receiverXy, geometry.d);
}

void ContourReceiver::recordSamples(const ShadowMapInputs& inputs, const TexelRectangle& samples,
  ProbeRecorder& recorder, const std::string& role) const
{
  for (int j = samples.lo.y; j <= samples.hi.y; ++j)
  {
    for (int i = samples.lo.x; i <= samples.hi.x; ++i)
    {
      const double stored = inputs.shadowMapLinear.at(i, j);
      const double compared = geometry.tapComparisonDepth(glm::dvec2(i, j) + 0.5, bias);
      recorder.texel({ { i, j }, role, stored, compared, stored < compared, 1.0 });
    }
  }
}

} // namespace sl
