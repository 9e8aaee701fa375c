// The layered moment map's separable box blur (LayeredMomentsBuild.glsl, x then y) evaluated only at the texels the
// receivers read (prefilter_region = receivers, sparse; structures/moments/ReceiverTiles.h), one invocation per listed
// texel and every layer: for each of the y pass's rows it forms the x pass's value there as that pass does (the same
// taps, clamped alike, warped into the layer, summed in the same order, divided by the width), then sums them as the y
// pass does, so a listed texel holds what the whole map holds there. Each depth is fetched once for all layers. The
// list is moments/ReceiverTiles.glsl's: word 0 the count, then x | y << 16 (repeats write the same value twice).
// CPU mirror: layeredBoxMoments (src/techniques/lvsm/LvsmTechnique.h).
layout(local_size_x = 64) in;

#include "layeredmoments/LayeredMomentsLayout.glsl"

layout(std430, binding = 0) readonly restrict buffer ReceiverReadTexels
{
  uint receiverReadTexels[];
};
uniform sampler2D shadowMapLinear;
uniform int blurWidth;
uniform int mapSize;
uniform int readTexelCount;
layout(rg32f, binding = 0) uniform writeonly image3D target;

void main()
{
  int entry = int(gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x + gl_GlobalInvocationID.x);
  if (entry >= readTexelCount)
  {
    return;
  }
  uint packedTexel = receiverReadTexels[1 + entry];
  ivec2 texel = ivec2(int(packedTexel & 0xFFFFu), int(packedTexel >> 16));
  int first = -(blurWidth - 1) / 2;
  vec2 sums[LAYERED_MAX_LAYERS];
  for (int layer = 0; layer < layeredLayers; ++layer)
  {
    sums[layer] = vec2(0.0);
  }
  for (int row = 0; row < blurWidth; ++row)
  {
    ivec2 rowTexel = clamp(texel + ivec2(0, first + row), ivec2(0), ivec2(mapSize - 1));
    vec2 rowSums[LAYERED_MAX_LAYERS];
    for (int layer = 0; layer < layeredLayers; ++layer)
    {
      rowSums[layer] = vec2(0.0);
    }
    for (int k = 0; k < blurWidth; ++k)
    {
      ivec2 tap = clamp(rowTexel + ivec2(first + k, 0), ivec2(0), ivec2(mapSize - 1));
      float depth = texelFetch(shadowMapLinear, tap, 0).r;
      for (int layer = 0; layer < layeredLayers; ++layer)
      {
        float warped = warpIntoLayer(depth, depthLayer(layer));
        rowSums[layer] += vec2(warped, warped * warped);
      }
    }
    for (int layer = 0; layer < layeredLayers; ++layer)
    {
      sums[layer] += rowSums[layer] / float(blurWidth);
    }
  }
  for (int layer = 0; layer < layeredLayers; ++layer)
  {
    imageStore(target, ivec3(texel, layer), vec4(sums[layer] / float(blurWidth), 0.0, 0.0));
  }
}
