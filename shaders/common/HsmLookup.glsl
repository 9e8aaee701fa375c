// Depth range of a texel rectangle from the min-max hierarchical shadow map (passes/vtkSLHsmPass), for the
// lit / umbra early-out of VSSM (Alg. 1 L8). Needs common/ShadowMapCommon.glsl (level 0 is the shadow map).
// CPU mirror: HierarchicalShadowMap::range (src/lightspace/HierarchicalShadowMap.cpp).
#include "common/HsmLayout.glsl"

#if HSM_LAYOUT == HSM_LAYOUT_MIPMAP
uniform sampler2D hsmTexture;
#else
uniform sampler3D hsmTexture; // N-buffers: layer k - 1 holds level k; dual-grid MSSM: layer k holds level k
#endif

// Node `texel` of `level`; for the dual-grid MSSM `texel` is a cell (-1 .. N - 1), stored at texel + 1.
vec2 hsmTexel(int level, ivec2 texel)
{
#if HSM_LAYOUT == HSM_LAYOUT_DUAL
  return texelFetch(hsmTexture, ivec3(texel + 1, level), 0).xy;
#else
  if (level == 0)
  {
    return vec2(texelFetch(shadowMapLinear, texel, 0).r);
  }
#if HSM_LAYOUT == HSM_LAYOUT_MIPMAP
  return texelFetch(hsmTexture, hsmAtlasOffset(level) + texel, 0).xy;
#else
  return texelFetch(hsmTexture, ivec3(texel, level - 1), 0).xy;
#endif
#endif
}

// (min, max) depth over the inclusive rectangle [lo, hi] inside the map (dual-grid MSSM: of cells).
// Mip-map: the <= 2 x 2 nodes of the first level as wide as the rectangle (a conservative superset);
// N-buffers and dual-grid MSSM: the rectangle tiled by the largest squares that fit, the last of each axis
// ending at hi (exact).
vec2 hsmRange(ivec2 lo, ivec2 hi)
{
  ivec2 extent = hi - lo + 1;
  vec2 range = vec2(1e30, -1e30);
#if HSM_LAYOUT == HSM_LAYOUT_MIPMAP
  int level = 0;
  while ((1 << level) < max(extent.x, extent.y))
  {
    ++level;
  }
  ivec2 first = lo >> level;
  ivec2 last = hi >> level;
  for (int y = first.y; y <= last.y; ++y)
  {
    for (int x = first.x; x <= last.x; ++x)
    {
      vec2 node = hsmTexel(level, ivec2(x, y));
      range = vec2(min(range.x, node.x), max(range.y, node.y));
    }
  }
#else
  int level = 0;
  while ((2 << level) <= min(extent.x, extent.y))
  {
    ++level;
  }
  int side = 1 << level;
  for (int y = lo.y;; y += side)
  {
    int sy = min(y, hi.y - side + 1);
    for (int x = lo.x;; x += side)
    {
      int sx = min(x, hi.x - side + 1);
      vec2 node = hsmTexel(level, ivec2(sx, sy));
      range = vec2(min(range.x, node.x), max(range.y, node.y));
      if (sx + side > hi.x)
      {
        break;
      }
    }
    if (sy + side > hi.y)
    {
      break;
    }
  }
#endif
  return range;
}

#if HSM_LAYOUT == HSM_LAYOUT_DUAL
// (min, max) depth over the samples [lo, hi] (at least 2 x 2), which are exactly the cells [lo, hi - 1].
vec2 mssmSampleRange(ivec2 lo, ivec2 hi)
{
  return hsmRange(lo, hi - 1);
}
#endif
