// Builds level `level` (>= 1) of the min-max hierarchical shadow map from level - 1 (level 0 is the shadow
// map), one invocation per texel (VSSM Alg. 1 L4, §6.1):
//  - HSM_LAYOUT_MIPMAP: texel (x, y) = range of the finer texels 2 (x, y) + {0, 1}^2, in the atlas;
//  - HSM_LAYOUT_NBUFFERS (Décoret 2005): texel (x, y) = range of the finer texels (x, y) + 2^(k-1) {0, 1}^2,
//    i.e. of the 2^k x 2^k square at (x, y), in layer k - 1 of a 3D texture.
//  - HSM_LAYOUT_DUAL (Yang et al. 2009 §4.2): the N-buffers of the dual grid, level 0 included: texel t holds
//    cell t - 1, level 0 the range of its 2 x 2 samples (outside the map: outsideDepth), level k the range of
//    the 2^k x 2^k cells starting there, in layer k of a 2D array texture.
// Reads past the finer level's edge are clamped, which keeps every range inside the map.
// CPU mirror: src/lightspace/HierarchicalShadowMap.cpp.
layout(local_size_x = 8, local_size_y = 8) in;

#include "common/HsmLayout.glsl"

uniform sampler2D shadowMapLinear;
uniform int level;
uniform float outsideDepth;

#if HSM_LAYOUT == HSM_LAYOUT_MIPMAP
layout(rg32f, binding = 0) uniform image2D hsmImage;
#elif HSM_LAYOUT == HSM_LAYOUT_DUAL
layout(rg32f, binding = 0) uniform image3D hsmImage; // layer k holds level k
#else
layout(rg32f, binding = 0) uniform image3D hsmImage; // layer k - 1 holds level k
#endif

#if HSM_LAYOUT == HSM_LAYOUT_DUAL
float sampleOrOutside(ivec2 texel)
{
  bool inside = all(greaterThanEqual(texel, ivec2(0))) && all(lessThan(texel, ivec2(hsmMapSize)));
  return inside ? texelFetch(shadowMapLinear, texel, 0).r : outsideDepth;
}

void main()
{
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  int size = hsmLevelSize(level);
  if (texel.x >= size || texel.y >= size)
  {
    return;
  }
  vec2 range;
  if (level == 0)
  {
    ivec2 cell = texel - 1;
    float a = sampleOrOutside(cell);
    float b = sampleOrOutside(cell + ivec2(1, 0));
    float c = sampleOrOutside(cell + ivec2(0, 1));
    float d = sampleOrOutside(cell + ivec2(1, 1));
    range = vec2(min(min(a, b), min(c, d)), max(max(a, b), max(c, d)));
  }
  else
  {
    int stride = 1 << (level - 1);
    range = imageLoad(hsmImage, ivec3(texel, level - 1)).xy;
    for (int child = 1; child < 4; ++child)
    {
      ivec2 finer = min(texel + stride * ivec2(child & 1, child >> 1), ivec2(size - 1));
      vec2 childRange = imageLoad(hsmImage, ivec3(finer, level - 1)).xy;
      range = vec2(min(range.x, childRange.x), max(range.y, childRange.y));
    }
  }
  imageStore(hsmImage, ivec3(texel, level), vec4(range, 0.0, 0.0));
}
#else
vec2 finerRange(ivec2 texel)
{
  int finerSize = level == 1 ? hsmMapSize : hsmLevelSize(level - 1);
  texel = min(texel, ivec2(finerSize - 1));
  if (level == 1)
  {
    return vec2(texelFetch(shadowMapLinear, texel, 0).r);
  }
#if HSM_LAYOUT == HSM_LAYOUT_MIPMAP
  return imageLoad(hsmImage, hsmAtlasOffset(level - 1) + texel).xy;
#else
  return imageLoad(hsmImage, ivec3(texel, level - 2)).xy;
#endif
}

void main()
{
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  int size = hsmLevelSize(level);
  if (texel.x >= size || texel.y >= size)
  {
    return;
  }
#if HSM_LAYOUT == HSM_LAYOUT_MIPMAP
  ivec2 first = 2 * texel;
  int stride = 1;
#else
  ivec2 first = texel;
  int stride = 1 << (level - 1);
#endif
  vec2 range = finerRange(first);
  for (int child = 1; child < 4; ++child)
  {
    vec2 childRange = finerRange(first + stride * ivec2(child & 1, child >> 1));
    range = vec2(min(range.x, childRange.x), max(range.y, childRange.y));
  }
#if HSM_LAYOUT == HSM_LAYOUT_MIPMAP
  imageStore(hsmImage, hsmAtlasOffset(level) + texel, vec4(range, 0.0, 0.0));
#else
  imageStore(hsmImage, ivec3(texel, level - 1), vec4(range, 0.0, 0.0));
#endif
}
#endif
