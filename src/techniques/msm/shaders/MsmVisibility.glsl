// Moment shadow mapping (Peters & Klein 2015), Hamburger 4MSM (their Algorithm 3, in the form public ports of the
// authors' shader code give it; not compared with the printed algorithm: README.md, Sources). From the prefiltered
// power moments b = E[(z, z^2, z^3, z^4)] over the filter region (depths normalised to [0, 1], structures/powermoments)
// and the receiver's depth z_f (its depth minus the bias, normalised alike), in four steps (our grouping, not the
// printed lines):
//   1. b' = (1 - alpha) b + alpha (0.5, 0.5, 0.5, 0.5)        (moment bias: keeps the Hankel matrix definite
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
layout(location = OUT_ROUNDING_SENSITIVITY) out float outRoundingSensitivity;
layout(location = OUT_KERNEL_TEXELS) out float outKernelTexels;
layout(location = OUT_DEPTH_BIAS) out float outDepthBias;

vec4 filteredPowerMoments(vec2 uvTexels)
{
  return prefilteredFetch(powerMomentMap, uvTexels);
}

struct MsmReconstruction
{
  float intensity; // G, unclamped
  float z2;        // support points
  float z3;
  float d33;       // last pivot
};

// MSM Alg. 3 on the moments b (before the bias) at the receiver's depth z_f. CPU mirror: msmHamburger4.
MsmReconstruction hamburger4Msm(vec4 moments, float zf)
{
  // Step 1: the moment bias.
  vec4 b = mix(moments, vec4(0.5), param_moment_bias);
  // Step 2: LDL^T of the Hankel matrix, only its non-trivial entries (D11 = 1, L21 = b1, L31 = b2).
  // D22, the variance of the biased depths: >= alpha / 4 in exact arithmetic (the bias mixes in mass alpha / 2 at
  // 0 and at 1); where the box holds one depth and the bias is lost in float, rounding leaves it at 0 or below and
  // l32 would be 0 / 0. Floored at 1e-12 as D33 (the twin alike); moment_bias >= 1e-6 keeps it above the rounding.
  float d22 = max(b.y - b.x * b.x, 1e-12);
  float l32d22 = b.z - b.x * b.y;
  float l32 = l32d22 / d22;
  // The third pivot, det(B) / D22: > 0 for alpha > 0 in exact arithmetic; float rounding can make it 0 or less,
  // and 1 / 0 would reach the support points as inf - inf. Floored at 1e-12 (the twin alike).
  float d33 = max((b.w - b.y * b.y) - l32d22 * l32, 1e-12);
  vec3 c = vec3(1.0, zf, zf * zf);
  c.y -= b.x;                // forward substitution, L c' = (1, z_f, z_f^2)
  c.z -= b.y + l32 * c.y;
  c.y /= d22;                // D c'' = c'
  c.z /= d33;
  c.y -= l32 * c.z;          // backward substitution, L^T c = c''
  c.x -= c.y * b.x + c.z * b.y;
  // Step 3: the other two support points, the roots of c1 + c2 z + c3 z^2. Alg. 3 divides by c3 (p = c2 / c3,
  // q = c1 / c3); where B is near singular c3 can round to ~0 in float and one root runs off to infinity while
  // the other cancels. The same roots by the stable form (the large one from -(c2 + sign(c2) sqrt(disc)) / 2, the
  // other by Vieta), clamped to +-1e6 (a support point that far from [0, 1] carries no weight): finite throughout.
  // The discriminant is >= 0 in exact arithmetic (B positive definite); rounding can push it below.
  float root = sqrt(max(c.y * c.y - 4.0 * c.x * c.z, 0.0));
  float large = -0.5 * (c.y + (c.y < 0.0 ? -root : root));
  float rootA = clamp(large / c.z, -1e6, 1e6);
  float rootB = clamp(c.x / large, -1e6, 1e6);
  float z2 = min(rootA, rootB);
  float z3 = max(rootA, rootB);
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
  return MsmReconstruction(intensity, z2, z3, d33);
}

// The sum over b1..b4 and z_f of the largest change of G when one of them moves by +-1e-6 (float rounding of the
// blurred moments): large where the Hankel matrix is near singular and G follows the rounding. CPU mirror:
// msmRoundingSensitivity.
float roundingSensitivity(vec4 moments, float zf, float intensity)
{
  const float delta = 1e-6;
  float sensitivity = 0.0;
  for (int k = 0; k < 5; ++k)
  {
    float largest = 0.0;
    for (int s = -1; s <= 1; s += 2)
    {
      vec4 moved = moments;
      float depth = zf;
      if (k < 4)
      {
        moved[k] += float(s) * delta;
      }
      else
      {
        depth += float(s) * delta;
      }
      float g = clamp(hamburger4Msm(moved, depth).intensity, 0.0, 1.0);
      largest = max(largest, abs(g - intensity));
    }
    sensitivity += largest;
  }
  return sensitivity;
}

void main()
{
  ShadowReceiver receiver = prepareShadowReceiver(ivec2(gl_FragCoord.xy));
  outVisibility = receiver.visibility;
  outLightLeak = 0.0;
  outSupportNear = 0.0;
  outSupportFar = 0.0;
  outHankelPivot = 0.0;
  outRoundingSensitivity = 0.0;
  outKernelTexels = 0.0;
  outDepthBias = receiver.bias;
  if (!receiver.needsShadowTest)
  {
    return;
  }
  vec4 moments = filteredPowerMoments(receiver.uvTexels);
  // z_f normalised as the moments' depths (PowerMomentsFromDepth.glsl), not clamped.
  float zf = (receiver.comparisonDepth - depthNear) / (depthFar - depthNear);
  MsmReconstruction msm = hamburger4Msm(moments, zf);
  float intensity = clamp(msm.intensity, 0.0, 1.0);
  float visibility = 1.0 - intensity;
  outVisibility = visibility;
  outLightLeak = visibility - boxPcf(receiver.uvTexels, leakComparisonDepth(receiver), kernelWidth);
  outSupportNear = msm.z2;
  outSupportFar = msm.z3;
  outHankelPivot = msm.d33;
  outRoundingSensitivity = roundingSensitivity(moments, zf, intensity);
  outKernelTexels = float(kernelWidth);
}
