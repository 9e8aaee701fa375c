// Moment map (VSM: Donnelly & Lauritzen 2006; ESM: Annen et al. 2008; survey §6): per shadow-map texel,
// (z, z^2, exp(c z_n), 1) with z the linear depth and z_n = (z - near) / (far - near) clamped to [0, 1], so
// the exponential stays finite for c up to 80 (e^80 < float max). Empty texels (no caster, 2 x far) are
// "far away", which lights everything in front of them; clamping them to z_n = 1 keeps that, as every
// receiver's t_n is at most 1.
#include "moments/MomentsOfDepth.glsl"

uniform sampler2D shadowMapLinear;

layout(location = 0) out vec4 outMoments;

void main()
{
  outMoments = momentsOfDepth(texelFetch(shadowMapLinear, ivec2(gl_FragCoord.xy), 0).r);
}
