// Summed-area table of the four power moments (moment soft shadow mapping, Peters et al. 2016/2017; Crow 1984), in
// two compute passes as sat/SatBuild.glsl: prefix sums along each row (MOMENT_SAT_PASS 0, from the shadow map), then
// along each column in place (MOMENT_SAT_PASS 1).
// Precision: each texel's moments b = (z, z^2, z^3, z^4) (z normalised to the light's range and clamped, as the
// power-moment map computes them) become fixed point floor(m 2^b) (m = 1: 2^b - 1), fixedPointScale = 2^b.
//  - MOMENT_SAT_WIDE 1 (int64): b = 32 and the sums are 64-bit integers held as two words (low: momentSatLow,
//    high: momentSatHigh), added with uaddCarry. An N x N map sums below N^2 2^32 (2^58 at 8192^2): the table holds
//    the true prefix sums and every box sum (usubBorrow) is exact.
//  - MOMENT_SAT_WIDE 0 (int32, the authors' form): b = 32 - ceil(log2(w^2)) and 32-bit sums that wrap: a box sum is
//    exact modulo 2^32, hence exact for boxes of at most w^2 texels.
// CPU mirror: src/lightspace/MomentSummedAreaTable.cpp.
layout(local_size_x = 64) in;

uniform sampler2D shadowMapLinear;
uniform float depthNear;
uniform float depthFar;
uniform float fixedPointScale; // 2^b

layout(rgba32ui, binding = 0) uniform uimage2D momentSatLow;
#if MOMENT_SAT_WIDE
layout(rgba32ui, binding = 1) uniform uimage2D momentSatHigh;
#endif

// A shadow-map texel's quantised moments (momentSatTexel).
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
  ivec2 size = imageSize(momentSatLow);
  uvec4 low = uvec4(0u);
  uvec4 carry;
#if MOMENT_SAT_WIDE
  uvec4 high = uvec4(0u);
#endif
#if MOMENT_SAT_PASS == 0
  if (line >= size.y)
  {
    return;
  }
  for (int x = 0; x < size.x; ++x)
  {
    low = uaddCarry(low, quantisedMoments(texelFetch(shadowMapLinear, ivec2(x, line), 0).r), carry);
    imageStore(momentSatLow, ivec2(x, line), low);
#if MOMENT_SAT_WIDE
    high += carry;
    imageStore(momentSatHigh, ivec2(x, line), high);
#endif
  }
#else
  if (line >= size.x)
  {
    return;
  }
  for (int y = 0; y < size.y; ++y)
  {
    low = uaddCarry(low, imageLoad(momentSatLow, ivec2(line, y)), carry);
    imageStore(momentSatLow, ivec2(line, y), low);
#if MOMENT_SAT_WIDE
    high += imageLoad(momentSatHigh, ivec2(line, y)) + carry;
    imageStore(momentSatHigh, ivec2(line, y), high);
#endif
  }
#endif
}
