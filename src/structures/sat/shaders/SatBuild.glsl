// Summed-area table of the shadow map's (z, z^2) (Crow 1984; SAVSM: Lauritzen 2007; survey §6.4), built
// in two compute passes: prefix sums along each row (SAT_PASS 0, from the shadow map), then along each
// column in place (SAT_PASS 1). Precision (survey §6.4, VSSM §6.4): a float SAT loses the low bits of a box
// sum to the large corner values, so
//  - SAT_PRECISION_FLOAT_CENTRED stores z - (near + far) / 2 and its square, halving the magnitudes;
//  - SAT_PRECISION_INT32 stores fixed point z_n = (z - near) / (far - near) and z_n^2, scaled by
//    fixedPointScale = 2^b - 1, in 32-bit unsigned integers: the sums wrap, but a box sum (four corners,
//    unsigned arithmetic) is exact modulo 2^32, hence exact for any box of at most 2^32 / 2^b texels. The
//    pass picks b = min(16, 32 - ceil(log2(N^2))) for an N x N map, so every box in the map is exact: the
//    integer table trades depth resolution (10 bits at 2048^2) for exact sums.
// Depths are clamped to [near, far] (empty texels, 2 x far, become far: lit for every receiver).
// CPU mirror: src/lightspace/SummedAreaTable.cpp.
layout(local_size_x = 64) in;

uniform sampler2D shadowMapLinear;
uniform float depthNear;
uniform float depthFar;
uniform float fixedPointScale;

#if SAT_PRECISION == SAT_PRECISION_INT32
layout(rg32ui, binding = 0) uniform uimage2D satImage;
#define SatSum uvec2
#else
layout(rg32f, binding = 0) uniform image2D satImage;
#define SatSum vec2
#endif

// A shadow-map texel's (z, z^2) in the table's representation.
SatSum satEntry(float z)
{
  z = clamp(z, depthNear, depthFar);
#if SAT_PRECISION == SAT_PRECISION_INT32
  float zNormalized = (z - depthNear) / (depthFar - depthNear);
  return uvec2(uint(round(zNormalized * fixedPointScale)), uint(round(zNormalized * zNormalized * fixedPointScale)));
#else
  float centred = z - 0.5 * (depthNear + depthFar);
  return vec2(centred, centred * centred);
#endif
}

void storeSat(ivec2 texel, SatSum value)
{
#if SAT_PRECISION == SAT_PRECISION_INT32
  imageStore(satImage, texel, uvec4(value, 0u, 0u));
#else
  imageStore(satImage, texel, vec4(value, 0.0, 0.0));
#endif
}

void main()
{
  int line = int(gl_GlobalInvocationID.x);
  ivec2 size = imageSize(satImage);
  SatSum running = SatSum(0);
#if SAT_PASS == 0
  if (line >= size.y)
  {
    return;
  }
  for (int x = 0; x < size.x; ++x)
  {
    running += satEntry(texelFetch(shadowMapLinear, ivec2(x, line), 0).r);
    storeSat(ivec2(x, line), running);
  }
#else
  if (line >= size.x)
  {
    return;
  }
  for (int y = 0; y < size.y; ++y)
  {
    running += imageLoad(satImage, ivec2(line, y)).xy;
    storeSat(ivec2(line, y), running);
  }
#endif
}
