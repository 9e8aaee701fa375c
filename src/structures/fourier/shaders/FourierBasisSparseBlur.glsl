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
  fourierBasisTerms(fourierSeriesDepth(z, depthNear, depthFar, depthRange), values);
}

#include "moments/SparseBoxBlur.glsl"
