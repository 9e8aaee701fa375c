// The min-max hierarchical shadow map (HSM) of VSSM (Yang et al. 2010, Alg. 1 L4 and §6.1), in double
// precision: the CPU mirror of shaders/hsm/HsmBuild.glsl and of the range query in
// shaders/common/HsmLookup.glsl. Two layouts (§6.1):
//  - mip-map: level k has ceil(N / 2^k) texels per side, texel (x, y) holds the (min, max) depth of the
//    shadow-map texels [x 2^k, (x + 1) 2^k) x [y 2^k, (y + 1) 2^k) (clipped to the map). A query covers a
//    rectangle with the at most 2 x 2 nodes of the first level whose nodes are as wide as the rectangle:
//    cheap, but conservative (the range of a superset). Levels 1..L are packed in one N x N atlas (level 1
//    at the origin, levels 2.. stacked in a column to its right; GL mip chains round sizes down, which would
//    drop the last row of odd levels), which is also what light_space.vti exports.
//  - N-buffers (Décoret 2005): level k has N x N texels, texel (x, y) holds the range of the 2^k x 2^k square
//    starting at (x, y) (clipped). A query tiles the rectangle with (overlapping) squares of the largest
//    level that fits: exact, at L times the memory.
// Level 0 is the shadow map itself (min = max = z; empty texels hold 2 x far and never occlude).
//  - dual-grid MSSM (Yang et al. 2009 §4.2): an N-buffer over the dual grid, whose cells are the 2 x 2 sample
//    blocks the contour methods examine. Cell (i, j) has the samples (i, j) .. (i + 1, j + 1); level 0 holds the
//    range of each cell, level k the range of the 2^k x 2^k cells starting at each cell, so every node covers
//    2^k + 1 samples per side and a quadtree over cells needs no neighbour reads. Cells -1 .. N - 1 exist (the
//    border ones half outside the map, whose outside samples hold `outsideDepth`, 2 x far: they never occlude),
//    so each level has (N + 1)^2 texels, texel t holding cell t - 1.
#pragma once

#include "core/Image.h"

#include <glm/glm.hpp>

#include <vector>

namespace sl
{

enum class HsmLayout
{
  MipMap,
  NBuffers,
  DualMssm
};

// Levels above 0 of an N x N map: ceil(log2 N) (the last mip level is 1 x 1).
int hsmLevelCount(int mapSize);
// Levels above 0 of the dual-grid MSSM: ceil(log2 (N + 1)), so that one node covers all N + 1 cells.
int dualMssmLevelCount(int mapSize);
// Texels per side of level k.
int hsmLevelSize(HsmLayout layout, int mapSize, int level);
// Mip-map layout: where level k >= 1 starts in the N x N atlas.
glm::ivec2 hsmAtlasOffset(int mapSize, int level);

struct HierarchicalShadowMap
{
  HsmLayout layout = HsmLayout::MipMap;
  int mapSize = 0;
  std::vector<ImageF> levels; // levels[k]: 2 components (min, max); levels[0] from the shadow map

  static HierarchicalShadowMap build(const ImageF& shadowMapLinear, HsmLayout layout);
  static HierarchicalShadowMap buildDual(const ImageF& shadowMapLinear, float outsideDepth);

  // (min, max) depth over the inclusive texel rectangle [lo, hi] (inside the map): exact for N-buffers and the
  // dual-grid MSSM (there [lo, hi] must be at least 2 x 2), the range of the covering nodes for the mip-map. `fetches` (optional) counts the texels read.
  glm::dvec2 range(glm::ivec2 lo, glm::ivec2 hi, int* fetches = nullptr) const;

  // Dual-grid MSSM: the node of `level` whose first cell is `cell` (-1 .. N - 1 per axis).
  glm::dvec2 dualNode(int level, glm::ivec2 cell) const;
  // Dual-grid MSSM: (min, max) over the inclusive cell rectangle [cellLo, cellHi], tiled like the N-buffers.
  glm::dvec2 dualRange(glm::ivec2 cellLo, glm::ivec2 cellHi, int* fetches = nullptr) const;

  // Mip-map layout: levels 1..L in the N x N atlas (2 components, 0 outside the levels).
  ImageF atlas() const;
};

} // namespace sl
