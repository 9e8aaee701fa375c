#include "techniques/convsm/ConvsmTechnique.h"

#include "structures/fourier/FourierBasisStructure.h"
#include "structures/moments/MomentMapStructure.h"
#include "structures/shadowmap/ShadowMapStructure.h"

#include "techniques/MomentReference.h"
#include "techniques/MomentTechniquePass.h"
#include "techniques/ProbeSupport.h"
#include "techniques/ShadowMapParameters.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sl
{

ConvsmSettings ConvsmSettings::from(const ParameterValues& values)
{
  ConvsmSettings settings;
  settings.bias = biasSettings(values);
  settings.prefilter = MomentPrefilterSettings::from(values);
  const FourierBasisSettings basis = FourierBasisSettings::from(values);
  settings.terms = basis.terms;
  settings.depthRange = basis.depthRange;
  settings.ringingAlpha = values.get("ringing_alpha");
  settings.reconstructionScale = values.get("reconstruction_scale");
  return settings;
}

double convsmFrequency(int k)
{
  return M_PI * (2.0 * k - 1.0);
}

double convsmDamping(int k, int terms, double alpha)
{
  const double kOverM = static_cast<double>(k) / terms;
  return std::exp(-alpha * kOverM * kOverM);
}

double convsmStepSeries(double dSeries, double zSeries, int terms, double alpha)
{
  double sum = 0.5;
  for (int k = 1; k <= terms; ++k)
  {
    const double ck = convsmFrequency(k);
    sum += 2.0 * convsmDamping(k, terms, alpha) / ck * std::sin(ck * (zSeries - dSeries));
  }
  return sum;
}

double convsmVisibility(double reconstruction, double reconstructionScale)
{
  return std::clamp(reconstructionScale * reconstruction, 0.0, 1.0);
}

double convsmNormalizedDepth(const ShadowMapInputs& inputs, double depthLin)
{
  const double nearDepth = inputs.lightView.nearDepth;
  const double farDepth = inputs.lightView.farDepth;
  return std::clamp((depthLin - nearDepth) / (farDepth - nearDepth), 0.0, 1.0);
}

double convsmSeriesDepth(const ShadowMapInputs& inputs, double depthLin, double depthRange)
{
  return depthRange * convsmNormalizedDepth(inputs, depthLin);
}

FourierCoefficients convsmBasisAverage(const ShadowMapInputs& inputs, const glm::dvec2& uvTexels, int width, int terms,
  double depthRange, ProbeRecorder* recorder)
{
  FourierCoefficients coefficients;
  coefficients.sine.assign(terms, 0.0);
  coefficients.cosine.assign(terms, 0.0);
  const double weight = 1.0 / (static_cast<double>(width) * width);
  visitPrefilterBox(inputs, uvTexels, width, [&](double z, const glm::ivec2& texel) {
    const double zSeries = convsmSeriesDepth(inputs, z, depthRange);
    for (int k = 1; k <= terms; ++k)
    {
      coefficients.sine[k - 1] += weight * std::sin(convsmFrequency(k) * zSeries);
      coefficients.cosine[k - 1] += weight * std::cos(convsmFrequency(k) * zSeries);
    }
    if (recorder)
    {
      recorder->texel({ texel, "fourier box", z, std::numeric_limits<double>::quiet_NaN(), false, weight });
    }
  });
  return coefficients;
}

double convsmReconstruct(double dSeries, const FourierCoefficients& coefficients, int terms, double alpha)
{
  double sum = 0.5;
  for (int k = 1; k <= terms; ++k)
  {
    const double ck = convsmFrequency(k);
    sum += 2.0 * convsmDamping(k, terms, alpha) / ck *
      (std::cos(ck * dSeries) * coefficients.sine[k - 1] - std::sin(ck * dSeries) * coefficients.cosine[k - 1]);
  }
  return sum;
}

TechniqueDescriptor convsmTechnique()
{
  // The bias keeps pcf's defaults: with reconstruction_scale 2 the scaled series reads 1 wherever every texel of
  // the box lies at or behind d (the partial sums of the step are >= 1/2 on [0, 1)), so the bias that makes a box
  // lit for pcf makes it lit here too (the public implementations' reconstruction offset plays this part).
  TechniqueDescriptor descriptor = describeShadowMapTechnique("convsm", "Convolution shadow maps",
    "Annen, Mertens, Bekaert, Seidel & Kautz 2007; survey §6");
  descriptor.addParameters(fourierBasisStructure().parameters);
  // The basis images are prefiltered as the moment map is, with its parameters (structures/fourier).
  descriptor.addParameters(momentMapStructure().parameters);
  descriptor.addParameters({
    { "ringing_alpha", 0, 0, 20, "",
      "alpha of the damping sigma_k = exp(-alpha (k / M)^2) of term k against ringing (CSM's ringing suppression; this form is not verified against the paper, see the page); 0: the plain truncated series", {}, false },
    { "reconstruction_scale", 2, 1, 4, "",
      "visibility = clamp(scale f, 0, 1) of the series f, mapping its 1/2 at z = d to lit (the form public CSM implementations use, clamp(2 f, 0, 1); not verified against the paper, see the page); 1: the raw series", {}, false },
  });
  descriptor.lightStructures = { &shadowMapStructure(), &fourierBasisStructure() };
  descriptor.buffers = {
    { "reconstruction", "", "the damped Fourier series of the filtered shadow test before clamping: outside [0, 1] where it rings", BufferKind::Signed },
    { "overshoot", "", "reconstruction minus its clamp to [0, 1]: > 0 above 1, < 0 below 0 (Gibbs ringing), 0 inside", BufferKind::Signed },
    onShadowTestedPixels({ "light_leak", "", "visibility minus pcf over the same box of texels (pcf's default bias): > 0 where it leaks light, < 0 where it darkens", BufferKind::Signed }),
    { "kernel_texels", "texels", "width of the prefilter box" },
    depthBiasBuffer(),
  };
  descriptor.lightSpaceRequest = [](const ParameterValues& values) {
    return LightSpaceRequest{ "prefilter_texels", static_cast<double>(ConvsmSettings::from(values).prefilter.texels) };
  };
  descriptor.createPass = momentTechniquePass("convsm/ConvsmVisibility.glsl");
  descriptor.probe = [](const ProbeContext& context, glm::ivec2 pixel, ProbeRecorder& recorder) {
    const ConvsmSettings settings = ConvsmSettings::from(context.frame->parameters);
    requireBlurPrefilter(settings.prefilter);
    const ShadowMapInputs inputs = shadowMapInputsOf(*context.frame, *context.scene, context.lightIndex);
    const ConvsmSample sample = convsmReference(inputs, settings, pixel.x, pixel.y, &recorder);
    // ConvsmTest: the GPU's float basis and sums agree with the twin within 5e-5 (measured at most 6e-6).
    ProbeOutcome outcome = probeOutcome(sample.sample, 5e-5, "convsmReference (convsm/ConvsmTechnique.h), double precision, prefilter = blur");
    if (sample.sample.evaluated)
    {
      const ShadowLookup lookup = prepareShadowLookup(inputs, settings.bias, pixel.x, pixel.y);
      noteMomentTexelEdge(outcome.ambiguity, lookup.sm.uvTexels);
    }
    return outcome;
  };
  descriptor.accuracy = prefilteredCentreShadowAccuracy();
  return descriptor;
}

ConvsmSample convsmReference(const ShadowMapInputs& inputs, const ConvsmSettings& settings, int x, int y,
  ProbeRecorder* recorder)
{
  ConvsmSample result;
  const ShadowLookup lookup = prepareShadowLookup(inputs, settings.bias, x, y, recorder);
  result.sample = lookup.sample;
  if (!lookup.sample.evaluated)
  {
    return result;
  }
  const int width = settings.prefilter.texels;
  const int terms = settings.terms;
  const double alpha = settings.ringingAlpha;
  if (recorder)
  {
    recordMomentBox(*recorder, inputs, lookup, width);
  }
  const double scale = settings.reconstructionScale;
  result.coefficients = convsmBasisAverage(inputs, lookup.sm.uvTexels, width, terms, settings.depthRange, recorder);
  result.dNormalized = convsmNormalizedDepth(inputs, lookup.comparisonDepth);
  result.dSeries = settings.depthRange * result.dNormalized;
  result.reconstruction = convsmReconstruct(result.dSeries, result.coefficients, terms, alpha);
  result.sample.visibility = convsmVisibility(result.reconstruction, scale);
  if (recorder)
  {
    recorder->beginGroup("fourier");
    recorder->quantity("terms", terms, "", "Annen et al. 2007: M, the terms of the series kept");
    recorder->quantity("depth_near", inputs.lightView.nearDepth, "linear depth", "ShadowLab: the light's depth range, normalising z and d to [0, 1]");
    recorder->quantity("depth_far", inputs.lightView.farDepth, "linear depth", "ShadowLab: the light's depth range, normalising z and d to [0, 1]");
    recorder->quantity("d_normalized", result.dNormalized, "", "Annen et al. 2007: d, the receiver's depth (minus the bias) in [0, 1]");
    recorder->quantity("depth_range", settings.depthRange, "", "ShadowLab: s, depths enter the series as s d_n, s z_n, so |z_s - d_s| <= s stays inside its period");
    recorder->quantity("d_series", result.dSeries, "", "ShadowLab: d_s = s d_n, the receiver's depth in the series");
    recorder->quantity("ringing_alpha", alpha, "", "ShadowLab: alpha of sigma_k = exp(-alpha (k / M)^2), CSM's ringing damping in a form not verified against the paper");
    for (int k = 1; k <= terms; ++k)
    {
      const std::string suffix = format("_", k);
      recorder->quantity("c" + suffix, convsmFrequency(k), "", "Annen et al. 2007: c_k = pi (2k - 1)");
      recorder->quantity("sigma" + suffix, convsmDamping(k, terms, alpha), "", "ShadowLab: sigma_k = exp(-alpha (k / M)^2) (form not verified against the paper)");
      recorder->quantity("filtered_sin" + suffix, result.coefficients.sine[k - 1], "",
        "Annen et al. 2007: [w * sin(c_k z_s)], the prefiltered sine basis image at the receiver (z_s = s z_n)");
      recorder->quantity("filtered_cos" + suffix, result.coefficients.cosine[k - 1], "",
        "Annen et al. 2007: [w * cos(c_k z_s)], the prefiltered cosine basis image at the receiver (z_s = s z_n)");
    }
    // The reconstructed (filtered) step as a function of the compared series depth, around the receiver's: where
    // it crosses 1/2 and how far it rings.
    for (int j = -4; j <= 4; ++j)
    {
      // d' stays in [0, s], the series depths' domain; beyond it the gaps leave [-s, s].
      const double dSample = std::clamp(result.dSeries + j / (2.0 * terms), 0.0, settings.depthRange);
      recorder->quantity(format("reconstructed_step_", j + 4), glm::dvec2(dSample, convsmReconstruct(dSample, result.coefficients, terms, alpha)), "",
        "Annen et al. 2007: (d', 1/2 + 2 sum_k sigma_k / c_k [cos(c_k d') E[sin(c_k z_s)] - sin(c_k d') E[cos(c_k z_s)]]), d' = d_s + j / 2M clamped to [0, s]");
    }
    recorder->quantity("reconstruction", result.reconstruction, "",
      "Annen et al. 2007: f = 1/2 + 2 sum_k sigma_k / c_k [cos(c_k d_s) E[sin(c_k z_s)] - sin(c_k d_s) E[cos(c_k z_s)]]");
    recorder->quantity("overshoot", result.reconstruction - std::clamp(result.reconstruction, 0.0, 1.0), "", "ShadowLab: f outside [0, 1] (Gibbs ringing)");
    recorder->quantity("reconstruction_scale", scale, "", "public CSM implementations' clamp(2 f, 0, 1), not verified against the paper: the scale of f");
    recorder->quantity("visibility", result.sample.visibility, "", "ShadowLab: clamp(reconstruction_scale f, 0, 1)");
    recorder->beginGroup("light leak");
  }
  // The leak's PCF compares as `pcf` does (its default bias), as vsm's and esm's do.
  const double leakDepth = prepareShadowLookup(inputs, defaultBiasSettings(), x, y).comparisonDepth;
  result.boxPcf = boxPcf(inputs, lookup.sm.uvTexels, leakDepth, width, recorder);
  result.lightLeak = result.sample.visibility - result.boxPcf;
  if (recorder)
  {
    recordLightLeak(*recorder, result.sample.visibility, result.boxPcf,
      boxPcfRange(inputs, lookup.sm.uvTexels, leakDepth, width, probeDepthAmbiguity),
      "Annen et al. 2007 vs Reeves et al. 1987: visibility - PCF over the same box");
  }
  return result;
}

} // namespace sl
