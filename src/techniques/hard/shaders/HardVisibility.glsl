// Hard shadow mapping (Williams 1978) with the survey's depth biasing (§5): one depth comparison against
// the texel containing the receiver. CPU mirror: hardReference in src/techniques/hard/HardTechnique.cpp.
#include "common/GBufferInputs.glsl"
#include "common/LightModel.glsl"
#include "common/ShadowMapCommon.glsl"
#include "common/ShadowReceiver.glsl"
#include "common/TexelRatio.glsl"

layout(location = OUT_VISIBILITY) out float outVisibility;
layout(location = OUT_KERNEL_TEXELS) out float outKernelTexels;
layout(location = OUT_TEXEL_RATIO) out float outTexelRatio;
layout(location = OUT_DEPTH_BIAS) out float outDepthBias;
layout(location = OUT_DEPTH_MARGIN) out float outDepthMargin;

void main()
{
  ShadowReceiver receiver = prepareShadowReceiver(ivec2(gl_FragCoord.xy));
  outVisibility = receiver.visibility;
  outKernelTexels = 0.0;
  outTexelRatio = 0.0;
  outDepthBias = 0.0;
  outDepthMargin = 0.0;
  if (!receiver.needsShadowTest)
  {
    return;
  }
  float stored = storedDepth(receiver.uvTexels);
#if defined(SHADOW_MAP_POLYGON_ID) && SHADOW_MAP_POLYGON_ID
  // Survey §5 (Hourcade & Nicolas 1985): lit iff the texel's nearest triangle is the receiver's own; no depth, no bias.
  uint storedId = texelFetch(shadowMapPolygonId, shadowMapTexel(receiver.uvTexels), 0).r;
  uint ownId = texelFetch(receiverPolygonId, ivec2(gl_FragCoord.xy), 0).r;
  // Id 0: the receiver casts no shadow, so it is not in the map; its depth decides, as without ids.
  outVisibility = ownId == 0u ? (receiver.comparisonDepth <= stored ? 1.0 : 0.0) : (storedId == ownId ? 1.0 : 0.0);
#else
  outVisibility = receiver.comparisonDepth <= stored ? 1.0 : 0.0; // shadowTest, with the depth kept for the margin
#endif
  outKernelTexels = 1.0;
  outTexelRatio = texelRatio(gl_FragCoord.xy, receiver.pWs, receiver.nWs);
  outDepthBias = receiver.bias;
  outDepthMargin = receiver.comparisonDepth - stored;
}
