// CPU mirror of the moment summed-area table (structures/momentsat: MomentSatBuild.glsl and MomentSatLookup.glsl):
// per shadow-map texel the four power moments b = (z, z^2, z^3, z^4) of the normalised depth (as the power-moment
// map computes them, in float), each quantised to 32-bit fixed point, summed in 64-bit integers. An N x N map sums
// below N^2 2^32 (2^58 at 8192^2, the largest shadow_map_size), so the table holds the true sums (no wrapping) and
// every box sum is exact.
#pragma once

#include "core/Image.h"

#include <glm/glm.hpp>

#include <array>
#include <cstdint>

namespace sl
{

// The fixed-point scale: a moment m in [0, 1) becomes floor(m 2^32) (exact in float: a power of two), m = 1 becomes
// 2^32 - 1. Decoded as q / 2^32.
inline constexpr double momentSatScale = 4294967296.0;
// The largest map the 64-bit sums hold exactly: 2^32 texels of at most 2^32 - 1 each stay below 2^64.
inline constexpr int momentSatMaxMapSize = 65536;

using MomentSums = std::array<std::uint64_t, 4>;

// A texel's quantised moments exactly as the GPU computes them: z = clamp((d - near) / (far - near), 0, 1) in float
// with the float near and far, z^2 = z z, z^3 = z^2 z, z^4 = z^2 z^2, then floor(m 2^32) clamped to 2^32 - 1.
std::array<std::uint32_t, 4> momentSatTexel(float depth, float nearDepth, float farDepth);

// The table exactly as the GPU builds it: 4 components per texel (row 0 at the bottom), the inclusive prefix sums.
Image<std::uint64_t> momentSummedAreaTable(const ImageF& shadowMapLinear, double nearDepth, double farDepth);
// The GPU's table read back as 8 words per texel (the low words of the four sums, then the high words).
Image<std::uint64_t> momentSummedAreaTableFromWords(const Image<std::uint32_t>& words);

// Sum of the quantised moments over the inclusive texels [lo, hi] (four corners, unsigned: exact).
MomentSums momentBoxSum(const Image<std::uint64_t>& table, glm::ivec2 lo, glm::ivec2 hi);
// The mean of the moments over [lo, hi], in double: the sums / (texels 2^32).
glm::dvec4 momentBoxMean(const Image<std::uint64_t>& table, glm::ivec2 lo, glm::ivec2 hi);

// The mean of the moments over the continuous rectangle [boxMin, boxMax] (texel units, texel i covering [i, i + 1]),
// clamped to the map: each texel weighted by the area of it the rectangle covers (the inner texels wholly, the
// border texels by their covered fraction, the corners by the product), from at most nine exact box sums. Continuous
// in the rectangle's edges. A rectangle of no area after clamping reads the texel holding its centre.
glm::dvec4 momentFractionalBoxMean(const Image<std::uint64_t>& table, glm::dvec2 boxMin, glm::dvec2 boxMax);

// The per-axis pieces of a fractional rectangle: up to three inclusive texel ranges with their covered widths.
struct FractionalSpan
{
  int count = 0;
  std::array<int, 3> first{};
  std::array<int, 3> last{};
  std::array<double, 3> width{};
};
FractionalSpan fractionalSpan(double lower, double upper, int mapSize);

} // namespace sl
