// Exponential shadow maps (Annen et al. 2008; survey §6): the test d <= z approximated by
// exp(c (z_n - t_n)) clamped to 1, which is linear in exp(c z_n) and so prefilterable:
//   visibility = clamp(E[exp(c z_n)] exp(-c t_n), 0, 1)
// with depths normalised to the light's range, z_n = (z - near) / (far - near), and t the receiver's depth
// minus the bias. Larger c sharpens the step and reduces light leaks near contact.
// CPU mirror: src/techniques/esm/EsmTechnique.cpp.
#include "common/GBufferInputs.glsl"
#include "common/LightModel.glsl"
#include "common/ShadowMapCommon.glsl"
#include "common/ShadowReceiver.glsl"
#include "common/MomentLookup.glsl"

uniform int kernelWidth; // prefilter_texels
uniform float depthNear;
uniform float depthFar;

layout(location = OUT_VISIBILITY) out float outVisibility;
layout(location = OUT_LIGHT_LEAK) out float outLightLeak;
layout(location = OUT_KERNEL_TEXELS) out float outKernelTexels;
layout(location = OUT_DEPTH_BIAS) out float outDepthBias;
layout(location = OUT_BIAS_GAIN) out float outBiasGain;

void main()
{
  ShadowReceiver receiver = prepareShadowReceiver(ivec2(gl_FragCoord.xy));
  outVisibility = receiver.visibility;
  outLightLeak = 0.0;
  outKernelTexels = 0.0;
  outDepthBias = receiver.bias;
  outBiasGain = 0.0;
  if (!receiver.needsShadowTest)
  {
    return;
  }
  float t = receiver.comparisonDepth;
  float tNormalized = (t - depthNear) / (depthFar - depthNear);
  float expected = filteredMoments(receiver.uvTexels).z;
  float visibility = clamp(expected * exp(-param_esm_exponent * tNormalized), 0.0, 1.0);
  outVisibility = visibility;
  outLightLeak = visibility - boxPcf(receiver.uvTexels, leakComparisonDepth(receiver), kernelWidth);
  outKernelTexels = float(kernelWidth);
  // A lit texel at the receiver's own depth weighs exp(c (d_n - t_n)) = exp(c bias_n), not 1 (EsmTechnique.cpp).
  outBiasGain = exp(param_esm_exponent * receiver.bias / (depthFar - depthNear));
}
