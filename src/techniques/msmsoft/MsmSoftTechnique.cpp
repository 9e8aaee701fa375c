#include "techniques/msmsoft/MsmSoftTechnique.h"

#include "lightspace/MomentSummedAreaTable.h"
#include "structures/momentsat/MomentSatStructure.h"
#include "structures/shadowmap/ShadowMapStructure.h"
#include "techniques/ApproximationRules.h"
#include "techniques/MomentReference.h"
#include "techniques/ProbeSupport.h"
#include "techniques/ShadowMapParameters.h"
#include "techniques/msmsoft/vtkSLMsmSoftPass.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sl
{

namespace
{

// The light-leak PCF's grid cap, declared as the PCSS family declares it.
ParameterSpec msmSoftMaxGridTapsParameter()
{
  for (const ParameterSpec& spec : softShadowParameters())
  {
    if (spec.name == "max_grid_taps")
    {
      return spec;
    }
  }
  return {};
}

// What MsmSoftVisibility.glsl's supportWeight computes: the weight of zi in the three-point distribution on
// (zi, zj, zk) with moments 1, b1, b2 (Lagrange); 0 where two support points coincide.
double msmSoftSupportWeight(double zi, double zj, double zk, const glm::dvec4& b)
{
  const double denominator = (zi - zj) * (zi - zk);
  return std::abs(denominator) > 1e-20 ? (zj * zk - b.x * (zj + zk) + b.y) / denominator : 0.0;
}

void recordHamburger(ProbeRecorder& recorder, const std::string& prefix, const MsmReconstruction& msm, const char* source)
{
  const auto name = [&](const char* quantity) { return prefix + quantity; };
  recorder.quantity(name("biased_moments"), glm::dvec3(msm.biasedMoments.x, msm.biasedMoments.y, msm.biasedMoments.z), "",
    std::string(source) + "; MSM Alg. 3, moment bias: b' = (1 - alpha) b + alpha (0.5, 0.5, 0.5, 0.5), components 1-3");
  recorder.quantity(name("biased_moment_4"), msm.biasedMoments.w, "", "MSM Alg. 3, moment bias: b4'");
  recorder.quantity(name("pivot_d22"), msm.pivot2, "", "MSM Alg. 3, Cholesky solve: D22 = b2' - b1'^2");
  recorder.quantity(name("hankel_pivot"), msm.pivot3, "", "MSM Alg. 3, Cholesky solve: D33 = det(B) / D22, the last pivot");
  recorder.quantity(name("polynomial"), msm.polynomial, "", "MSM Alg. 3, Cholesky solve: c solving B c = (1, z_f, z_f^2)");
  recorder.quantity(name("support_depth_near"), msm.supportNear, "moment depth", "MSM Alg. 3, quadratic: the smaller root of c1 + c2 z + c3 z^2");
  recorder.quantity(name("support_depth_far"), msm.supportFar, "moment depth", "MSM Alg. 3, quadratic: the larger root");
  recorder.quantity(name("support_weights"), msm.weights, "",
    "ShadowLab (Lagrange): weights of z_f and the two support points in the distribution matching 1, b1', b2'");
}


// Steps 4-6 of MsmSoftVisibility.glsl from the search moments and z_f; `filterShift` is added to the filter
// moments (the rounding sensitivity moves them, 0 otherwise).
struct MsmSoftSteps
{
  MsmSoftBlockers blockers;
  double averageBlockerDepth = 0.0;
  glm::dvec2 filterHalfTexels{ 0.0 };
  glm::dvec2 filterMin{ 0.0 };
  glm::dvec2 filterMax{ 0.0 };
  glm::dvec4 filterMoments{ 0.0 };
  MsmReconstruction filter;
};

MsmSoftSteps msmSoftSteps(const glm::dvec4& searchMoments, double zf, const glm::dvec4& filterShift,
  const glm::dvec2& uv, const glm::dvec2& searchHalfTexels, const SoftShadowGeometry& geometry, const LightView& view,
  const MsmSoftSettings& settings, const MomentSatTable& momentTable)
{
  MsmSoftSteps steps;
  // Step 4, back to linear depth.
  steps.blockers = msmSoftBlockers(searchMoments, settings.momentBias, settings.fullyLitBias, zf);
  steps.averageBlockerDepth = view.nearDepth + steps.blockers.averageDepth * (view.farDepth - view.nearDepth);
  // Step 5.
  const glm::dvec2 minimumHalf(0.5 * settings.minKernelTexels);
  steps.filterHalfTexels = glm::min(glm::max(geometry.kernelHalfTexels(steps.averageBlockerDepth), minimumHalf),
    glm::max(searchHalfTexels, minimumHalf));
  // Step 6.
  steps.filterMin = uv - steps.filterHalfTexels;
  steps.filterMax = uv + steps.filterHalfTexels;
  steps.filterMoments = momentFractionalBoxMean(momentTable, steps.filterMin, steps.filterMax) + filterShift;
  steps.filter = msmHamburger4(steps.filterMoments, settings.momentBias, zf);
  return steps;
}

} // namespace

MsmSoftSettings MsmSoftSettings::from(const ParameterValues& values)
{
  MsmSoftSettings settings;
  settings.bias = biasSettings(values);
  settings.momentBias = values.get("moment_bias");
  settings.fullyLitBias = values.get("fully_lit_bias");
  settings.minKernelTexels = values.get("min_kernel_texels");
  settings.maxGridTaps = values.getInt("max_grid_taps");
  settings.receiverPlaneBias = receiverPlaneBiasOf(values);
  settings.satFormat = momentSatFormat(values);
  return settings;
}

TechniqueDescriptor msmSoftTechnique()
{
  TechniqueDescriptor descriptor = describeShadowMapTechnique("msmsoft", "Moment soft shadow mapping",
    "Peters, Münstermann, Wetzstein & Klein 2016 (I3D; JCGT 6(1) 2017), with PCSS's search kernel (Fernando 2005)");
  descriptor.addParameters(momentSatStructure().parameters);
  descriptor.addParameters({
    momentBiasParameter(), // in the blocker search and the filter
    { "fully_lit_bias", 1e-3, 1e-6, 0.1, "",
      "epsilon of the average blocker depth z_avg = (epsilon z_f + sum w_i z_i) / (epsilon + G_b) (the authors' "
      "constant): without blockers z_avg -> z_f and the kernel shrinks to min_kernel_texels", {}, false },
    { "min_kernel_texels", 1.0, 0.1, 64.0, "texels",
      "smallest width of the penumbra kernel (the filter over fewer texels is a hard shadow with msm's moment bias)", {}, false },
    msmSoftMaxGridTapsParameter(),
    receiverPlaneBiasParameter(),
  });
  descriptor.lightStructures = { &shadowMapStructure(), &momentSatStructure() };
  descriptor.buffers = {
    onShadowTestedPixels({ "light_leak", "", "visibility minus the PCF over the filter rectangle's integer cover (every texel it touches), "
      "compared as pcss filters (bias, receiver plane): > 0 where the moment bound leaks light", BufferKind::Signed }),
    { "blocker_kernel_texels", "texels", "width of the blocker search kernel w_i (PCSS's, VSSM Alg. 1 L7)" },
    { "blocker_intensity", "", "G_b: the weight of the canonical representation's support points in front of z_f over the search region" },
    { "avg_blocker_depth", "world units", "average blocker depth from the canonical representation (linear depth; the receiver's own depth minus the bias where no blocker)" },
    { "penumbra_kernel_texels", "texels", "width of the penumbra kernel (similar triangles at avg_blocker_depth, clamped to [min_kernel_texels, w_i])" },
    depthBiasBuffer(),
  };
  BufferSpec overflow{ "moment_sat_overflow", "",
    "1 where moment_sat_precision = int32 and the search box or the filter's integer cover holds more texels than the "
    "table sums exactly (moment_sat_max_kernel_texels squared): its sums wrapped, the value is wrong (0 otherwise)" };
  overflow.flagAtOrAbove = 0.5;
  overflow.flagWarning = "the int32 moment SAT's sums wrapped over boxes wider than moment_sat_max_kernel_texels; raise "
                         "it or use moment_sat_precision=int64";
  descriptor.buffers.push_back(overflow);
  // The filter step's Hamburger 4MSM, stored by the shader into an image (eight render targets at most).
  BufferSpec supportNear{ "support_depth_near", "moment depth",
    "z_2 of the filter step's Hamburger 4MSM, the nearer support point beside z_f (moment depth: (d - near) / (far - near))",
    BufferKind::Signed };
  BufferSpec supportFar{ "support_depth_far", "moment depth", "z_3 of the filter step, the farther one", BufferKind::Signed };
  BufferSpec pivot{ "hankel_pivot", "", "D33 of the filter step: the last pivot of the biased Hankel matrix (near 0: rounding dominates)" };
  for (BufferSpec* spec : { &supportNear, &supportFar, &pivot })
  {
    spec->fromPass = true;
    descriptor.buffers.push_back(*spec);
  }
  descriptor.supportedLights = { LightType::Area, LightType::Point, LightType::Spot };
  descriptor.coversLightArea = true;
  descriptor.createPass = newTechniquePass<vtkSLMsmSoftPass>;
  descriptor.probe = [](const ProbeContext& context, glm::ivec2 pixel, ProbeRecorder& recorder) {
    const MsmSoftSettings settings = MsmSoftSettings::from(context.frame->parameters);
    const ShadowMapInputs inputs = shadowMapInputsOf(*context.frame, *context.scene, context.lightIndex);
    const MomentSatTable table = momentSummedAreaTable(
      inputs.shadowMapLinear, inputs.lightView.nearDepth, inputs.lightView.farDepth, settings.satFormat);
    const MsmSoftSample sample = msmSoftReference(inputs, settings, table, pixel.x, pixel.y, &recorder);
    // MsmSoftTest: within msmSoftTwinTolerance where the search edges and the pivots leave float rounding no say.
    ProbeOutcome outcome = probeOutcome(sample.sample, msmSoftTwinTolerance,
      "msmSoftReference (msmsoft/MsmSoftTechnique.h), double precision, exact box sums");
    if (sample.sample.evaluated)
    {
      noteAmbiguity(outcome.ambiguity, "search kernel edge from a texel centre (texels)", sample.searchEdgeMargin,
        probeTexelEdgeAmbiguity);
      if (sample.satOverflow)
      {
        outcome.ambiguity += std::string(outcome.ambiguity.empty() ? "" : ", ") +
          "int32 moment SAT: a box beyond moment_sat_max_kernel_texels^2 texels (the GPU's sums wrapped; the twin's are exact)";
      }
      recorder.beginGroup("conditioning");
      recorder.quantity("rounding_sensitivity", sample.sensitivity.visibility, "",
        "ShadowLab: sum of |visibility change| when a search or filter moment or z_f moves by 1e-6 (float rounding); "
        "ill-conditioned above 1e-3");
      noteAmbiguity(outcome.ambiguity, "headroom against float rounding (1e-3 / rounding sensitivity)",
        msmSoftSensitivityLimit / std::max(sample.sensitivity.visibility, 1e-300), 1.0);
      // A root of a nearly linear or degenerate quadratic (c3 near 0, a lit kernel) moves far with the moments: the
      // recorded support depths may then differ from the GPU's float ones though the visibility agrees, so the probe
      // counts them instead of comparing them (as the tests do every ill-conditioned quantity).
      recorder.quantity("support_depth_sensitivity", sample.sensitivity.supportDepth, "",
        "ShadowLab: sum of the support depths' largest change (relative beyond 1) when a moment or z_f moves by 1e-6; "
        "ill-conditioned above 1e-3");
    }
    return outcome;
  };
  // PCSS's single average blocker depth (here from the moments), then the moment bound over the kernel instead of
  // its PCF: a lower bound on the shadow, equal where the kernel's depths are two-valued.
  descriptor.accuracy = momentBoundSoftShadowContract(
    { "moment bound", "the value differs from the kernel's PCF by more than 0.01 (light_leak)" }, 0.1);
  return descriptor;
}

MsmSoftBlockers msmSoftBlockers(const glm::dvec4& searchMoments, double momentBias, double fullyLitBias, double zf)
{
  MsmSoftBlockers result;
  result.canonical = msmHamburger4(searchMoments, momentBias, zf);
  const glm::dvec4& b = result.canonical.biasedMoments;
  const double z1 = result.canonical.supportNear;
  const double z2 = result.canonical.supportFar;
  // >= 0 in exact arithmetic (B positive definite); floored against rounding as the shader does.
  result.weights = glm::dvec2(std::max(msmSoftSupportWeight(z1, zf, z2, b), 0.0),
    std::max(msmSoftSupportWeight(z2, zf, z1, b), 0.0));
  double weightedDepth = 0.0;
  if (z1 < zf)
  {
    result.intensity += result.weights.x;
    weightedDepth += result.weights.x * std::max(z1, 0.0);
  }
  if (z2 < zf)
  {
    result.intensity += result.weights.y;
    weightedDepth += result.weights.y * std::max(z2, 0.0);
  }
  result.averageDepth =
    std::clamp((fullyLitBias * zf + weightedDepth) / (fullyLitBias + result.intensity), 0.0, std::max(zf, 0.0));
  return result;
}

MsmSoftSample msmSoftReference(const ShadowMapInputs& inputs, const MsmSoftSettings& settings,
  const MomentSatTable& momentTable, int x, int y, ProbeRecorder* recorder)
{
  MsmSoftSample result;
  const ShadowLookup lookup = prepareShadowLookup(inputs, settings.bias, x, y, recorder);
  result.sample = lookup.sample;
  if (!lookup.sample.evaluated)
  {
    return result;
  }
  const LightView& view = inputs.lightView;
  const double range = view.farDepth - view.nearDepth;
  const int size = inputs.shadowMapLinear.width;
  const glm::dvec2 uv = lookup.sm.uvTexels;
  const SoftShadowGeometry geometry = softShadowGeometry(inputs, lookup, settings.receiverPlaneBias, x, y);

  // Step 1.
  result.fragmentDepth = (lookup.comparisonDepth - view.nearDepth) / range;
  const double zf = result.fragmentDepth;
  // Steps 2-3.
  result.searchHalfTexels = geometry.kernelHalfTexels(geometry.nearDepth);
  const TexelRectangle search = kernelRectangle(uv, result.searchHalfTexels, size, &result.searchEdgeMargin);
  result.searchLo = search.lo;
  result.searchHi = search.hi;
  result.searchMoments = momentBoxMean(momentTable, search.lo, search.hi);
  // Steps 4-6.
  const MsmSoftSteps steps =
    msmSoftSteps(result.searchMoments, zf, glm::dvec4(0.0), uv, result.searchHalfTexels, geometry, view, settings, momentTable);
  result.blockers = steps.blockers;
  result.averageBlockerDepth = steps.averageBlockerDepth;
  result.filterHalfTexels = steps.filterHalfTexels;
  result.filterMin = steps.filterMin;
  result.filterMax = steps.filterMax;
  result.filterMoments = steps.filterMoments;
  result.filter = steps.filter;
  // How far float rounding of the moments and of z_f (msmSoftMomentRounding) moves steps 4-6.
  const double kernel = 2.0 * std::max(steps.filterHalfTexels.x, steps.filterHalfTexels.y);
  for (int k = 0; k < 9; ++k)
  {
    MsmSoftSensitivity largest;
    for (const double sign : { -1.0, 1.0 })
    {
      glm::dvec4 searchMoments = result.searchMoments;
      glm::dvec4 filterShift(0.0);
      double depth = zf;
      const double delta = sign * msmSoftMomentRounding;
      (k < 4 ? searchMoments[k] : k < 8 ? filterShift[k - 4] : depth) += delta;
      const MsmSoftSteps moved =
        msmSoftSteps(searchMoments, depth, filterShift, uv, result.searchHalfTexels, geometry, view, settings, momentTable);
      const double movedKernel = 2.0 * std::max(moved.filterHalfTexels.x, moved.filterHalfTexels.y);
      largest.visibility = std::max(largest.visibility, std::abs(moved.filter.shadowIntensity - steps.filter.shadowIntensity));
      largest.blockerIntensity = std::max(largest.blockerIntensity,
        std::abs(std::min(moved.blockers.intensity, 1.0) - std::min(steps.blockers.intensity, 1.0)));
      largest.averageDepth = std::max(largest.averageDepth,
        std::abs(moved.averageBlockerDepth - steps.averageBlockerDepth) / steps.averageBlockerDepth);
      largest.kernel = std::max(largest.kernel, std::abs(movedKernel - kernel) / kernel);
      for (const auto root : { &MsmReconstruction::supportNear, &MsmReconstruction::supportFar })
      {
        largest.supportDepth = std::max(largest.supportDepth,
          std::abs(moved.filter.*root - steps.filter.*root) / std::max(1.0, std::abs(steps.filter.*root)));
      }
    }
    result.sensitivity.visibility += largest.visibility;
    result.sensitivity.blockerIntensity += largest.blockerIntensity;
    result.sensitivity.averageDepth += largest.averageDepth;
    result.sensitivity.kernel += largest.kernel;
    result.sensitivity.supportDepth += largest.supportDepth;
  }
  result.sample.visibility = 1.0 - result.filter.shadowIntensity;
  result.coverLo = glm::clamp(glm::ivec2(glm::floor(result.filterMin)), glm::ivec2(0), glm::ivec2(size - 1));
  result.coverHi = glm::clamp(glm::ivec2(glm::ceil(result.filterMax)) - 1, result.coverLo, glm::ivec2(size - 1));
  const double coverTexels =
    static_cast<double>(result.coverHi.x - result.coverLo.x + 1) * (result.coverHi.y - result.coverLo.y + 1);
  result.satOverflow = std::max(search.area(), coverTexels) > settings.satFormat.exactTexels();

  if (recorder)
  {
    recorder->beginGroup("blocker search (moments)");
    recorder->quantity("fragment_depth", zf, "moment depth",
      "MSM Alg. 3: z_f, the receiver's depth minus the bias, normalised as the moments' depths");
    recorder->quantity("light_size", geometry.lightSize, "world units", "Fernando 2005 (w_light; 0 for point and spot lights)");
    recorder->quantity("search_plane_depth", geometry.nearDepth, "linear depth",
      "Fernando 2005 step 1: the plane the search kernel w_i is measured on (the map's near plane)");
    recorder->quantity("blocker_kernel_texels", 2.0 * std::max(result.searchHalfTexels.x, result.searchHalfTexels.y),
      "texels", "Fernando 2005 step 1 (VSSM Alg. 1 L7): the search kernel w_i at the near plane");
    recorder->kernel({ "blocker search", uv - result.searchHalfTexels, uv + result.searchHalfTexels, "w_i",
      "Fernando 2005 step 1: the light's footprint at the near plane (the authors search a fixed kernel: README.md)" });
    recorder->kernel({ "search SAT box", glm::dvec2(search.lo), glm::dvec2(search.hi) + 1.0, "texels",
      "ShadowLab: the texels whose centres lie in w_i (kernelRectangle), summed exactly by the moment SAT" });
    recorder->quantity("search_box_texels", search.area(), "count", "ShadowLab: texels the search box sums cover");
    recorder->quantity("search_moments", glm::dvec3(result.searchMoments.x, result.searchMoments.y, result.searchMoments.z),
      "", "Peters et al. 2016: E[z], E[z^2], E[z^3] over the search box (exact box sums / texels)");
    recorder->quantity("search_moment_4", result.searchMoments.w, "", "Peters et al. 2016: E[z^4] over the search box");
    recorder->beginGroup("canonical representation");
    recordHamburger(*recorder, "search_", result.blockers.canonical, "Peters et al. 2016 (blocker search)");
    recorder->quantity("blocker_weights", result.blockers.weights, "",
      "Peters et al. 2016: weights of the two support points beside z_f, floored at 0");
    recorder->quantity("blocker_intensity", std::min(result.blockers.intensity, 1.0), "",
      "Peters et al. 2016: G_b, the weights of the support points in front of z_f");
    recorder->quantity("fully_lit_bias", settings.fullyLitBias, "", "Peters et al. 2016 (authors' code): epsilon");
    recorder->quantity("avg_blocker_moment_depth", result.blockers.averageDepth, "moment depth",
      "Peters et al. 2016: z_avg = (epsilon z_f + sum_{z_i < z_f} w_i z_i) / (epsilon + G_b)");
    recorder->quantity("avg_blocker_depth", result.averageBlockerDepth, "linear depth", "ShadowLab: near + z_avg (far - near)");
    recorder->beginGroup("penumbra kernel");
    recorder->quantity("penumbra_kernel_texels", 2.0 * std::max(result.filterHalfTexels.x, result.filterHalfTexels.y),
      "texels", "Fernando 2005 step 2 (similar triangles at z_avg), clamped to [min_kernel_texels, w_i]");
    recorder->kernel({ "penumbra", result.filterMin, result.filterMax, "w_p",
      "Peters et al. 2016: the filter rectangle with fractional edges (border texels weighted by their covered fraction)" });
    recorder->quantity("filter_moments", glm::dvec3(result.filterMoments.x, result.filterMoments.y, result.filterMoments.z),
      "", "Peters et al. 2016: E[z], E[z^2], E[z^3] over w_p, texels weighted by covered area");
    recorder->quantity("filter_moment_4", result.filterMoments.w, "", "Peters et al. 2016: E[z^4] over w_p");
    recorder->beginGroup("hamburger 4msm (filter)");
    recordHamburger(*recorder, "", result.filter, "Peters & Klein 2015 (filter)");
    recorder->quantity("shadow_intensity", result.filter.shadowIntensity, "",
      "MSM Alg. 3, weights: the weights of the support points in front of z_f, clamped to [0, 1]");
    recorder->quantity("visibility", result.sample.visibility, "", "ShadowLab: 1 - shadow intensity");
    recorder->beginGroup("light leak");
    recorder->kernel({ "light-leak cover", glm::dvec2(result.coverLo), glm::dvec2(result.coverHi) + 1.0, "texels",
      "ShadowLab: the texels w_p touches, compared as pcss filters" });
  }
  PcfRange leakRange;
  const double pcf = rectanglePcf(inputs, geometry, settings.maxGridTaps, lookup.sample.bias, result.coverLo,
    result.coverHi, recorder ? &leakRange : nullptr, recorder);
  result.lightLeak = result.sample.visibility - pcf;
  if (recorder)
  {
    recordLightLeak(*recorder, result.sample.visibility, pcf, leakRange,
      "ShadowLab: visibility - PCF over w_p's integer cover, compared as pcss filters");
  }
  return result;
}

} // namespace sl
