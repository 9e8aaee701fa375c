// The named light-sample sets (src/lightspace/LightSampleSet.h; Forest et al. 2009 §4.1): N base points in the
// unit square and a per-pixel toroidal shift, bound by the structure `light_samples`
// (src/structures/lightsamples/LightSampleSetStructure.cpp). The GLSL twin of LightSampleSet: the shift is the same
// uint arithmetic and every coordinate a multiple of 2^-16, so lightSampleUnit equals LightSampleSet::unitSample
// bit for bit (tests/render/LightSampleSetGpuTest.cpp); lightSampleOffset and lightSamplePoint follow
// lightPlaneOffset and pointOnAreaLight in float.
// LIGHT_SAMPLE_COUNT (= lightSampleCount, N) comes from the structure's preamble, for per-sample arrays and loops.

uniform sampler2D lightSampleBase;  // N x 1 RG32F: the base points (pattern 0), multiples of 2^-16 in [0, 1)
uniform int lightSampleCount;       // N
uniform int lightSampleSeed;        // the 32-bit seed's bits (VTK 9.1 sets no unsigned uniforms): uint() restores it
uniform int lightSampleInterleaved; // 1: shifts from the pixel's place in a 4 x 4 tile, 0: hashed per pixel
uniform int lightSampleGridSide;    // sqrt(N)
uniform int lightSampleDisk;        // 1: a disk light (concentric map), 0: a square one
uniform float lightSampleSize;      // side or diameter, world units; 0 for a light that is not an area light
uniform vec3 lightSampleCenterWs;
uniform vec3 lightSampleRightWs;    // Light::right() = up x normal
uniform vec3 lightSampleUpWs;

// Wellons' lowbias32, as hash32 in LightSampleSet.cpp (uint arithmetic wraps modulo 2^32 in both languages).
uint lightSampleHash32(uint value)
{
  value ^= value >> 16u;
  value *= 0x7FEB352Du;
  value ^= value >> 15u;
  value *= 0x846CA68Bu;
  value ^= value >> 16u;
  return value;
}

// A pixel's toroidal shift in 2^-16 units (LightSampleSet::pixelShift): hashed from (seed, x, y), or, interleaved,
// fract(frameShift + ((x mod 4 + 1/2) / 4, (y mod 4 + 1/2) / 4) / sqrt N) with (2 a + 1) (8192 / sqrt N) units
// per tile offset (Keller & Heidrich 2001; why it fills the 4 sqrt(N) grid: LightSampleSet.h).
uvec2 lightSampleShiftFixedPoint(ivec2 pixel)
{
  uint seed = uint(lightSampleSeed);
  uint bits;
  if (lightSampleInterleaved == 0)
  {
    uint h0 = lightSampleHash32(seed + 0x9E3779B9u);
    bits = lightSampleHash32(lightSampleHash32(h0 ^ uint(pixel.x)) + uint(pixel.y));
    return uvec2(bits >> 16u, bits & 0xFFFFu);
  }
  bits = lightSampleHash32(seed + 0x6A09E667u);
  uvec2 frameShift = uvec2(bits >> 16u, bits & 0xFFFFu);
  uint halfStep = 8192u / uint(lightSampleGridSide);
  uvec2 tile = uvec2(pixel) & 3u;
  return (frameShift + (2u * tile + 1u) * halfStep) & 0xFFFFu;
}

// The shift on the unit square, [0, 1)^2 (exact: an integer below 2^16 times 2^-16).
vec2 lightSampleShift(ivec2 pixel)
{
  return vec2(lightSampleShiftFixedPoint(pixel)) * (1.0 / 65536.0);
}

// Sample `index` (0..N-1) for a pixel whose shift is `shift`: fract(base + shift), exact in float (both terms are
// multiples of 2^-16 below 1). The overload for loops over the samples, which compute the shift once.
vec2 lightSampleUnit(vec2 shift, int index)
{
  return fract(texelFetch(lightSampleBase, ivec2(index, 0), 0).xy + shift);
}

vec2 lightSampleUnit(ivec2 pixel, int index)
{
  return lightSampleUnit(lightSampleShift(pixel), index);
}

// Shirley & Chiu's concentric map of [0, 1)^2 onto the unit disk (concentricDiskMap, LightSamples.cpp).
vec2 lightSampleConcentricDisk(vec2 unit)
{
  vec2 offset = 2.0 * unit - 1.0;
  if (offset.x == 0.0 && offset.y == 0.0)
  {
    return vec2(0.0);
  }
  const float quarterPi = 0.78539816339744831;
  float radius;
  float theta;
  if (abs(offset.x) > abs(offset.y))
  {
    radius = offset.x;
    theta = quarterPi * (offset.y / offset.x);
  }
  else
  {
    radius = offset.y;
    theta = 2.0 * quarterPi - quarterPi * (offset.x / offset.y);
  }
  return radius * vec2(cos(theta), sin(theta));
}

// Where a unit-square point lies on the light's plane, in its (right, up) frame from its centre, world units
// (lightPlaneOffset): (u - 1/2, v - 1/2) size on a square, concentric(u, v) size / 2 on a disk.
vec2 lightSampleOffset(vec2 unit)
{
  if (lightSampleDisk != 0)
  {
    return (0.5 * lightSampleSize) * lightSampleConcentricDisk(unit);
  }
  return (unit - 0.5) * lightSampleSize;
}

// Sample `index` of `pixel` on the light, world space (LightSampleSet::point, pointOnAreaLight).
vec3 lightSamplePoint(ivec2 pixel, int index)
{
  vec2 offset = lightSampleOffset(lightSampleUnit(pixel, index));
  return lightSampleCenterWs + offset.x * lightSampleRightWs + offset.y * lightSampleUpWs;
}
