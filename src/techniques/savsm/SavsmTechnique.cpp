#include "techniques/savsm/SavsmTechnique.h"

#include "techniques/ApproximationRules.h"

#include "structures/sat/SatStructure.h"
#include "structures/shadowmap/ShadowMapStructure.h"

#include "techniques/MomentReference.h"
#include "techniques/ProbeSupport.h"
#include "techniques/ShadowMapParameters.h"
#include "techniques/SoftShadowSupport.h"
#include "techniques/PcssReference.h"
#include "lightspace/SummedAreaTable.h"
#include "techniques/savsm/vtkSLSavsmPass.h"

#include <algorithm>
#include <cmath>

namespace sl
{

SavsmSettings SavsmSettings::from(const ParameterValues& values)
{
  SavsmSettings settings;
  settings.pcss = PcssSettings::from(values);
  settings.sat = summedAreaTableSettings(values);
  settings.lightBleedingReduction = values.get("light_bleeding_reduction");
  settings.minVariance = values.get("min_variance");
  return settings;
}

TechniqueDescriptor savsmTechnique()
{
  TechniqueDescriptor descriptor = describeShadowMapTechnique("savsm", "SAT-based variance soft shadow mapping",
    "Lauritzen 2007 (GPU Gems 3 ch. 8); VSSM (Yang et al. 2010) §2.3 baseline; survey §6.4");
  // The bias applies to the blocker search (the receiver must not find itself); Chebyshev compares the
  // receiver's own depth, where it is exact for two depths (see vsm).
  const std::vector<ParameterSpec> soft = softShadowParameters();
  descriptor.addParameters(soft);
  descriptor.addParameters({
    { "sat_precision", 1, 0, 1, "", "float_centred: float SAT of z - (near + far) / 2; int32: 16-bit fixed point, exact box sums (survey §6.4)", { "float_centred", "int32" }, true },
    { "light_bleeding_reduction", 0.0, 0, 0.99, "", "p_max below this amount becomes 0 and [amount, 1] maps to [0, 1] (Lauritzen 2007)", {}, false },
    { "min_variance", 1e-6, 0, 0.01, "d^2", "floor of the variance, relative to the squared receiver depth", {}, false },
  });
  descriptor.lightStructures = { &shadowMapStructure(), &summedAreaTableStructure() };
  descriptor.buffers = {
    { "p_max", "", "Chebyshev upper bound on the lit fraction over w_p, before light-bleeding reduction" },
    onShadowTestedPixels({ "light_leak", "", "p_max minus the PCF over the same rectangle of texels, compared as pcss filters (bias, receiver plane)", BufferKind::Signed }),
    { "blocker_kernel_texels", "texels", "width of the blocker search kernel w_i (Alg. 1 L7)" },
    { "blocker_samples", "taps", "depth samples read in the blocker search" },
    { "avg_blocker_depth", "world units", "average depth of the blockers found (0: none, lit)" },
    { "penumbra_kernel_texels", "texels", "width of the penumbra kernel w_p (Alg. 1 L16)" },
    depthBiasBuffer(),
  };
  descriptor.supportedLights = { LightType::Area, LightType::Point, LightType::Spot };
  descriptor.coversLightArea = true;
  descriptor.createPass = newTechniquePass<vtkSLSavsmPass>;
  descriptor.probe = [](const ProbeContext& context, glm::ivec2 pixel, ProbeRecorder& recorder) {
    const SavsmSettings settings = SavsmSettings::from(context.frame->parameters);
    const ShadowMapInputs inputs = shadowMapInputsOf(*context.frame, *context.scene, context.lightIndex);
    const SavsmSample sample = savsmReference(inputs, settings, pixel.x, pixel.y, &recorder);
    // SavsmTest (sat_precision = int32): <= 2e-3 on pixels without a kernel edge within 1e-4 texel of a texel
    // centre, a comparison within float rounding, or a variance under 1e-3 d^2 (float cancellation).
    ProbeOutcome outcome =
      probeOutcome(sample.sample, 2e-3, "savsmReference (savsm/SavsmTechnique.h), double precision, exact box moments");
    if (sample.sample.evaluated)
    {
      noteAmbiguity(outcome.ambiguity, "grid kernel edge from a texel centre (texels)", sample.kernelEdgeMargin,
        probeTexelEdgeAmbiguity);
      if (sample.foundBlockers)
      {
        const ShadowLookup lookup = prepareShadowLookup(inputs, settings.pcss.bias, pixel.x, pixel.y);
        const double d = lookup.sm.depthLin;
        noteAmbiguity(outcome.ambiguity, "variance / d^2 (float cancellation in E[z^2] - E[z]^2)",
          sample.variance / (d * d), 1e-3);
        if (!settings.sat.integer)
        {
          // The twin sums exactly; the GPU's float table rounds each corner sum (sums over up to N^2 texels, so
          // the error grows with the map). SavsmTest compares visibility at int32 only; measured once at 512^2
          // maps, 96 x 80 (stacked-occluders, contact, bunny, near-light): max |GPU - twin| 5e-4 - 2.2e-3, over
          // the int32 tolerance on the bunny. No tolerance is claimed: the pixel is reported, not failed.
          outcome.ambiguity += std::string(outcome.ambiguity.empty() ? "" : ", ") +
            "sat_precision=float_centred (the GPU's float box sums are not replayed; compared at int32 only)";
        }
      }
    }
    return outcome;
  };
  // PCSS's average blocker depth (Fernando 2005), then the Chebyshev bound over the kernel instead of its PCF
  // (Lauritzen 2007): an upper bound, equal only where the kernel's depths are two-valued.
  descriptor.accuracy = momentBoundSoftShadowContract(
    { "chebyshev bound", "the value exceeds the kernel's PCF by more than 0.01 (light_leak)" }, 0.1);
  return descriptor;
}

namespace
{

// What SavsmVisibility.glsl's light_leak buffer compares p_max with: the PCF over the penumbra rectangle
// (rectanglePcf, common/RectanglePcf.glsl). With `recorder`, the taps and the light leak (recordLightLeak).
double lightLeakPcf(const ShadowMapInputs& inputs, const SoftShadowSettings& soft, const SoftShadowGeometry& geometry,
  double bias, glm::ivec2 lo, glm::ivec2 hi, double pMax, ProbeRecorder* recorder)
{
  PcfRange range;
  const double pcf = rectanglePcf(inputs, geometry, soft.maxGridTaps, bias, lo, hi, recorder ? &range : nullptr, recorder);
  if (recorder)
  {
    recordLightLeak(*recorder, pMax, pcf, range, "Lauritzen 2007 (light bleeding): p_max - PCF over w_p, compared as PCSS filters");
  }
  return pcf;
}

} // namespace

SavsmSample savsmReference(const ShadowMapInputs& inputs, const SavsmSettings& settings, int x, int y,
  ProbeRecorder* recorder)
{
  // Blocker search and w_p are PCSS's; its PCF step runs (the margins are the whole twin's) but is not recorded.
  const PcssSample pcss = pcssReference(inputs, settings.pcss, x, y, recorder, false);
  SavsmSample result;
  result.sample = pcss.sample;
  result.kernelEdgeMargin = pcss.kernelEdgeMargin;
  result.foundBlockers = pcss.foundBlockers;
  if (!pcss.sample.evaluated || !pcss.foundBlockers)
  {
    return result;
  }
  const TexelRectangle rectangle = kernelRectangle(pcss.uvTexels, pcss.filterHalfTexels, inputs.shadowMapLinear.width);
  result.lo = rectangle.lo;
  result.hi = rectangle.hi;
  const LightView& view = inputs.lightView;
  const bool integer = settings.sat.integer;
  const BoxMoments moments =
    exactBoxMoments(inputs.shadowMapLinear, result.lo, result.hi, view.nearDepth, view.farDepth, integer);
  const ShadowLookup lookup = prepareShadowLookup(inputs, settings.pcss.bias, x, y);
  const double d = lookup.sm.depthLin;
  const double t = d;
  result.variance = std::max(moments.variance, settings.minVariance * d * d);
  result.pMax = t <= moments.mean ? 1.0 : result.variance / (result.variance + (t - moments.mean) * (t - moments.mean));
  const double amount = settings.lightBleedingReduction;
  result.sample.visibility = std::clamp((result.pMax - amount) / (1.0 - amount), 0.0, 1.0);
  if (recorder)
  {
    recorder->beginGroup("moments (summed-area table)");
    recorder->category("sat_precision", integer ? "int32: 16-bit fixed point, exact box sums" : "float_centred: float sums of z - (near + far) / 2",
      "survey §6.4 (SAT precision)");
    recorder->kernel({ "SAT box", glm::dvec2(result.lo), glm::dvec2(result.hi) + 1.0, "w_p texels",
      "Lauritzen 2007 (GPU Gems 3 ch. 8): the kernel's moments from four SAT fetches" });
    recorder->quantity("box_texels", rectangle.area(), "count", "Lauritzen 2007: texels the box sums cover");
    recorder->quantity("mean", moments.mean, "linear depth", "Lauritzen 2007: E[z] over w_p (depths clamped to [near, far] as encoded)");
    recorder->quantity("variance_unfloored", moments.variance, "linear depth^2", "Eq. 1, VSSM (Yang et al. 2010): sigma^2 = E[z^2] - E[z]^2");
    recorder->quantity("variance", result.variance, "linear depth^2",
      "ShadowLab (min_variance): sigma^2 floored at min_variance d^2");
    recorder->beginGroup("chebyshev");
    recorder->quantity("compared_depth", t, "linear depth", "ShadowLab: t = d, the receiver's own depth (Chebyshev is exact there for two depths)");
    recorder->quantity("p_max", result.pMax, "",
      "Eq. 1, VSSM (Yang et al. 2010): p_max = sigma^2 / (sigma^2 + (t - mu)^2) for t > mu, else 1");
    recorder->quantity("light_bleeding_reduction", amount, "", "Lauritzen 2007 (GPU Gems 3 ch. 8): [amount, 1] -> [0, 1]");
    recorder->quantity("visibility", result.sample.visibility, "", "Lauritzen 2007: clamp((p_max - amount) / (1 - amount), 0, 1)");
    recorder->beginGroup("light leak");
  }
  const SoftShadowGeometry geometry =
    softShadowGeometry(inputs, lookup, settings.pcss.soft.receiverPlaneBias, x, y);
  result.lightLeak = result.pMax -
    lightLeakPcf(inputs, settings.pcss.soft, geometry, lookup.sample.bias, result.lo, result.hi, result.pMax, recorder);
  return result;
}

} // namespace sl
