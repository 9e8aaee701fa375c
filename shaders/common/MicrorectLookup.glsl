// Microrects (Schwarz & Stamminger 2008, §5.2): the extent and depth of microrect `index` of `level`,
// from the two atlases the microrect build leaves (structures/microrect/MicrorectStructure.h, bound by the
// structure: microrectExtentTexture, microrectDepthTexture, microrectMapSize). Level 0 is the shadow map's
// micropatches, so the including shader declares `uniform sampler2D shadowMapLinear` first (common/
// ShadowMapCommon.glsl does). No loops: a technique calls this once per micro-occluder.
// CPU mirror: Microrects::at (src/lightspace/Microrects.h, where the construction is defined).
#include "common/MipAtlasLayout.glsl"

uniform usampler2D microrectExtentTexture; // RGBA16UI atlas of levels 1..L: x0, y0, x1, y1 (inclusive level-0 texels)
uniform sampler2D microrectDepthTexture;   // R32F atlas of levels 1..L: min linear depth of the members
uniform int microrectMapSize;              // N, the shadow map's side

// Microrects per side of `level` (0..L): ceil(N / 2^level).
int microrectLevelSize(int level)
{
  return mipAtlasLevelSize(microrectMapSize, level);
}

// Its reference point, the level-0 texel it is anchored at (subsampling, §5.2).
ivec2 microrectReferencePoint(int level, ivec2 index)
{
  return index << level;
}

// `index` must lie inside microrectLevelSize(level) per axis.
void microrectAt(int level, ivec2 index, out ivec4 extent, out float depth)
{
  if (level == 0)
  {
    extent = ivec4(index, index);
    depth = texelFetch(shadowMapLinear, index, 0).r;
    return;
  }
  ivec2 texel = mipAtlasOffset(microrectMapSize, level) + index;
  extent = ivec4(texelFetch(microrectExtentTexture, texel, 0));
  depth = texelFetch(microrectDepthTexture, texel, 0).r;
}
