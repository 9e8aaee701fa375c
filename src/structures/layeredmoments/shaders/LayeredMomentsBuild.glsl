// One direction of the layered moment map's separable box blur (prefilter_texels, taps at -(w - 1)/2 ..
// (w - 1)/2, clamp to edge, as moments/BoxBlur.glsl), for layer `layer`:
//  - LAYERED_BLUR_PASS 0: along x, from the shadow map, warping each depth into the layer first
//    (phi_i(z), phi_i(z)^2: Lauritzen & McCool 2008), into a temporary 3D texture;
//  - LAYERED_BLUR_PASS 1: along y, from that temporary, into the layered moment map (slice i = layer i).
// CPU mirror: layeredBoxMoments (src/techniques/lvsm/LvsmTechnique.h).
layout(local_size_x = 8, local_size_y = 8) in;

#include "layeredmoments/LayeredMomentsLayout.glsl"

uniform int blurWidth;
uniform int layer;
uniform float layerNearEnd; // p_i of `layer`, set per dispatch
uniform float layerFarEnd;  // q_i
uniform int mapSize;
layout(rg32f, binding = 0) uniform writeonly image3D target;
#if LAYERED_BLUR_PASS == 0
uniform sampler2D shadowMapLinear;
#else
uniform sampler3D horizontal;
#endif

void main()
{
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(texel, ivec2(mapSize))))
  {
    return;
  }
  vec2 interval = vec2(layerNearEnd, layerFarEnd);
  vec2 sum = vec2(0.0);
  int first = -(blurWidth - 1) / 2;
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
