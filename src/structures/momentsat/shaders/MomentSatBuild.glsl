// Summed-area table of the four power moments (moment soft shadow mapping, Peters et al. 2016/2017; Crow 1984), in
// two compute passes as sat/SatBuild.glsl: prefix sums along each row (MOMENT_SAT_PASS 0, from the shadow map), then
// along each column in place (MOMENT_SAT_PASS 1).
// Precision: each texel's moments b = (z, z^2, z^3, z^4) (z normalised to the light's range and clamped, as the
// power-moment map computes them) become 32-bit fixed point floor(m 2^32) (m = 1: 2^32 - 1), and the sums are
// 64-bit integers held as two words (low: momentSatLow, high: momentSatHigh), added with uaddCarry. An N x N map sums
// below N^2 2^32 (2^58 at 8192^2): the table holds the true prefix sums and every box sum (usubBorrow) is exact.
// CPU mirror: src/lightspace/MomentSummedAreaTable.cpp.
layout(local_size_x = 64) in;

uniform sampler2D shadowMapLinear;
uniform float depthNear;
uniform float depthFar;

layout(rgba32ui, binding = 0) uniform uimage2D momentSatLow;
layout(rgba32ui, binding = 1) uniform uimage2D momentSatHigh;

// A shadow-map texel's quantised moments (momentSatTexel).
uvec4 quantisedMoments(float depth)
{
  float z = clamp((depth - depthNear) / (depthFar - depthNear), 0.0, 1.0);
  float z2 = z * z;
  vec4 moments = vec4(z, z2, z2 * z, z2 * z2);
  // m 2^32 is exact in float (a power of two); below 2^32 it converts to uint without overflow.
  uvec4 quantised = uvec4(moments * 4294967296.0);
  return mix(quantised, uvec4(0xFFFFFFFFu), greaterThanEqual(moments, vec4(1.0)));
}

void main()
{
  int line = int(gl_GlobalInvocationID.x);
  ivec2 size = imageSize(momentSatLow);
  uvec4 low = uvec4(0u);
  uvec4 high = uvec4(0u);
  uvec4 carry;
#if MOMENT_SAT_PASS == 0
  if (line >= size.y)
  {
    return;
  }
  for (int x = 0; x < size.x; ++x)
  {
    low = uaddCarry(low, quantisedMoments(texelFetch(shadowMapLinear, ivec2(x, line), 0).r), carry);
    high += carry;
    imageStore(momentSatLow, ivec2(x, line), low);
    imageStore(momentSatHigh, ivec2(x, line), high);
  }
#else
  if (line >= size.x)
  {
    return;
  }
  for (int y = 0; y < size.y; ++y)
  {
    low = uaddCarry(low, imageLoad(momentSatLow, ivec2(line, y)), carry);
    high += imageLoad(momentSatHigh, ivec2(line, y)) + carry;
    imageStore(momentSatLow, ivec2(line, y), low);
    imageStore(momentSatHigh, ivec2(line, y), high);
  }
#endif
}
