#include "techniques/msm/MsmTechnique.h"

#include "structures/moments/MomentMapStructure.h"
#include "structures/powermoments/PowerMomentMapStructure.h"
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

namespace
{

BufferSpec msmRoundingSensitivityBuffer()
{
  BufferSpec spec{ "rounding_sensitivity", "",
    "sum over b1..b4 and z_f of the largest change of the shadow intensity when one moves by 1e-6 (float rounding): at "
    "1e-3 or more the Hankel matrix is near singular and the value follows the rounding (0 where not tested)" };
  spec.flagAtOrAbove = msmSensitivityLimit;
  spec.flagWarning = "the biased Hankel matrix is near singular there, so float rounding of the moments moves the "
                     "result by 1e-3 or more; a larger moment_bias conditions it";
  return spec;
}

} // namespace

MsmSettings MsmSettings::from(const ParameterValues& values)
{
  MsmSettings settings;
  settings.bias = biasSettings(values);
  settings.prefilter = MomentPrefilterSettings::from(values);
  settings.momentBias = values.get("moment_bias");
  return settings;
}

TechniqueDescriptor msmTechnique()
{
  TechniqueDescriptor descriptor = describeShadowMapTechnique("msm", "Moment shadow maps",
    "Peters & Klein 2015 (Hamburger 4MSM, Algorithm 3)");
  // The power moments are prefiltered as the moment map is, with its parameters (structures/powermoments).
  descriptor.addParameters(momentMapStructure().parameters);
  descriptor.addParameters({
    momentBiasParameter(), // here the moments are RGBA32F
  });
  descriptor.lightStructures = { &shadowMapStructure(), &powerMomentMapStructure() };
  descriptor.buffers = {
    onShadowTestedPixels({ "light_leak", "", "visibility minus pcf over the same box of texels (pcf's default bias): > 0 where MSM leaks light", BufferKind::Signed }),
    { "support_depth_near", "moment depth",
      "z_2, the nearer of the two support points Hamburger 4MSM adds to the receiver's z_f (moment depth: (d - near) / (far - near) of the light's range)", BufferKind::Signed },
    { "support_depth_far", "moment depth", "z_3, the farther one", BufferKind::Signed },
    { "hankel_pivot", "", "D33, the last pivot of the LDL^T of the biased Hankel matrix (det(B) / D22): near 0 the float "
      "reconstruction is dominated by rounding, held off by the moment bias" },
    msmRoundingSensitivityBuffer(),
    { "kernel_texels", "texels", "width of the prefilter box" },
    depthBiasBuffer(),
  };
  descriptor.lightSpaceRequest = [](const ParameterValues& values) {
    return LightSpaceRequest{ "prefilter_texels", static_cast<double>(MsmSettings::from(values).prefilter.texels) };
  };
  descriptor.createPass = momentTechniquePass("msm/MsmVisibility.glsl");
  descriptor.probe = [](const ProbeContext& context, glm::ivec2 pixel, ProbeRecorder& recorder) {
    const MsmSettings settings = MsmSettings::from(context.frame->parameters);
    requireBlurPrefilter(settings.prefilter);
    const ShadowMapInputs inputs = shadowMapInputsOf(*context.frame, *context.scene, context.lightIndex);
    const MsmSample sample = msmReference(inputs, settings, pixel.x, pixel.y, &recorder);
    // MsmTest: <= 2e-3 where the rounding sensitivity is at most msmSensitivityLimit; above it the float moments'
    // rounding decides the support points (a near-singular Hankel matrix).
    ProbeOutcome outcome = probeOutcome(sample.sample, 2e-3, "msmReference (msm/MsmTechnique.h), double precision, prefilter = blur");
    if (sample.sample.evaluated)
    {
      const ShadowLookup lookup = prepareShadowLookup(inputs, settings.bias, pixel.x, pixel.y);
      const double sensitivity = msmRoundingSensitivity(sample.moments, settings.momentBias, sample.fragmentDepth);
      recorder.beginGroup("conditioning");
      recorder.quantity("rounding_sensitivity", sensitivity, "",
        "ShadowLab: sum of |G change| when b1..b4 and z_f move by 1e-6 (float rounding); ill-conditioned above 1e-3");
      noteAmbiguity(outcome.ambiguity, "headroom against float rounding (1e-3 / rounding sensitivity)",
        msmSensitivityLimit / std::max(sensitivity, 1e-300), 1.0);
      noteMomentTexelEdge(outcome.ambiguity, lookup.sm.uvTexels);
    }
    return outcome;
  };
  descriptor.accuracy = prefilteredCentreShadowAccuracy();
  return descriptor;
}

double msmRoundingSensitivity(const glm::dvec4& moments, double momentBias, double fragmentDepth)
{
  const double intensity = msmHamburger4(moments, momentBias, fragmentDepth).shadowIntensity;
  double sensitivity = 0.0;
  for (int k = 0; k < 5; ++k)
  {
    double largest = 0.0;
    for (const double sign : { -1.0, 1.0 })
    {
      glm::dvec4 moved = moments;
      double depth = fragmentDepth;
      (k < 4 ? moved[k] : depth) += sign * msmMomentRounding;
      largest = std::max(largest, std::abs(msmHamburger4(moved, momentBias, depth).shadowIntensity - intensity));
    }
    sensitivity += largest;
  }
  return sensitivity;
}

glm::dvec4 msmBoxPowerMoments(const ShadowMapInputs& inputs, const glm::dvec2& uvTexels, int width, ProbeRecorder* recorder)
{
  const double nearDepth = inputs.lightView.nearDepth;
  const double farDepth = inputs.lightView.farDepth;
  const double weight = 1.0 / (static_cast<double>(width) * width);
  glm::dvec4 sum(0.0);
  visitPrefilterBox(inputs, uvTexels, width, [&](double depth, const glm::ivec2& texel) {
    const double z = PowerMomentMapSettings::normalisedDepth(depth, nearDepth, farDepth);
    sum += glm::dvec4(z, z * z, z * z * z, z * z * z * z);
    if (recorder)
    {
      recorder->texel({ texel, "moment box", depth, std::numeric_limits<double>::quiet_NaN(), false, weight });
    }
  });
  return sum * weight;
}

MsmSample msmReference(const ShadowMapInputs& inputs, const MsmSettings& settings, int x, int y, ProbeRecorder* recorder)
{
  MsmSample result;
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
  result.moments = msmBoxPowerMoments(inputs, lookup.sm.uvTexels, width, recorder);
  const LightView& view = inputs.lightView;
  result.fragmentDepth = (lookup.comparisonDepth - view.nearDepth) / (view.farDepth - view.nearDepth);
  result.reconstruction = msmHamburger4(result.moments, settings.momentBias, result.fragmentDepth);
  const MsmReconstruction& msm = result.reconstruction;
  result.sample.visibility = 1.0 - msm.shadowIntensity;
  if (recorder)
  {
    recorder->quantity("power_moments", glm::dvec3(result.moments.x, result.moments.y, result.moments.z), "",
      "Peters & Klein 2015: E[z], E[z^2], E[z^3] over the box, z = (d - near) / (far - near)");
    recorder->quantity("power_moment_4", result.moments.w, "", "Peters & Klein 2015: E[z^4]");
    recorder->beginGroup("hamburger 4msm");
    recorder->quantity("moment_bias", settings.momentBias, "", "MSM Alg. 3, moment bias: alpha");
    recorder->quantity("biased_moments", glm::dvec3(msm.biasedMoments.x, msm.biasedMoments.y, msm.biasedMoments.z), "",
      "MSM Alg. 3, moment bias: b' = (1 - alpha) b + alpha (0.5, 0.5, 0.5, 0.5), components 1-3");
    recorder->quantity("biased_moment_4", msm.biasedMoments.w, "", "MSM Alg. 3, moment bias: b4'");
    recorder->quantity("fragment_depth", result.fragmentDepth, "moment depth",
      "MSM Alg. 3: z_f, the receiver's depth minus the bias, normalised as the moments' depths");
    recorder->quantity("pivot_d22", msm.pivot2, "", "MSM Alg. 3, Cholesky solve: D22 = b2' - b1'^2 (Cholesky of the Hankel matrix)");
    recorder->quantity("hankel_pivot", msm.pivot3, "", "MSM Alg. 3, Cholesky solve: D33 = det(B) / D22, the last pivot");
    recorder->quantity("polynomial", msm.polynomial, "", "MSM Alg. 3, Cholesky solve: c solving B c = (1, z_f, z_f^2)");
    recorder->quantity("support_depth_near", msm.supportNear, "moment depth", "MSM Alg. 3, quadratic: z_2, smaller root of c1 + c2 z + c3 z^2");
    recorder->quantity("support_depth_far", msm.supportFar, "moment depth", "MSM Alg. 3, quadratic: z_3, larger root");
    recorder->quantity("support_weights", msm.weights, "",
      "ShadowLab (Lagrange): weights of z_f, z_2, z_3 in the distribution matching 1, b1', b2'");
    recorder->quantity("shadow_intensity", msm.shadowIntensity, "",
      "MSM Alg. 3, weights: the weights of the support points in front of z_f, clamped to [0, 1]");
    recorder->quantity("visibility", result.sample.visibility, "", "ShadowLab: 1 - shadow intensity");
    recorder->beginGroup("light leak");
  }
  // The leak's PCF compares as `pcf` does (its default bias), like vsm's and esm's.
  const double leakDepth = prepareShadowLookup(inputs, defaultBiasSettings(), x, y).comparisonDepth;
  const double pcf = boxPcf(inputs, lookup.sm.uvTexels, leakDepth, width, recorder);
  result.lightLeak = result.sample.visibility - pcf;
  if (recorder)
  {
    recordLightLeak(*recorder, result.sample.visibility, pcf,
      boxPcfRange(inputs, lookup.sm.uvTexels, leakDepth, width, probeDepthAmbiguity),
      "ShadowLab: visibility - PCF over the same box");
  }
  return result;
}

} // namespace sl
