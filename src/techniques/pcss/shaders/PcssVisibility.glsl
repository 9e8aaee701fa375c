// Percentage-closer soft shadows (Fernando 2005), as the VSSM paper (Yang et al. 2010, §1, Alg. 1)
// describes its three steps, on the shadow map rendered from the light's centre:
//  1. blocker search: average the depths z < d - bias in the initial kernel w_i, the region of the map
//     through which occluders can hide part of the light from P (Alg. 1 L7: the frustum from P to the light
//     cut by the map's near plane, which focusing places at the nearest caster);
//  2. penumbra estimate by similar triangles (planar, parallel blockers): the same construction with the
//     average blocker depth plane instead (Alg. 1 L16), w_p = w_light (d - z_avg) / z_avg at the receiver;
//  3. PCF over the penumbra kernel.
// Kernels are rectangles in texels (the map's texels may be anisotropic). Sampling, per step:
// grid = every texel whose centre lies in the kernel (the brute-force baseline of the VSSM paper), or a
// MAX_GRID_TAPS x MAX_GRID_TAPS regular sub-grid when the kernel is wider (banding, as the paper notes);
// poisson = poisson_samples taps of the rotated Poisson disk stretched over the kernel.
// Receiver-plane depth bias (Isidoro 2006; not in Fernando 2005, parameter receiver_plane_bias): across a
// wide kernel a receiver sloped relative to the light moves in depth by much more than the per-point bias,
// so it would shadow itself. With it, each tap compares against the receiver's tangent plane where the
// tap's light ray meets it (exact for planar receivers; clamped to [d/2, 2d] where the plane extrapolates
// badly), minus the bias.
// CPU mirror: src/techniques/pcss/PcssTechnique.cpp.
#include "common/GBufferInputs.glsl"
#include "common/LightModel.glsl"
#include "common/ShadowMapCommon.glsl"
#include "common/ShadowReceiver.glsl"
#include "common/SamplingPatterns.glsl"
#include "common/SoftShadowKernels.glsl"

layout(location = OUT_VISIBILITY) out float outVisibility;
layout(location = OUT_BLOCKER_KERNEL_TEXELS) out float outBlockerKernelTexels;
layout(location = OUT_BLOCKER_SAMPLES) out float outBlockerSamples;
layout(location = OUT_AVG_BLOCKER_DEPTH) out float outAvgBlockerDepth;
layout(location = OUT_PENUMBRA_WIDTH) out float outPenumbraWidth;
layout(location = OUT_PENUMBRA_KERNEL_TEXELS) out float outPenumbraKernelTexels;
layout(location = OUT_PCF_SAMPLES) out float outPcfSamples;
layout(location = OUT_DEPTH_BIAS) out float outDepthBias;

void main()
{
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  ShadowReceiver receiver = prepareShadowReceiver(pixel);
  outVisibility = receiver.visibility;
  outBlockerKernelTexels = 0.0;
  outBlockerSamples = 0.0;
  outAvgBlockerDepth = 0.0;
  outPenumbraWidth = 0.0;
  outPenumbraKernelTexels = 0.0;
  outPcfSamples = 0.0;
  outDepthBias = receiver.bias;
  if (!receiver.needsShadowTest)
  {
    return;
  }
  float d = receiver.depthLin;
  float bias = receiver.bias;
  setReceiverPlane(receiver.pWs, receiver.nWs);
  mat2 rotation = pixelRotation(uvec2(pixel));

  // 1. Blocker search over w_i (Alg. 1 L7).
  vec2 searchHalf = kernelHalfTexels(d, lightNearDepth);
  outBlockerKernelTexels = 2.0 * max(searchHalf.x, searchHalf.y);
  BlockerSearch blockers = searchBlockers(receiver.uvTexels, searchHalf, d, bias, rotation);
  int searchTaps = blockers.taps;
  int blockerCount = blockers.blockers;
  float blockerDepthSum = blockers.depthSum;
  outBlockerSamples = float(searchTaps);
  if (blockerCount == 0)
  {
    outVisibility = 1.0; // no blocker can hide any part of the light
    return;
  }

  // 2. Penumbra estimate (similar triangles, Alg. 1 L16).
  float averageBlockerDepth = blockerDepthSum / float(blockerCount);
  outAvgBlockerDepth = averageBlockerDepth;
  outPenumbraWidth = lightSizeWorld * (d - averageBlockerDepth) / averageBlockerDepth;
  vec2 filterHalf = kernelHalfTexels(d, averageBlockerDepth);
  outPenumbraKernelTexels = 2.0 * max(filterHalf.x, filterHalf.y);

  // 3. PCF over w_p.
  float litSum = 0.0;
  int filterTaps = 0;
#if FILTER == FILTER_GRID
  KernelGrid kernel = kernelGrid(receiver.uvTexels, filterHalf);
  for (int j = 0; j < kernel.count.y; ++j)
  {
    for (int i = 0; i < kernel.count.x; ++i)
    {
      vec2 tap = kernel.origin + vec2(i, j) * kernel.step;
      litSum += shadowTest(tap, tapComparisonDepth(tap, d, bias));
    }
  }
  filterTaps = kernel.count.x * kernel.count.y;
#else
  filterTaps = int(param_poisson_samples);
  for (int k = 0; k < filterTaps; ++k)
  {
    vec2 tap = receiver.uvTexels + filterHalf * (rotation * poissonDisk[k]);
    litSum += shadowTest(tap, tapComparisonDepth(tap, d, bias));
  }
#endif
  outPcfSamples = float(filterTaps);
  outVisibility = litSum / float(filterTaps);
}
