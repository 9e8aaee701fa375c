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
#include "common/PixelHash.glsl"

uniform float lightSizeWorld;    // area light side or diameter; 0 for point and spot lights
uniform float lightNearDepth;    // the map's near plane: the blocker-search plane of Alg. 1 L7
uniform vec2 shadowTexelTangent; // size of a texel in tangent units (x / depth, y / depth)
uniform vec2 shadowWindowMin;    // tangent of texel coordinate (0, 0)
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

// The comparison depth of a tap at `tapTexels`: the receiver's depth, or (receiver_plane_bias) the depth
// of its tangent plane along the tap's light ray; minus the bias either way.
vec3 receiverPlane; // light view space normal, scaled so that dot(receiverPlane, X) = 1 on the plane
bool hasReceiverPlane;

float tapComparisonDepth(vec2 tapTexels, float d, float bias)
{
#if RECEIVER_PLANE_BIAS == RECEIVER_PLANE_BIAS_ON
  if (hasReceiverPlane)
  {
    vec3 ray = vec3(shadowWindowMin + tapTexels * shadowTexelTangent, -1.0); // depth 1 along the axis
    float planeDepth = 1.0 / dot(receiverPlane, ray);
    if (planeDepth > 0.0)
    {
      return clamp(planeDepth, 0.5 * d, 2.0 * d) - bias;
    }
  }
#endif
  return d - bias;
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
  float bias = receiver.bias;
  vec3 nLs = mat3(lightViewFromWorld) * receiver.nWs;
  vec3 pLs = (lightViewFromWorld * vec4(receiver.pWs, 1.0)).xyz;
  float planeOffset = dot(nLs, pLs);
  hasReceiverPlane = abs(planeOffset) > 1e-12;
  receiverPlane = hasReceiverPlane ? nLs / planeOffset : vec3(0.0);
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
      vec2 tap = search.origin + vec2(i, j) * search.step;
      float z = storedDepth(tap);
      if (z < tapComparisonDepth(tap, d, bias))
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
    vec2 tap = receiver.uvTexels + searchHalf * (rotation * poissonDisk[k]);
    float z = storedDepth(tap);
    if (z < tapComparisonDepth(tap, d, bias))
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
