// Named light-sample sets shared by object-space soft shadows (technique `dcs`, Forest, Barthe & Paulin 2008 as
// used by Forest et al. 2009 §4.1) and the ray-traced reference (`shadowlab reference
// --light-samples PATTERN --samples N --seed S`): both take the very same N points per pixel, so the technique's
// per-sample depth complexity can be checked sample by sample, not statistically.
//
// A set is one base pattern of N points in the unit square (Forest et al. 2009 §4.1):
//  - grid:       the sqrt(N) x sqrt(N) cell centres;
//  - stratified: one uniformly jittered point per cell of the same grid (Forest et al. 2009 Fig. 5 b);
//  - poisson:    a Poisson-disk set in the unit square with the paper's minimum distances, 0.2456139 for N = 16
//                and 0.1076681 for N = 64 (Forest et al. 2009 §4.1); for N = 256, which the paper does not use, the
//                distance at the same packing density (see LightSampleSet.cpp);
//  - zero_two:   the first N points of the Sobol (0,2)-sequence (its first two dimensions), a (0, log2 N, 2)-net;
// and a per-pixel toroidal shift (Cranley-Patterson rotation) that decorrelates neighbouring pixels. The paper
// rotates its samples per pixel (Forest et al. 2009 §4.1); a rotation would carry samples off a square light, a toroidal
// shift keeps every sample on it and keeps the set's stratification. With the suffix `_4x4`, the shift is
// not hashed per pixel but set by the pixel's place in a 4 x 4 tile (interleaved sampling, Keller & Heidrich
// 2001, Forest et al. 2009 Fig. 5 f): the 16 shifted copies of a grid-like pattern fill a 4 sqrt(N) x 4 sqrt(N) grid.
//
// The shifts, exactly (the GLSL twin repeats this in uint arithmetic; hash32 is Wellons' "lowbias32", a
// bijection of 32-bit words, h0 = hash32(seed + 0x9E3779B9)):
//  - per pixel:   h = hash32(hash32(h0 ^ x) + y); shift = (h >> 16, h & 0xFFFF) 2^-16;
//  - interleaved: f = hash32(seed + 0x6A09E667) gives frameShift = (f >> 16, f & 0xFFFF) 2^-16, one per seed, and
//                 shift = fract(frameShift + ((x mod 4 + 1/2) / 4, (y mod 4 + 1/2) / 4) / sqrt(N)).
//    Why this is Keller & Heidrich's interleaving: a tile offset (a + 1/2) / (4 sqrt N), a = 0..3, moves a grid
//    point (i + 1/2) / sqrt(N) to (4 i + a + 2 + 1/2) / (4 sqrt N), the centre of cell 4 i + a + 2 of the grid
//    four times finer; over the 16 pixels of a tile, (i, a) -> 4 i + a + 2 (mod 4 sqrt N) meets every cell once
//    per axis, so the tile's 16 N samples are that whole 4 sqrt(N) x 4 sqrt(N) grid (shifted by frameShift): the
//    tile as a whole is sampled 16 times more densely, each pixel by a regular subset of it. Other patterns get
//    the same 16 offsets: each base point's 16 copies fall one per cell in a 4 x 4 block of that finer grid.
//
// Exactness between CPU and GPU: base points and shifts are multiples of 2^-16, so fract(base + shift) is exact in
// float and the GLSL twin (shaders/common/LightSampleSet.glsl) yields the same unit-square point bit for bit. The
// unit point maps onto the light with pointOnAreaLight (lightspace/LightSamples.h): square or disk (Shirley &
// Chiu's concentric map), the reference's mapping. Sets are for area lights: a point, spot or directional light
// has every sample at its centre (offset 0).
#pragma once

#include "scene/Scene.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace sl
{

enum class LightSamplePattern
{
  Grid,
  Stratified,
  Poisson,
  ZeroTwo
};

struct LightSampleSetSettings
{
  LightSamplePattern pattern = LightSamplePattern::Poisson;
  bool interleaved = false; // 4 x 4 interleaved shifts instead of per-pixel hashed ones
  int count = 16;           // N: 16, 64 or 256
  std::uint32_t seed = 1;   // draws the stratified jitter, the Poisson set and the per-pixel shifts
};

// The sample counts a set can have (perfect squares and powers of two: every pattern is defined for them).
const std::vector<int>& lightSampleCounts();
// "grid", "stratified", "poisson", "zero_two", then the same four with "_4x4" (interleaved), in that order: the
// choices of the parameter `light_samples` and of `--light-samples`.
const std::vector<std::string>& lightSamplePatternNames();
// The settings named `patternName` (one of lightSamplePatternNames()) with `count` samples and `seed`. Throws
// InputError naming the bad value and the valid ones ("--light-samples spiral: ...", "--samples 10: ...").
LightSampleSetSettings lightSampleSetSettings(const std::string& patternName, int count, std::uint32_t seed);
// The name lightSamplePatternNames() gives `settings`' pattern and interleaving.
std::string lightSamplePatternName(const LightSampleSetSettings& settings);
// The minimum distance between the `count` points of a poisson set (unit square, not toroidal): Forest et al. 2009's 0.2456139
// (N = 16) and 0.1076681 (N = 64); for N = 256 the distance at N = 64's packing density (LightSampleSet.cpp).
double lightSamplePoissonDistance(int count);

class LightSampleSet
{
public:
  explicit LightSampleSet(const LightSampleSetSettings& settings); // SL_CHECKs a valid count
  const LightSampleSetSettings& settings() const { return settings_; }
  int count() const { return settings_.count; }

  // Pattern 0: the N base points in [0, 1)^2, multiples of 2^-16 (exported as light_samples).
  const std::vector<glm::dvec2>& basePoints() const { return basePoints_; }
  // The toroidal shift of pixel (x, y) (row 0 at the bottom), in [0, 1)^2, multiples of 2^-16.
  glm::dvec2 pixelShift(int x, int y) const;
  // Sample `index` of pixel (x, y) on the unit square: fract(base + shift), exactly.
  glm::dvec2 unitSample(int x, int y, int index) const;
  // The same sample on `light` (an area light), world space: pointOnAreaLight(light, unitSample(x, y, index)).
  glm::dvec3 point(const Light& light, int x, int y, int index) const;

private:
  LightSampleSetSettings settings_;
  std::vector<glm::dvec2> basePoints_;
};

// Where a unit-square point lies on `light`'s plane, in the light's (right(), up) frame, world units from its
// centre: (u - 1/2, v - 1/2) size for a square, concentricDiskMap(u, v) size / 2 for a disk. pointOnAreaLight is
// center + offset.x right() + offset.y up.
glm::dvec2 lightPlaneOffset(const Light& light, const glm::dvec2& unitSquare);

} // namespace sl
