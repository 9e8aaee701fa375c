// Layered variance shadow maps (Lauritzen & McCool 2008; survey §6). The receiver at depth t reads the layer i
// whose interval [p_i, q_i] holds t, and applies the one-tailed Chebyshev bound of VSM to that layer's prefiltered
// moments of the warped depths phi_i(z) at its own warped depth phi_i(t):
//   p_max = sigma^2 / (sigma^2 + (phi_i(t) - mu)^2)  for phi_i(t) > mu (1 otherwise).
// phi_i is affine inside the layer, so vsm's variance floor min_variance d^2 (linear depth^2) is rescaled by
// 1 / (q_i - p_i)^2 into warped units: a box whose depths all lie in the layer gets vsm's bound exactly (Chebyshev's
// bound is invariant under an affine map of the depths), and one layer is vsm. Depths of nearer layers all clamp to
// phi = 0, toward the receiver: where that lifts the bound more than 0.05 above vsm's, clamped_above_vsm flags the
// pixel (README.md, "Where layering cannot help"; e.g. a receiver just behind its layer's near end, whose nearer
// occluders the variance floor then cannot tell from contact).
// layer_bound=tightest (tightestBound, ShadowLab's extension, README.md "Bound from several layers"): every phi_j is
// monotone, so z >= t implies phi_j(z) >= phi_j(t) and Chebyshev's bound on layer j's moments at phi_j(t) also bounds
// the lit fraction; p_max is the least of all layers' bounds and vsm's (the unwarped depths of the same box).
// Light bleeding is reduced as vsm does (Lauritzen 2007).
// Also written, to check the issue's claim per pixel, from vsm's bound on the unwarped depths of the same box: where
// vsm leaks more than LVSM_VSM_LEAK_THRESHOLD, whether the layered bound leaks less and if not why
// (vsm_comparison, in the order of sl::lvsmVsmComparison).
// CPU mirror: src/techniques/lvsm/LvsmTechnique.cpp.
#include "common/GBufferInputs.glsl"
#include "common/LightModel.glsl"
#include "common/ShadowMapCommon.glsl"
#include "common/ShadowReceiver.glsl"
#include "common/LeakPcf.glsl"
#include "common/Chebyshev.glsl"
#include "layeredmoments/LayeredMomentsLayout.glsl"

uniform sampler3D layeredMoments; // slice i: (E[phi_i(z)], E[phi_i(z)^2]) over the box
uniform int kernelWidth;          // prefilter_texels
uniform int tightestBound;        // layer_bound: 0 own, 1 tightest

layout(location = OUT_VISIBILITY) out float outVisibility;
layout(location = OUT_P_MAX) out float outPMax;
layout(location = OUT_LIGHT_LEAK) out float outLightLeak;
layout(location = OUT_LAYER) out float outLayer;
layout(location = OUT_WARPED_DEPTH) out float outWarpedDepth;
layout(location = OUT_CLAMPED_ABOVE_VSM) out float outClampedAboveVsm;
layout(location = OUT_VSM_COMPARISON) out float outVsmComparison;
layout(location = OUT_DEPTH_BIAS) out float outDepthBias;

// vsm's bound over the same box, from the shadow map's depths (vsm's moment map is not built for lvsm), and the
// number of the box's depths in front of and behind the layer `interval`. The depths are summed relative to the
// receiver's t: Chebyshev's bound is invariant under that shift, and the float variance E[(z-t)^2] - E[z-t]^2 then
// does not cancel as E[z^2] - E[z]^2 does at depths of several units (it is a candidate of layer_bound=tightest,
// compared with the twin at 2e-3).
float unlayeredBound(vec2 uvTexels, float t, float d, vec2 interval, out int inFront, out int behind)
{
  inFront = 0;
  behind = 0;
  ivec2 center = shadowMapTexel(uvTexels);
  int first = -(kernelWidth - 1) / 2;
  vec2 sum = vec2(0.0);
  for (int j = 0; j < kernelWidth; ++j)
  {
    for (int i = 0; i < kernelWidth; ++i)
    {
      ivec2 texel = clamp(center + ivec2(first + i, first + j), ivec2(0), ivec2(shadowMapSize - 1));
      float z = texelFetch(shadowMapLinear, texel, 0).r;
      float shifted = z - t;
      sum += vec2(shifted, shifted * shifted);
      inFront += z < interval.x ? 1 : 0;
      behind += z > interval.y ? 1 : 0;
    }
  }
  vec2 moments = sum / float(kernelWidth * kernelWidth);
  float variance = max(moments.y - moments.x * moments.x, param_min_variance * d * d);
  return chebyshevUpperBound(moments.x, variance, 0.0);
}

// Chebyshev's bound on layer `layer`'s moments at phi(t), vsm's floor rescaled into the layer's warped units.
float layerBound(ivec2 texel, int layer, float t, float d)
{
  vec2 interval = depthLayer(layer);
  vec2 moments = texelFetch(layeredMoments, ivec3(texel, layer), 0).xy;
  float layerScale = 1.0 / (interval.y - interval.x);
  float varianceFloor = param_min_variance * d * d * layerScale * layerScale;
  float variance = max(moments.y - moments.x * moments.x, varianceFloor);
  return chebyshevUpperBound(moments.x, variance, warpIntoLayer(t, interval));
}

void main()
{
  ShadowReceiver receiver = prepareShadowReceiver(ivec2(gl_FragCoord.xy));
  outVisibility = receiver.visibility;
  outPMax = 0.0;
  outLightLeak = 0.0;
  outLayer = -1.0;
  outWarpedDepth = 0.0;
  outClampedAboveVsm = 0.0;
  outVsmComparison = float(VSM_COMPARISON_VSM_BELOW_THRESHOLD);
  outDepthBias = receiver.bias;
  if (!receiver.needsShadowTest)
  {
    return;
  }
  float t = receiver.comparisonDepth;
  int layer = depthLayerIndex(t);
  vec2 interval = depthLayer(layer);
  float warpedT = warpIntoLayer(t, interval);
  ivec2 texel = shadowMapTexel(receiver.uvTexels);
  float d = receiver.depthLin;
  float ownPMax = layerBound(texel, layer, t, d);
  int inFront;
  int behind;
  float vsmPMax = unlayeredBound(receiver.uvTexels, t, d, interval, inFront, behind);
  float pMax = ownPMax;
  if (tightestBound != 0)
  {
    // Same order and ties as lvsmReference.
    for (int j = 0; j < layeredLayers; ++j)
    {
      if (j != layer)
      {
        pMax = min(pMax, layerBound(texel, j, t, d));
      }
    }
    pMax = min(pMax, vsmPMax);
  }
  outVisibility = reduceLightBleeding(pMax, param_light_bleeding_reduction);
  outPMax = pMax;
  float pcf = boxPcf(receiver.uvTexels, leakComparisonDepth(receiver), kernelWidth);
  outLightLeak = pMax - pcf;
  outLayer = float(layer);
  outWarpedDepth = warpedT;
  outClampedAboveVsm = inFront > 0 && pMax > vsmPMax + LVSM_VSM_LEAK_THRESHOLD ? 1.0 : 0.0;
  float vsmLeak = vsmPMax - pcf;
  int comparison = VSM_COMPARISON_VSM_BELOW_THRESHOLD;
  if (vsmLeak > LVSM_VSM_LEAK_THRESHOLD)
  {
    comparison = inFront + behind == 0                 ? VSM_COMPARISON_SAME_LAYER
      : pMax >= 1.0 && vsmPMax >= 1.0                   ? VSM_COMPARISON_SATURATED
      : pMax - pcf < vsmLeak                            ? VSM_COMPARISON_LEAKS_LESS
      : tightestBound != 0 && pMax >= vsmPMax           ? VSM_COMPARISON_VSM_BOUND_TIGHTEST
      : inFront > 0                                     ? VSM_COMPARISON_CLAMPED_IN_FRONT
                                                        : VSM_COMPARISON_UNEXPLAINED;
  }
  outVsmComparison = float(comparison);
}
