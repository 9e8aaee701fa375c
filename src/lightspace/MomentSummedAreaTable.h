// CPU mirror of the moment summed-area table (structures/momentsat: MomentSatBuild.glsl and MomentSatLookup.glsl):
// per shadow-map texel the four power moments b = (z, z^2, z^3, z^4) of the normalised depth (as the power-moment
// map computes them, in float), each quantised to fixed point of `bits` bits, summed exactly.
//  - int64 (32 bits per texel, 64-bit sums): an N x N map sums below N^2 2^32 (2^58 at 8192^2, the largest
//    shadow_map_size), so the GPU's table holds the true sums and every box sum is exact.
//  - int32 (the authors' form: 32 - ceil(log2(w^2)) bits for the largest exact box of w x w texels, 32-bit sums that
//    wrap): a box sum is exact modulo 2^32, hence exact for boxes of at most 2^(32 - bits) texels.
// The mirror keeps the exact 64-bit sums either way; the GPU's int32 table is their low words.
#pragma once

#include "core/Image.h"

#include <glm/glm.hpp>

#include <array>
#include <cmath>
#include <cstdint>

namespace sl
{

// The fixed point: a moment m in [0, 1) becomes floor(m 2^bits) (exact in float: a power of two), m = 1 becomes
// 2^bits - 1. Decoded as q / 2^bits.
struct MomentSatFormat
{
  int bits = 32;    // fixed-point bits per texel and moment
  bool wide = true; // 64-bit sums (int64); else 32-bit sums that wrap (int32)

  double scale() const { return std::ldexp(1.0, bits); }
  // The largest box (texels) whose sum the table holds exactly: 2^(32 - bits) for int32; for int64 2^64, more than
  // any map holds.
  double exactTexels() const { return std::ldexp(1.0, wide ? 64 : 32 - bits); }
};
// int32 for boxes up to maxKernelTexels x maxKernelTexels: bits = 32 - ceil(log2(maxKernelTexels^2)).
MomentSatFormat int32MomentSatFormat(int maxKernelTexels);
// The largest map the 64-bit sums hold exactly: 2^32 texels of at most 2^32 - 1 each stay below 2^64.
inline constexpr int momentSatMaxMapSize = 65536;

using MomentSums = std::array<std::uint64_t, 4>;

// A texel's quantised moments exactly as the GPU computes them: z = clamp((d - near) / (far - near), 0, 1) in float
// with the float near and far, z^2 = z z, z^3 = z^2 z, z^4 = z^2 z^2, then floor(m 2^bits) clamped to 2^bits - 1.
std::array<std::uint32_t, 4> momentSatTexel(float depth, float nearDepth, float farDepth, int bits = 32);

// The exact prefix sums of the quantised moments: 4 components per texel (row 0 at the bottom), and their format.
struct MomentSatTable
{
  Image<std::uint64_t> sums;
  MomentSatFormat format;
};
MomentSatTable momentSummedAreaTable(const ImageF& shadowMapLinear, double nearDepth, double farDepth,
  const MomentSatFormat& format = {});
// The GPU's table read back: 8 words per texel (int64: the low words of the four sums, then the high words) or 4
// (int32: the wrapped sums).
Image<std::uint64_t> momentSummedAreaTableFromWords(const Image<std::uint32_t>& words);

// Sum of the quantised moments over the inclusive texels [lo, hi] (four corners, unsigned: exact).
MomentSums momentBoxSum(const Image<std::uint64_t>& sums, glm::ivec2 lo, glm::ivec2 hi);
// The mean of the moments over [lo, hi], in double: the sums / (texels 2^bits).
glm::dvec4 momentBoxMean(const MomentSatTable& table, glm::ivec2 lo, glm::ivec2 hi);

// The mean of the moments over the continuous rectangle [boxMin, boxMax] (texel units, texel i covering [i, i + 1]),
// clamped to the map: each texel weighted by the area of it the rectangle covers (the inner texels wholly, the
// border texels by their covered fraction, the corners by the product), from at most nine exact box sums. Continuous
// in the rectangle's edges. A rectangle of no area after clamping reads the texel holding its centre.
glm::dvec4 momentFractionalBoxMean(const MomentSatTable& table, glm::dvec2 boxMin, glm::dvec2 boxMax);

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
