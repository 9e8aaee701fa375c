// Depth range of a texel rectangle from the min-max hierarchical shadow map (passes/vtkSLHsmPass), for the
// lit / umbra early-out of VSSM (Alg. 1 L8). Needs common/ShadowMapCommon.glsl (level 0 is the shadow map).
// CPU mirror: HierarchicalShadowMap::range (src/lightspace/HierarchicalShadowMap.cpp).
#include "common/HsmLayout.glsl"

#if HSM_LAYOUT == HSM_LAYOUT_MIPMAP || HSM_LAYOUT == HSM_LAYOUT_YSM
uniform sampler2D hsmTexture; // the atlas of levels 1..L
#else
uniform sampler3D hsmTexture; // N-buffers: layer k - 1 holds level k; dual-grid MSSM: layer k holds level k
// The last level built (HierarchicalShadowMap::topLevel, minMaxTopLevel): the N-buffers and the dual grid are built
// only up to the level of the frame's widest query, and wider queries tile with squares of this level.
uniform int hsmTopLevel;
#endif
#if HSM_LAYOUT == HSM_LAYOUT_YSM
// The Y shadow map's MSSM part (SS08 §6): N-buffers over the nodes of HSM level ysmBaseLevel
// (its level 0, not stored); layer j - 1 holds its level j.
uniform sampler3D ysmMssmTexture;
uniform int ysmBaseLevel;
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
#if HSM_LAYOUT == HSM_LAYOUT_MIPMAP || HSM_LAYOUT == HSM_LAYOUT_YSM
  return texelFetch(hsmTexture, hsmAtlasOffset(level) + texel, 0).xy;
#else
  return texelFetch(hsmTexture, ivec3(texel, level - 1), 0).xy;
#endif
#endif
}

#if HSM_LAYOUT != HSM_LAYOUT_DUAL
// (min, max) over the aligned block [index 2^level, (index + 1) 2^level) (clipped to the map), the node of the
// mip-map quadtree; level 0 is the shadow map. N-buffers hold the same range at texel index 2^level.
// CPU mirror: HierarchicalShadowMap::node.
vec2 hsmNode(int level, ivec2 index)
{
#if HSM_LAYOUT == HSM_LAYOUT_NBUFFERS
  return hsmTexel(level, index << level);
#else
  return hsmTexel(level, index);
#endif
}
#endif

#if HSM_LAYOUT != HSM_LAYOUT_MIPMAP
// Square `level` at `texel` of the grid the exact tiling runs over: the N-buffers (of texels, or of dual
// cells), or the YSM's MSSM part over the level-ysmBaseLevel nodes (its level 0 is that HSM level).
vec2 hsmSquare(int level, ivec2 texel)
{
#if HSM_LAYOUT == HSM_LAYOUT_YSM
  if (level == 0)
  {
    return hsmTexel(ysmBaseLevel, texel);
  }
  return texelFetch(ysmMssmTexture, ivec3(texel, level - 1), 0).xy;
#else
  return hsmTexel(level, texel);
#endif
}

// (min, max) over the inclusive rectangle [lo, hi] of that grid, tiled by the largest squares not wider than
// its shorter side nor above the top level built, the last of each axis ending at hi (exact; at most 2 squares
// along the shorter side below the top level).
vec2 hsmTiledRange(ivec2 lo, ivec2 hi)
{
  ivec2 extent = hi - lo + 1;
  vec2 range = vec2(1e30, -1e30);
#if HSM_LAYOUT == HSM_LAYOUT_YSM
  int topLevel = 30; // the MSSM part is built whole (as wide as any query of it)
#else
  int topLevel = hsmTopLevel;
#endif
  int level = 0;
  while (level < topLevel && (2 << level) <= min(extent.x, extent.y))
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
      vec2 node = hsmSquare(level, ivec2(sx, sy));
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
  return range;
}
#endif

// (min, max) depth over the inclusive rectangle [lo, hi] inside the map (dual-grid MSSM: of cells).
// Mip-map: the <= 2 x 2 nodes of the first level k as wide as the rectangle (a conservative superset);
// N-buffers and dual-grid MSSM: the rectangle tiled by the largest squares that fit, the last of each axis
// ending at hi (exact). YSM (SS08 §6): the mip-map query for k <= ysmBaseLevel, else the rectangle's
// level-ysmBaseLevel nodes tiled by the MSSM part (exact on rectangles aligned to those nodes, and never looser
// than the mip-map query, whose level-k nodes contain them).
vec2 hsmRange(ivec2 lo, ivec2 hi)
{
#if HSM_LAYOUT == HSM_LAYOUT_MIPMAP || HSM_LAYOUT == HSM_LAYOUT_YSM
  ivec2 extent = hi - lo + 1;
  vec2 range = vec2(1e30, -1e30);
  int level = 0;
  while ((1 << level) < max(extent.x, extent.y))
  {
    ++level;
  }
#if HSM_LAYOUT == HSM_LAYOUT_YSM
  if (level > ysmBaseLevel)
  {
    return hsmTiledRange(lo >> ysmBaseLevel, hi >> ysmBaseLevel);
  }
#endif
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
  return range;
#else
  return hsmTiledRange(lo, hi);
#endif
}

#if HSM_LAYOUT == HSM_LAYOUT_DUAL
// (min, max) depth over the samples [lo, hi] (at least 2 x 2), which are exactly the cells [lo, hi - 1].
vec2 mssmSampleRange(ivec2 lo, ivec2 hi)
{
  return hsmRange(lo, hi - 1);
}
#endif
