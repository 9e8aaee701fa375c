// Summed-area table of the shadow map's (z, z^2) (Crow 1984; SAVSM: Lauritzen 2007; survey §6.4), built
// band by band (a band: bandRows rows of the map, in a storage buffer the pass then copies into the table) in two
// compute passes: prefix sums along each of the band's rows (SAT_PASS 0, from the shadow map), then along each
// column in place, continuing from the table's row above the band (SAT_PASS 1, columnCarry). Each texel's sum is
// added in the same order as one pass over the whole map, so the table does not depend on the band height.
// Precision (survey §6.4, VSSM §6.4): a float SAT loses the low bits of a box sum to the large corner values, so
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
uniform int mapSize;      // texels per side of the map and of the table
uniform int bandFirstRow; // the map row of the band's row 0
uniform int bandRows;     // rows in this band

#if SAT_PRECISION == SAT_PRECISION_INT32
#define SatSum uvec2
#else
#define SatSum vec2
#endif

// The band's sums, row-major (mapSize per row), as the table's texels (RG32UI or RG32F) for the copy into it.
layout(std430, binding = 0) restrict buffer SatBand
{
  SatSum bandSums[];
};
// Per column, the table's value in the row above the band (0 above the first band); the column pass updates it.
layout(std430, binding = 1) restrict buffer SatColumnCarry
{
  SatSum columnCarry[];
};

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

void main()
{
  int line = int(gl_GlobalInvocationID.x);
#if SAT_PASS == 0
  // One invocation per row of the band.
  if (line >= bandRows)
  {
    return;
  }
  int rowStart = line * mapSize;
  SatSum running = SatSum(0);
  for (int x = 0; x < mapSize; ++x)
  {
    running += satEntry(texelFetch(shadowMapLinear, ivec2(x, bandFirstRow + line), 0).r);
    bandSums[rowStart + x] = running;
  }
#else
  // One invocation per column.
  if (line >= mapSize)
  {
    return;
  }
  SatSum running = columnCarry[line];
  for (int y = 0; y < bandRows; ++y)
  {
    running += bandSums[y * mapSize + line];
    bandSums[y * mapSize + line] = running;
  }
  columnCarry[line] = running;
#endif
}
