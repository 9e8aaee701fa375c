// Box means of the four power moments from the moment summed-area table (structures/momentsat, MomentSatBuild.glsl):
// exact 64-bit box sums (two 32-bit words, uaddCarry / usubBorrow; moment_sat_precision = int64) or 32-bit sums
// exact modulo 2^32 (int32: exact up to momentSatExactTexels texels), over an inclusive texel rectangle or over a
// continuous rectangle with fractional edges. MOMENT_SAT_PRECISION_* come from the technique's moment_sat_precision
// parameter. CPU mirror: src/lightspace/MomentSummedAreaTable.cpp.
uniform usampler2D momentSatLow;
#if MOMENT_SAT_PRECISION == MOMENT_SAT_PRECISION_INT64
uniform usampler2D momentSatHigh;
#endif
uniform float momentSatScale;       // 2^b, the fixed point of a texel's moment
uniform float momentSatExactTexels; // the largest box summed exactly (int32; 2^64 for int64)

struct MomentSum
{
  uvec4 low;
  uvec4 high;
};

MomentSum momentSatCorner(ivec2 texel)
{
#if MOMENT_SAT_PRECISION == MOMENT_SAT_PRECISION_INT64
  return MomentSum(texelFetch(momentSatLow, texel, 0), texelFetch(momentSatHigh, texel, 0));
#else
  return MomentSum(texelFetch(momentSatLow, texel, 0), uvec4(0u)); // wrapped 32-bit sums: the high words stay 0
#endif
}

MomentSum addMomentSums(MomentSum a, MomentSum b)
{
  uvec4 carry;
  a.low = uaddCarry(a.low, b.low, carry);
  a.high += b.high + carry;
  return a;
}

MomentSum subtractMomentSums(MomentSum a, MomentSum b)
{
  uvec4 borrow;
  a.low = usubBorrow(a.low, b.low, borrow);
  a.high -= b.high + borrow;
  return a;
}

// The exact sum of the quantised moments over the texels [lo, hi] (inclusive), from four corners (momentBoxSum).
MomentSum momentSatBoxSum(ivec2 lo, ivec2 hi)
{
  MomentSum sum = momentSatCorner(hi);
  if (lo.x > 0)
  {
    sum = subtractMomentSums(sum, momentSatCorner(ivec2(lo.x - 1, hi.y)));
  }
  if (lo.y > 0)
  {
    sum = subtractMomentSums(sum, momentSatCorner(ivec2(hi.x, lo.y - 1)));
  }
  if (lo.x > 0 && lo.y > 0)
  {
    sum = addMomentSums(sum, momentSatCorner(lo - 1));
  }
  return sum;
}

// A box sum in moment units: (float(high) 2^32 + float(low)) / 2^b, the scalings exact. int32: the low words are
// the sum modulo 2^32 and the high words (borrows of the wrapped differences) are ignored.
vec4 decodedMomentSum(MomentSum sum)
{
#if MOMENT_SAT_PRECISION == MOMENT_SAT_PRECISION_INT64
  return (vec4(sum.high) * 4294967296.0 + vec4(sum.low)) / momentSatScale;
#else
  return vec4(sum.low) / momentSatScale;
#endif
}

// The moments' mean over the texels [lo, hi] (inclusive; clamped to the map by the caller) (momentBoxMean).
vec4 momentSatBoxMean(ivec2 lo, ivec2 hi)
{
  float texels = float((hi.x - lo.x + 1) * (hi.y - lo.y + 1));
  return decodedMomentSum(momentSatBoxSum(lo, hi)) / texels;
}

// One axis of a continuous rectangle [lower, upper] (texel i covers [i, i + 1]), clamped to [0, size]: up to three
// inclusive texel ranges, the partial first texel, the whole inner ones and the partial last one, with the width of
// each texel of a range the rectangle covers (fractionalSpan).
struct FractionalSpan
{
  int count;
  ivec3 first;
  ivec3 last;
  vec3 width;
};

FractionalSpan fractionalSpan(float lower, float upper, int size)
{
  lower = clamp(lower, 0.0, float(size));
  upper = clamp(upper, 0.0, float(size));
  FractionalSpan span;
  span.first = ivec3(0);
  span.last = ivec3(0);
  span.width = vec3(0.0);
  if (!(upper > lower))
  {
    int texel = clamp(int(floor(0.5 * (lower + upper))), 0, size - 1);
    span.count = 1;
    span.first[0] = texel;
    span.last[0] = texel;
    span.width[0] = 1.0;
    return span;
  }
  int first = min(int(floor(lower)), size - 1);
  int last = max(int(ceil(upper)) - 1, first);
  if (first == last)
  {
    span.count = 1;
    span.first[0] = first;
    span.last[0] = first;
    span.width[0] = upper - lower;
    return span;
  }
  span.first[0] = first;
  span.last[0] = first;
  span.width[0] = float(first + 1) - lower;
  span.count = 1;
  if (last - 1 >= first + 1)
  {
    span.first[1] = first + 1;
    span.last[1] = last - 1;
    span.width[1] = 1.0;
    span.count = 2;
  }
  span.first[span.count] = last;
  span.last[span.count] = last;
  span.width[span.count] = upper - float(last);
  ++span.count;
  return span;
}

// The moments' mean over the continuous rectangle [boxMin, boxMax] (texels), clamped to the map: every texel
// weighted by the area of it the rectangle covers, from at most nine exact box sums (the authors' rectangle
// integral with fractional edges; momentFractionalBoxMean). Continuous in the edges, so the kernel size changes
// without banding.
vec4 momentSatFractionalMean(vec2 boxMin, vec2 boxMax)
{
  ivec2 size = textureSize(momentSatLow, 0);
  FractionalSpan spanX = fractionalSpan(boxMin.x, boxMax.x, size.x);
  FractionalSpan spanY = fractionalSpan(boxMin.y, boxMax.y, size.y);
  vec4 sum = vec4(0.0);
  float area = 0.0;
  for (int j = 0; j < spanY.count; ++j)
  {
    for (int i = 0; i < spanX.count; ++i)
    {
      ivec2 lo = ivec2(spanX.first[i], spanY.first[j]);
      ivec2 hi = ivec2(spanX.last[i], spanY.last[j]);
      float weight = spanX.width[i] * spanY.width[j];
      sum += weight * decodedMomentSum(momentSatBoxSum(lo, hi));
      area += weight * float((hi.x - lo.x + 1) * (hi.y - lo.y + 1));
    }
  }
  return sum / area;
}
