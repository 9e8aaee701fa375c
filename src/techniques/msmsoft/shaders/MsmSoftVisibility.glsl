// Moment soft shadow mapping (Peters, Münstermann, Wetzstein & Klein, I3D 2016; JCGT 6(1) 2017), in the form the
// authors' published shader code gives it (README.md, Sources; the printed equations were not compared), with
// PCSS's search kernel (README.md says why). Per receiver, from the moment summed-area table (structures/momentsat):
//   1. z_f: the receiver's comparison depth (minus the bias), normalised as the power moments (msm).
//   2. blocker search region: PCSS's search kernel w_i (kernelHalfTexels(d, near), its texel rectangle).
//   3. the four moments over it from the SAT (exact box sums), moment bias as msm.
//   4. the canonical representation at z_f (Hamburger 4MSM's support z_1 <= z_2 with z_f, weights matching
//      b'_0..b'_2): blocker intensity G_b = sum of the weights of the z_i < z_f, average blocker depth
//      z_avg = (eps z_f + sum w_i z_i) / (eps + G_b) (eps = fully_lit_bias: no blocker, z_avg -> z_f).
//   5. penumbra kernel by PCSS's similar triangles at z_avg, clamped to [min_kernel_texels, w_i].
//   6. the moments over it with fractional edges, Hamburger 4MSM at z_f: visibility = 1 - clamp(G, 0, 1).
// CPU mirror: src/techniques/msmsoft/MsmSoftTechnique.cpp (msmSoftReference).
#include "common/GBufferInputs.glsl"
#include "common/LightModel.glsl"
#include "common/ShadowMapCommon.glsl"
#include "common/ShadowReceiver.glsl"
#include "common/SoftShadowKernels.glsl"
#include "common/RectanglePcf.glsl"
#include "common/MomentHamburger.glsl"
#include "momentsat/MomentSatLookup.glsl"

uniform float depthNear;
uniform float depthFar;

layout(location = OUT_VISIBILITY) out float outVisibility;
layout(location = OUT_LIGHT_LEAK) out float outLightLeak;
layout(location = OUT_BLOCKER_KERNEL_TEXELS) out float outBlockerKernelTexels;
layout(location = OUT_BLOCKER_INTENSITY) out float outBlockerIntensity;
layout(location = OUT_AVG_BLOCKER_DEPTH) out float outAvgBlockerDepth;
layout(location = OUT_PENUMBRA_KERNEL_TEXELS) out float outPenumbraKernelTexels;
layout(location = OUT_DEPTH_BIAS) out float outDepthBias;
layout(location = OUT_MOMENT_SAT_OVERFLOW) out float outMomentSatOverflow;
// The filter step's (support_depth_near, support_depth_far, hankel_pivot, 0): beyond the eight render targets, stored
// into an image the pass reads back (vtkSLMsmSoftPass).
layout(rgba32f, binding = 0) uniform writeonly image2D filterSupport;

// The weight of support point zi in the three-point distribution on (zi, zj, zk) with moments 1, b1, b2 (Lagrange,
// as MomentHamburger.glsl's step 4); 0 where two support points coincide (no distribution on fewer points to split).
float supportWeight(float zi, float zj, float zk, vec4 b)
{
  float denominator = (zi - zj) * (zi - zk);
  return abs(denominator) > 1e-20 ? (zj * zk - b.x * (zj + zk) + b.y) / denominator : 0.0;
}

struct BlockerEstimate
{
  float intensity;    // G_b
  float averageDepth; // z_avg, moment depth
};

// Step 4: the blocker intensity and average blocker depth at z_f from the search region's moments (msmSoftBlockers).
BlockerEstimate estimateBlockers(vec4 moments, float zf)
{
  MsmReconstruction canonical = hamburger4Msm(moments, zf);
  vec4 b = mix(moments, vec4(0.5), param_moment_bias);
  float z1 = canonical.z2;
  float z2 = canonical.z3;
  // In exact arithmetic the weights are >= 0 (B positive definite); rounding can leave them slightly negative.
  float w1 = max(supportWeight(z1, zf, z2, b), 0.0);
  float w2 = max(supportWeight(z2, zf, z1, b), 0.0);
  float intensity = 0.0;
  float weightedDepth = 0.0;
  // Support points below 0 are clamped to 0 (the depths lie in [0, 1]; such a point carries a tiny weight).
  if (z1 < zf)
  {
    intensity += w1;
    weightedDepth += w1 * max(z1, 0.0);
  }
  if (z2 < zf)
  {
    intensity += w2;
    weightedDepth += w2 * max(z2, 0.0);
  }
  float epsilon = param_fully_lit_bias;
  BlockerEstimate estimate;
  estimate.intensity = min(intensity, 1.0);
  estimate.averageDepth = clamp((epsilon * zf + weightedDepth) / (epsilon + intensity), 0.0, max(zf, 0.0));
  return estimate;
}

void main()
{
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  ShadowReceiver receiver = prepareShadowReceiver(pixel);
  outVisibility = receiver.visibility;
  outLightLeak = 0.0;
  outBlockerKernelTexels = 0.0;
  outBlockerIntensity = 0.0;
  outAvgBlockerDepth = 0.0;
  outPenumbraKernelTexels = 0.0;
  imageStore(filterSupport, pixel, vec4(0.0));
  outDepthBias = receiver.bias;
  outMomentSatOverflow = 0.0;
  if (!receiver.needsShadowTest)
  {
    return;
  }
  float d = receiver.depthLin;
  float range = depthFar - depthNear;
  // Step 1: z_f as msm normalises it (not clamped).
  float zf = (receiver.comparisonDepth - depthNear) / range;
  setReceiverPlane(receiver.pWs, receiver.nWs);

  // Steps 2-3: the search region's moments.
  vec2 searchHalf = kernelHalfTexels(d, lightNearDepth);
  outBlockerKernelTexels = 2.0 * max(searchHalf.x, searchHalf.y);
  ivec2 searchLo;
  ivec2 searchHi;
  kernelRectangle(receiver.uvTexels, searchHalf, searchLo, searchHi);
  vec4 searchMoments = momentSatBoxMean(searchLo, searchHi);

  // Step 4: blocker intensity and average blocker depth, back to linear depth.
  BlockerEstimate blockers = estimateBlockers(searchMoments, zf);
  float averageBlockerDepth = depthNear + blockers.averageDepth * range;
  outBlockerIntensity = blockers.intensity;
  outAvgBlockerDepth = averageBlockerDepth;

  // Step 5: the penumbra kernel, clamped to [min_kernel_texels, the search kernel] (per axis, half widths).
  float minimumHalf = 0.5 * param_min_kernel_texels;
  vec2 filterHalf = max(kernelHalfTexels(d, averageBlockerDepth), vec2(minimumHalf));
  filterHalf = min(filterHalf, max(searchHalf, vec2(minimumHalf)));
  outPenumbraKernelTexels = 2.0 * max(filterHalf.x, filterHalf.y);

  // Step 6: the moments over the kernel with fractional edges, Hamburger 4MSM at z_f.
  vec2 boxMin = receiver.uvTexels - filterHalf;
  vec2 boxMax = receiver.uvTexels + filterHalf;
  vec4 filterMoments = momentSatFractionalMean(boxMin, boxMax);
  MsmReconstruction msm = hamburger4Msm(filterMoments, zf);
  float visibility = 1.0 - clamp(msm.intensity, 0.0, 1.0);
  outVisibility = visibility;
  imageStore(filterSupport, pixel, vec4(msm.z2, msm.z3, msm.d33, 0.0));

  // Light leak: against the PCF over the fractional rectangle's integer cover (every texel it touches).
  ivec2 coverLo = clamp(ivec2(floor(boxMin)), ivec2(0), ivec2(shadowMapSize - 1));
  ivec2 coverHi = clamp(ivec2(ceil(boxMax)) - 1, coverLo, ivec2(shadowMapSize - 1));
  outLightLeak = visibility - pcfOverRectangle(coverLo, coverHi, d, receiver.bias);
  // int32 table: a box beyond the exact size wrapped (its sum is wrong): flagged.
  float searchTexels = float(searchHi.x - searchLo.x + 1) * float(searchHi.y - searchLo.y + 1);
  float coverTexels = float(coverHi.x - coverLo.x + 1) * float(coverHi.y - coverLo.y + 1);
  outMomentSatOverflow = max(searchTexels, coverTexels) > momentSatExactTexels ? 1.0 : 0.0;
}
