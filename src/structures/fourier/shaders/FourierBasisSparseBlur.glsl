// The Fourier basis' sparse blur (prefilter_region = receivers, sparse), one basis texture per dispatch: the four
// terms of texture `fourierGroup` of each tap (sine, or cosine with fourierCosine = 1), as FourierBasis.glsl forms
// them, summed by the moment map's shared body.
#include "fourier/FourierTerms.glsl"

uniform float depthNear;
uniform float depthFar;
uniform float depthRange; // s
uniform int fourierGroup;
uniform int fourierCosine;

vec4 momentsOfDepth(float z)
{
  float zSeries = fourierSeriesDepth(z, depthNear, depthFar, depthRange);
  vec4 ck = fourierFrequencies(fourierTermNumbers(fourierGroup));
  return fourierCosine != 0 ? cos(ck * zSeries) : sin(ck * zSeries);
}

#include "moments/SparseBoxBlur.glsl"
