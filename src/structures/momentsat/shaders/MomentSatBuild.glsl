// Summed-area table of the four power moments (moment soft shadow mapping, Peters et al. 2016/2017; Crow 1984),
// built band by band as sat/SatBuild.glsl (gl/BandedPrefixSums.h): prefix sums along each of the band's rows
// (MOMENT_SAT_PASS 0, from the shadow map), then along each column in place, continuing from the table's row above
// the band (MOMENT_SAT_PASS 1, the carries), in storage buffers the pass copies into the tables.
// Precision: each texel's moments b = (z, z^2, z^3, z^4) (z normalised to the light's range and clamped, as the
// power-moment map computes them) become fixed point floor(m 2^b) (m = 1: 2^b - 1), fixedPointScale = 2^b.
//  - MOMENT_SAT_WIDE 1 (int64): b = 32 and the sums are 64-bit integers held as two words (low: momentSatLow,
//    high: the high band), added with uaddCarry. An N x N map sums below N^2 2^32 (2^58 at 8192^2): the table holds
//    the true prefix sums and every box sum (usubBorrow) is exact.
//  - MOMENT_SAT_WIDE 0 (int32, the authors' form): b = 32 - ceil(log2(w^2)) and 32-bit sums that wrap: a box sum is
//    exact modulo 2^32, hence exact for boxes of at most w^2 texels.
// CPU mirror: src/lightspace/MomentSummedAreaTable.cpp.
layout(local_size_x = 64) in;

uniform sampler2D shadowMapLinear;
uniform float depthNear;
uniform float depthFar;
uniform float fixedPointScale; // 2^b
uniform int mapSize;           // texels per side of the map and of the tables
uniform int bandFirstRow;      // the map row of the band's row 0
uniform int bandRows;          // rows in this band

// The band's sums, row-major (mapSize per row), as the tables' RGBA32UI texels; per column, the table's value in the
// row above the band (0 above the first band), which the column pass updates.
layout(std430, binding = 0) restrict buffer MomentSatLowBand
{
  uvec4 lowSums[];
};
layout(std430, binding = 1) restrict buffer MomentSatLowCarry
{
  uvec4 lowCarry[];
};
#if MOMENT_SAT_WIDE
layout(std430, binding = 2) restrict buffer MomentSatHighBand
{
  uvec4 highSums[];
};
layout(std430, binding = 3) restrict buffer MomentSatHighCarry
{
  uvec4 highCarry[];
};
#endif

uvec4 quantisedMoments(float depth)
{
  float z = clamp((depth - depthNear) / (depthFar - depthNear), 0.0, 1.0);
  float z2 = z * z;
  vec4 moments = vec4(z, z2, z2 * z, z2 * z2);
  // m 2^b is exact in float (a power of two); below 2^b <= 2^32 it converts to uint without overflow. 2^b - 1 as
  // 2 (2^(b-1)) - 1, which wraps to 2^32 - 1 for b = 32.
  uvec4 quantised = uvec4(moments * fixedPointScale);
  uint largest = 2u * uint(0.5 * fixedPointScale) - 1u;
  return mix(quantised, uvec4(largest), greaterThanEqual(moments, vec4(1.0)));
}

void main()
{
  int line = int(gl_GlobalInvocationID.x);
  uvec4 carry;
#if MOMENT_SAT_PASS == 0
  // One invocation per row of the band.
  if (line >= bandRows)
  {
    return;
  }
  uvec4 low = uvec4(0u);
#if MOMENT_SAT_WIDE
  uvec4 high = uvec4(0u);
#endif
  for (int x = 0; x < mapSize; ++x)
  {
    int index = line * mapSize + x;
    low = uaddCarry(low, quantisedMoments(texelFetch(shadowMapLinear, ivec2(x, bandFirstRow + line), 0).r), carry);
    lowSums[index] = low;
#if MOMENT_SAT_WIDE
    high += carry;
    highSums[index] = high;
#endif
  }
#else
  // One invocation per column.
  if (line >= mapSize)
  {
    return;
  }
  uvec4 low = lowCarry[line];
#if MOMENT_SAT_WIDE
  uvec4 high = highCarry[line];
#endif
  for (int y = 0; y < bandRows; ++y)
  {
    int index = y * mapSize + line;
    low = uaddCarry(low, lowSums[index], carry);
    lowSums[index] = low;
#if MOMENT_SAT_WIDE
    high += highSums[index] + carry;
    highSums[index] = high;
#endif
  }
  lowCarry[line] = low;
#if MOMENT_SAT_WIDE
  highCarry[line] = high;
#endif
#endif
}
