// What the basis build (fourier/FourierBasis.glsl) and the lookup (convsm/ConvsmVisibility.glsl) of convolution
// shadow maps must agree on: the series depth of a linear light depth, and the term numbers and frequencies of the
// four terms one RGBA basis texture holds.

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
