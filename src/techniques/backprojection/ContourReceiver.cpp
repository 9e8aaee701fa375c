#include "techniques/backprojection/ContourReceiver.h"

#include "core/Error.h"
#include "techniques/backprojection/ContourBackprojection.h"
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

TexelRectangle ringed(const TexelRectangle& kernel, int mapSize)
{
  return { glm::max(kernel.lo - 1, glm::ivec2(0)), glm::min(kernel.hi + 1, glm::ivec2(mapSize - 1)) };
}

ContourReceiver prepareContourReceiver(const ShadowMapInputs& inputs, const ParameterValues& values,
  const DepthRangeQuery& range, int x, int y)
{
  ContourReceiver receiver;
  receiver.lookup = prepareShadowLookup(inputs, biasSettings(values), x, y);
  if (!receiver.lookup.sample.evaluated)
  {
    return receiver;
  }
  receiver.geometry = softShadowGeometry(inputs, receiver.lookup, values.choice("receiver_plane_bias") == "on", x, y);
  receiver.bias = receiver.lookup.sample.bias;
  const SoftShadowGeometry& geometry = receiver.geometry;
  const double d = geometry.d;
  const int size = geometry.mapSize;
  const glm::dvec2 uv = receiver.lookup.sm.uvTexels;
  // Eq. 1 with the map's near plane, then with the minimum depth found inside the kernel.
  glm::dvec2 half = geometry.kernelHalfTexels(geometry.nearDepth);
  receiver.kernel = kernelRectangle(uv, half, size, &receiver.kernelEdgeMargin);
  receiver.samples = ringed(receiver.kernel, size); // the samples whose dual cells can hold edges
  glm::dvec2 depthRange = range(receiver.samples.lo, receiver.samples.hi);
  for (int refinement = 0; refinement < values.getInt("kernel_refinements"); ++refinement)
  {
    half = geometry.kernelHalfTexels(std::clamp(depthRange.x, geometry.nearDepth, d));
    receiver.kernel = kernelRectangle(uv, half, size, &receiver.kernelEdgeMargin);
    receiver.samples = ringed(receiver.kernel, size); // the samples whose dual cells can hold edges
    depthRange = range(receiver.samples.lo, receiver.samples.hi);
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
  return receiver;
}

ContourReceiver prepareContourReceiver(const ShadowMapInputs& inputs, const ParameterValues& values,
  const HierarchicalShadowMap& structure, int x, int y)
{
  return prepareContourReceiver(inputs, values, [&](glm::ivec2 lo, glm::ivec2 hi) { return structure.range(lo, hi); }, x, y);
}

void recordReceiver(const ContourReceiver& receiver, BackprojectionClass classification, BackprojectionPixel& pixel)
{
  pixel.sample = receiver.lookup.sample;
  pixel.classification = classification;
  pixel.kernelTexels = receiver.kernelTexels;
  pixel.kernelEdgeMargin = receiver.kernelEdgeMargin;
  pixel.decisionMargin = receiver.decisionMargin;
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

bool ContourReceiver::centreOccluded(const ShadowMapInputs& inputs)
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
  return insideReconstructedOccluder(occluding, glm::dvec2(cell) + 0.5, uv);
}

double ContourReceiver::edgeArea(const glm::dvec2& a, double depthA, const glm::dvec2& b, double depthB) const
{
  const double d = geometry.d;
  const glm::dvec2 backA = backProject(geometry.windowMin + a * geometry.texelTangent, depthA, receiverXy, d);
  const glm::dvec2 backB = backProject(geometry.windowMin + b * geometry.texelTangent, depthB, receiverXy, d);
  return radialEdgeArea(backA, backB, lightHalfSize);
}

} // namespace sl
