// The moments of one shadow-map depth (MomentsFromDepth.glsl's, also evaluated inline by SparseBoxBlur.glsl, so that
// both compute them with the same code): (z, z^2, exp(c z_n), 1), z_n = (z - near) / (far - near) clamped to [0, 1].
uniform float depthNear;
uniform float depthFar;
uniform float esmExponent;

vec4 momentsOfDepth(float z)
{
  float zNormalized = clamp((z - depthNear) / (depthFar - depthNear), 0.0, 1.0);
  return vec4(z, z * z, exp(esmExponent * zNormalized), 1.0);
}
