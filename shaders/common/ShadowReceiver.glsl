// The per-pixel preamble every shadow-map technique shares (mirrors sl::prepareShadowLookup,
// src/techniques/ShadowMapReference.cpp): pixels that never reach a shadow test get their visibility
// here (uncovered 0, not receiving 1, unreachable 0); the others get their shadow-map position, bias
// (survey §5) and the depth to compare against.
// Needs common/GBufferInputs.glsl, common/LightModel.glsl and common/ShadowMapCommon.glsl.
struct ShadowReceiver
{
  bool needsShadowTest;
  float visibility; // final when !needsShadowTest
  vec3 pWs;
  vec3 nWs;
  vec2 uvTexels;
  float depthLin;
  float bias;
  float comparisonDepth; // depthLin - bias
};

ShadowReceiver prepareShadowReceiver(ivec2 pixel)
{
  Surface surface = readSurface(pixel);
  ShadowReceiver receiver;
  receiver.needsShadowTest = false;
  receiver.visibility = 0.0;
  receiver.pWs = surface.pWs;
  receiver.nWs = surface.nWs;
  receiver.uvTexels = vec2(0.0);
  receiver.depthLin = 0.0;
  receiver.bias = 0.0;
  receiver.comparisonDepth = 0.0;
  if (!surface.covered)
  {
    return receiver;
  }
  if (!surface.receivesShadows)
  {
    receiver.visibility = 1.0;
    return receiver;
  }
  if (!lightCanReach(surface.pWs, surface.nWs))
  {
    return receiver;
  }
  vec3 sm = projectToShadowMap(surface.pWs);
  receiver.needsShadowTest = true;
  receiver.uvTexels = sm.xy;
  receiver.depthLin = sm.z;
  receiver.bias = depthBiasAt(tanAngleToLight(surface.nWs, directionToLight(surface.pWs)), surface.pWs, sm.z);
  receiver.comparisonDepth = sm.z - receiver.bias;
  return receiver;
}
