// The min-max hierarchical shadow map (HSM) of VSSM (Yang et al. 2010, Alg. 1 L4 and §6.1), in double
// precision: the CPU mirror of structures/hsm/shaders/HsmBuild.glsl and of the range query in
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
//  - Y shadow map (YSM; Schwarz & Stamminger 2008, §6, Table 1): a hybrid of the two. The
//    full mip-map HSM above (`levels`, the same atlas; the paper's implementation keeps the HSM untruncated for
//    micro-occluder construction, §6) plus an "MSSM part": the N-buffers of HSM level b (the paper's
//    n - 1), b = max(0, floor(log2 (N / 256))) so that the part is about 256^2 (§6: 256^2 at N = 1024
//    and 2048; b = 0, the part as large as the map, for N <= 511). The part's level 0 is HSM level b and is not
//    stored (§6); `mssmPart[j - 1]` holds its level j = 1..ceil(log2 M), M = ceil(N / 2^b), as M x M.
//    A query first takes the mip-map level k the mip-map query would use; for k <= b it is that query, else
//    the rectangle's level-b nodes [lo >> b, hi >> b] are tiled like the N-buffers by the part's squares:
//    conservative, exact on rectangles aligned to level-b blocks, never looser than the mip-map query (the mip
//    nodes of level k > b cover every level-b node the tiling reads). Memory (RG32F): the N x N atlas plus
//    8 M^2 ceil(log2 M) bytes, i.e. + 4 MiB at 1024^2 and 2048^2, Table 1's YSM - HSM.
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
  DualMssm,
  Ysm // the mip-map levels plus an N-buffers part from level ysmBaseLevel (SS08 §6)
};

// Levels above 0 of an N x N map: ceil(log2 N) (the last mip level is 1 x 1).
int hsmLevelCount(int mapSize);
// Levels above 0 of the dual-grid MSSM: ceil(log2 (N + 1)), so that one node covers all N + 1 cells.
int dualMssmLevelCount(int mapSize);
// Texels per side of level k.
int hsmLevelSize(HsmLayout layout, int mapSize, int level);
// Mip-map layout (and the YSM's): where level k >= 1 starts in the N x N atlas.
glm::ivec2 hsmAtlasOffset(int mapSize, int level);
// YSM: the MSSM part's resolution the paper recommends (SS08 §6).
constexpr int ysmMssmPartTargetSize = 256;
// YSM: the HSM level b the MSSM part is built from: the largest b with 256 * 2^b <= N, 0 for N < 512.
int ysmBaseLevel(int mapSize);
// YSM: texels per side of the MSSM part, M = ceil(N / 2^b) (= N for b = 0).
int ysmMssmPartSize(int mapSize);
// YSM: levels of the MSSM part stored (1..ceil(log2 M); level 0 is HSM level b).
int ysmMssmPartLevelCount(int mapSize);

// The top level an exactly tiled hierarchy (N-buffers, dual-grid MSSM) is built to when the frame's queries read
// levels up to `levelRead`: that level, within [levelCount - maxLevelsLeftOut, levelCount]. Each level of those
// layouts holds N^2 texels, so the levels above it are that share of the build (issue 33: structures built at the
// level of detail the frame reads). Queries wider than that stay exact: they are tiled with more squares of the top
// level, at most (2^maxLevelsLeftOut + 1)^2 for the whole map, which the floor bounds.
constexpr int minMaxMaxLevelsLeftOut = 4;
int minMaxTopLevel(int levelCount, int levelRead);

// A node a range query read (`shadowlab probe` records them): the shadow-map texels it covers (inclusive,
// clipped to the map; for the dual-grid MSSM the samples of its cells), the range it holds, and its width as a
// level: a node of `level` spans 2^level texels (cells) per side.
struct HsmQueryNode
{
  const char* part = "";   // "mip-map", "n-buffers", "ysm mssm part", "dual-grid mssm"
  int level = 0;
  glm::ivec2 lo{ 0 };
  glm::ivec2 hi{ 0 };
  glm::dvec2 range{ 0.0 }; // (min, max) linear depth
};

struct HierarchicalShadowMap
{
  HsmLayout layout = HsmLayout::MipMap;
  int mapSize = 0;
  std::vector<ImageF> levels; // levels[k]: 2 components (min, max); levels[0] from the shadow map, up to topLevel()
  // YSM only: the MSSM part, mssmPart[j - 1] = its N-buffer level j (M x M) over the nodes of HSM level
  // ysmBaseLevel (its level 0).
  int ysmBaseLevel = 0;
  std::vector<ImageF> mssmPart;

  // `topLevel` (N-buffers and dual grid only; -1: every level): the last level built (minMaxTopLevel). Queries
  // tile with squares of at most that level, so every range stays exact; the GPU builds (vtkSLHsmPass) alike.
  static HierarchicalShadowMap build(const ImageF& shadowMapLinear, HsmLayout layout, int topLevel = -1);
  static HierarchicalShadowMap buildDual(const ImageF& shadowMapLinear, float outsideDepth, int topLevel = -1);
  int topLevel() const { return static_cast<int>(levels.size()) - 1; }

  // (min, max) depth over the inclusive texel rectangle [lo, hi] (inside the map): exact for N-buffers and the
  // dual-grid MSSM (there [lo, hi] must be at least 2 x 2), the range of the covering nodes for the mip-map. `fetches` (optional) counts the texels read.
  // YSM: conservative, exact on rectangles aligned to level-ysmBaseLevel blocks, never looser than the mip-map.
  // `nodes` (optional) receives the nodes read, in the order read; the result does not depend on it.
  glm::dvec2 range(glm::ivec2 lo, glm::ivec2 hi, int* fetches = nullptr, std::vector<HsmQueryNode>* nodes = nullptr) const;

  // Every layout but the dual grid: (min, max) over the aligned block [index 2^level, (index + 1) 2^level)
  // (clipped to the map) of the mip-map quadtree; level 0 is the shadow map. Mip-map and YSM: texel `index` of
  // the level; N-buffers: the square at texel index 2^level (the same range). GLSL: hsmNode.
  glm::dvec2 node(int level, glm::ivec2 index) const;

  // Dual-grid MSSM: the node of `level` whose first cell is `cell` (-1 .. N - 1 per axis).
  glm::dvec2 dualNode(int level, glm::ivec2 cell) const;
  // Dual-grid MSSM: (min, max) over the inclusive cell rectangle [cellLo, cellHi], tiled like the N-buffers.
  glm::dvec2 dualRange(glm::ivec2 cellLo, glm::ivec2 cellHi, int* fetches = nullptr,
    std::vector<HsmQueryNode>* nodes = nullptr) const;

  // Mip-map layout and YSM: levels 1..L in the N x N atlas (2 components, 0 outside the levels).
  ImageF atlas() const;
};

} // namespace sl
