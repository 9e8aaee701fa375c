// Hard shadow mapping (Williams 1978) with the survey's depth biasing (§5): one depth comparison against
// the texel containing the receiver. CPU mirror: src/techniques/hard/HardReference.cpp.
#include "common/GBufferInputs.glsl"
#include "common/LightModel.glsl"
#include "common/ShadowMapCommon.glsl"
#include "common/TexelRatio.glsl"

layout(location = OUT_VISIBILITY) out float outVisibility;
layout(location = OUT_KERNEL_TEXELS) out float outKernelTexels;
layout(location = OUT_TEXEL_RATIO) out float outTexelRatio;
layout(location = OUT_DEPTH_BIAS) out float outDepthBias;
layout(location = OUT_DEPTH_MARGIN) out float outDepthMargin;

void main()
{
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  Surface surface = readSurface(pixel);
  outVisibility = 0.0;
  outKernelTexels = 0.0;
  outTexelRatio = 0.0;
  outDepthBias = 0.0;
  outDepthMargin = 0.0;
  if (!surface.covered)
  {
    return;
  }
  if (!surface.receivesShadows)
  {
    outVisibility = 1.0;
    return;
  }
  if (!lightCanReach(surface.pWs, surface.nWs))
  {
    return;
  }
  vec3 sm = projectToShadowMap(surface.pWs);
  float bias = depthBias(tanAngleToLight(surface.nWs, directionToLight(surface.pWs)), sm.z);
  float comparisonDepth = sm.z - bias;
  outVisibility = shadowTest(sm.xy, comparisonDepth);
  outKernelTexels = 1.0;
  outTexelRatio = texelRatio(gl_FragCoord.xy, surface.pWs, surface.nWs);
  outDepthBias = bias;
  outDepthMargin = comparisonDepth - storedDepth(sm.xy);
}
