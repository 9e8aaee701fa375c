// Builds level `level` (>= 1) of the microrects from level - 1 (Schwarz & Stamminger 2008, §5.2,
// Fig. 6), one invocation per level-`level` microrect (x, y), in two dispatches:
//  - MICRORECT_BUILD_PASS 1 (§5.2): the retained A = (2x, 2y) of level - 1 absorbs B = (2x+1, 2y) unless
//    C = (2x+2, 2y) exists and is strictly closer in depth (ties to A), D = (2x, 2y+1) against G = (2x, 2y+2)
//    likewise, then E = (2x+1, 2y+1) if the rectangle so far contains E's extent or (2x+2, 2y+2) does not exist.
//    Writes the partial extent and depth into the level's atlas texels and what it claimed into the claim image.
//  - MICRORECT_BUILD_PASS 2 (§5.2): adds F = (2x-1, 2y), H = (2x, 2y-1), E' = (2x-1, 2y-1) unless their own
//    retained microrect claimed them in pass 1.
// Extent = bounding rectangle of the members' extents, depth = min of their depths (§5.2). Level
// - 1 is read through the lookup a technique uses (common/MicrorectLookup.glsl: level 0 from the shadow map,
// the others from the atlases as textures, written by earlier dispatches); level `level` through images.
// The definition and the proofs (every microrect absorbed once, reference points): src/lightspace/Microrects.h,
// whose build is the CPU twin of this one, bit for bit.
layout(local_size_x = 8, local_size_y = 8) in;

uniform sampler2D shadowMapLinear;
#include "common/MicrorectLookup.glsl"

uniform int level; // the level built, >= 1

layout(rgba16ui, binding = 0) uniform uimage2D microrectExtentImage; // the extent atlas (as microrectExtentTexture)
layout(r32f, binding = 1) uniform image2D microrectDepthImage;       // the depth atlas (as microrectDepthTexture)
layout(r8ui, binding = 2) uniform uimage2D microrectClaimImage;      // pass 1's claims of each level-`level` texel

// What a retained microrect absorbed in pass 1: the preamble's CLAIMED_B, CLAIMED_D, CLAIMED_E (lightspace/Microrects.h
// MicrorectClaims).

bool finerExists(ivec2 index)
{
  return all(greaterThanEqual(index, ivec2(0))) && all(lessThan(index, ivec2(microrectLevelSize(level - 1))));
}

void absorb(inout ivec4 extent, inout float depth, ivec4 memberExtent, float memberDepth)
{
  extent = ivec4(min(extent.xy, memberExtent.xy), max(extent.zw, memberExtent.zw));
  depth = min(depth, memberDepth);
}

#if MICRORECT_BUILD_PASS == 1
// Whether `candidate` (B or D, which exists) joins A rather than its other partner (C or G): the partner of the
// smaller depth difference, A on a tie or when the other partner does not exist.
bool joinsA(float candidateDepth, float depthA, ivec2 otherPartner)
{
  if (!finerExists(otherPartner))
  {
    return true;
  }
  ivec4 otherExtent;
  float otherDepth;
  microrectAt(level - 1, otherPartner, otherExtent, otherDepth);
  // precise: the CPU twin takes these differences in IEEE float; no reassociation may change a decision.
  precise float toA = abs(candidateDepth - depthA);
  precise float toOther = abs(candidateDepth - otherDepth);
  return toA <= toOther;
}

// Pass 1 for B (step (1, 0)) or D (step (0, 1)) of retained A: absorbed when it exists and joins A rather than
// its other partner A + 2 step (C or G).
void absorbPartner(ivec2 a, ivec2 step, uint claim, float depthA, inout ivec4 extent, inout float depth, inout uint claims)
{
  ivec2 candidate = a + step;
  if (finerExists(candidate))
  {
    ivec4 memberExtent;
    float memberDepth;
    microrectAt(level - 1, candidate, memberExtent, memberDepth);
    if (joinsA(memberDepth, depthA, a + 2 * step))
    {
      absorb(extent, depth, memberExtent, memberDepth);
      claims |= claim;
    }
  }
}

void main()
{
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(texel, ivec2(microrectLevelSize(level)))))
  {
    return;
  }
  ivec2 a = 2 * texel;
  ivec4 extent;
  float depth;
  microrectAt(level - 1, a, extent, depth);
  float depthA = depth;
  uint claims = 0u;

  absorbPartner(a, ivec2(1, 0), uint(CLAIMED_B), depthA, extent, depth, claims); // B, against C
  absorbPartner(a, ivec2(0, 1), uint(CLAIMED_D), depthA, extent, depth, claims); // D, against G
  ivec4 memberExtent;
  float memberDepth;
  ivec2 e = a + ivec2(1, 1);
  if (finerExists(e))
  {
    microrectAt(level - 1, e, memberExtent, memberDepth);
    bool contained = all(lessThanEqual(extent.xy, memberExtent.xy)) && all(lessThanEqual(memberExtent.zw, extent.zw));
    if (contained || !finerExists(a + ivec2(2, 2)))
    {
      absorb(extent, depth, memberExtent, memberDepth);
      claims |= uint(CLAIMED_E);
    }
  }
  ivec2 atlasTexel = mipAtlasOffset(microrectMapSize, level) + texel;
  imageStore(microrectExtentImage, atlasTexel, uvec4(extent));
  imageStore(microrectDepthImage, atlasTexel, vec4(depth, 0.0, 0.0, 0.0));
  imageStore(microrectClaimImage, texel, uvec4(claims, 0u, 0u, 0u));
}
#else
// Absorbs `member` of level - 1 unless `owner` (a level-`level` texel) claimed it as `claim` in pass 1.
void absorbUnclaimed(ivec2 owner, uint claim, ivec2 member, inout ivec4 extent, inout float depth)
{
  if ((imageLoad(microrectClaimImage, owner).r & claim) != 0u)
  {
    return;
  }
  ivec4 memberExtent;
  float memberDepth;
  microrectAt(level - 1, member, memberExtent, memberDepth);
  absorb(extent, depth, memberExtent, memberDepth);
}

void main()
{
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(texel, ivec2(microrectLevelSize(level)))))
  {
    return;
  }
  ivec2 atlasTexel = mipAtlasOffset(microrectMapSize, level) + texel;
  ivec4 extent = ivec4(imageLoad(microrectExtentImage, atlasTexel));
  float depth = imageLoad(microrectDepthImage, atlasTexel).r;
  ivec2 p = 2 * texel;
  if (texel.x > 0)
  {
    absorbUnclaimed(texel - ivec2(1, 0), uint(CLAIMED_B), p - ivec2(1, 0), extent, depth); // F
  }
  if (texel.y > 0)
  {
    absorbUnclaimed(texel - ivec2(0, 1), uint(CLAIMED_D), p - ivec2(0, 1), extent, depth); // H
  }
  if (texel.x > 0 && texel.y > 0)
  {
    absorbUnclaimed(texel - ivec2(1, 1), uint(CLAIMED_E), p - ivec2(1, 1), extent, depth); // E'
  }
  imageStore(microrectExtentImage, atlasTexel, uvec4(extent));
  imageStore(microrectDepthImage, atlasTexel, vec4(depth, 0.0, 0.0, 0.0));
}
#endif
