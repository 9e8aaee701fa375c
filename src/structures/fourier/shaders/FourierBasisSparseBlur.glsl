// The Fourier basis' sparse blur (prefilter_region = receivers, sparse): every basis texture in one dispatch, the
// sine ones into images 0 .. T - 1 and the cosine ones into T .. 2T - 1 as FourierBasis.glsl writes its locations,
// each tap's terms formed once by fourierBasisTerms and summed by the moment map's shared body.
#include "fourier/FourierTerms.glsl"

uniform float depthNear;
uniform float depthFar;
uniform float depthRange; // s

#define SPARSE_BLUR_IMAGES (FOURIER_TERMS / 2)
void momentsOfDepthImages(float z, out vec4 values[SPARSE_BLUR_IMAGES])
{
  vec4 sines[FOURIER_TEXTURES];
  vec4 cosines[FOURIER_TEXTURES];
  fourierBasisTerms(fourierSeriesDepth(z, depthNear, depthFar, depthRange), sines, cosines);
  for (int group = 0; group < FOURIER_TEXTURES; ++group)
  {
    values[group] = sines[group];
    values[FOURIER_TEXTURES + group] = cosines[group];
  }
}

#include "moments/SparseBoxBlur.glsl"
