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
  settings.terms = FourierBasisSettings::from(values).terms;
  settings.ringingAlpha = values.get("ringing_alpha");
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

double convsmStepSeries(double dNormalized, double zNormalized, int terms, double alpha)
{
  double sum = 0.5;
  for (int k = 1; k <= terms; ++k)
  {
    const double ck = convsmFrequency(k);
    sum += 2.0 * convsmDamping(k, terms, alpha) / ck * std::sin(ck * (zNormalized - dNormalized));
  }
  return sum;
}

double convsmNormalizedDepth(const ShadowMapInputs& inputs, double depthLin)
{
  const double nearDepth = inputs.lightView.nearDepth;
  const double farDepth = inputs.lightView.farDepth;
  return std::clamp((depthLin - nearDepth) / (farDepth - nearDepth), 0.0, 1.0);
}

FourierCoefficients convsmBasisAverage(const ShadowMapInputs& inputs, const glm::dvec2& uvTexels, int width, int terms,
  ProbeRecorder* recorder)
{
  FourierCoefficients coefficients;
  coefficients.sine.assign(terms, 0.0);
  coefficients.cosine.assign(terms, 0.0);
  const int size = inputs.shadowMapLinear.width;
  const int centerX = std::clamp(static_cast<int>(std::floor(uvTexels.x)), 0, size - 1);
  const int centerY = std::clamp(static_cast<int>(std::floor(uvTexels.y)), 0, size - 1);
  const int first = -(width - 1) / 2;
  const double weight = 1.0 / (static_cast<double>(width) * width);
  for (int j = 0; j < width; ++j)
  {
    for (int i = 0; i < width; ++i)
    {
      const glm::ivec2 texel(std::clamp(centerX + first + i, 0, size - 1), std::clamp(centerY + first + j, 0, size - 1));
      const double z = inputs.shadowMapLinear.at(texel.x, texel.y);
      const double zNormalized = convsmNormalizedDepth(inputs, z);
      for (int k = 1; k <= terms; ++k)
      {
        coefficients.sine[k - 1] += weight * std::sin(convsmFrequency(k) * zNormalized);
        coefficients.cosine[k - 1] += weight * std::cos(convsmFrequency(k) * zNormalized);
      }
      if (recorder)
      {
        recorder->texel({ texel, "fourier box", z, std::numeric_limits<double>::quiet_NaN(), false, weight });
      }
    }
  }
  return coefficients;
}

double convsmReconstruct(double dNormalized, const FourierCoefficients& coefficients, int terms, double alpha)
{
  double sum = 0.5;
  for (int k = 1; k <= terms; ++k)
  {
    const double ck = convsmFrequency(k);
    sum += 2.0 * convsmDamping(k, terms, alpha) / ck *
      (std::cos(ck * dNormalized) * coefficients.sine[k - 1] - std::sin(ck * dNormalized) * coefficients.cosine[k - 1]);
  }
  return sum;
}

TechniqueDescriptor convsmTechnique()
{
  TechniqueDescriptor descriptor = describeShadowMapTechnique("convsm", "Convolution shadow maps",
    "Annen, Mertens, Bekaert, Seidel & Kautz 2007; survey §6");
  for (ParameterSpec& spec : descriptor.parameters)
  {
    // The paper compares the receiver's own depth: the series' transition, about 1 / M of the light's depth range
    // wide, dwarfs a bias of a few texel footprints, which would only shift where it reads 1/2.
    if (spec.name == "bias_constant_texels" || spec.name == "bias_slope_texels")
    {
      spec.defaultValue = 0.0;
    }
  }
  descriptor.addParameters(fourierBasisStructure().parameters);
  // The basis images are prefiltered as the moment map is, with its parameters (structures/fourier).
  descriptor.addParameters(momentMapStructure().parameters);
  descriptor.addParameters({
    { "ringing_alpha", 0, 0, 20, "",
      "alpha of the damping sigma_k = exp(-alpha (k / M)^2) of term k against ringing (CSM's ringing suppression; this form is not verified against the paper, see the page); 0: the plain truncated series", {}, false },
  });
  descriptor.lightStructures = { &shadowMapStructure(), &fourierBasisStructure() };
  descriptor.buffers = {
    { "reconstruction", "", "the damped Fourier series of the filtered shadow test before clamping: outside [0, 1] where it rings", BufferKind::Signed },
    { "overshoot", "", "reconstruction minus its clamp to [0, 1]: > 0 above 1, < 0 below 0 (Gibbs ringing), 0 inside", BufferKind::Signed },
    { "light_leak", "", "visibility minus pcf over the same box of texels (pcf's default bias): > 0 where it leaks light, < 0 where it darkens", BufferKind::Signed },
    { "kernel_texels", "texels", "width of the prefilter box" },
    depthBiasBuffer(),
  };
  descriptor.lightSpaceRequest = [](const ParameterValues& values) {
    return LightSpaceRequest{ "prefilter_texels", static_cast<double>(ConvsmSettings::from(values).prefilter.texels) };
  };
  descriptor.createPass = [] {
    auto pass = vtkSmartPointer<vtkSLMomentTechniquePass>::New();
    pass->SetFragmentShaderPath("convsm/ConvsmVisibility.glsl");
    return vtkSmartPointer<vtkSLTechniquePass>(pass);
  };
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
  result.coefficients = convsmBasisAverage(inputs, lookup.sm.uvTexels, width, terms, recorder);
  result.dNormalized = convsmNormalizedDepth(inputs, lookup.comparisonDepth);
  result.reconstruction = convsmReconstruct(result.dNormalized, result.coefficients, terms, alpha);
  result.sample.visibility = std::clamp(result.reconstruction, 0.0, 1.0);
  if (recorder)
  {
    recorder->beginGroup("fourier");
    recorder->quantity("terms", terms, "", "Annen et al. 2007: M, the terms of the series kept");
    recorder->quantity("depth_near", inputs.lightView.nearDepth, "linear depth", "ShadowLab: the light's depth range, normalising z and d to [0, 1]");
    recorder->quantity("depth_far", inputs.lightView.farDepth, "linear depth", "ShadowLab: the light's depth range, normalising z and d to [0, 1]");
    recorder->quantity("d_normalized", result.dNormalized, "", "Annen et al. 2007: d, the receiver's depth (minus the bias) in [0, 1]");
    recorder->quantity("ringing_alpha", alpha, "", "ShadowLab: alpha of sigma_k = exp(-alpha (k / M)^2), CSM's ringing damping in a form not verified against the paper");
    for (int k = 1; k <= terms; ++k)
    {
      const std::string suffix = format("_", k);
      recorder->quantity("c" + suffix, convsmFrequency(k), "", "Annen et al. 2007: c_k = pi (2k - 1)");
      recorder->quantity("sigma" + suffix, convsmDamping(k, terms, alpha), "", "ShadowLab: sigma_k = exp(-alpha (k / M)^2) (form not verified against the paper)");
      recorder->quantity("filtered_sin" + suffix, result.coefficients.sine[k - 1], "",
        "Annen et al. 2007: [w * sin(c_k z)], the prefiltered sine basis image at the receiver");
      recorder->quantity("filtered_cos" + suffix, result.coefficients.cosine[k - 1], "",
        "Annen et al. 2007: [w * cos(c_k z)], the prefiltered cosine basis image at the receiver");
    }
    // The reconstructed (filtered) step as a function of the compared depth, around the receiver's: where it
    // crosses 1/2 and how far it rings.
    for (int j = -4; j <= 4; ++j)
    {
      // d' stays in [0, 1], the depths' domain; beyond it the series repeats (period 2).
      const double dSample = std::clamp(result.dNormalized + j / (2.0 * terms), 0.0, 1.0);
      recorder->quantity(format("reconstructed_step_", j + 4), glm::dvec2(dSample, convsmReconstruct(dSample, result.coefficients, terms, alpha)), "",
        "Annen et al. 2007: (d', 1/2 + 2 sum_k sigma_k / c_k [cos(c_k d') E[sin(c_k z)] - sin(c_k d') E[cos(c_k z)]]), d' = d + j / 2M clamped to [0, 1]");
    }
    recorder->quantity("reconstruction", result.reconstruction, "",
      "Annen et al. 2007: 1/2 + 2 sum_k sigma_k / c_k [cos(c_k d) E[sin(c_k z)] - sin(c_k d) E[cos(c_k z)]]");
    recorder->quantity("overshoot", result.reconstruction - result.sample.visibility, "", "ShadowLab: the reconstruction outside [0, 1] (Gibbs ringing)");
    recorder->quantity("visibility", result.sample.visibility, "", "ShadowLab: the reconstruction clamped to [0, 1]");
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
