// The depth layers of layered variance shadow maps (Lauritzen & McCool 2008): the partition of the light view's
// linear depth range into layeredLayers disjoint intervals given by their ends layeredEnds[0..layeredLayers]
// (layer_placement: uniform, or boundaries in the depth histogram's widest gaps; computed on the CPU,
// LayeredMoments.cpp, and passed as uniforms), and the warp phi_i into [0, 1] that clamps depths in front of layer i
// to its near end and behind it to its far end.
// CPU mirror: src/structures/layeredmoments/LayeredMoments.cpp (same formulas, in double).
#define LAYERED_MAX_LAYERS 16
uniform int layeredLayers;
uniform float layeredEnds[LAYERED_MAX_LAYERS + 1];

// (p_i, q_i) of layer `layer`.
vec2 depthLayer(int layer)
{
  return vec2(layeredEnds[layer], layeredEnds[layer + 1]);
}

// The last layer whose near end is at or before `depth` (depths outside the range: the first or last layer).
int depthLayerIndex(float depth)
{
  int index = 0;
  for (int i = 1; i < layeredLayers; ++i)
  {
    index = depth >= layeredEnds[i] ? i : index;
  }
  return index;
}

float warpIntoLayer(float depth, vec2 layer)
{
  return clamp((depth - layer.x) / (layer.y - layer.x), 0.0, 1.0);
}
