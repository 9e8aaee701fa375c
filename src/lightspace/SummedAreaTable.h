// CPU mirror of the summed-area table (structures/sat/shaders/SatBuild.glsl) and its box lookups
// (shaders/common/SatLookup.glsl), in double precision, plus the exact box moments they approximate.
#pragma once

#include "core/Image.h"

#include <glm/glm.hpp>

#include <cstdint>

namespace sl
{

struct BoxMoments
{
  double mean = 0.0;
  double variance = 0.0;
};

// The int32 fixed-point scale the GPU uses for an N x N map: 2^b - 1, b = min(16, 32 - ceil(log2(N^2))).
double satFixedPointScale(int mapSize);
// The int32 table exactly as the GPU builds it (fixed point z_n and z_n^2, sums modulo 2^32).
Image<std::uint32_t> integerSummedAreaTable(const ImageF& shadowMapLinear, double nearDepth, double farDepth);

// Mean and variance, in double, of the depths of the inclusive texel rectangle [lo, hi] as the table encodes
// them: clamped to [near, far], and for int32 quantised to 16-bit fixed point. What a perfect-precision SAT
// would return.
BoxMoments exactBoxMoments(const ImageF& shadowMapLinear, glm::ivec2 lo, glm::ivec2 hi, double nearDepth,
  double farDepth, bool integer);

// The same from a table read back from the GPU (four corners, in double): float_centred (2 components:
// centred sums) or int32.
BoxMoments boxMomentsFromFloatTable(const ImageF& table, glm::ivec2 lo, glm::ivec2 hi, double nearDepth, double farDepth);
BoxMoments boxMomentsFromIntegerTable(const Image<std::uint32_t>& table, glm::ivec2 lo, glm::ivec2 hi,
  double nearDepth, double farDepth);

} // namespace sl
