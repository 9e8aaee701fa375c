// Microrects (Schwarz & Stamminger 2008, "Quality Scalability of Soft Shadow Mapping", SS08 §5.2,
// Figs. 4-6): micro-occluders of shadow-map level i whose extent is any rectangle of level-0 texels
// instead of the 2^i x 2^i block of a micropatch. The CPU twin of structures/microrect/shaders/MicrorectBuild.glsl and of
// the lookup shaders/common/MicrorectLookup.glsl; the GPU build must equal it bit for bit.
//
// Definition (the paper's text, made exact; the choices the paper leaves open are marked "project choice"):
//  - Level 0 microrects are micropatches (§5.2): microrect (x, y) of level 0 is texel (x, y), extent
//    [x, x] x [y, y] in level-0 texels (inclusive), depth the shadow map's linear depth (empty texels hold
//    2 x far and never occlude).
//  - Level i >= 1 has ceil(size_{i-1} / 2) = ceil(N / 2^i) microrects per side, the HSM mip levels' sizes
//    (hsmLevelSize), so levels 0..L exist with L = hsmLevelCount(N) = ceil(log2 N). One microrect per texel
//    (§5.2). Reference points by subsampling (§5.2): level-i microrect (x, y) keeps level-(i-1)
//    microrect A = (2x, 2y), so its reference point is the centre of level-0 texel (2^i x, 2^i y).
//  - Construction from level i - 1, greedy and in two passes (§5.2, Fig. 6). With B = (2x+1, 2y),
//    C = (2x+2, 2y), D = (2x, 2y+1), G = (2x, 2y+2), E = (2x+1, 2y+1) of level i - 1 ("exists" = inside level
//    i - 1):
//      pass 1 (§5.2): A absorbs B if B exists and (C does not, or |z_B - z_A| <= |z_B - z_C|): B joins the
//      partner of smaller depth difference (§5.2), and on a tie the negative-side partner A (project
//      choice). Likewise D against G. A absorbs E if E exists and (the bounding rectangle of A and what A
//      absorbed so far contains E's extent (§5.2), or E's other retained neighbour (2x+2, 2y+2) does not
//      exist: project choice, or E would be absorbed by nobody).
//      pass 2 (§5.2): each retained P = (2x, 2y) absorbs every negative-side neighbour F = (2x-1, 2y),
//      H = (2x, 2y-1), E' = (2x-1, 2y-1) that exists and was not absorbed in pass 1 by its own retained
//      microrect ((2x-2, 2y), (2x, 2y-2), (2x-2, 2y-2) respectively).
//    Extent = bounding rectangle of the absorbed members' extents (§5.2); depth = min of their depths (min
//    aggregation, §5.2). No third pass (§5.2). Depth differences are taken in float, as the
//    GPU does, so that every decision (ties included) is the GPU's.
//  - Every level-(i-1) microrect is absorbed exactly once: A by itself; B by A or else, in pass 2, by C (which
//    then exists, C = (2(x+1), 2y) is retained and B is its F); D by A or G likewise (B's H); E by A or else by
//    (2x+2, 2y+2) (which then exists; E is its E').
//  - The extent contains the microrect's own reference point and no other level-i reference point (§5.2),
//    by induction: a level-(i-1) extent at index u lies strictly between the neighbouring level-(i-1) reference
//    points, inside (2^(i-1) (u - 1), 2^(i-1) (u + 1)) per axis (level 0: [u, u] inside (u - 1, u + 1)). The
//    members of level-i microrect x have u in {2x - 1, 2x, 2x + 1}, so their union lies inside
//    (2^i (x - 1), 2^i (x + 1)), which holds level-i reference point 2^i x and no other; it contains it because
//    A's extent contains A's reference point, which is the same texel. Overlaps between microrects are allowed
//    (§5.2); Microrects::overlapCount counts them.
//  - Extents are inside the map, so they fit RGBA16UI for every map side up to 65536 (kMaxImageSide is 16384).
//
// Storage on the GPU (§5.2: "two additional textures"): levels 1..L in two N x N atlases laid out like the
// HSM mip-map atlas (level 1 at the origin, levels 2.. stacked in a column to its right; hsmAtlasOffset):
// extents RGBA16UI (x0, y0, x1, y1) and depths R32F; level 0 is the shadow map itself.
#pragma once

#include "core/Image.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace sl
{

struct Microrect
{
  glm::ivec2 lo{ 0, 0 }; // inclusive extent in level-0 texels
  glm::ivec2 hi{ 0, 0 };
  float depth = 0.0f; // linear light depth, the min over the level-0 texels it represents
};

// Pass-1 claims of a retained microrect (bits of the claim image): which of B, D, E it absorbed. Declared once: the
// GPU build's preamble defines them as CLAIMED_B, CLAIMED_D, CLAIMED_E (structures/microrect/MicrorectStructure.h).
struct MicrorectClaims
{
  static constexpr std::uint8_t kB = 1;
  static constexpr std::uint8_t kD = 2;
  static constexpr std::uint8_t kE = 4;
};

struct Microrects
{
  // N for the square maps the GPU builds; the CPU twin also builds W x H maps (the tests' 1-D rows of Fig. 5),
  // whose level i has ceil(W / 2^i) x ceil(H / 2^i) microrects.
  int mapSize = 0;
  int mapHeight = 0;
  // levels[i][x + y * levelSize(i).x]; levels[0] are the micropatches.
  std::vector<std::vector<Microrect>> levels;
  // Only when built with trackMembers: members[i][x + y * levelSize(i).x] lists the level-(i-1) microrects that
  // level-i microrect absorbed (A first); members[0] is empty.
  std::vector<std::vector<std::vector<glm::ivec2>>> members;

  static Microrects build(const ImageF& shadowMapLinear, bool trackMembers = false);
  // The GPU build read back: the extent atlas (4 components x0, y0, x1, y1) and the depth atlas (1 component),
  // levels 1..L at hsmAtlasOffset; level 0 from the shadow map.
  static Microrects fromAtlases(
    const ImageF& shadowMapLinear, const Image<std::uint32_t>& extentAtlas, const ImageF& depthAtlas);

  // L: levels 0..L exist (ceil(log2 max(W, H)), hsmLevelCount for a square map).
  int levelCount() const { return static_cast<int>(levels.size()) - 1; }
  // Microrects per side of `level`: ceil(W / 2^level) x ceil(H / 2^level).
  glm::ivec2 levelSize(int level) const;
  // Microrect `index` of `level` (0..levelCount()), `index` inside levelSize(level).
  Microrect at(int level, glm::ivec2 index) const;
  // Its reference point: level-0 texel (2^level x, 2^level y) (subsampling, §5.2).
  static glm::ivec2 referencePoint(int level, glm::ivec2 index);

  // Levels 1..L in the N x N atlas (square maps only), 0 outside the levels: extents (4 components) and depths.
  Image<std::uint32_t> extentAtlas() const;
  ImageF depthAtlas() const;
  // How many level-`level` microrects' extents cover each level-0 texel (a 2-D difference array: O(W H)).
  ImageF overlapCount(int level) const;
};

// How many of `microrects` cover each texel of a width x height map, by a 2-D difference array.
ImageF microrectOverlapCount(const std::vector<Microrect>& microrects, int width, int height);

} // namespace sl
