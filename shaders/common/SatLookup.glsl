// Box moments from the summed-area table (passes/vtkSLSatPass): mean depth and variance over an inclusive
// texel rectangle, from four corners. SAT_PRECISION_* come from the technique's `sat_precision` parameter.
#if SAT_PRECISION == SAT_PRECISION_INT32
uniform usampler2D satTable;
#else
uniform sampler2D satTable;
#endif
uniform float satDepthNear;
uniform float satDepthFar;
uniform float satFixedPointScale; // int32: 2^b - 1 (passes/vtkSLSatPass)

// Sum of the table's (z, z^2) entries over the texels [lo, hi] (inclusive), from four corners.
#if SAT_PRECISION == SAT_PRECISION_INT32
#define SatSum uvec2
#else
#define SatSum vec2
#endif
SatSum satBoxSum(ivec2 lo, ivec2 hi)
{
  SatSum sum = texelFetch(satTable, hi, 0).xy;
  if (lo.x > 0)
  {
    sum -= texelFetch(satTable, ivec2(lo.x - 1, hi.y), 0).xy;
  }
  if (lo.y > 0)
  {
    sum -= texelFetch(satTable, ivec2(hi.x, lo.y - 1), 0).xy;
  }
  if (lo.x > 0 && lo.y > 0)
  {
    sum += texelFetch(satTable, lo - 1, 0).xy;
  }
  return sum;
}

// x = E[z], y = Var[z] over the texels [lo, hi] (inclusive; clamped to the map by the caller).
vec2 satBoxMoments(ivec2 lo, ivec2 hi)
{
  float count = float((hi.x - lo.x + 1) * (hi.y - lo.y + 1));
  SatSum sum = satBoxSum(lo, hi);
#if SAT_PRECISION == SAT_PRECISION_INT32
  // Unsigned arithmetic wraps, so the box sums are exact even where the table's values overflowed.
  float meanNormalized = float(sum.x) / (satFixedPointScale * count);
  float secondNormalized = float(sum.y) / (satFixedPointScale * count);
  float range = satDepthFar - satDepthNear;
  return vec2(satDepthNear + meanNormalized * range,
    max(secondNormalized - meanNormalized * meanNormalized, 0.0) * range * range);
#else
  float meanCentred = sum.x / count;
  return vec2(meanCentred + 0.5 * (satDepthNear + satDepthFar), max(sum.y / count - meanCentred * meanCentred, 0.0));
#endif
}
