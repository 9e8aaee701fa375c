// The depth layers of layered variance shadow maps (Lauritzen & McCool 2008): the uniform partition of the light
// view's linear depth range [layeredDepthNear, layeredDepthFar] into layeredLayers disjoint intervals, and the
// warp phi_i into [0, 1] that clamps depths in front of layer i to its near end and behind it to its far end.
// CPU mirror: src/structures/layeredmoments/LayeredMoments.cpp (same formulas, in double).
uniform int layeredLayers;
uniform float layeredDepthNear;
uniform float layeredDepthFar;

// (p_i, q_i) of layer `layer`.
vec2 depthLayer(int layer)
{
  float width = (layeredDepthFar - layeredDepthNear) / float(layeredLayers);
  float farEnd = layer + 1 == layeredLayers ? layeredDepthFar : layeredDepthNear + float(layer + 1) * width;
  return vec2(layeredDepthNear + float(layer) * width, farEnd);
}

int depthLayerIndex(float depth)
{
  float position = (depth - layeredDepthNear) / (layeredDepthFar - layeredDepthNear) * float(layeredLayers);
  return clamp(int(floor(position)), 0, layeredLayers - 1);
}

float warpIntoLayer(float depth, vec2 layer)
{
  return clamp((depth - layer.x) / (layer.y - layer.x), 0.0, 1.0);
}
