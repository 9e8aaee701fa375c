// Power-moment map (moment shadow mapping, Peters & Klein 2015): per shadow-map texel the four power moments
// b(z) = (z, z^2, z^3, z^4) of the depth mapped into [0, 1], the paper's depth range:
//   z = m + (1 - 2 m) clamp((d - near) / (far - near), 0, 1),   m = depthMargin (power_moment_depth_margin)
// The paper's moment bias pulls b towards (0.5, 0.5, 0.5, 0.5), the moments of half the mass at 0 and half at 1.
// Our light ranges are fitted to the scene, so a caster at the near plane over a receiver at the far plane would put
// the scene's depths on that same support and the bias would not regularise (msm/README.md, measured); m keeps them
// inside. Empty texels (no caster, 2 x far) clamp to the far end, behind every receiver.
uniform sampler2D shadowMapLinear;
uniform float depthNear;
uniform float depthFar;
uniform float depthMargin;

layout(location = 0) out vec4 outMoments;

void main()
{
  float d = texelFetch(shadowMapLinear, ivec2(gl_FragCoord.xy), 0).r;
  float z = depthMargin + (1.0 - 2.0 * depthMargin) * clamp((d - depthNear) / (depthFar - depthNear), 0.0, 1.0);
  float z2 = z * z;
  outMoments = vec4(z, z2, z2 * z, z2 * z2);
}
