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

constexpr double msmPivotFloor = 1e-12; // D22's and D33's floor, as MsmVisibility.glsl

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
    // 3e-5: the value public ports of the authors' code use for 16-bit storage in their optimised basis (README.md
    // says what was and was not found); here the moments are RGBA32F.
    // Minimum 1e-6: below it the bias vanishes in the float moments (README.md, Parameters).
    { "moment_bias", 3e-5, 1e-6, 0.1, "",
      "alpha of MSM Alg. 3: b' = (1 - alpha) b + alpha (0.5, 0.5, 0.5, 0.5), keeps the Hankel matrix definite "
      "against rounding; larger leaks more light", {}, false },
  });
  descriptor.lightStructures = { &shadowMapStructure(), &powerMomentMapStructure() };
  descriptor.buffers = {
    { "light_leak", "", "visibility minus pcf over the same box of texels (pcf's default bias): > 0 where MSM leaks light", BufferKind::Signed },
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

MsmReconstruction msmHamburger4(const glm::dvec4& moments, double momentBias, double fragmentDepth)
{
  MsmReconstruction result;
  // Step 1: the moment bias.
  const glm::dvec4 b = (1.0 - momentBias) * moments + momentBias * glm::dvec4(0.5);
  result.biasedMoments = b;
  const double zf = fragmentDepth;
  // Step 2: B c = (1, z_f, z_f^2) by LDL^T (D11 = 1, L21 = b1, L31 = b2).
  // D22 >= alpha / 4 in exact arithmetic; floored as D33 only against float rounding (MsmVisibility.glsl).
  const double d22 = std::max(b.y - b.x * b.x, msmPivotFloor);
  const double l32d22 = b.z - b.x * b.y;
  const double l32 = l32d22 / d22;
  // B is positive definite for alpha > 0, so D33 > 0; only float rounding makes it 0 or less (MsmVisibility.glsl).
  const double d33 = std::max((b.w - b.y * b.y) - l32d22 * l32, msmPivotFloor);
  result.pivot2 = d22;
  result.pivot3 = d33;
  glm::dvec3 c(1.0, zf, zf * zf);
  c.y -= b.x;
  c.z -= b.y + l32 * c.y;
  c.y /= d22;
  c.z /= d33;
  c.y -= l32 * c.z;
  c.x -= c.y * b.x + c.z * b.y;
  result.polynomial = c;
  // Step 3: the two other support points, the roots of c1 + c2 z + c3 z^2, by the stable form MsmVisibility.glsl
  // uses (equal to Alg. 3's -p/2 -+ sqrt(p^2/4 - q) in exact arithmetic), clamped to +-1e6 as there.
  const double root = std::sqrt(std::max(c.y * c.y - 4.0 * c.x * c.z, 0.0));
  const double large = -0.5 * (c.y + (c.y < 0.0 ? -root : root));
  const double rootA = std::clamp(large / c.z, -1e6, 1e6);
  const double rootB = std::clamp(c.x / large, -1e6, 1e6);
  const double z2 = std::min(rootA, rootB);
  const double z3 = std::max(rootA, rootB);
  result.supportNear = z2;
  result.supportFar = z3;
  // The weights of the three-point distribution on (z_f, z_2, z_3) with moments 1, b1', b2' (Lagrange: the weight
  // of z_i is E[(z - z_j)(z - z_k)] / ((z_i - z_j)(z_i - z_k))).
  const auto weight = [&](double zi, double zj, double zk) {
    return (zj * zk - b.x * (zj + zk) + b.y) / ((zi - zj) * (zi - zk));
  };
  result.weights = glm::dvec3(weight(zf, z2, z3), weight(z2, zf, z3), weight(z3, zf, z2));
  // Step 4: the weights of the support points in front of z_f, in the shader's form.
  double intensity = 0.0;
  if (zf <= z2)
  {
    intensity = 0.0;
  }
  else if (zf <= z3)
  {
    intensity = (zf * z3 - b.x * (zf + z3) + b.y) / ((z3 - z2) * (zf - z2));
  }
  else
  {
    intensity = 1.0 - (z2 * z3 - b.x * (z2 + z3) + b.y) / ((zf - z2) * (zf - z3));
  }
  result.shadowIntensity = std::clamp(intensity, 0.0, 1.0);
  return result;
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
