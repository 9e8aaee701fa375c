// Percentage-closer soft shadows (Fernando 2005), as the VSSM paper (Yang et al. 2010, §1, Alg. 1)
// describes its three steps, on the shadow map rendered from the light's centre:
//  1. blocker search: average the depths z < d - bias in the initial kernel w_i, the region of the map
//     through which occluders can hide part of the light from P (Alg. 1 L7: the frustum from P to the light
//     cut by the map's near plane, which focusing places at the nearest caster);
//  2. penumbra estimate by similar triangles (planar, parallel blockers): the same construction with the
//     average blocker depth plane instead (L16), w_p = w_light (d - z_avg) / z_avg at the receiver;
//  3. PCF over the penumbra kernel.
// Kernels are rectangles in texels (the map's texels may be anisotropic). Sampling, per step:
// grid = every texel whose centre lies in the kernel (the brute-force baseline of the VSSM paper), or a
// MAX_GRID_TAPS x MAX_GRID_TAPS regular sub-grid when the kernel is wider (banding, as the paper notes);
// poisson = poisson_samples taps of the rotated Poisson disk stretched over the kernel.
// CPU mirror: src/techniques/pcss/PcssTechnique.cpp.
#include "common/GBufferInputs.glsl"
#include "common/LightModel.glsl"
#include "common/ShadowMapCommon.glsl"
#include "common/ShadowReceiver.glsl"
#include "common/PixelHash.glsl"

uniform float lightSizeWorld;    // area light side or diameter; 0 for point and spot lights
uniform float lightNearDepth;    // the map's near plane: the blocker-search plane of Alg. 1 L7
uniform vec2 shadowTexelTangent; // size of a texel in tangent units (x / depth, y / depth)
uniform vec2 poissonDisk[MAX_POISSON_SAMPLES];

layout(location = OUT_VISIBILITY) out float outVisibility;
layout(location = OUT_BLOCKER_KERNEL_TEXELS) out float outBlockerKernelTexels;
layout(location = OUT_BLOCKER_SAMPLES) out float outBlockerSamples;
layout(location = OUT_AVG_BLOCKER_DEPTH) out float outAvgBlockerDepth;
layout(location = OUT_PENUMBRA_WIDTH) out float outPenumbraWidth;
layout(location = OUT_PENUMBRA_KERNEL_TEXELS) out float outPenumbraKernelTexels;
layout(location = OUT_PCF_SAMPLES) out float outPcfSamples;
layout(location = OUT_DEPTH_BIAS) out float outDepthBias;

// Half extent, in texels, of the map region through which occluders on the plane at `planeDepth` can hide
// part of the light from a receiver at `receiverDepth` (similar triangles through the light's edges).
vec2 kernelHalfTexels(float receiverDepth, float planeDepth)
{
  float halfTangent = 0.5 * lightSizeWorld * (receiverDepth - planeDepth) / (planeDepth * receiverDepth);
  return vec2(max(halfTangent, 0.0)) / shadowTexelTangent;
}

// Grid sampling of a kernel, per axis: the texels whose centres lie in [uv - h, uv + h] (at least the
// texel containing uv), or MAX_GRID_TAPS evenly spaced taps when that is more.
struct KernelGrid
{
  vec2 origin; // position of tap (0, 0)
  vec2 step;   // spacing in texels
  ivec2 count;
};

KernelGrid kernelGrid(vec2 uv, vec2 halfTexels)
{
  KernelGrid grid;
  for (int axis = 0; axis < 2; ++axis)
  {
    float first = ceil(uv[axis] - halfTexels[axis] - 0.5);
    float last = floor(uv[axis] + halfTexels[axis] - 0.5);
    if (last < first)
    {
      first = floor(uv[axis]);
      last = first;
    }
    int dense = int(last - first) + 1;
    if (dense <= int(param_max_grid_taps))
    {
      grid.origin[axis] = first + 0.5;
      grid.step[axis] = 1.0;
      grid.count[axis] = dense;
    }
    else
    {
      grid.count[axis] = int(param_max_grid_taps);
      grid.step[axis] = 2.0 * halfTexels[axis] / param_max_grid_taps;
      grid.origin[axis] = uv[axis] - halfTexels[axis] + 0.5 * grid.step[axis];
    }
  }
  return grid;
}

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
  float comparison = receiver.comparisonDepth;
  float angle = pixelHashAngle(uvec2(pixel));
  mat2 rotation = mat2(cos(angle), sin(angle), -sin(angle), cos(angle));

  // 1. Blocker search over w_i (Alg. 1 L7).
  vec2 searchHalf = kernelHalfTexels(d, lightNearDepth);
  outBlockerKernelTexels = 2.0 * max(searchHalf.x, searchHalf.y);
  float blockerDepthSum = 0.0;
  int blockerCount = 0;
  int searchTaps = 0;
#if BLOCKER_SEARCH == BLOCKER_SEARCH_GRID
  KernelGrid search = kernelGrid(receiver.uvTexels, searchHalf);
  for (int j = 0; j < search.count.y; ++j)
  {
    for (int i = 0; i < search.count.x; ++i)
    {
      float z = storedDepth(search.origin + vec2(i, j) * search.step);
      if (z < comparison)
      {
        blockerDepthSum += z;
        ++blockerCount;
      }
    }
  }
  searchTaps = search.count.x * search.count.y;
#else
  searchTaps = int(param_poisson_samples);
  for (int k = 0; k < searchTaps; ++k)
  {
    float z = storedDepth(receiver.uvTexels + searchHalf * (rotation * poissonDisk[k]));
    if (z < comparison)
    {
      blockerDepthSum += z;
      ++blockerCount;
    }
  }
#endif
  outBlockerSamples = float(searchTaps);
  if (blockerCount == 0)
  {
    outVisibility = 1.0; // no blocker can hide any part of the light
    return;
  }

  // 2. Penumbra estimate (similar triangles, L16).
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
      litSum += shadowTest(kernel.origin + vec2(i, j) * kernel.step, comparison);
    }
  }
  filterTaps = kernel.count.x * kernel.count.y;
#else
  filterTaps = int(param_poisson_samples);
  for (int k = 0; k < filterTaps; ++k)
  {
    litSum += shadowTest(receiver.uvTexels + filterHalf * (rotation * poissonDisk[k]), comparison);
  }
#endif
  outPcfSamples = float(filterTaps);
  outVisibility = litSum / float(filterTaps);
}
