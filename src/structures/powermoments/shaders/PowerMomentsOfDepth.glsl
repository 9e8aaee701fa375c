// The four power moments of one shadow-map depth (PowerMomentsFromDepth.glsl's, also evaluated inline by the sparse
// blur, PowerMomentsSparseBlur.glsl, so that both compute them with the same code): b(z) = (z, z^2, z^3, z^4) of the
// depth normalised to the light's range, z = clamp((d - near) / (far - near), 0, 1) (Peters & Klein 2015).
uniform float depthNear;
uniform float depthFar;

vec4 momentsOfDepth(float d)
{
  float z = clamp((d - depthNear) / (depthFar - depthNear), 0.0, 1.0);
  float z2 = z * z;
  return vec4(z, z2, z2 * z, z2 * z2);
}
