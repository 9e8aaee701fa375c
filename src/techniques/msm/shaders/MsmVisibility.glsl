// Moment shadow mapping (Peters & Klein 2015), Hamburger 4MSM (their Algorithm 3). From the prefiltered power
// moments b = E[(z, z^2, z^3, z^4)] over the filter region (depths normalised to [0, 1]) and the receiver's
// normalised depth z_f (its depth minus the bias):
//   1. b' = (1 - alpha) b + alpha (0.5, 0.5, 0.5, 0.5)        (moment bias, §5: keeps the Hankel matrix definite
//                                                              against rounding in the float moments)
//   2. solve B c = (1, z_f, z_f^2) with B = [[1, b1', b2'], [b1', b2', b3'], [b2', b3', b4']] (Cholesky, LDL^T)
//   3. z_2 <= z_3: the roots of c1 + c2 z + c3 z^2 (with z_f, the support of the distribution the bound picks)
//   4. shadow intensity G = 0 (z_f <= z_2), the weight of z_2 (z_2 < z_f <= z_3), 1 - the weight of z_f (else)
// and visibility = 1 - clamp(G, 0, 1): the sharpest lower bound on the shadow intensity that four moments give
// (Hamburger moment problem), so visibility never falls below the true PCF except through the bias.
// Exact when the region holds two depths (a planar occluder over a planar receiver), up to the bias.
// CPU mirror: src/techniques/msm/MsmTechnique.cpp (msmHamburger4).
#include "common/GBufferInputs.glsl"
#include "common/LightModel.glsl"
#include "common/ShadowMapCommon.glsl"
#include "common/ShadowReceiver.glsl"
#include "common/MomentLookup.glsl"

uniform sampler2D powerMomentMap;
uniform int kernelWidth; // prefilter_texels
uniform float depthNear;
uniform float depthFar;

layout(location = OUT_VISIBILITY) out float outVisibility;
layout(location = OUT_LIGHT_LEAK) out float outLightLeak;
layout(location = OUT_SUPPORT_DEPTH_NEAR) out float outSupportNear;
layout(location = OUT_SUPPORT_DEPTH_FAR) out float outSupportFar;
layout(location = OUT_HANKEL_PIVOT) out float outHankelPivot;
layout(location = OUT_KERNEL_TEXELS) out float outKernelTexels;
layout(location = OUT_DEPTH_BIAS) out float outDepthBias;

vec4 filteredPowerMoments(vec2 uvTexels)
{
#if PREFILTER == PREFILTER_MIPMAP
  return textureLod(powerMomentMap, uvTexels / float(shadowMapSize), momentLod);
#else
  // blur: the texel containing the receiver holds the average over the box centred on it
  return texelFetch(powerMomentMap, shadowMapTexel(uvTexels), 0);
#endif
}

void main()
{
  ShadowReceiver receiver = prepareShadowReceiver(ivec2(gl_FragCoord.xy));
  outVisibility = receiver.visibility;
  outLightLeak = 0.0;
  outSupportNear = 0.0;
  outSupportFar = 0.0;
  outHankelPivot = 0.0;
  outKernelTexels = 0.0;
  outDepthBias = receiver.bias;
  if (!receiver.needsShadowTest)
  {
    return;
  }
  // MSM Alg. 3, step 1: the moment bias.
  vec4 b = mix(filteredPowerMoments(receiver.uvTexels), vec4(0.5), param_moment_bias);
  float zf = (receiver.comparisonDepth - depthNear) / (depthFar - depthNear);
  // Step 2: LDL^T of the Hankel matrix, only its non-trivial entries (D11 = 1, L21 = b1, L31 = b2).
  float d22 = b.y - b.x * b.x;
  float l32d22 = b.z - b.x * b.y;
  float l32 = l32d22 / d22;
  float d33 = (b.w - b.y * b.y) - l32d22 * l32; // the third pivot: det(B) / D22
  vec3 c = vec3(1.0, zf, zf * zf);
  c.y -= b.x;                // forward substitution, L c' = (1, z_f, z_f^2)
  c.z -= b.y + l32 * c.y;
  c.y /= d22;                // D c'' = c'
  c.z /= d33;
  c.y -= l32 * c.z;          // backward substitution, L^T c = c''
  c.x -= c.y * b.x + c.z * b.y;
  // Step 3: the other two support points. D >= 0 in exact arithmetic (B positive definite); float rounding of a
  // near-singular B can push it below, and sqrt would give NaN.
  float p = c.y / c.z;
  float q = c.x / c.z;
  float r = sqrt(max(p * p * 0.25 - q, 0.0));
  float z2 = -0.5 * p - r;
  float z3 = -0.5 * p + r;
  // Step 4: sum the weights of the support points in front of z_f.
  float intensity;
  if (zf <= z2)
  {
    intensity = 0.0;
  }
  else if (zf <= z3)
  {
    intensity = (zf * z3 - b.x * (zf + z3) + b.y) / ((z3 - z2) * (zf - z2));
  }
  else
  {
    intensity = 1.0 - (z2 * z3 - b.x * (z2 + z3) + b.y) / ((zf - z2) * (zf - z3));
  }
  float visibility = 1.0 - clamp(intensity, 0.0, 1.0);
  outVisibility = visibility;
  outLightLeak = visibility - boxPcf(receiver.uvTexels, leakComparisonDepth(receiver), kernelWidth);
  outSupportNear = z2;
  outSupportFar = z3;
  outHankelPivot = d33;
  outKernelTexels = float(kernelWidth);
}
