// Power-moment map (moment shadow mapping, Peters & Klein 2015): per shadow-map texel the four power moments
// b(z) = (z, z^2, z^3, z^4) of the depth normalised to the light's range, z = clamp((d - near) / (far - near), 0, 1):
// the paper's depths are in [0, 1] (its moment bias pulls b towards (0.5, 0.5, 0.5, 0.5), the moments of half the mass
// at 0 and half at 1). Empty texels (no caster, 2 x far) clamp to z = 1, behind every receiver, as for esm.
#include "powermoments/PowerMomentsOfDepth.glsl"

uniform sampler2D shadowMapLinear;

layout(location = 0) out vec4 outMoments;

void main()
{
  outMoments = momentsOfDepth(texelFetch(shadowMapLinear, ivec2(gl_FragCoord.xy), 0).r);
}
