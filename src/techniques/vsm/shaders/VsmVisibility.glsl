// Variance shadow maps (Donnelly & Lauritzen 2006; survey §6; VSSM §4.1): from the prefiltered moments
// mu = E[z], sigma^2 = E[z^2] - mu^2 over the filter region, the one-tailed Chebyshev bound
//   P(z >= t) <= p_max = sigma^2 / (sigma^2 + (t - mu)^2)   for t > mu (1 otherwise)
// with t the receiver's depth minus the bias. It is exact when the region holds two depths (a planar
// occluder over a planar receiver) and overestimates otherwise: light bleeding, reduced by mapping
// [amount, 1] to [0, 1] (Lauritzen 2007). sigma^2 is floored at min_variance d^2 against float
// cancellation. CPU mirror: src/techniques/vsm/VsmTechnique.cpp.
#include "common/GBufferInputs.glsl"
#include "common/LightModel.glsl"
#include "common/ShadowMapCommon.glsl"
#include "common/ShadowReceiver.glsl"
#include "common/MomentLookup.glsl"
#include "common/Chebyshev.glsl"

uniform int kernelWidth; // prefilter_texels

layout(location = OUT_VISIBILITY) out float outVisibility;
layout(location = OUT_P_MAX) out float outPMax;
layout(location = OUT_LIGHT_LEAK) out float outLightLeak;
layout(location = OUT_KERNEL_TEXELS) out float outKernelTexels;
layout(location = OUT_DEPTH_BIAS) out float outDepthBias;

void main()
{
  ShadowReceiver receiver = prepareShadowReceiver(ivec2(gl_FragCoord.xy));
  outVisibility = receiver.visibility;
  outPMax = 0.0;
  outLightLeak = 0.0;
  outKernelTexels = 0.0;
  outDepthBias = receiver.bias;
  if (!receiver.needsShadowTest)
  {
    return;
  }
  vec4 moments = filteredMoments(receiver.uvTexels);
  float mean = moments.x;
  float d = receiver.depthLin;
  float variance = max(moments.y - mean * mean, param_min_variance * d * d);
  float t = receiver.comparisonDepth;
  float pMax = chebyshevUpperBound(mean, variance, t);
  outVisibility = reduceLightBleeding(pMax, param_light_bleeding_reduction);
  outPMax = pMax;
  outLightLeak = pMax - boxPcf(receiver.uvTexels, leakComparisonDepth(receiver), kernelWidth);
  outKernelTexels = float(kernelWidth);
}
