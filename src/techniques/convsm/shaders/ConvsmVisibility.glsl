// Convolution shadow maps (Annen et al. 2007; survey §6). The shadow test H(z_n - d_n), both depths normalised to
// the light's [near, far] and mapped to z_s = s z_n, d_s = s d_n (s = depth_range, so |z_s - d_s| <= s stays
// inside the series' period, away from its jump back at +-1), is expanded in the M-term Fourier series of the
// step on [-1, 1] (M = terms):
//   H(z - d) ~ 1/2 + 2 sum_k sigma_k / c_k sin(c_k (z - d)),   c_k = pi (2k - 1)
//            = 1/2 + 2 sum_k sigma_k / c_k [cos(c_k d) sin(c_k z) - sin(c_k d) cos(c_k z)],
// separable in d and z, so prefiltering the basis images sin(c_k z_s), cos(c_k z_s) (structures/fourier) filters
// the shadow test itself. sigma_k = exp(-alpha (k / M)^2) damps the high terms against ringing (ringing_alpha; 0:
// the plain truncated series; the form of CSM's damping is not verified against the paper, see the technique's
// page). The series f overshoots [0, 1] (Gibbs) and reads 1/2 at d = z; visibility = clamp(scale f, 0, 1)
// (reconstruction_scale, public CSM implementations' clamp(2 f, 0, 1)) maps that 1/2 to lit.
// CPU mirror: src/techniques/convsm/ConvsmTechnique.cpp.
#include "common/GBufferInputs.glsl"
#include "common/LightModel.glsl"
#include "common/ShadowMapCommon.glsl"
#include "common/ShadowReceiver.glsl"
#include "common/MomentLookup.glsl"
#include "fourier/FourierTerms.glsl"

uniform int kernelWidth; // prefilter_texels
uniform float depthNear;
uniform float depthFar;

uniform sampler2D fourierSin0;
uniform sampler2D fourierCos0;
#if FOURIER_TERMS > 4
uniform sampler2D fourierSin1;
uniform sampler2D fourierCos1;
#endif
#if FOURIER_TERMS > 8
uniform sampler2D fourierSin2;
uniform sampler2D fourierCos2;
#endif
#if FOURIER_TERMS > 12
uniform sampler2D fourierSin3;
uniform sampler2D fourierCos3;
#endif

layout(location = OUT_VISIBILITY) out float outVisibility;
layout(location = OUT_RECONSTRUCTION) out float outReconstruction;
layout(location = OUT_OVERSHOOT) out float outOvershoot;
layout(location = OUT_LIGHT_LEAK) out float outLightLeak;
layout(location = OUT_KERNEL_TEXELS) out float outKernelTexels;
layout(location = OUT_DEPTH_BIAS) out float outDepthBias;

// The prefiltered sin (cosine = false) or cos of terms 4 group + 1 .. 4 group + 4.
vec4 filteredTerms(int group, bool cosine, vec2 uvTexels)
{
#if FOURIER_TERMS > 4
  if (group == 1)
  {
    return cosine ? prefilteredFetch(fourierCos1, uvTexels) : prefilteredFetch(fourierSin1, uvTexels);
  }
#endif
#if FOURIER_TERMS > 8
  if (group == 2)
  {
    return cosine ? prefilteredFetch(fourierCos2, uvTexels) : prefilteredFetch(fourierSin2, uvTexels);
  }
#endif
#if FOURIER_TERMS > 12
  if (group == 3)
  {
    return cosine ? prefilteredFetch(fourierCos3, uvTexels) : prefilteredFetch(fourierSin3, uvTexels);
  }
#endif
  return cosine ? prefilteredFetch(fourierCos0, uvTexels) : prefilteredFetch(fourierSin0, uvTexels);
}

void main()
{
  ShadowReceiver receiver = prepareShadowReceiver(ivec2(gl_FragCoord.xy));
  outVisibility = receiver.visibility;
  outReconstruction = receiver.visibility;
  outOvershoot = 0.0;
  outLightLeak = 0.0;
  outKernelTexels = 0.0;
  outDepthBias = receiver.bias;
  if (!receiver.needsShadowTest)
  {
    return;
  }
  float dSeries = fourierSeriesDepth(receiver.comparisonDepth, depthNear, depthFar, param_depth_range);
  float reconstruction = 0.5;
  for (int group = 0; group < FOURIER_TERMS / 4; ++group)
  {
    vec4 k = fourierTermNumbers(group);
    vec4 ck = fourierFrequencies(k);
    vec4 kOverM = k / float(FOURIER_TERMS);
    vec4 weight = 2.0 * exp(-param_ringing_alpha * kOverM * kOverM) / ck;
    vec4 filteredSin = filteredTerms(group, false, receiver.uvTexels);
    vec4 filteredCos = filteredTerms(group, true, receiver.uvTexels);
    reconstruction += dot(weight, cos(ck * dSeries) * filteredSin - sin(ck * dSeries) * filteredCos);
  }
  outVisibility = clamp(param_reconstruction_scale * reconstruction, 0.0, 1.0);
  outReconstruction = reconstruction;
  outOvershoot = reconstruction - clamp(reconstruction, 0.0, 1.0);
  outLightLeak = outVisibility - boxPcf(receiver.uvTexels, leakComparisonDepth(receiver), kernelWidth);
  outKernelTexels = float(kernelWidth);
}
