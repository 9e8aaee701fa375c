// Points on an area light for the ray-traced reference, counter-based: sample `index` of pixel (x, y)
// depends only on (seed, x, y, index) -- never on a shared RNG, the thread, or the order of evaluation --
// so the reference is identical for any thread count.
//
// A sample is first a point u in [0,1)^2, then mapped onto the light:
//  - square: center + (u.x - 1/2) size right + (u.y - 1/2) size up, with right = light.right(), up = light.up
//    (the square spanned by light.right() and light.up, side light.size);
//  - disk: Shirley & Chiu's concentric map of u onto the unit disk (area preserving and nearly
//    stratification preserving), scaled by the radius light.size / 2 in the same right/up frame.
//
// Unit-square points, two patterns (LightSampling):
//  - Stratified (jittered): a columns x rows grid of equal strata with columns = ceil(sqrt N) and
//    rows = ceil(N / columns), one uniformly jittered point per stratum. When columns * rows == N (every
//    perfect square, and N = k (k + 1)) each stratum gets exactly one sample. Otherwise (e.g. N = 10:
//    4 x 3 = 12 strata) the N samples take N *distinct* strata, chosen per pixel by a hashed permutation
//    of the strata (Kensler, "Correlated Multi-Jittered Sampling", Pixar 2013: permute()). Because the
//    subset is uniformly random per pixel, every sample is still uniform over the square, so the estimate
//    stays unbiased; only the variance is a little above that of a full grid. A fixed subset would bias
//    it (the strata never taken would never be seen).
//  - Halton: points index = 0 .. N-1 of the (2, 3) Halton sequence, with a per-pixel Cranley-Patterson
//    rotation (a uniform toroidal shift of the whole set, hashed from (seed, x, y)), which makes each point
//    uniform and the estimate unbiased while keeping the low discrepancy.
// Hashing: splitmix64's finaliser chained over the tuple (see hashTuple).
#pragma once

#include "lightspace/LightSamples.h" // radicalInverse, concentricDiskMap, pointOnAreaLight
#include "scene/Scene.h"

#include <glm/glm.hpp>

#include <cstdint>

namespace sl
{

enum class LightSampling
{
  Stratified,
  Halton
};

class LightSampler
{
public:
  // `light` must be an area light (SL_CHECK) and sampleCount >= 1.
  LightSampler(const Light& light, int sampleCount, LightSampling sampling, std::uint64_t seed);

  int sampleCount() const { return sampleCount_; }
  LightSampling sampling() const { return sampling_; }
  // The stratified grid (also set for Halton, where it is unused).
  int columns() const { return columns_; }
  int rows() const { return rows_; }

  // Sample `index` (0 <= index < sampleCount) of pixel (x, y) in [0,1)^2.
  glm::dvec2 unitSample(int x, int y, int index) const;
  // The same sample on the light, world space.
  glm::dvec3 point(int x, int y, int index) const;
  // Maps a unit-square point onto the light (see above).
  glm::dvec3 lightPoint(const glm::dvec2& unit) const;

private:
  Light light_;
  int sampleCount_;
  LightSampling sampling_;
  std::uint64_t seed_;
  int columns_;
  int rows_;
};

// A well-mixed 64-bit hash of the tuple (splitmix64's finaliser, chained).
std::uint64_t hashTuple(std::uint64_t seed, std::uint64_t a, std::uint64_t b, std::uint64_t c);
// Kensler's hashed permutation of [0, length): a bijection for each `pattern`.
std::uint32_t permuteIndex(std::uint32_t index, std::uint32_t length, std::uint32_t pattern);

} // namespace sl
