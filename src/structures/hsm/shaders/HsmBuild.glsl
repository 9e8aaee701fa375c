// Builds level `level` (>= 1) of the min-max hierarchical shadow map from level - 1 (level 0 is the shadow
// map), one invocation per texel (VSSM Alg. 1 L4, §6.1):
//  - HSM_LAYOUT_MIPMAP: texel (x, y) = range of the finer texels 2 (x, y) + {0, 1}^2, in the atlas;
//  - HSM_LAYOUT_NBUFFERS (Décoret 2005): texel (x, y) = range of the finer texels (x, y) + 2^(k-1) {0, 1}^2,
//    i.e. of the 2^k x 2^k square at (x, y), in layer k - 1 of a 3D texture.
//  - HSM_LAYOUT_DUAL (Yang et al. 2009 §4.2): the N-buffers of the dual grid, level 0 included: texel t holds
//    cell t - 1, level 0 the range of its 2 x 2 samples (outside the map: outsideDepth), level k the range of
//    the 2^k x 2^k cells starting there, in layer k of a 2D array texture.
// Reads past the finer level's edge are clamped, which keeps every range inside the map. The N-buffers' and the
// dual grid's levels >= 1 run one invocation per 2 x 2 texels (x, y) + 2^(k-1) {0, 1}^2, whose finer squares
// overlap: 3 x 3 reads instead of 4 x 4 (vtkSLHsmPass::LevelInvocations sizes the dispatch).
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
#endif

// Texel `texel` of level - 1, clamped to that level.
vec2 finerRange(ivec2 texel)
{
#if HSM_LAYOUT == HSM_LAYOUT_DUAL
  texel = min(texel, ivec2(hsmLevelSize(level - 1) - 1));
  return imageLoad(hsmImage, ivec3(texel, level - 1)).xy;
#else
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
#endif
}

void storeRange(ivec2 texel, vec2 range)
{
#if HSM_LAYOUT == HSM_LAYOUT_MIPMAP
  imageStore(hsmImage, hsmAtlasOffset(level) + texel, vec4(range, 0.0, 0.0));
#elif HSM_LAYOUT == HSM_LAYOUT_DUAL
  imageStore(hsmImage, ivec3(texel, level), vec4(range, 0.0, 0.0));
#else
  imageStore(hsmImage, ivec3(texel, level - 1), vec4(range, 0.0, 0.0));
#endif
}

vec2 rangeOf(vec2 a, vec2 b, vec2 c, vec2 d)
{
  return vec2(min(min(a.x, b.x), min(c.x, d.x)), max(max(a.y, b.y), max(c.y, d.y)));
}

#if HSM_LAYOUT == HSM_LAYOUT_DUAL
// Dual level 0: the range of each cell's 2 x 2 samples (texel t holds cell t - 1).
void buildCells()
{
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  int size = hsmLevelSize(0);
  if (texel.x >= size || texel.y >= size)
  {
    return;
  }
  ivec2 cell = texel - 1;
  storeRange(texel, rangeOf(vec2(sampleOrOutside(cell)), vec2(sampleOrOutside(cell + ivec2(1, 0))),
    vec2(sampleOrOutside(cell + ivec2(0, 1))), vec2(sampleOrOutside(cell + ivec2(1, 1)))));
}
#endif

#if HSM_LAYOUT == HSM_LAYOUT_MIPMAP
// Mip-map: texel (x, y) from the finer texels 2 (x, y) + {0, 1}^2, which no other texel reads.
void buildLevel()
{
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  int size = hsmLevelSize(level);
  if (texel.x >= size || texel.y >= size)
  {
    return;
  }
  ivec2 first = 2 * texel;
  storeRange(texel, rangeOf(finerRange(first), finerRange(first + ivec2(1, 0)), finerRange(first + ivec2(0, 1)),
    finerRange(first + ivec2(1, 1))));
}
#else
// N-buffers and dual grid: invocation (i, j) builds the texels first + stride {0, 1}^2, first = (i, j) with bit k - 1
// of each coordinate inserted as 0 (the shared children's 3 x 3 reads at first + stride {0, 1, 2}^2).
void buildLevel()
{
  int size = hsmLevelSize(level);
  int stride = 1 << (level - 1);
  ivec2 invocation = ivec2(gl_GlobalInvocationID.xy);
  ivec2 first = (invocation / stride) * (2 * stride) + invocation % stride;
  if (first.x >= size || first.y >= size)
  {
    return;
  }
  vec2 finer[9];
  for (int j = 0; j < 3; ++j)
  {
    for (int i = 0; i < 3; ++i)
    {
      finer[3 * j + i] = finerRange(first + stride * ivec2(i, j));
    }
  }
  for (int j = 0; j < 2; ++j)
  {
    for (int i = 0; i < 2; ++i)
    {
      ivec2 texel = first + stride * ivec2(i, j);
      if (texel.x < size && texel.y < size)
      {
        storeRange(texel, rangeOf(finer[3 * j + i], finer[3 * j + i + 1], finer[3 * j + i + 3], finer[3 * j + i + 4]));
      }
    }
  }
}
#endif

void main()
{
#if HSM_LAYOUT == HSM_LAYOUT_DUAL
  if (level == 0)
  {
    buildCells();
    return;
  }
#endif
  buildLevel();
}
