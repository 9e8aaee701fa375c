// What the basis build (fourier/FourierBasis.glsl, fourier/FourierBasisSparseBlur.glsl) and the lookup
// (convsm/ConvsmVisibility.glsl) of convolution shadow maps must agree on: the series depth of a linear light depth,
// and the term numbers and frequencies of the four terms one RGBA basis texture holds.

// z_s = s z_n: the depth normalised to the light's [near, far], clamped, and scaled by s = depth_range.
float fourierSeriesDepth(float linearDepth, float depthNear, float depthFar, float depthRange)
{
  return depthRange * clamp((linearDepth - depthNear) / (depthFar - depthNear), 0.0, 1.0);
}

// k = 4 group + 1 .. 4 group + 4.
vec4 fourierTermNumbers(int group)
{
  return vec4(4 * group + 1, 4 * group + 2, 4 * group + 3, 4 * group + 4);
}

// c_k = pi (2k - 1): the odd harmonics of the step's series on [-1, 1].
vec4 fourierFrequencies(vec4 k)
{
  return 3.14159265358979 * (2.0 * k - 1.0);
}

#ifdef FOURIER_TERMS
const int FOURIER_TEXTURES = FOURIER_TERMS / 4;

// Every basis term of one depth as the basis textures hold them: sin(c_k z_s) for k = 1 .. FOURIER_TERMS, four per
// vec4, in basis[0 .. T - 1], then cos(c_k z_s) in basis[T .. 2T - 1]. Two transcendentals, then each term from the
// one before by the angle-addition rotation through 2 pi z_s (c_{k+1} = c_k + 2 pi): in float this is as accurate
// as sin(c_k z_s) itself (the argument's rounding, up to 31 pi z_s, dominates both), and the builds form
// FOURIER_TERMS x 2 values per tap of the blur. `precise` keeps every build path's products unfused, so the two
// builds store the same bits.
void fourierBasisTerms(float zSeries, out vec4 basis[2 * FOURIER_TEXTURES])
{
  precise float firstAngle = fourierFrequencies(vec4(1.0)).x * zSeries;
  precise float sine = sin(firstAngle);
  precise float cosine = cos(firstAngle);
  precise float stepSine = 2.0 * sine * cosine;
  precise float stepCosine = 1.0 - 2.0 * sine * sine;
  for (int group = 0; group < FOURIER_TEXTURES; ++group)
  {
    for (int term = 0; term < 4; ++term)
    {
      basis[group][term] = sine;
      basis[FOURIER_TEXTURES + group][term] = cosine;
      precise float nextSine = sine * stepCosine + cosine * stepSine;
      precise float nextCosine = cosine * stepCosine - sine * stepSine;
      sine = nextSine;
      cosine = nextCosine;
    }
  }
}
#endif
