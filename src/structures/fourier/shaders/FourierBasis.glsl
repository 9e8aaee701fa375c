// Convolution shadow maps (Annen et al. 2007; survey §6): the basis images of the Fourier expansion of the shadow
// test. Per shadow-map texel, z_n = (z - near) / (far - near) clamped to [0, 1], mapped to the series' depth
// z_s = s z_n, s = depth_range (the series is H(t) only on (-1, 1) and jumps back at +-1: with s <= 1 every gap
// z_s - d_s lies in [-s, s]; 1/2 keeps it half a period from the jump), and for k = 1..FOURIER_TERMS with
// c_k = pi (2k - 1):
//   sin(c_k z_s) into the sine textures (locations 0 .. T - 1), cos(c_k z_s) into the cosine ones (T .. 2T - 1),
// four terms per RGBA texture, T = FOURIER_TERMS / 4 (formed by fourierBasisTerms). Empty texels (no caster,
// 2 x far) clamp to z_n = 1: every receiver's d_n is at most 1, so they light it. CPU mirror: convsmBasisAverage
// (convsm/ConvsmTechnique.cpp).
#include "fourier/FourierTerms.glsl"

uniform sampler2D shadowMapLinear;
uniform float depthNear;
uniform float depthFar;
uniform float depthRange; // s

layout(location = 0) out vec4 outBasis[2 * FOURIER_TEXTURES];

void main()
{
  float z = texelFetch(shadowMapLinear, ivec2(gl_FragCoord.xy), 0).r;
  fourierBasisTerms(fourierSeriesDepth(z, depthNear, depthFar, depthRange), outBasis);
}
