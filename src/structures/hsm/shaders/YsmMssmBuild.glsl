// Builds level `level` (>= 1) of the Y shadow map's MSSM part (Schwarz & Stamminger 2008, §6),
// one invocation per texel: the N-buffers (Décoret 2005) over the M x M nodes of HSM level b =
// ysmBaseLevel, whose level 0 is that HSM level itself (read from the mip-map atlas, already built by
// hsm/HsmBuild.glsl with HSM_LAYOUT_MIPMAP, or from the shadow map for b = 0) and is not stored. Texel (x, y)
// of level j = range of the four level j - 1 squares at (x, y) + 2^(j-1) {0, 1}^2, reads clamped to the grid;
// level j goes to layer j - 1 of a 3-D texture.
// CPU mirror: HierarchicalShadowMap::build (src/lightspace/HierarchicalShadowMap.cpp).
layout(local_size_x = 8, local_size_y = 8) in;

#include "common/HsmLayout.glsl"

uniform sampler2D shadowMapLinear;
uniform sampler2D hsmAtlas;
uniform int ysmBaseLevel;
uniform int level;

layout(rg32f, binding = 0) uniform image3D mssmPart; // layer j - 1 holds level j

int partSize()
{
  return ysmBaseLevel == 0 ? hsmMapSize : hsmLevelSize(ysmBaseLevel);
}

// Level `level` - 1 of the part at `texel` (inside the grid).
vec2 finerRange(ivec2 texel)
{
  if (level > 1)
  {
    return imageLoad(mssmPart, ivec3(texel, level - 2)).xy;
  }
  if (ysmBaseLevel == 0)
  {
    return vec2(texelFetch(shadowMapLinear, texel, 0).r);
  }
  return texelFetch(hsmAtlas, hsmAtlasOffset(ysmBaseLevel) + texel, 0).xy;
}

void main()
{
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  int size = partSize();
  if (texel.x >= size || texel.y >= size)
  {
    return;
  }
  int stride = 1 << (level - 1);
  vec2 range = finerRange(texel);
  for (int child = 1; child < 4; ++child)
  {
    vec2 childRange = finerRange(min(texel + stride * ivec2(child & 1, child >> 1), ivec2(size - 1)));
    range = vec2(min(range.x, childRange.x), max(range.y, childRange.y));
  }
  imageStore(mssmPart, ivec3(texel, level - 1), vec4(range, 0.0, 0.0));
}
