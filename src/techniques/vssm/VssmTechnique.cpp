#include "techniques/vssm/VssmTechnique.h"

#include "lightspace/hsm/HsmStructure.h"
#include "lightspace/sat/SatStructure.h"
#include "lightspace/shadowmap/ShadowMapStructure.h"

#include "core/Error.h"
#include "techniques/SamplingPatterns.h"
#include "techniques/ShadowMapParameters.h"
#include "techniques/SoftShadowSupport.h"
#include "techniques/vssm/vtkSLVssmPass.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <iterator>

namespace sl
{

namespace
{

// In code order (checked below).
const Category<VssmClass> vssmCategories[] = {
  { VssmClass::NotTested, "NOT_TESTED", "not tested" },
  { VssmClass::Lit, "LIT", "lit" },
  { VssmClass::Umbra, "UMBRA", "umbra" },
  { VssmClass::Penumbra, "PENUMBRA", "penumbra" },
  { VssmClass::Contact, "CONTACT", "contact" },
};

BufferSpec classificationBuffer()
{
  return categoricalBuffer("classification", "how the pixel was decided", vssmCategories);
}

} // namespace

TechniqueDescriptor vssmTechnique()
{
  TechniqueDescriptor descriptor;
  descriptor.name = "vssm";
  descriptor.title = "Variance soft shadow mapping";
  descriptor.paper = "Yang et al. 2010 (VSSM), Alg. 1 and 2, Eq. 1-5, §5-6";
  descriptor.parameters = shadowMapParameters();
  descriptor.parameters.push_back(receiverPlaneBiasParameter());
  const std::vector<std::string> schemes = { "none", "uniform", "adaptive" };
  descriptor.parameters.insert(descriptor.parameters.end(), {
    { "sat_precision", 1, 0, 1, "", "float_centred: float SAT of z - (near + far) / 2; int32: fixed point, exact box sums (§6.4)", { "float_centred", "int32" }, true },
    { "hsm", 0, 0, 2, "", "min-max hierarchical shadow map: mipmap (conservative ranges, the paper's choice), nbuffers (exact ranges, L times the memory) (§6.1) or ysm (the mip-map plus an MSSM of its ~256^2 level, Schwarz & Stamminger 2008 §6)", { "mipmap", "nbuffers", "ysm" }, true },
    { "hsm_early_out", 1, 0, 1, "", "on: lit / umbra pixels decided from the HSM over w_i (Alg. 1 L8-10)", { "off", "on" }, true },
    { "blocker_subdivision", 1, 0, 2, "", "sub-kernels of w_i for the average blocker depth (§5): none (VSM's lit assumption), uniform m x m, adaptive (Alg. 2)", schemes, true },
    { "blocker_uniform_m", 5, 1, 16, "sub-kernels per axis", "m of the uniform blocker subdivision (§6.2: m = 5)", {}, true },
    { "blocker_tree_height", 3, 0, 5, "levels", "H of the adaptive blocker subdivision", {}, true },
    { "shadow_subdivision", 2, 0, 2, "", "sub-kernels of w_p for the visibility (§5): none (VSM's lit assumption, Fig. 3a), uniform n x n, adaptive (Alg. 2)", schemes, true },
    { "shadow_uniform_n", 8, 1, 16, "sub-kernels per axis", "n of the uniform shadow subdivision (§6.2: n = 8)", {}, true },
    { "shadow_tree_height", 3, 0, 5, "levels", "H of the adaptive shadow subdivision (§6.2: H = 3)", {}, true },
    { "nonplanar_pcf_taps", 2, 1, 8, "taps per axis", "k x k PCF in a non-planar leaf (§5.1 option 2: 2 x 2)", {}, true },
    { "lit_variance_threshold", 1e-4, 0, 1, "r", "a non-planar sub-kernel with variance below this times r is lit (§6.5: 0.0001 r; r = scene bounding-sphere radius)", {}, false },
    { "contact_threshold", 0.01, 0, 1, "r", "eps of the contact test, times r: below it, 3 x 3 jittered bilinear PCF instead of the SAT (§6.4: 0.01 r; 0 = off)", {}, false },
    { "contact_test", 0, 0, 1, "", "§6.4's contact test: blocker_average (d - z_occ of Eq. 4 < eps, once per pixel; PCF over all of w_p) or subkernel_mean (t_c - E(x) < eps for each normal sub-kernel of w_p, with its own SAT mean; PCF over that sub-kernel)", { "blocker_average", "subkernel_mean" }, true },
    { "min_variance", 1e-6, 0, 0.01, "d^2", "floor of the pooled variance, relative to the squared receiver depth", {}, false },
  });
  descriptor.lightStructures = { &shadowMapStructure(), &summedAreaTableStructure(),
    &hierarchicalShadowMapStructure() };
  descriptor.buffers = {
    { "blocker_kernel_texels", "texels", "width of the blocker search kernel w_i (Alg. 1 L7)" },
    { "penumbra_kernel_texels", "texels", "width of the penumbra kernel w_p (Alg. 1 L16)" },
    { "avg_blocker_depth", "world units", "average blocker depth z_avg, Eq. 4 combined with the PCF sub-kernels (0: none)" },
    classificationBuffer(),
    { "nonplanar_subkernels", "sub-kernels", "sub-kernels with E(x) >= t, both steps (§5.1)" },
    { "quadtree_nodes_visited", "nodes", "nodes of the adaptive quad-trees traversed, both steps (Alg. 2)" },
    { "pcf_samples", "taps", "point-sampled depth comparisons: non-planar leaves and contact PCF" },
  };
  // The shader's subdivide() takes either parameter's value: SCHEME_NONE, SCHEME_UNIFORM, SCHEME_ADAPTIVE.
  for (std::size_t code = 0; code < schemes.size(); ++code)
  {
    std::string name = "SCHEME_" + schemes[code];
    std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::toupper(c); });
    descriptor.shaderConstants.push_back({ name, static_cast<int>(code),
      "value of blocker_subdivision and shadow_subdivision: " + schemes[code] });
  }
  descriptor.supportedLights = { LightType::Area, LightType::Point, LightType::Spot };
  descriptor.coversLightArea = true;
  descriptor.createPass = [] { return vtkSmartPointer<vtkSLTechniquePass>(vtkSmartPointer<vtkSLVssmPass>::New()); };
  return descriptor;
}

glm::ivec3 quadTreeChild(glm::ivec3 node)
{
  return { 2 * node.x, 2 * node.y, node.z + 1 };
}

std::optional<glm::ivec3> quadTreeNext(glm::ivec3 node)
{
  while (node.z > 0 && (node.x & 1) == 1 && (node.y & 1) == 1)
  {
    node = { node.x >> 1, node.y >> 1, node.z - 1 };
  }
  if (node.z == 0)
  {
    return std::nullopt;
  }
  return (node.x & 1) == 0 ? glm::ivec3(node.x + 1, node.y, node.z) : glm::ivec3(node.x - 1, node.y + 1, node.z);
}

std::vector<QuadTreeNode> linearQuadTree(int height)
{
  // Depth-first layout: a node, then its four subtrees in the order (0,0), (1,0), (0,1), (1,1).
  std::vector<QuadTreeNode> nodes;
  const auto build = [&](const auto& self, glm::ivec3 cell) -> void {
    const std::size_t index = nodes.size();
    nodes.push_back({ cell, -1, -1 });
    if (cell.z < height)
    {
      nodes[index].child = static_cast<int>(nodes.size());
      for (int child = 0; child < 4; ++child)
      {
        self(self, glm::ivec3(2 * cell.x + (child & 1), 2 * cell.y + (child >> 1), cell.z + 1));
      }
    }
    nodes[index].next = static_cast<int>(nodes.size()); // the first node after this subtree
  };
  build(build, glm::ivec3(0));
  for (QuadTreeNode& node : nodes)
  {
    if (node.next == static_cast<int>(nodes.size()))
    {
      node.next = -1;
    }
  }
  return nodes;
}

double vssmSatHalfStep(bool integer, int mapSize, double nearDepth, double farDepth)
{
  return integer ? 0.5 * (farDepth - nearDepth) / satFixedPointScale(mapSize) : 0.0;
}

BoxMoments VssmReferenceInputs::boxMoments(glm::ivec2 lo, glm::ivec2 hi) const
{
  const LightView& view = shadowMap->lightView;
  return integerTable ? boxMomentsFromIntegerTable(*integerTable, lo, hi, view.nearDepth, view.farDepth)
                      : boxMomentsFromFloatTable(floatTable, lo, hi, view.nearDepth, view.farDepth);
}

VssmReferenceInputs vssmReferenceInputs(const ShadowMapInputs& shadowMap, const ParameterValues& values,
  const std::optional<Image<std::uint32_t>>& integerTable, const ImageF& floatTable, double sceneRadius)
{
  VssmReferenceInputs inputs;
  inputs.shadowMap = &shadowMap;
  inputs.hsm = HierarchicalShadowMap::build(shadowMap.shadowMapLinear, hierarchicalShadowMapSettings(values).layout);
  const bool integer = values.choice("sat_precision") == "int32";
  if (integer)
  {
    inputs.integerTable = integerTable;
  }
  inputs.floatTable = floatTable;
  inputs.sceneRadius = sceneRadius;
  inputs.satHalfStep = vssmSatHalfStep(integer, shadowMap.shadowMapLinear.width, shadowMap.lightView.nearDepth,
    shadowMap.lightView.farDepth);
  return inputs;
}

namespace
{

struct Accumulation
{
  double vsmArea = 0.0;
  double vsmSum = 0.0;
  double vsmSumSquares = 0.0;
  double litArea = 0.0;
  double pcfArea = 0.0;
  double pcfBlockedArea = 0.0;
  double pcfBlockerDepthSum = 0.0;
};

// One pixel's evaluation, mirroring VssmVisibility.glsl function by function.
class VssmEvaluation
{
public:
  VssmEvaluation(const VssmReferenceInputs& inputs, const ParameterValues& values, const SoftShadowGeometry& geometry,
    double bias, const glm::dmat2& contactJitter, VssmSample& result)
    : inputs_(inputs), values_(values), geometry_(geometry), bias_(bias), contactJitter_(contactJitter), result_(result)
  {
  }

  int contactSubkernels() const { return contactSubkernels_; }

  void noteDecision(double value, double boundary, double scale)
  {
    result_.decisionMargin = std::min(result_.decisionMargin, std::abs(value - boundary) / std::max(scale, 1e-30));
  }

  double storedDepth(const glm::dvec2& tap) const
  {
    const ImageF& map = inputs_.shadowMap->shadowMapLinear;
    const int x = std::clamp(static_cast<int>(std::floor(tap.x)), 0, map.width - 1);
    const int y = std::clamp(static_cast<int>(std::floor(tap.y)), 0, map.height - 1);
    return map.at(x, y);
  }

  // A tap's nearest-texel comparison, with its margins (depth, and texel edges whose neighbour decides
  // otherwise).
  bool blocks(const glm::dvec2& tap, double comparison)
  {
    return nearestTexelTest(*inputs_.shadowMap, tap, comparison, result_.sample) == 0.0;
  }

  void pcfLeaf(glm::ivec2 lo, glm::ivec2 hi, double area, Accumulation& acc)
  {
    const int taps = values_.getInt("nonplanar_pcf_taps");
    const glm::dvec2 spacing = glm::dvec2(hi - lo + 1) / static_cast<double>(taps);
    int blocked = 0;
    double blockerDepthSum = 0.0;
    for (int j = 0; j < taps; ++j)
    {
      for (int i = 0; i < taps; ++i)
      {
        const glm::dvec2 tap = glm::dvec2(lo) + (glm::dvec2(i, j) + 0.5) * spacing;
        if (blocks(tap, geometry_.tapComparisonDepth(tap, bias_)))
        {
          ++blocked;
          blockerDepthSum += storedDepth(tap);
        }
      }
    }
    const double tapCount = static_cast<double>(taps) * taps;
    result_.pcfSamples += taps * taps;
    acc.pcfArea += area;
    acc.pcfBlockedArea += area * blocked / tapCount;
    acc.pcfBlockerDepthSum += area * blockerDepthSum / tapCount;
  }

  bool visitSubKernel(glm::ivec2 lo, glm::ivec2 hi, bool isLeaf, bool nonPlanarIsLit, bool detectContact, Accumulation& acc)
  {
    const BoxMoments moments = inputs_.boxMoments(lo, hi);
    const double area = static_cast<double>(hi.x - lo.x + 1) * (hi.y - lo.y + 1);
    const double t = geometry_.tapComparisonDepth(0.5 * glm::dvec2(lo + hi + 1), bias_ + inputs_.satHalfStep);
    const double meanOffset = moments.mean - t;
    noteDecision(meanOffset, 0.0, geometry_.d);
    if (meanOffset < 0.0)
    {
      if (detectContact)
      {
        const double contactDistance = values_.get("contact_threshold") * inputs_.sceneRadius;
        noteDecision(-meanOffset, contactDistance, geometry_.d);
        if (-meanOffset < contactDistance)
        {
          ++contactSubkernels_;
          const double lit = contactShadow(0.5 * glm::dvec2(lo + hi + 1), 0.5 * glm::dvec2(hi - lo + 1), contactJitter_);
          acc.pcfArea += area;
          acc.pcfBlockedArea += area * (1.0 - lit);
          return false;
        }
      }
      acc.vsmArea += area;
      acc.vsmSum += area * meanOffset;
      acc.vsmSumSquares += area * (moments.variance + meanOffset * meanOffset);
      return false;
    }
    ++result_.nonplanarSubkernels;
    const double threshold = values_.get("lit_variance_threshold") * inputs_.sceneRadius;
    if (!nonPlanarIsLit)
    {
      noteDecision(moments.variance, threshold, std::max(threshold, 1e-3 * geometry_.d * geometry_.d));
    }
    if (nonPlanarIsLit || moments.variance < threshold)
    {
      acc.litArea += area;
      return false;
    }
    if (!isLeaf)
    {
      return true;
    }
    pcfLeaf(lo, hi, area, acc);
    return false;
  }

  Accumulation subdivide(glm::ivec2 lo, glm::ivec2 hi, const std::string& scheme, int cells, int height, bool detectContact)
  {
    Accumulation acc;
    const glm::ivec2 extent = hi - lo + 1;
    if (scheme == "none")
    {
      visitSubKernel(lo, hi, true, true, detectContact, acc);
    }
    else if (scheme == "uniform")
    {
      for (int j = 0; j < cells; ++j)
      {
        for (int i = 0; i < cells; ++i)
        {
          const glm::ivec2 subLo = lo + (extent * glm::ivec2(i, j)) / cells;
          const glm::ivec2 subHi = lo + (extent * glm::ivec2(i + 1, j + 1)) / cells - 1;
          if (subHi.x >= subLo.x && subHi.y >= subLo.y)
          {
            visitSubKernel(subLo, subHi, true, false, detectContact, acc);
          }
        }
      }
    }
    else
    {
      std::optional<glm::ivec3> node = glm::ivec3(0);
      while (node)
      {
        ++result_.quadtreeNodesVisited;
        const int parts = 1 << node->z;
        const glm::ivec2 cell(node->x, node->y);
        const glm::ivec2 subLo = lo + (extent * cell) / parts;
        const glm::ivec2 subHi = lo + (extent * (cell + 1)) / parts - 1;
        const bool refine = subHi.x >= subLo.x && subHi.y >= subLo.y && visitSubKernel(subLo, subHi, node->z == height, false, detectContact, acc);
        node = refine ? quadTreeChild(*node) : quadTreeNext(*node);
      }
    }
    return acc;
  }

  double bilinearShadowTest(const glm::dvec2& tap)
  {
    const glm::dvec2 position = tap - 0.5;
    const glm::dvec2 base = glm::floor(position);
    const glm::dvec2 weight = position - base;
    const double comparison = geometry_.tapComparisonDepth(tap, bias_);
    double lit = 0.0;
    for (int corner = 0; corner < 4; ++corner)
    {
      const glm::ivec2 offset(corner & 1, corner >> 1);
      const double test = blocks(base + glm::dvec2(offset) + 0.5, comparison) ? 0.0 : 1.0;
      lit += test * (offset.x == 1 ? weight.x : 1.0 - weight.x) * (offset.y == 1 ? weight.y : 1.0 - weight.y);
    }
    return lit;
  }

  double contactShadow(const glm::dvec2& uv, const glm::dvec2& filterHalf, const glm::dmat2& rotation)
  {
    double lit = 0.0;
    for (int j = 0; j < 3; ++j)
    {
      for (int i = 0; i < 3; ++i)
      {
        const glm::dvec2 offset = (glm::dvec2(i, j) - 1.0) * (2.0 / 3.0) * filterHalf;
        lit += bilinearShadowTest(uv + rotation * offset);
      }
    }
    result_.pcfSamples += 36;
    return lit / 9.0;
  }

  // Chebyshev's P(x >= t) over pooled offset moments, and their variance.
  double pooledChebyshev(const Accumulation& acc, double& variance)
  {
    const double mean = acc.vsmSum / acc.vsmArea;
    const double d = geometry_.d;
    variance = std::max(acc.vsmSumSquares / acc.vsmArea - mean * mean, values_.get("min_variance") * d * d);
    return mean >= 0.0 ? 1.0 : variance / (variance + mean * mean);
  }

private:
  const VssmReferenceInputs& inputs_;
  const ParameterValues& values_;
  const SoftShadowGeometry& geometry_;
  double bias_;
  glm::dmat2 contactJitter_;
  VssmSample& result_;
  int contactSubkernels_ = 0;
};

} // namespace

VssmSample vssmReference(const VssmReferenceInputs& inputs, const ParameterValues& values, int x, int y)
{
  VssmSample result;
  const ShadowMapInputs& shadowMap = *inputs.shadowMap;
  const ShadowLookup lookup = prepareShadowLookup(shadowMap, biasSettings(values), x, y);
  result.sample = lookup.sample;
  if (!lookup.sample.evaluated)
  {
    return result;
  }
  const SoftShadowGeometry geometry =
    softShadowGeometry(shadowMap, lookup, values.choice("receiver_plane_bias") == "on", x, y);
  const double d = geometry.d;
  const double bias = lookup.sample.bias;
  VssmEvaluation evaluation(inputs, values, geometry, bias, pixelRotation(x, y), result);
  const bool contactPerSubkernel = values.choice("contact_test") == "subkernel_mean";
  const glm::dvec2 uv = lookup.sm.uvTexels;
  const auto finish = [&](double visibility, VssmClass classification) {
    result.sample.visibility = visibility;
    result.classification = classification;
    return result;
  };

  // L7.
  const glm::dvec2 searchHalf = geometry.kernelHalfTexels(geometry.nearDepth);
  result.blockerKernelTexels = 2.0 * std::max(searchHalf.x, searchHalf.y);
  const TexelRectangle search = kernelRectangle(uv, searchHalf, geometry.mapSize, &result.kernelEdgeMargin);

  // L8-10.
  if (values.choice("hsm_early_out") == "on")
  {
    const glm::dvec2 depthRange = inputs.hsm.range(search.lo, search.hi);
    const glm::dvec2 comparisonRange = geometry.comparisonDepthRange(search.lo, search.hi, bias);
    evaluation.noteDecision(depthRange.x, comparisonRange.y, d);
    evaluation.noteDecision(depthRange.y, comparisonRange.x, d);
    if (depthRange.x >= comparisonRange.y)
    {
      return finish(1.0, VssmClass::Lit);
    }
    if (depthRange.y < comparisonRange.x)
    {
      return finish(0.0, VssmClass::Umbra);
    }
  }

  // L11-15.
  const Accumulation blockers = evaluation.subdivide(search.lo, search.hi, values.choice("blocker_subdivision"),
    values.getInt("blocker_uniform_m"), values.getInt("blocker_tree_height"), false);
  double blockedArea = blockers.pcfBlockedArea;
  double blockerDepthSum = blockers.pcfBlockerDepthSum;
  if (blockers.vsmArea > 0.0)
  {
    double variance = 0.0;
    const double unoccluded = evaluation.pooledChebyshev(blockers, variance);
    const double occludedArea = blockers.vsmArea * (1.0 - unoccluded);
    blockedArea += occludedArea;
    blockerDepthSum += occludedArea * (d - bias - inputs.satHalfStep) + blockers.vsmSum;
  }
  const double blockedThreshold = 1e-5 * search.area();
  evaluation.noteDecision(blockedArea, blockedThreshold, blockedThreshold);
  if (!(blockedArea > blockedThreshold))
  {
    return finish(1.0, VssmClass::Lit);
  }
  result.averageBlockerDepth = std::clamp(blockerDepthSum / blockedArea, geometry.nearDepth, d);

  // L16.
  const glm::dvec2 filterHalf = geometry.kernelHalfTexels(result.averageBlockerDepth);
  result.penumbraKernelTexels = 2.0 * std::max(filterHalf.x, filterHalf.y);

  // §6.4, contact_test = blocker_average.
  if (!contactPerSubkernel)
  {
    const double contactDistance = values.get("contact_threshold") * inputs.sceneRadius;
    evaluation.noteDecision(d - result.averageBlockerDepth, contactDistance, d);
    if (d - result.averageBlockerDepth < contactDistance)
    {
      return finish(evaluation.contactShadow(uv, filterHalf, pixelRotation(x, y)), VssmClass::Contact);
    }
  }

  // L17-20.
  const TexelRectangle filter = kernelRectangle(uv, filterHalf, geometry.mapSize, &result.kernelEdgeMargin);
  const Accumulation shadow = evaluation.subdivide(filter.lo, filter.hi, values.choice("shadow_subdivision"),
    values.getInt("shadow_uniform_n"), values.getInt("shadow_tree_height"), contactPerSubkernel);
  double chebyshevLit = 0.0;
  if (shadow.vsmArea > 0.0)
  {
    double variance = 0.0;
    chebyshevLit = evaluation.pooledChebyshev(shadow, variance);
  }
  const double totalArea = shadow.vsmArea + shadow.litArea + shadow.pcfArea;
  const double visibility =
    (chebyshevLit * shadow.vsmArea + shadow.litArea + shadow.pcfArea - shadow.pcfBlockedArea) / totalArea;
  return finish(std::clamp(visibility, 0.0, 1.0),
    evaluation.contactSubkernels() > 0 ? VssmClass::Contact : VssmClass::Penumbra);
}

} // namespace sl
