// Technique `msm`: moment shadow mapping (Peters & Klein 2015), four power moments of the normalised depth
// (structures/powermoments), prefiltered by a box blur or by mip-mapping, reconstructed by Hamburger 4MSM (their
// Algorithm 3) with the moment bias alpha. Math: msm/shaders/MsmVisibility.glsl.
// Parameters: the shadow-map ones and prefilter (blur|mipmap), prefilter_texels, moment_bias. Buffers: light_leak
// (visibility - pcf, at pcf's default bias, over the same box), support_depth_near/_far (the two support points the
// reconstruction adds to z_f), hankel_pivot (third pivot of the biased Hankel matrix), rounding_sensitivity (how far
// float rounding of the moments moves the result; flagged at msmSensitivityLimit), kernel_texels, depth_bias.
#pragma once

#include "frame/TechniqueDescriptor.h"
#include "lightspace/MomentHamburger.h" // MsmReconstruction, msmHamburger4 (shared with msmsoft)
#include "techniques/MomentReference.h"
#include "techniques/ShadowMapReference.h"

#include <glm/glm.hpp>

namespace sl
{

TechniqueDescriptor msmTechnique();

// msm's parameters, typed (parsed once, by from()).
struct MsmSettings
{
  BiasSettings bias;
  MomentPrefilterSettings prefilter;
  double momentBias{}; // alpha of MSM Alg. 3

  static MsmSettings from(const ParameterValues& values);
};

// The four power moments of the normalised depth over the box of `width` texels around the texel containing
// uvTexels (clamp to edge), as the blur averages them. `recorder` (optional): the box's texels (role "moment box").
glm::dvec4 msmBoxPowerMoments(const ShadowMapInputs& inputs, const glm::dvec2& uvTexels, int width,
  ProbeRecorder* recorder = nullptr);

struct MsmSample
{
  ReferenceSample sample;
  MsmReconstruction reconstruction;
  glm::dvec4 moments{ 0.0 };  // unbiased, box-filtered
  double fragmentDepth = 0.0; // z_f, normalised as the moments' depths
  double lightLeak = 0.0;
};

// CPU reference (double precision) of MsmVisibility.glsl for prefilter = blur. `recorder` (optional, `shadowlab
// probe`): the receiver, the moment box, the moments (unbiased and biased), the Cholesky pivots, the support depths
// and their weights, the shadow intensity, and the light leak against the true PCF over the same box.
MsmSample msmReference(const ShadowMapInputs& inputs, const MsmSettings& settings, int x, int y,
  ProbeRecorder* recorder = nullptr);

// How far the reconstruction moves when the moments and z_f move by float rounding: the sum over b1..b4 and z_f of
// max |G(x + delta) - G(x)|, delta = +-msmMomentRounding (the absolute rounding a float moment in [0, 1] carries
// after the blur's sums). Where the biased Hankel matrix is near singular (D33 tiny) the roots of step 3 follow the
// rounding and so does G; the GPU's result is then the twin's only within this sensitivity.
inline constexpr double msmMomentRounding = 1e-6;
double msmRoundingSensitivity(const glm::dvec4& moments, double momentBias, double fragmentDepth);
// Above this sensitivity a pixel is ill-conditioned: tests and probes count it instead of comparing it.
inline constexpr double msmSensitivityLimit = 1e-3;

} // namespace sl
