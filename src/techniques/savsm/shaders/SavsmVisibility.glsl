// SAT-based variance soft shadow mapping (Lauritzen 2007, GPU Gems 3 ch. 8), the baseline of the VSSM paper
// (Yang et al. 2010, §2.3): PCSS's blocker search by point sampling (brute force by default), the penumbra
// kernel w_p by similar triangles, then the kernel's mean and variance from the summed-area table in four
// fetches and the one-tailed Chebyshev bound (as vsm) instead of PCF. Non-planar blockers in w_p make it
// bleed light (VSSM's motivation). CPU mirror: src/techniques/savsm/SavsmTechnique.cpp.
#include "common/GBufferInputs.glsl"
#include "common/LightModel.glsl"
#include "common/ShadowMapCommon.glsl"
#include "common/ShadowReceiver.glsl"
#include "common/SamplingPatterns.glsl"
#include "common/SoftShadowKernels.glsl"
#include "common/SatLookup.glsl"
#include "common/RectanglePcf.glsl"
#include "common/Chebyshev.glsl"

layout(location = OUT_VISIBILITY) out float outVisibility;
layout(location = OUT_P_MAX) out float outPMax;
layout(location = OUT_LIGHT_LEAK) out float outLightLeak;
layout(location = OUT_BLOCKER_KERNEL_TEXELS) out float outBlockerKernelTexels;
layout(location = OUT_BLOCKER_SAMPLES) out float outBlockerSamples;
layout(location = OUT_AVG_BLOCKER_DEPTH) out float outAvgBlockerDepth;
layout(location = OUT_PENUMBRA_KERNEL_TEXELS) out float outPenumbraKernelTexels;
layout(location = OUT_DEPTH_BIAS) out float outDepthBias;

void main()
{
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  ShadowReceiver receiver = prepareShadowReceiver(pixel);
  outVisibility = receiver.visibility;
  outPMax = 0.0;
  outLightLeak = 0.0;
  outBlockerKernelTexels = 0.0;
  outBlockerSamples = 0.0;
  outAvgBlockerDepth = 0.0;
  outPenumbraKernelTexels = 0.0;
  outDepthBias = receiver.bias;
  if (!receiver.needsShadowTest)
  {
    return;
  }
  float d = receiver.depthLin;
  // The bias keeps the blocker search from finding the receiver itself; Chebyshev compares the receiver's
  // own depth, where it is exact for two depths (see vsm).
  float t = d;
  setReceiverPlane(receiver.pWs, receiver.nWs);
  mat2 rotation = pixelRotation(uvec2(pixel));

  // Blocker search (PCSS step 1, Alg. 1 L7's kernel).
  vec2 searchHalf = kernelHalfTexels(d, lightNearDepth);
  outBlockerKernelTexels = 2.0 * max(searchHalf.x, searchHalf.y);
  BlockerSearch blockers = searchBlockers(receiver.uvTexels, searchHalf, d, receiver.bias, rotation);
  outBlockerSamples = float(blockers.taps);
  if (blockers.blockers == 0)
  {
    outVisibility = 1.0;
    return;
  }
  float averageBlockerDepth = blockers.depthSum / float(blockers.blockers);
  outAvgBlockerDepth = averageBlockerDepth;
  vec2 filterHalf = kernelHalfTexels(d, averageBlockerDepth);
  outPenumbraKernelTexels = 2.0 * max(filterHalf.x, filterHalf.y);

  // Chebyshev over w_p from the SAT.
  ivec2 lo;
  ivec2 hi;
  kernelRectangle(receiver.uvTexels, filterHalf, lo, hi);
  vec2 moments = satBoxMoments(lo, hi);
  float mean = moments.x;
  float variance = max(moments.y, param_min_variance * d * d);
  float pMax = chebyshevUpperBound(mean, variance, t);
  outVisibility = reduceLightBleeding(pMax, param_light_bleeding_reduction);
  outPMax = pMax;
  // Light leak: p_max against the PCF over the same rectangle.
  outLightLeak = pMax - pcfOverRectangle(lo, hi, d, receiver.bias);
}
