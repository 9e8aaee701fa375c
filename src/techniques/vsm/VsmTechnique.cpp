#include "techniques/vsm/VsmTechnique.h"


#include "structures/moments/MomentMapStructure.h"
#include "structures/shadowmap/ShadowMapStructure.h"

#include "techniques/MomentReference.h"
#include "techniques/MomentTechniquePass.h"
#include "techniques/ProbeSupport.h"
#include "techniques/ShadowMapParameters.h"

#include <algorithm>

namespace sl
{

VsmSettings VsmSettings::from(const ParameterValues& values)
{
  VsmSettings settings;
  settings.bias = biasSettings(values);
  settings.prefilter = MomentPrefilterSettings::from(values);
  settings.lightBleedingReduction = values.get("light_bleeding_reduction");
  settings.minVariance = values.get("min_variance");
  return settings;
}

TechniqueDescriptor vsmTechnique()
{
  TechniqueDescriptor descriptor = describeShadowMapTechnique("vsm", "Variance shadow maps",
    "Donnelly & Lauritzen 2006; Lauritzen 2007 (light bleeding); survey §6; VSSM §4.1");
  for (ParameterSpec& spec : descriptor.parameters)
  {
    // VSM compares the receiver's own depth: the variance (and its floor) absorbs the depth slope within the
    // filter region, and a bias would inflate p_max (Chebyshev is exact at t = the receiver's depth).
    if (spec.name == "bias_constant_texels" || spec.name == "bias_slope_texels")
    {
      spec.defaultValue = 0.0;
    }
  }
  const std::vector<ParameterSpec>& prefilter = momentMapStructure().parameters;
  descriptor.addParameters(prefilter);
  descriptor.addParameters({
    { "light_bleeding_reduction", 0.2, 0, 0.99, "", "p_max below this amount becomes 0 and [amount, 1] maps to [0, 1] (Lauritzen 2007)", {}, false },
    { "min_variance", 1e-6, 0, 0.01, "d^2", "floor of the variance, relative to the squared receiver depth (float cancellation in E[z^2] - E[z]^2)", {}, false },
  });
  descriptor.lightStructures = { &shadowMapStructure(), &momentMapStructure() };
  descriptor.buffers = {
    { "p_max", "", "Chebyshev upper bound on the lit fraction, before light-bleeding reduction" },
    onShadowTestedPixels({ "light_leak", "", "p_max minus pcf over the same box of texels (pcf's default bias): > 0 where VSM bleeds light", BufferKind::Signed }),
    { "kernel_texels", "texels", "width of the prefilter box" },
    depthBiasBuffer(),
  };
  descriptor.lightSpaceRequest = [](const ParameterValues& values) {
    return LightSpaceRequest{ "prefilter_texels", static_cast<double>(VsmSettings::from(values).prefilter.texels) };
  };
  descriptor.createPass = momentTechniquePass("vsm/VsmVisibility.glsl");
  descriptor.probe = [](const ProbeContext& context, glm::ivec2 pixel, ProbeRecorder& recorder) {
    const VsmSettings settings = VsmSettings::from(context.frame->parameters);
    requireBlurPrefilter(settings.prefilter);
    const ShadowMapInputs inputs = shadowMapInputsOf(*context.frame, *context.scene, context.lightIndex);
    const VsmSample sample = vsmReference(inputs, settings, pixel.x, pixel.y, &recorder);
    // MomentTest: <= 2e-3 where the variance is at least 1e-3 d^2; below it E[z^2] - E[z]^2 cancels in float
    // (~1e-5 d^2 after the blur) and the pixel is not compared.
    ProbeOutcome outcome = probeOutcome(sample.sample, 2e-3, "vsmReference (vsm/VsmTechnique.h), double precision, prefilter = blur");
    if (sample.sample.evaluated)
    {
      const ShadowLookup lookup = prepareShadowLookup(inputs, settings.bias, pixel.x, pixel.y);
      const double d = lookup.sm.depthLin;
      noteAmbiguity(outcome.ambiguity, "variance / d^2 (float cancellation in E[z^2] - E[z]^2)", sample.variance / (d * d), 1e-3);
      noteMomentTexelEdge(outcome.ambiguity, lookup.sm.uvTexels);
    }
    return outcome;
  };
  descriptor.accuracy = prefilteredCentreShadowAccuracy();
  return descriptor;
}

VsmSample vsmReference(const ShadowMapInputs& inputs, const VsmSettings& settings, int x, int y,
  ProbeRecorder* recorder)
{
  VsmSample result;
  const ShadowLookup lookup = prepareShadowLookup(inputs, settings.bias, x, y, recorder);
  result.sample = lookup.sample;
  if (!lookup.sample.evaluated)
  {
    return result;
  }
  const int width = settings.prefilter.texels;
  if (recorder)
  {
    recordMomentBox(*recorder, inputs, lookup, width);
  }
  const FilteredMoments moments = boxMoments(inputs, lookup.sm.uvTexels, width, 0.0, recorder);
  const double d = lookup.sm.depthLin;
  result.variance = std::max(moments.second - moments.mean * moments.mean, settings.minVariance * d * d);
  const double t = lookup.comparisonDepth;
  result.pMax = t <= moments.mean ? 1.0 : result.variance / (result.variance + (t - moments.mean) * (t - moments.mean));
  const double amount = settings.lightBleedingReduction;
  result.sample.visibility = std::clamp((result.pMax - amount) / (1.0 - amount), 0.0, 1.0);
  if (recorder)
  {
    recorder->quantity("mean", moments.mean, "linear depth", "Donnelly & Lauritzen 2006 (M1 = E[z] over the filter region)");
    recorder->quantity("second_moment", moments.second, "linear depth^2", "Donnelly & Lauritzen 2006 (M2 = E[z^2])");
    recorder->quantity("variance_unfloored", moments.second - moments.mean * moments.mean, "linear depth^2",
      "Eq. 1, VSSM (Yang et al. 2010): sigma^2 = E[z^2] - E[z]^2");
    recorder->quantity("variance", result.variance, "linear depth^2",
      "ShadowLab (min_variance): sigma^2 floored at min_variance d^2 against float cancellation");
    recorder->beginGroup("chebyshev");
    recorder->quantity("compared_depth", t, "linear depth", "Eq. 1, VSSM (Yang et al. 2010): t, the receiver's depth minus the bias");
    recorder->quantity("p_max", result.pMax, "",
      "Eq. 1, VSSM (Yang et al. 2010): p_max = sigma^2 / (sigma^2 + (t - mu)^2) for t > mu, else 1 (Donnelly & Lauritzen 2006)");
    recorder->quantity("light_bleeding_reduction", amount, "", "Lauritzen 2007 (GPU Gems 3 ch. 8): [amount, 1] -> [0, 1]");
    recorder->quantity("visibility", result.sample.visibility, "", "Lauritzen 2007: clamp((p_max - amount) / (1 - amount), 0, 1)");
    recorder->beginGroup("light leak");
  }
  // The leak's PCF compares as `pcf` does (its default bias), not with t: unbiased, a receiver sloped in depth
  // fails against its own texels and the "leak" would be p_max minus self-shadowing.
  const double leakDepth = prepareShadowLookup(inputs, defaultBiasSettings(), x, y).comparisonDepth;
  const double pcf = boxPcf(inputs, lookup.sm.uvTexels, leakDepth, width, recorder);
  result.lightLeak = result.pMax - pcf;
  if (recorder)
  {
    recordLightLeak(*recorder, result.pMax, pcf,
      boxPcfRange(inputs, lookup.sm.uvTexels, leakDepth, width, probeDepthAmbiguity),
      "Lauritzen 2007 (light bleeding): p_max - PCF over the same box");
  }
  return result;
}

} // namespace sl
