// Moment shadow mapping (Peters & Klein 2015), Hamburger 4MSM (their Algorithm 3, in the form public ports of the
// authors' shader code give it; the printed Algorithm 3 was not available, steps 2-4 were compared with the general
// algorithm of Peters et al. 2017, Alg. 1, at m = 4: README.md, Sources). From the prefiltered
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
// Steps 1-4: common/MomentHamburger.glsl (hamburger4Msm). CPU mirror: src/lightspace/MomentHamburger.cpp
// (msmHamburger4).
#include "common/GBufferInputs.glsl"
#include "common/LightModel.glsl"
#include "common/ShadowMapCommon.glsl"
#include "common/ShadowReceiver.glsl"
#include "common/MomentLookup.glsl"
#include "common/MomentHamburger.glsl"

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
