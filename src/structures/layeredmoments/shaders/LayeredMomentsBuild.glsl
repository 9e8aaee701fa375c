// One direction of the layered moment map's separable box blur (prefilter_texels, taps at -(w - 1)/2 ..
// (w - 1)/2, clamp to edge, as moments/BoxBlur.glsl), over a list of tiles, every layer at once:
//  - LAYERED_BLUR_PASS 0: along x, from the shadow map, warping each depth into the layer first
//    (phi_i(z), phi_i(z)^2: Lauritzen & McCool 2008), into a temporary 3D texture;
//  - LAYERED_BLUR_PASS 1: along y, from that temporary, into the layered moment map (slice i = layer i).
// Work group (k, 0, i) builds tile layeredTiles[k] (x | y << 16, in tiles of tileTexels^2 texels) of layer i, each
// invocation every 8th texel of it along x and y. prefilter_region = receivers lists the receivers' tiles for the y
// pass and those grown by the box's reach along y for the x pass (structures/moments/ReceiverTiles.h); whole_map lists
// every tile. A texel's sum does not depend on the list, so a listed texel holds what the whole map holds there.
// CPU mirror: layeredBoxMoments (src/techniques/lvsm/LvsmTechnique.h).
layout(local_size_x = 8, local_size_y = 8) in;

#include "layeredmoments/LayeredMomentsLayout.glsl"

uniform int blurWidth;
uniform int mapSize;
uniform int tileTexels;
layout(rg32f, binding = 0) uniform writeonly image3D target;
layout(std430, binding = 1) readonly restrict buffer LayeredTiles
{
  uint layeredTiles[];
};
#if LAYERED_BLUR_PASS == 0
uniform sampler2D shadowMapLinear;
#else
uniform sampler3D horizontal;
#endif

void main()
{
  uint tile = layeredTiles[gl_WorkGroupID.x];
  ivec2 tileOrigin = ivec2(int(tile & 0xffffu), int(tile >> 16)) * tileTexels;
  int layer = int(gl_WorkGroupID.z);
  vec2 interval = depthLayer(layer);
  int first = -(blurWidth - 1) / 2;
  for (int dy = int(gl_LocalInvocationID.y); dy < tileTexels; dy += 8)
  {
    for (int dx = int(gl_LocalInvocationID.x); dx < tileTexels; dx += 8)
    {
      ivec2 texel = tileOrigin + ivec2(dx, dy);
      if (any(greaterThanEqual(texel, ivec2(mapSize))))
      {
        continue;
      }
      vec2 sum = vec2(0.0);
      for (int k = 0; k < blurWidth; ++k)
      {
#if LAYERED_BLUR_PASS == 0
        ivec2 tap = clamp(texel + ivec2(first + k, 0), ivec2(0), ivec2(mapSize - 1));
        float warped = warpIntoLayer(texelFetch(shadowMapLinear, tap, 0).r, interval);
        sum += vec2(warped, warped * warped);
#else
        ivec2 tap = clamp(texel + ivec2(0, first + k), ivec2(0), ivec2(mapSize - 1));
        sum += texelFetch(horizontal, ivec3(tap, layer), 0).xy;
#endif
      }
      imageStore(target, ivec3(texel, layer), vec4(sum / float(blurWidth), 0.0, 0.0));
    }
  }
}
