// Kernels of the PCSS family (PCSS, SAVSM, VSSM; VSSM Alg. 1 L7/L16) and the receiver-plane depth bias
// (Isidoro 2006) they share. Needs common/ShadowMapCommon.glsl and, for Poisson taps, common/SamplingPatterns.glsl.
// RECEIVER_PLANE_BIAS_* come from the technique's `receiver_plane_bias` parameter; param_max_grid_taps from
// its `max_grid_taps`.
uniform float lightSizeWorld;    // area light side or diameter; 0 for point and spot lights
uniform float lightNearDepth;    // the map's near plane: the blocker-search plane of Alg. 1 L7
uniform vec2 shadowTexelTangent; // size of a texel in tangent units (x / depth, y / depth)
uniform vec2 shadowWindowMin;    // tangent of texel coordinate (0, 0)

// Half extent, in texels, of the map region through which occluders on the plane at `planeDepth` can hide
// part of the light from a receiver at `receiverDepth` (similar triangles through the light's edges).
vec2 kernelHalfTexels(float receiverDepth, float planeDepth)
{
  float halfTangent = 0.5 * lightSizeWorld * (receiverDepth - planeDepth) / (planeDepth * receiverDepth);
  return vec2(max(halfTangent, 0.0)) / shadowTexelTangent;
}

// The texel rectangle of a kernel: texels whose centres lie in [uv - h, uv + h] (at least the texel
// containing uv), clamped to the map.
void kernelRectangle(vec2 uvTexels, vec2 halfTexels, out ivec2 lo, out ivec2 hi)
{
  vec2 first = ceil(uvTexels - halfTexels - 0.5);
  vec2 last = floor(uvTexels + halfTexels - 0.5);
  for (int axis = 0; axis < 2; ++axis)
  {
    if (last[axis] < first[axis])
    {
      first[axis] = floor(uvTexels[axis]);
      last[axis] = first[axis];
    }
  }
  // Clamped as floats: a kernel far wider than the map must not overflow the int conversion.
  lo = ivec2(clamp(first, vec2(0.0), vec2(shadowMapSize - 1)));
  hi = ivec2(clamp(last, vec2(0.0), vec2(shadowMapSize - 1)));
}

// Grid kernels and the blocker search: techniques with PCSS's blocker_search and max_grid_taps parameters.
#ifdef BLOCKER_SEARCH
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

#endif

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

#ifdef BLOCKER_SEARCH
// Blocker search over the kernel of half extent `searchHalf` (texels) around uvTexels: the sum and count of
// the depths nearer than each tap's comparison depth, and the taps read. Grid (every texel, capped at
// MAX_GRID_TAPS per axis) or rotated Poisson per BLOCKER_SEARCH.
struct BlockerSearch
{
  float depthSum;
  int blockers;
  int taps;
};

BlockerSearch searchBlockers(vec2 uvTexels, vec2 searchHalf, float d, float bias, mat2 rotation)
{
  BlockerSearch result;
  result.depthSum = 0.0;
  result.blockers = 0;
#if BLOCKER_SEARCH == BLOCKER_SEARCH_GRID
  KernelGrid search = kernelGrid(uvTexels, searchHalf);
  for (int j = 0; j < search.count.y; ++j)
  {
    for (int i = 0; i < search.count.x; ++i)
    {
      vec2 tap = search.origin + vec2(i, j) * search.step;
      float z = storedDepth(tap);
      if (z < tapComparisonDepth(tap, d, bias))
      {
        result.depthSum += z;
        ++result.blockers;
      }
    }
  }
  result.taps = search.count.x * search.count.y;
#else
  result.taps = int(param_poisson_samples);
  for (int k = 0; k < result.taps; ++k)
  {
    vec2 tap = uvTexels + searchHalf * (rotation * poissonDisk[k]);
    float z = storedDepth(tap);
    if (z < tapComparisonDepth(tap, d, bias))
    {
      result.depthSum += z;
      ++result.blockers;
    }
  }
#endif
  return result;
}
#endif

// Lowest and highest comparison depth of the taps in the texels [lo, hi]: tapComparisonDepth is
// 1 / (linear in the tap) per receiver plane, so its extremes over a rectangle are at the corners, unless
// the plane turns away inside it (then the clamp range).
vec2 comparisonDepthRange(ivec2 lo, ivec2 hi, float d, float bias)
{
  vec2 range = vec2(d - bias);
#if RECEIVER_PLANE_BIAS == RECEIVER_PLANE_BIAS_ON
  if (hasReceiverPlane)
  {
    for (int corner = 0; corner < 4; ++corner)
    {
      vec2 position = vec2((corner & 1) == 0 ? lo.x : hi.x + 1, (corner >> 1) == 0 ? lo.y : hi.y + 1);
      vec3 ray = vec3(shadowWindowMin + position * shadowTexelTangent, -1.0);
      float planeDepth = 1.0 / dot(receiverPlane, ray);
      if (!(planeDepth > 0.0))
      {
        return vec2(0.5 * d, 2.0 * d) - bias;
      }
      float depth = clamp(planeDepth, 0.5 * d, 2.0 * d) - bias;
      range = vec2(min(range.x, depth), max(range.y, depth));
    }
  }
#endif
  return range;
}

// Sets up receiverPlane for tapComparisonDepth from the receiver's world position and normal.
void setReceiverPlane(vec3 pWs, vec3 nWs)
{
  vec3 nLs = mat3(lightViewFromWorld) * nWs;
  vec3 pLs = (lightViewFromWorld * vec4(pWs, 1.0)).xyz;
  float planeOffset = dot(nLs, pLs);
  hasReceiverPlane = abs(planeOffset) > 1e-12;
  receiverPlane = hasReceiverPlane ? nLs / planeOffset : vec3(0.0);
}
