#include "techniques/esm/EsmTechnique.h"


#include "structures/moments/MomentMapStructure.h"
#include "structures/shadowmap/ShadowMapStructure.h"

#include "techniques/MomentReference.h"
#include "techniques/MomentTechniquePass.h"
#include "techniques/ProbeSupport.h"
#include "techniques/ShadowMapParameters.h"

#include <algorithm>
#include <cmath>

namespace sl
{

BufferSpec esmBiasGainBuffer()
{
  // exp(c (z_n - t_n)) weighs a lit texel at the receiver's own depth by exp(c bias_n), not 1: the bias, in
  // texel footprints, grows with the texel, so on a small map one lit texel can outweigh a box of occluders
  // (stacked-occluders at shadow_map_size=16: e^5, every pixel lit). ESM's exponential holds only where no
  // texel lies behind the compared depth (survey §6: "for larger kernel sizes this approximation does not
  // hold"; VSSM §2.2: ESM "relies on standard PCF for non-planarity regions").
  BufferSpec spec{ "bias_gain", "",
    "exp(c bias_n): the weight the depth bias gives a lit texel at the receiver's own depth (1 = none); at 2 or more "
    "a half-lit box reads fully lit (0 where not tested)" };
  spec.flagAtOrAbove = 2.0;
  spec.flagWarning = "the depth bias, in texel footprints, doubles the weight of every lit texel in the exponential, "
                     "so those pixels read too bright (up to fully lit); use a larger shadow_map_size, a smaller "
                     "esm_exponent or bias_constant_texels/bias_slope_texels";
  return spec;
}

EsmSettings EsmSettings::from(const ParameterValues& values)
{
  EsmSettings settings;
  settings.bias = biasSettings(values);
  settings.prefilter = MomentPrefilterSettings::from(values);
  settings.exponent = values.get("esm_exponent");
  return settings;
}

TechniqueDescriptor esmTechnique()
{
  TechniqueDescriptor descriptor = describeShadowMapTechnique("esm", "Exponential shadow maps",
    "Annen, Mertens, Seidel, Flerackers & Kautz 2008; survey §6");
  const std::vector<ParameterSpec>& prefilter = momentMapStructure().parameters;
  descriptor.addParameters(prefilter);
  descriptor.addParameters({
    { "esm_exponent", 40, 1, 80, "", "c in exp(c (z_n - t_n)), depths normalised to the light's range: sharper with larger c", {}, false },
  });
  descriptor.lightStructures = { &shadowMapStructure(), &momentMapStructure() };
  descriptor.buffers = {
    onShadowTestedPixels({ "light_leak", "", "visibility minus pcf over the same box of texels (pcf's default bias)", BufferKind::Signed }),
    { "kernel_texels", "texels", "width of the prefilter box" },
    depthBiasBuffer(),
    esmBiasGainBuffer(),
  };
  descriptor.lightSpaceRequest = [](const ParameterValues& values) {
    const EsmSettings settings = EsmSettings::from(values);
    return LightSpaceRequest{ "prefilter_texels", static_cast<double>(settings.prefilter.texels), settings.exponent };
  };
  descriptor.createPass = momentTechniquePass("esm/EsmVisibility.glsl");
  descriptor.probe = [](const ProbeContext& context, glm::ivec2 pixel, ProbeRecorder& recorder) {
    const EsmSettings settings = EsmSettings::from(context.frame->parameters);
    requireBlurPrefilter(settings.prefilter);
    const ShadowMapInputs inputs = shadowMapInputsOf(*context.frame, *context.scene, context.lightIndex);
    const ReferenceSample sample = esmReference(inputs, settings, pixel.x, pixel.y, &recorder);
    // MomentTest: <= 1e-4 (the sums of exp(c z_n) are well conditioned in float).
    ProbeOutcome outcome = probeOutcome(sample, 1e-4, "esmReference (esm/EsmTechnique.h), double precision, prefilter = blur");
    if (sample.evaluated)
    {
      const ShadowLookup lookup = prepareShadowLookup(inputs, settings.bias, pixel.x, pixel.y);
      noteMomentTexelEdge(outcome.ambiguity, lookup.sm.uvTexels);
    }
    return outcome;
  };
  descriptor.accuracy = prefilteredCentreShadowAccuracy();
  return descriptor;
}

ReferenceSample esmReference(const ShadowMapInputs& inputs, const EsmSettings& settings, int x, int y,
  ProbeRecorder* recorder)
{
  ShadowLookup lookup = prepareShadowLookup(inputs, settings.bias, x, y, recorder);
  if (!lookup.sample.evaluated)
  {
    return lookup.sample;
  }
  const double exponent = settings.exponent;
  const int width = settings.prefilter.texels;
  if (recorder)
  {
    recordMomentBox(*recorder, inputs, lookup, width);
  }
  const FilteredMoments moments = boxMoments(inputs, lookup.sm.uvTexels, width, exponent, recorder);
  const LightView& view = inputs.lightView;
  const double t = (lookup.comparisonDepth - view.nearDepth) / (view.farDepth - view.nearDepth);
  const double unclamped = moments.exponential * std::exp(-exponent * t);
  lookup.sample.visibility = std::clamp(unclamped, 0.0, 1.0);
  if (recorder)
  {
    recorder->quantity("esm_exponent", exponent, "", "Annen et al. 2008 (c, the exponential's sharpness)");
    recorder->quantity("exponential_moment", moments.exponential, "",
      "Annen et al. 2008: E[exp(c z_n)] over the box, z_n = (z - near) / (far - near)");
    recorder->beginGroup("exponential test");
    recorder->quantity("normalized_compared_depth", t, "", "Annen et al. 2008: t_n = (d - bias - near) / (far - near)");
    recorder->quantity("exp_minus_c_t", std::exp(-exponent * t), "", "Annen et al. 2008: exp(-c t_n)");
    recorder->quantity("visibility_unclamped", unclamped, "", "Annen et al. 2008: E[exp(c z_n)] exp(-c t_n) (the step d <= z as exp(c (z_n - t_n)))");
    recorder->quantity("visibility", lookup.sample.visibility, "", "Annen et al. 2008: clamped to [0, 1]");
    recorder->beginGroup("light leak");
    // As `pcf` compares (its default bias), whatever esm's own bias (MomentLookup.glsl leakComparisonDepth).
    const double leakDepth = prepareShadowLookup(inputs, defaultBiasSettings(), x, y).comparisonDepth;
    const double pcf = boxPcf(inputs, lookup.sm.uvTexels, leakDepth, width, recorder);
    recordLightLeak(*recorder, lookup.sample.visibility, pcf,
      boxPcfRange(inputs, lookup.sm.uvTexels, leakDepth, width, probeDepthAmbiguity),
      "ShadowLab: visibility - PCF over the same box");
  }
  return lookup.sample;
}

} // namespace sl
