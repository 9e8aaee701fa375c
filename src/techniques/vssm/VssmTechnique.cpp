#include "techniques/vssm/VssmTechnique.h"

#include "techniques/ApproximationRules.h"

#include "structures/hsm/HsmStructure.h"
#include "structures/sat/SatStructure.h"
#include "structures/shadowmap/ShadowMapStructure.h"

#include "core/Error.h"
#include "frame/FrameResult.h"
#include "techniques/ProbeSupport.h"
#include "techniques/SamplingPatterns.h"
#include "techniques/ShadowMapParameters.h"
#include "techniques/SoftShadowSupport.h"
#include "techniques/ContourReceiver.h" // probeNodeOf: HSM query nodes as probe nodes
#include "techniques/vssm/vtkSLVssmPass.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <iterator>
#include <limits>

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

const char* const vssmPaper = "VSSM (Yang et al. 2010)";

std::string cite(const std::string& where)
{
  return where + ", " + vssmPaper;
}

// A categorical quantity that a buffer publishes as a code: the code as its value, the label as its text.
void recordCode(ProbeRecorder& recorder, const std::string& name, int code, const std::string& label,
  const std::string& source)
{
  recorder.quantity(name, code, "code", source);
  recorder.record().quantities.back().text = label;
}

const char* const chebyshevBoundDescription =
  "the value exceeds by more than 0.05 the PCF over the pixel's penumbra kernel w_p (its texels compared as the "
  "filter step compares them; for a pixel the blocker step called lit although texels of w_i lie in front of it, "
  "w_p of those texels' mean depth): Eq. 1's Chebyshev bound over the normal sub-kernels is exact only for two "
  "depths one of which is the receiver's, an upper bound elsewhere (e.g. a caster over empty texels far behind the "
  "receiver), and with blocker_subdivision=none it can hide every blocker";

// The PCF over `kernel` (at most 32 x 32 taps, a regular sub-grid beyond, as savsm's light_leak), each tap compared as
// the filter step compares it, and the blocked taps' depth sum and count. `litWithinReach` counts as lit the blocked
// taps that cannot hide any of the light from the point at `centre`: the light's footprint at the tap's own depth
// (kernelHalfTexels of it, plus half a texel) does not reach the tap.
struct KernelPcf
{
  double lit = 1.0;
  double litWithinReach = 1.0;
  double blockedDepthSum = 0.0;
  int blocked = 0;
  int blockedBeyondReach = 0;
};
KernelPcf pcfOver(const ImageF& map, const SoftShadowGeometry& geometry, double bias, const TexelRectangle& kernel,
  const glm::dvec2& centre)
{
  constexpr int kTapsPerAxis = 32;
  const glm::ivec2 texels = kernel.hi - kernel.lo + 1;
  const glm::ivec2 taps = glm::min(texels, glm::ivec2(kTapsPerAxis));
  const glm::dvec2 step = glm::dvec2(texels) / glm::dvec2(taps);
  KernelPcf result;
  for (int j = 0; j < taps.y; ++j)
  {
    for (int i = 0; i < taps.x; ++i)
    {
      const glm::dvec2 tap = glm::dvec2(kernel.lo) + (glm::dvec2(i, j) + 0.5) * step;
      const glm::ivec2 texel = glm::clamp(glm::ivec2(glm::floor(tap)), glm::ivec2(0), glm::ivec2(map.width - 1));
      const double z = map.at(texel.x, texel.y);
      if (z < geometry.tapComparisonDepth(tap, bias))
      {
        result.blockedDepthSum += z;
        ++result.blocked;
        const glm::dvec2 reach = geometry.kernelHalfTexels(z) + 0.5;
        const glm::dvec2 offset = glm::abs(glm::dvec2(texel) + 0.5 - centre);
        result.blockedBeyondReach += offset.x > reach.x || offset.y > reach.y ? 1 : 0;
      }
    }
  }
  const double tapCount = static_cast<double>(taps.x) * taps.y;
  result.lit = 1.0 - result.blocked / tapCount;
  result.litWithinReach = 1.0 - (result.blocked - result.blockedBeyondReach) / tapCount;
  return result;
}

// The PCF over the kernel of blockers at `planeDepth` about the pixel's point: w_i at the near plane, w_p at z_avg.
KernelPcf planePcf(const ShadowMapInputs& inputs, const ShadowLookup& lookup, const SoftShadowGeometry& geometry,
  double planeDepth)
{
  return pcfOver(inputs.shadowMapLinear, geometry, lookup.sample.bias,
    kernelRectangle(lookup.sm.uvTexels, geometry.kernelHalfTexels(planeDepth), geometry.mapSize), lookup.sm.uvTexels);
}

const char* const penumbraKernelBeyondTheLightDescription =
  "the penumbra kernel w_p, one kernel for all blockers at the average blocker depth (Eq. 4, Alg. 1 L16), holds "
  "texels the filter step counts as blocked although at their own depth they cannot hide any of the light from the "
  "point, and the value differs by more than 0.05 from the PCF over w_p that counts only the texels that can";

const char* const contactPcfDescription =
  "a contact pixel's value differs by more than 0.05 from the PCF over its penumbra kernel w_p: §6.4 filters the "
  "contact sub-kernels (or all of w_p, contact_test=blocker_average) by a 3 x 3 jittered bilinear PCF, nine taps "
  "for the kernel's texels";

// VSSM's two estimates of the PCF the filter step stands for, in one walk over the receivers no earlier rule marked
// (each pixel's lookup and w_p PCF computed once):
//  - `chebyshevCode` where the value exceeds that PCF by more than `excess`. Alg. 1 L17-20 estimate the PCF over w_p:
//    the normal sub-kernels by Chebyshev's one-tailed bound (Eq. 1 on Eq. 5's moments), which overestimates the lit
//    fraction wherever a sub-kernel's depths spread beyond the receiver (§5 only subdivides sub-kernels whose mean
//    lies behind it). Penumbra pixels (and, with contact_test=subkernel_mean, contact pixels, whose other sub-kernels
//    still take the bound) are held to the PCF over their own w_p (avg_blocker_depth); a pixel the blocker step
//    (Alg. 1 L11-15) called lit although w_i holds texels in front of it (the same bound, or VSM's lit assumption,
//    hid them) to the PCF over the w_p those texels' mean depth gives. A lit pixel the HSM decided has no such texel.
//  - `contactCode` where a contact pixel (§6.4) lies otherwise more than `excess` from the PCF over its w_p.
//  - `beyondReachCode` where w_p, one kernel for all blockers at z_avg (Eq. 4, Alg. 1 L16), holds blocked texels
//    whose own depth puts them outside the light's footprint, and the value lies more than `excess` from the PCF
//    that leaves them lit (differential seed 6: a caster 0.5 in front of the receiver, 43 texels out, where its
//    footprint is 8 texels wide).
void markFilterEstimates(const ApproximationContext& context, ImageF& codes, float chebyshevCode, float contactCode,
  float beyondReachCode, double excess)
{
  const FrameResult& frame = *context.frame;
  const NamedImage* visibility = frame.find("visibility");
  const NamedImage* classification = frame.find("classification");
  const NamedImage* blockerDepth = frame.find("avg_blocker_depth");
  if (!visibility || !classification || !blockerDepth)
  {
    return;
  }
  const ShadowMapInputs inputs = shadowMapInputsOf(frame, *context.scene, context.lightIndex, false);
  const VssmSettings settings = VssmSettings::from(frame.parameters);
  const BiasSettings bias = settings.bias;
  const bool receiverPlaneBias = settings.receiverPlaneBias;
  const bool contactPerSubkernel = settings.contactTest == VssmContactTest::SubkernelMean;
  for (int y = 0; y < codes.height; ++y)
  {
    for (int x = 0; x < codes.width; ++x)
    {
      const auto pixelClass = static_cast<VssmClass>(static_cast<int>(classification->image.at(x, y)));
      const bool contact = pixelClass == VssmClass::Contact;
      if (codes.at(x, y) != 0.0f || !(pixelClass == VssmClass::Penumbra || pixelClass == VssmClass::Lit || contact))
      {
        continue;
      }
      const ShadowLookup lookup = prepareShadowLookup(inputs, bias, x, y);
      if (!lookup.sample.evaluated)
      {
        continue;
      }
      const SoftShadowGeometry geometry = softShadowGeometry(inputs, lookup, receiverPlaneBias, x, y);
      const double value = visibility->image.at(x, y);
      double planeDepth = blockerDepth->image.at(x, y);
      if (pixelClass == VssmClass::Lit)
      {
        const KernelPcf search = planePcf(inputs, lookup, geometry, geometry.nearDepth);
        if (search.blocked == 0)
        {
          continue;
        }
        planeDepth = std::clamp(search.blockedDepthSum / search.blocked, geometry.nearDepth, geometry.d);
      }
      const KernelPcf penumbraPcf = planePcf(inputs, lookup, geometry, planeDepth);
      const double pcf = penumbraPcf.lit;
      if ((!contact || contactPerSubkernel) && value > pcf + excess)
      {
        codes.at(x, y) = chebyshevCode;
      }
      else if (contact && std::abs(value - pcf) > excess)
      {
        codes.at(x, y) = contactCode;
      }
      else if (penumbraPcf.blockedBeyondReach > 0 && std::abs(value - penumbraPcf.litWithinReach) > excess)
      {
        codes.at(x, y) = beyondReachCode;
      }
    }
  }
}

} // namespace

VssmSettings VssmSettings::from(const ParameterValues& values)
{
  const auto subdivision = [&](const char* scheme, const char* cells, const char* height) {
    VssmSubdivisionSettings settings;
    settings.scheme = choiceOf<VssmSubdivision>(values, scheme,
      { { "none", VssmSubdivision::None }, { "uniform", VssmSubdivision::Uniform }, { "adaptive", VssmSubdivision::Adaptive } });
    settings.uniformCells = values.getInt(cells);
    settings.treeHeight = values.getInt(height);
    return settings;
  };
  VssmSettings settings;
  settings.bias = biasSettings(values);
  settings.receiverPlaneBias = receiverPlaneBiasOf(values);
  settings.sat = summedAreaTableSettings(values);
  settings.hsmEarlyOut = values.choice("hsm_early_out") == "on";
  settings.blockerSubdivision = subdivision("blocker_subdivision", "blocker_uniform_m", "blocker_tree_height");
  settings.shadowSubdivision = subdivision("shadow_subdivision", "shadow_uniform_n", "shadow_tree_height");
  settings.nonplanarPcfTaps = values.getInt("nonplanar_pcf_taps");
  settings.litVarianceThreshold = values.get("lit_variance_threshold");
  settings.contactThreshold = values.get("contact_threshold");
  settings.contactTest = choiceOf<VssmContactTest>(values, "contact_test",
    { { "blocker_average", VssmContactTest::BlockerAverage }, { "subkernel_mean", VssmContactTest::SubkernelMean } });
  settings.minVariance = values.get("min_variance");
  return settings;
}

TechniqueDescriptor vssmTechnique()
{
  TechniqueDescriptor descriptor = describeShadowMapTechnique("vssm", "Variance soft shadow mapping",
    "Yang et al. 2010 (VSSM), Alg. 1 and 2, Eq. 1-5, §5-6");
  descriptor.parameters.push_back(receiverPlaneBiasParameter());
  const std::vector<std::string> schemes = { "none", "uniform", "adaptive" };
  descriptor.addParameters({
    { "sat_precision", 1, 0, 1, "", "float_centred: float SAT of z - (near + far) / 2; int32: fixed point, exact box sums (§6.4)", { "float_centred", "int32" }, true },
    { "hsm", 0, 0, 2, "", "min-max hierarchical shadow map: mipmap (conservative ranges, the paper's choice), nbuffers (exact ranges, L times the memory) (§6.1) or ysm (the mip-map plus an MSSM of its ~256^2 level, Schwarz & Stamminger 2008 §6)", { "mipmap", "nbuffers", "ysm" }, true },
    hsmLevelsParameter("hsm_levels", "N-buffers (hsm=nbuffers)"),
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
    // Every sub-kernel §5.1's test calls "non-planarity" (its mean not in front of t), quad-tree nodes included:
    // most are then lit by the variance threshold (§6.5); only leaves are filtered point by point (pcf_samples).
    { "subkernels_mean_not_in_front", "sub-kernels", "sub-kernels visited whose mean depth is not in front of the "
      "receiver (E(x) >= t, §5.1's non-planarity test), both steps, quad-tree nodes included: each is then lit "
      "(variance below lit_variance_threshold), refined, or a leaf filtered point by point (counted in pcf_samples)" },
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
  descriptor.createPass = newTechniquePass<vtkSLVssmPass>;
  descriptor.probe = [](const ProbeContext& context, glm::ivec2 pixel, ProbeRecorder& recorder) {
    const FrameResult& frame = *context.frame;
    const ShadowMapInputs shadowMap = shadowMapInputsOf(frame, *context.scene, context.lightIndex);
    const VssmReferenceInputs inputs = vssmReferenceInputsOf(frame, *context.scene, shadowMap);
    const VssmSample sample = vssmReference(inputs, VssmSettings::from(frame.parameters), pixel.x, pixel.y, &recorder);
    // Vssm.MatchesTheCpuImplementation: |GPU - twin| <= 2e-3 on pixels none of whose decisions lies within float
    // rounding of its boundary: the receiver's (ambiguityOf), a kernel edge within 1e-4 texel of a texel centre,
    // a continuous decision (E(x) >= t, the variance and blocked-area thresholds, the contact test, the HSM
    // tests) within 1e-4 of its boundary, relative to d.
    ProbeOutcome outcome = probeOutcome(sample.sample, 2e-3,
      "vssmReference (vssm/VssmTechnique.h), double precision, on the summed-area table the GPU built (read back) "
      "and the HSM rebuilt from the shadow map");
    if (sample.sample.evaluated)
    {
      noteAmbiguity(outcome.ambiguity, "kernel edge from a texel centre (texels)", sample.kernelEdgeMargin, 1e-4);
      noteAmbiguity(outcome.ambiguity, "continuous decision from its boundary (relative to d)", sample.decisionMargin,
        1e-4);
    }
    return outcome;
  };
  // VSSM's average blocker depth (Eq. 4) and penumbra kernel are PCSS's: exact for blockers on one plane parallel to
  // the light, approximate wherever the casters that hide part of the light lie at different depths.
  descriptor.accuracy = oneLayerSoftShadowContract(BlockerDepthModel::Average, 0.1);
  descriptor.accuracy.approximations.push_back({ "chebyshev bound", chebyshevBoundDescription });
  const float chebyshevCode = static_cast<float>(descriptor.accuracy.approximations.size());
  descriptor.accuracy.approximations.push_back({ "contact pcf", contactPcfDescription });
  const float contactCode = static_cast<float>(descriptor.accuracy.approximations.size());
  descriptor.accuracy.approximations.push_back({ "penumbra kernel beyond the light",
    penumbraKernelBeyondTheLightDescription });
  const float beyondReachCode = static_cast<float>(descriptor.accuracy.approximations.size());
  descriptor.accuracy.markApproximations = [shared = descriptor.accuracy.markApproximations, chebyshevCode,
                                             contactCode, beyondReachCode](const ApproximationContext& context,
                                             ImageF& codes) {
    shared(context, codes);
    markFilterEstimates(context, codes, chebyshevCode, contactCode, beyondReachCode, 0.05);
  };
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

ImageF floatSummedAreaTableOf(const FrameResult& frame)
{
  const NamedImage* sumZ = nullptr;
  const NamedImage* sumZ2 = nullptr;
  for (const NamedImage& named : frame.lightSpace)
  {
    sumZ = named.name == "sat_z" ? &named : sumZ;
    sumZ2 = named.name == "sat_z2" ? &named : sumZ2;
  }
  SL_CHECK_MSG(sumZ && sumZ2, "frame of ", frame.technique, " exports no float summed-area table (sat_z, sat_z2)");
  ImageF table(sumZ->image.width, sumZ->image.height, 2);
  for (std::size_t i = 0; i < sumZ->image.data.size(); ++i)
  {
    table.data[i * 2] = sumZ->image.data[i];
    table.data[i * 2 + 1] = sumZ2->image.data[i];
  }
  return table;
}

VssmReferenceInputs vssmReferenceInputsOf(const FrameResult& frame, const Scene& scene, const ShadowMapInputs& shadowMap)
{
  const ImageF floatTable = frame.integerSummedAreaTable ? ImageF() : floatSummedAreaTableOf(frame);
  return vssmReferenceInputs(
    shadowMap, frame.parameters, frame.integerSummedAreaTable, floatTable, scene.bounds().radius());
}

VssmReferenceInputs vssmReferenceInputs(const ShadowMapInputs& shadowMap, const ParameterValues& values,
  const std::optional<Image<std::uint32_t>>& integerTable, const ImageF& floatTable, double sceneRadius)
{
  VssmReferenceInputs inputs;
  inputs.shadowMap = &shadowMap;
  inputs.hsm = buildHierarchicalShadowMap(shadowMap.shadowMapLinear, values, shadowMap.lightView, *shadowMap.light, true);
  const bool integer = VssmSettings::from(values).sat.integer;
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
  VssmEvaluation(const VssmReferenceInputs& inputs, const VssmSettings& settings, const SoftShadowGeometry& geometry,
    double bias, const glm::dmat2& contactJitter, VssmSample& result, ProbeRecorder* recorder)
    : inputs_(inputs), settings_(settings), geometry_(geometry), bias_(bias), contactJitter_(contactJitter), result_(result),
      recorder_(recorder)
  {
  }

  // The kernel whose sub-kernels are visited next (probe groups and kernel roles): "blocker" (w_i) or "penumbra"
  // (w_p).
  void beginStep(const std::string& step)
  {
    step_ = step;
    subKernelCount_ = 0;
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
  // otherwise). `role` and `weight`: the probe's record of the texel.
  bool blocks(const glm::dvec2& tap, double comparison, const char* role, double weight)
  {
    return nearestTexelTest(*inputs_.shadowMap, tap, comparison, result_.sample, recorder_, role, weight) == 0.0;
  }

  void pcfLeaf(glm::ivec2 lo, glm::ivec2 hi, double area, Accumulation& acc)
  {
    const int taps = settings_.nonplanarPcfTaps;
    const glm::dvec2 spacing = glm::dvec2(hi - lo + 1) / static_cast<double>(taps);
    int blocked = 0;
    double blockerDepthSum = 0.0;
    for (int j = 0; j < taps; ++j)
    {
      for (int i = 0; i < taps; ++i)
      {
        const glm::dvec2 tap = glm::dvec2(lo) + (glm::dvec2(i, j) + 0.5) * spacing;
        if (blocks(tap, geometry_.tapComparisonDepth(tap, bias_), "non-planar pcf tap", 1.0 / (taps * taps)))
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
    if (recorder_)
    {
      recorder_->quantity("pcf_blocked_fraction", blocked / tapCount, "",
        cite("§5.1 option 2 (k x k PCF in a non-planar sub-kernel); Alg. 2 L23-26"));
    }
  }

  // The probe's record of a sub-kernel [lo, hi] of the current step: its group, rectangle, SAT moments and the
  // comparison depth t at its centre (Alg. 2 L6-8).
  void recordSubKernel(glm::ivec2 lo, glm::ivec2 hi, const BoxMoments& moments, double t, double area)
  {
    recorder_->beginGroup(step_ + " sub-kernel " + std::to_string(subKernelCount_++));
    recorder_->quantity("texel_lo", glm::dvec2(lo), "texels", cite("§5.2-5.3 (sub-kernel w_ci, first texel)"));
    recorder_->quantity("texel_hi", glm::dvec2(hi), "texels", cite("§5.2-5.3 (sub-kernel w_ci, last texel)"));
    recorder_->quantity("area", area, "texels", cite("Alg. 2 L6 (T_ci)"));
    recorder_->quantity("mean_depth", moments.mean, "linear depth", cite("Alg. 2 L7 (E(x)_ci from the SAT)"));
    recorder_->quantity("variance", moments.variance, "linear depth^2", cite("Alg. 2 L8 (sigma^2 = E(x^2) - E(x)^2)"));
    recorder_->quantity("comparison_depth", t, "linear depth",
      "ShadowLab: t at the sub-kernel's centre (receiver plane or d) minus the bias and half a SAT step");
    recorder_->quantity("mean_offset", moments.mean - t, "linear depth", cite("§5.1 (E(x)_ci - t: >= 0 is non-planar)"));
  }

  // The class of the sub-kernel just visited: a probe kernel (unless it is refined: its children follow), the
  // class as a quantity of its group, and the quad-tree node's decision.
  void classifySubKernel(glm::ivec2 lo, glm::ivec2 hi, const std::string& label, const std::string& source)
  {
    lastDecision_ = label;
    if (!recorder_)
    {
      return;
    }
    recorder_->category("class", label, source);
    if (label != "descend")
    {
      recorder_->kernel({ step_ + " sub-kernel", glm::dvec2(lo), glm::dvec2(hi + 1), label, source });
    }
  }

  bool visitSubKernel(glm::ivec2 lo, glm::ivec2 hi, bool isLeaf, bool nonPlanarIsLit, bool detectContact, Accumulation& acc)
  {
    const BoxMoments moments = inputs_.boxMoments(lo, hi);
    const double area = static_cast<double>(hi.x - lo.x + 1) * (hi.y - lo.y + 1);
    const double t = geometry_.tapComparisonDepth(0.5 * glm::dvec2(lo + hi + 1), bias_ + inputs_.satHalfStep);
    const double meanOffset = moments.mean - t;
    if (recorder_)
    {
      recordSubKernel(lo, hi, moments, t, area);
    }
    noteDecision(meanOffset, 0.0, geometry_.d);
    if (meanOffset < 0.0)
    {
      if (detectContact)
      {
        const double contactDistance = settings_.contactThreshold * inputs_.sceneRadius;
        noteDecision(-meanOffset, contactDistance, geometry_.d);
        if (-meanOffset < contactDistance)
        {
          ++contactSubkernels_;
          classifySubKernel(lo, hi, "contact", cite("§6.4 (t - E(x)_ci < eps: 3 x 3 jittered bilinear PCF)"));
          const double lit = contactShadow(0.5 * glm::dvec2(lo + hi + 1), 0.5 * glm::dvec2(hi - lo + 1), contactJitter_);
          acc.pcfArea += area;
          acc.pcfBlockedArea += area * (1.0 - lit);
          return false;
        }
      }
      classifySubKernel(lo, hi, "planar", cite("Alg. 2 L13-18 (E(x)_ci < t: pooled into Eq. 5)"));
      if (recorder_)
      {
        // Eq. 1 on this sub-kernel's own moments, for reading: the visibility pools the planar sub-kernels'
        // moments first (Eq. 5) and applies Eq. 1 once.
        const double variance = std::max(moments.variance, settings_.minVariance * geometry_.d * geometry_.d);
        recorder_->quantity("chebyshev_bound", variance / (variance + meanOffset * meanOffset), "",
          cite("Eq. 1 on this sub-kernel alone (the visibility pools them first, Eq. 5)"));
      }
      acc.vsmArea += area;
      acc.vsmSum += area * meanOffset;
      acc.vsmSumSquares += area * (moments.variance + meanOffset * meanOffset);
      return false;
    }
    ++result_.subkernelsMeanNotInFront;
    const double threshold = settings_.litVarianceThreshold * inputs_.sceneRadius;
    if (!nonPlanarIsLit)
    {
      noteDecision(moments.variance, threshold, std::max(threshold, 1e-3 * geometry_.d * geometry_.d));
    }
    if (nonPlanarIsLit || moments.variance < threshold)
    {
      classifySubKernel(lo, hi, "lit",
        nonPlanarIsLit ? cite("§5.1 option 1 / Fig. 3 a (no subdivision: VSM's lit assumption)")
                       : cite("Alg. 2 L10-12 (E(x)_ci >= t and sigma^2 < Threshold: fully lit)"));
      acc.litArea += area;
      return false;
    }
    if (!isLeaf)
    {
      classifySubKernel(lo, hi, "descend", cite("Alg. 2 L20-21 (non-planar, not a leaf: TreeNode.Child)"));
      return true;
    }
    classifySubKernel(lo, hi, "non-planar", cite("Alg. 2 L22-26 (non-planar leaf: PCF, §5.1 option 2)"));
    pcfLeaf(lo, hi, area, acc);
    return false;
  }

  Accumulation subdivide(glm::ivec2 lo, glm::ivec2 hi, const VssmSubdivisionSettings& subdivision, bool detectContact)
  {
    Accumulation acc;
    const glm::ivec2 extent = hi - lo + 1;
    const int cells = subdivision.uniformCells;
    const int height = subdivision.treeHeight;
    if (subdivision.scheme == VssmSubdivision::None)
    {
      visitSubKernel(lo, hi, true, true, detectContact, acc);
    }
    else if (subdivision.scheme == VssmSubdivision::Uniform)
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
        const bool empty = !(subHi.x >= subLo.x && subHi.y >= subLo.y);
        const bool refine = !empty && visitSubKernel(subLo, subHi, node->z == height, false, detectContact, acc);
        if (recorder_)
        {
          recorder_->node({ "quadtree", node->z, subLo, subHi, std::numeric_limits<double>::quiet_NaN(),
            std::numeric_limits<double>::quiet_NaN(), empty ? "empty (no texels)" : lastDecision_ });
        }
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
      const double tapWeight = (offset.x == 1 ? weight.x : 1.0 - weight.x) * (offset.y == 1 ? weight.y : 1.0 - weight.y);
      const double test = blocks(base + glm::dvec2(offset) + 0.5, comparison, "contact pcf tap", tapWeight / 9.0) ? 0.0 : 1.0;
      lit += test * tapWeight;
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
    if (recorder_)
    {
      recorder_->kernel({ "contact pcf", uv - filterHalf, uv + filterHalf, "contact",
        cite("§6.4 (3 x 3 jittered bilinear PCF over the kernel)") });
      recorder_->quantity("contact_pcf_visibility", lit / 9.0, "", cite("§6.4 (3 x 3 bilinear PCF, 36 depth comparisons)"));
    }
    return lit / 9.0;
  }

  // Chebyshev's P(x >= t) over pooled offset moments, and their variance.
  double pooledChebyshev(const Accumulation& acc, double& variance)
  {
    const double mean = acc.vsmSum / acc.vsmArea;
    const double d = geometry_.d;
    variance = std::max(acc.vsmSumSquares / acc.vsmArea - mean * mean, settings_.minVariance * d * d);
    return mean >= 0.0 ? 1.0 : variance / (variance + mean * mean);
  }

  // Alg. 1 L7: the blocker search kernel w_i, the light's extent seen from the receiver at the near plane (the
  // shader's initialKernel).
  TexelRectangle initialKernel(const glm::dvec2& uv)
  {
    const glm::dvec2 searchHalf = geometry_.kernelHalfTexels(geometry_.nearDepth);
    result_.blockerKernelTexels = 2.0 * std::max(searchHalf.x, searchHalf.y);
    const TexelRectangle search = kernelRectangle(uv, searchHalf, geometry_.mapSize, &result_.kernelEdgeMargin);
    if (recorder_)
    {
      recorder_->beginGroup("blocker search");
      recorder_->quantity("light_size", geometry_.lightSize, "world units", "scene (area light side)");
      recorder_->quantity("near_depth", geometry_.nearDepth, "linear depth", "light view (near plane)");
      recorder_->quantity("search_half_texels", searchHalf, "texels",
        cite("Alg. 1 L7 (w_i: the light's extent seen from the receiver, at the near plane; PCSS step 1)"));
      recorder_->quantity("blocker_kernel_texels", result_.blockerKernelTexels, "texels", cite("Alg. 1 L7 (w_i)"));
      recorder_->quantity("lit_variance_threshold", settings_.litVarianceThreshold * inputs_.sceneRadius,
        "linear depth^2", cite("§6.5 (Threshold = 0.0001 r: a non-planar sub-kernel with less variance is lit)"));
      recorder_->kernel({ "blocker search", glm::dvec2(search.lo), glm::dvec2(search.hi + 1), "", cite("Alg. 1 L7 (w_i)") });
    }
    return search;
  }

  // Alg. 1 L8-10: lit when no texel of w_i can be nearer than its comparison depth, umbra when all are (the
  // HSM's min-max over w_i, §6.1); nothing when undecided (the shader's hsmEarlyOut).
  std::optional<VssmClass> hsmEarlyOut(const TexelRectangle& search)
  {
    std::vector<HsmQueryNode> queryNodes; // the nodes the query read, for the probe
    const glm::dvec2 depthRange = inputs_.hsm.range(search.lo, search.hi, nullptr, recorder_ ? &queryNodes : nullptr);
    const glm::dvec2 comparisonRange = geometry_.comparisonDepthRange(search.lo, search.hi, bias_);
    noteDecision(depthRange.x, comparisonRange.y, geometry_.d);
    noteDecision(depthRange.y, comparisonRange.x, geometry_.d);
    const bool lit = depthRange.x >= comparisonRange.y;
    const bool umbra = !lit && depthRange.y < comparisonRange.x;
    if (recorder_)
    {
      recorder_->beginGroup("hsm test");
      recorder_->quantity("hsm_min_depth", depthRange.x, "linear depth", cite("Alg. 1 L8 (min over w_i from the HSM, §6.1)"));
      recorder_->quantity("hsm_max_depth", depthRange.y, "linear depth", cite("Alg. 1 L8 (max over w_i from the HSM, §6.1)"));
      recorder_->quantity("comparison_depth_min", comparisonRange.x, "linear depth",
        "ShadowLab: the smallest comparison depth over w_i (receiver plane or d, minus the bias)");
      recorder_->quantity("comparison_depth_max", comparisonRange.y, "linear depth",
        "ShadowLab: the largest comparison depth over w_i");
      const std::string decision = lit ? "lit" : umbra ? "umbra" : "undecided";
      recorder_->quantity("hsm_nodes_read", static_cast<double>(queryNodes.size()), "count",
        "ShadowLab: nodes the range query read (HierarchicalShadowMap::range; mip-map: at most 2 x 2)");
      for (const HsmQueryNode& node : queryNodes)
      {
        recorder_->node(probeNodeOf(node, decision));
      }
      recorder_->category("hsm_decision", decision,
        cite("Alg. 1 L8-10 (lit: min >= every comparison depth; umbra: max < every one)"));
    }
    if (lit)
    {
      return VssmClass::Lit;
    }
    if (umbra)
    {
      return VssmClass::Umbra;
    }
    return std::nullopt;
  }

  // Alg. 1 L11-15: the average blocker depth over w_i, Eq. 4 with z_unocc = t over the planar sub-kernels,
  // combined with the PCF-sampled blockers of the non-planar ones, weighted by their blocked areas (§5.2).
  // False when w_i holds no blocker (the pixel is lit). The shader's estimateAverageBlockerDepth.
  bool estimateAverageBlockerDepth(const TexelRectangle& search)
  {
    const double d = geometry_.d;
    beginStep("blocker");
    const Accumulation blockers = subdivide(search.lo, search.hi, settings_.blockerSubdivision, false);
    double blockedArea = blockers.pcfBlockedArea;
    double blockerDepthSum = blockers.pcfBlockerDepthSum;
    double blockerVariance = 0.0;
    double blockerUnoccluded = 1.0;
    if (blockers.vsmArea > 0.0)
    {
      blockerUnoccluded = pooledChebyshev(blockers, blockerVariance);
      const double occludedArea = blockers.vsmArea * (1.0 - blockerUnoccluded);
      blockedArea += occludedArea;
      blockerDepthSum += occludedArea * (d - bias_ - inputs_.satHalfStep) + blockers.vsmSum;
    }
    const double blockedThreshold = 1e-5 * search.area();
    noteDecision(blockedArea, blockedThreshold, blockedThreshold);
    if (recorder_)
    {
      recorder_->beginGroup("average blocker depth");
      recordPooled(blockers, blockerVariance, blockerUnoccluded);
      recorder_->quantity("blocked_area", blockedArea, "texels",
        cite("Eq. 3-4 ((1 - P(x >= t)) of the planar area, plus the PCF sub-kernels' blocked area, §5.2)"));
      recorder_->quantity("blocked_area_threshold", blockedThreshold, "texels",
        "ShadowLab: 1e-5 of w_i (no blocker: lit)");
    }
    if (!(blockedArea > blockedThreshold))
    {
      if (recorder_)
      {
        recorder_->category("blocker_decision", "no blocker: lit", cite("Alg. 1 L9-10 (no blocker in w_i)"));
      }
      return false;
    }
    result_.averageBlockerDepth = std::clamp(blockerDepthSum / blockedArea, geometry_.nearDepth, d);
    if (recorder_)
    {
      recorder_->quantity("avg_blocker_depth", result_.averageBlockerDepth, "linear depth",
        cite("Eq. 4 with z_unocc = t, combined with the PCF sub-kernels' blocker depths (§5.2), clamped to [near, d]"));
    }
    return true;
  }

  // Alg. 1 L16: the penumbra kernel w_p, the light's extent seen from the receiver at z_avg; its half extent
  // in texels (the shader's penumbraKernel).
  glm::dvec2 penumbraKernel()
  {
    const glm::dvec2 filterHalf = geometry_.kernelHalfTexels(result_.averageBlockerDepth);
    result_.penumbraKernelTexels = 2.0 * std::max(filterHalf.x, filterHalf.y);
    if (recorder_)
    {
      recorder_->beginGroup("penumbra kernel");
      recorder_->quantity("penumbra_half_texels", filterHalf, "texels",
        cite("Alg. 1 L16 (w_p: the light's extent seen from the receiver, at z_avg; PCSS step 2)"));
      recorder_->quantity("penumbra_kernel_texels", result_.penumbraKernelTexels, "texels", cite("Alg. 1 L16 (w_p)"));
      // The estimate on the receiver (PCSS step 2) that w_p scales down to the plane at z_avg; the probe figure
      // draws it with its similar triangles.
      recorder_->quantity("penumbra_width",
        geometry_.lightSize * (geometry_.d - result_.averageBlockerDepth) / result_.averageBlockerDepth, "world units",
        "Fernando 2005 step 2: w_penumbra = (d_receiver - d_blocker) w_light / d_blocker");
    }
    return filterHalf;
  }

  // §6.4 (contact_test = blocker_average): d - z_occ < eps r, once per pixel with Eq. 4's average (the
  // shader's contactTest).
  bool contactTest()
  {
    const double d = geometry_.d;
    const double contactDistance = settings_.contactThreshold * inputs_.sceneRadius;
    noteDecision(d - result_.averageBlockerDepth, contactDistance, d);
    const bool contact = d - result_.averageBlockerDepth < contactDistance;
    if (recorder_)
    {
      recorder_->beginGroup("contact test");
      recorder_->quantity("receiver_minus_blocker_depth", d - result_.averageBlockerDepth, "linear depth",
        cite("§6.4 (d - z_occ)"));
      recorder_->quantity("contact_distance", contactDistance, "linear depth", cite("§6.4 (eps = 0.01 r)"));
      recorder_->category("contact_decision", contact ? "contact: PCF over w_p" : "no contact: the SAT",
        cite("§6.4 (d - z_occ < eps: 3 x 3 jittered bilinear PCF instead of the SAT)"));
    }
    return contact;
  }

  // Alg. 1 L17-20: the visibility over w_p, L = Chebyshev (Eq. 1) over the pooled planar sub-kernels (Eq. 5),
  // the lit area and the PCF leaves, weighted by their areas (Alg. 2 L29-32), clamped to [0, 1]. The shader's
  // filterPenumbraKernel.
  double filterPenumbraKernel(const glm::dvec2& uv, const glm::dvec2& filterHalf, bool contactPerSubkernel)
  {
    const TexelRectangle filter = kernelRectangle(uv, filterHalf, geometry_.mapSize, &result_.kernelEdgeMargin);
    if (recorder_)
    {
      recorder_->beginGroup("penumbra kernel");
      recorder_->kernel({ "penumbra", glm::dvec2(filter.lo), glm::dvec2(filter.hi + 1), "", cite("Alg. 1 L16 (w_p)") });
    }
    beginStep("penumbra");
    const Accumulation shadow = subdivide(filter.lo, filter.hi, settings_.shadowSubdivision, contactPerSubkernel);
    double chebyshevLit = 0.0;
    double shadowVariance = 0.0;
    if (shadow.vsmArea > 0.0)
    {
      chebyshevLit = pooledChebyshev(shadow, shadowVariance);
    }
    const double totalArea = shadow.vsmArea + shadow.litArea + shadow.pcfArea;
    const double visibility =
      (chebyshevLit * shadow.vsmArea + shadow.litArea + shadow.pcfArea - shadow.pcfBlockedArea) / totalArea;
    if (recorder_)
    {
      recorder_->beginGroup("visibility");
      recordPooled(shadow, shadowVariance, chebyshevLit);
      recorder_->quantity("unclamped_visibility", visibility, "",
        cite("Alg. 2 L29-32 ((L VSMArea + LitArea + PCFArea - PCFBArea) / (VSMArea + LitArea + PCFArea))"));
    }
    return std::clamp(visibility, 0.0, 1.0);
  }

private:
  // The probe's record of a step's pooled moments and Chebyshev bound (Eq. 5, Eq. 1).
  void recordPooled(const Accumulation& acc, double variance, double unoccluded)
  {
    recorder_->quantity("vsm_area", acc.vsmArea, "texels", cite("Alg. 2 L17 (VSMArea: planar sub-kernels)"));
    recorder_->quantity("lit_area", acc.litArea, "texels", cite("Alg. 2 L12 (LitArea)"));
    recorder_->quantity("pcf_area", acc.pcfArea, "texels", cite("Alg. 2 L24 (PCFArea: non-planar leaves, contact)"));
    recorder_->quantity("pcf_blocked_area", acc.pcfBlockedArea, "texels", cite("Alg. 2 L25 (PCFBArea)"));
    if (acc.vsmArea > 0.0)
    {
      recorder_->quantity("pooled_mean_offset", acc.vsmSum / acc.vsmArea, "linear depth", cite("Eq. 5 (mu - t)"));
      recorder_->quantity("pooled_variance", variance, "linear depth^2",
        cite("Eq. 5 (sigma^2, floored at min_variance d^2)"));
      recorder_->quantity("chebyshev_unoccluded", unoccluded, "", cite("Eq. 1 (p_max(t) = P(x >= t) on Eq. 5's moments)"));
    }
  }
  const VssmReferenceInputs& inputs_;
  const VssmSettings& settings_;
  const SoftShadowGeometry& geometry_;
  double bias_;
  glm::dmat2 contactJitter_;
  VssmSample& result_;
  ProbeRecorder* recorder_ = nullptr;
  std::string step_;
  int subKernelCount_ = 0;
  std::string lastDecision_; // the class of the sub-kernel visited last (the quad-tree node's decision)
  int contactSubkernels_ = 0;
};

// The buffers' values under their names (the probe sweep compares them with the GPU's at the pixel), those
// not recorded at their step yet.
void recordResultBuffers(ProbeRecorder& recorder, const VssmSample& result)
{
  recorder.beginGroup("result");
  const auto once = [&](const std::string& name, double value, const std::string& unit, const std::string& source) {
    if (!recorder.record().find(name))
    {
      recorder.quantity(name, value, unit, source);
    }
  };
  once("blocker_kernel_texels", result.blockerKernelTexels, "texels", cite("Alg. 1 L7 (w_i)"));
  once("avg_blocker_depth", result.averageBlockerDepth, "linear depth", cite("Eq. 4 (0: not computed)"));
  once("penumbra_kernel_texels", result.penumbraKernelTexels, "texels", cite("Alg. 1 L16 (w_p; 0: not computed)"));
  recorder.quantity("subkernels_mean_not_in_front", result.subkernelsMeanNotInFront, "count",
    cite("§5.1 (sub-kernels with E(x) >= t: lit, refined or point-sampled; both steps)"));
  recorder.quantity("quadtree_nodes_visited", result.quadtreeNodesVisited, "count",
    cite("Alg. 2 L4 (linear quad-tree nodes traversed, both steps)"));
  recorder.quantity("pcf_samples", result.pcfSamples, "count",
    cite("§5.1 option 2 and §6.4 (point-sampled depth comparisons)"));
  const int code = static_cast<int>(result.classification);
  recordCode(recorder, "classification", code, vssmCategories[code].label, cite("Alg. 1 L9-20 (how the pixel was decided)"));
  recorder.quantity("visibility", result.sample.visibility, "", cite("Alg. 1 L20-21 / Alg. 2 L29-32"));
}

} // namespace

// Alg. 1 L7-20 for one pixel, in the steps of VssmVisibility.glsl's main(), with the same names.
VssmSample vssmReference(const VssmReferenceInputs& inputs, const VssmSettings& settings, int x, int y,
  ProbeRecorder* recorder)
{
  VssmSample result;
  const ShadowMapInputs& shadowMap = *inputs.shadowMap;
  const ShadowLookup lookup = prepareShadowLookup(shadowMap, settings.bias, x, y, recorder);
  result.sample = lookup.sample;
  const auto finish = [&](double visibility, VssmClass classification) {
    result.sample.visibility = visibility;
    result.classification = classification;
    if (recorder)
    {
      recordResultBuffers(*recorder, result);
    }
    return result;
  };
  if (!lookup.sample.evaluated)
  {
    if (recorder)
    {
      recordResultBuffers(*recorder, result);
    }
    return result;
  }
  const SoftShadowGeometry geometry =
    softShadowGeometry(shadowMap, lookup, settings.receiverPlaneBias, x, y);
  VssmEvaluation evaluation(inputs, settings, geometry, lookup.sample.bias, pixelRotation(x, y), result, recorder);
  const bool contactPerSubkernel = settings.contactTest == VssmContactTest::SubkernelMean;
  const glm::dvec2 uv = lookup.sm.uvTexels;
  const TexelRectangle search = evaluation.initialKernel(uv);
  if (settings.hsmEarlyOut)
  {
    if (const std::optional<VssmClass> decided = evaluation.hsmEarlyOut(search))
    {
      return finish(*decided == VssmClass::Lit ? 1.0 : 0.0, *decided);
    }
  }
  if (!evaluation.estimateAverageBlockerDepth(search))
  {
    return finish(1.0, VssmClass::Lit);
  }
  const glm::dvec2 filterHalf = evaluation.penumbraKernel();
  if (!contactPerSubkernel && evaluation.contactTest())
  {
    return finish(evaluation.contactShadow(uv, filterHalf, pixelRotation(x, y)), VssmClass::Contact);
  }
  const double visibility = evaluation.filterPenumbraKernel(uv, filterHalf, contactPerSubkernel);
  return finish(visibility, evaluation.contactSubkernels() > 0 ? VssmClass::Contact : VssmClass::Penumbra);
}

} // namespace sl
