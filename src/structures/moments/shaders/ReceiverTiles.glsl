// Marks the tiles of the light-space map that the frame's receivers read (structures/moments/ReceiverTiles.h): each
// covered G-buffer pixel is projected into the map as the technique projects it (projectToShadowMap,
// common/ShadowMapCommon.glsl) and flags the tile of every texel within half a texel of its projection, clamped to
// the map as shadowMapTexel clamps. The half texel covers a different rounding of the same projection in the
// technique's own shader; the clamp covers receivers outside the map, which read its edge. Conservative: a pixel
// the technique does not test (lightCanReach false) may still flag its tile.
// CPU mirror: ReceiverTiles (the flags are read back into it).
layout(local_size_x = 8, local_size_y = 8) in;

uniform sampler2D gbufferPosition; // xyz = pWs, w = coverage
uniform sampler2D gbufferNormal;   // w = 1 where the surface receives shadows
// 1 for a point light or a spot of half-angle >= 90 degrees, which can light a receiver behind its plane
uniform int behindLightReads;
uniform mat4 lightClipFromWorld;
uniform int shadowMapSize;
uniform int tileTexels;
uniform int tilesPerSide;
layout(std430, binding = 0) buffer ReceiverTileFlags
{
  uint receiverTileFlags[];
};
// The texels themselves, for the passes that draw them as points: word 0 counts them (past the capacity: too many,
// the tiles are drawn instead), then x | y << 16 each, four per pixel (its footprint, below), repeated when several
// receivers read one texel. Capacity 0: not listed.
uniform int readTexelCapacity;
layout(std430, binding = 1) buffer ReceiverReadTexels
{
  uint receiverReadTexels[];
};

void main()
{
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, textureSize(gbufferPosition, 0))))
  {
    return;
  }
  vec4 position = texelFetch(gbufferPosition, pixel, 0);
  if (position.w == 0.0)
  {
    return;
  }
  if (texelFetch(gbufferNormal, pixel, 0).w == 0.0)
  {
    return; // not a receiver: its visibility is 1 without a lookup (prepareShadowReceiver)
  }
  vec4 clip = lightClipFromWorld * vec4(position.xyz, 1.0);
  vec2 uvTexels = (clip.xy / clip.w * 0.5 + 0.5) * float(shadowMapSize);
  bool finite = !any(isnan(uvTexels)) && !any(isinf(uvTexels));
  if (clip.w <= 0.0 && behindLightReads == 0)
  {
    return; // behind the light's plane: outside an area light's hemisphere or a spot's cone (lightCanReach), no lookup
  }
  if (clip.w <= 0.0 || !finite)
  {
    // Its lookup, after the clamp, may land on any texel of the border: the word after the tiles asks for the
    // whole map.
    receiverTileFlags[tilesPerSide * tilesPerSide] = 1u;
    return;
  }
  vec2 bounded = clamp(uvTexels, vec2(-1.0), vec2(float(shadowMapSize) + 1.0));
  ivec2 firstTexel = clamp(ivec2(floor(bounded - 0.5)), ivec2(0), ivec2(shadowMapSize - 1));
  ivec2 lastTexel = clamp(ivec2(floor(bounded + 0.5)), ivec2(0), ivec2(shadowMapSize - 1));
  for (int y = firstTexel.y; y <= lastTexel.y; ++y)
  {
    for (int x = firstTexel.x; x <= lastTexel.x; ++x)
    {
      receiverTileFlags[(y / tileTexels) * tilesPerSide + x / tileTexels] = 1u;
    }
  }
  if (readTexelCapacity > 0)
  {
    // The pixel's footprint as four consecutive entries, (0, 0), (1, 0), (0, 1), (1, 1) from firstTexel, each clamped
    // to lastTexel (the two differ by at most 1 per axis): a footprint the clamp narrowed repeats its texels. The
    // sparse blur (SparseBoxBlur.glsl) forms a footprint's texels together from the taps they share.
    uint slot = atomicAdd(receiverReadTexels[0], 4u);
    if (slot + 4u <= uint(readTexelCapacity))
    {
      for (int entry = 0; entry < 4; ++entry)
      {
        ivec2 texel = min(firstTexel + ivec2(entry & 1, entry >> 1), lastTexel);
        receiverReadTexels[1u + slot + uint(entry)] = uint(texel.x) | (uint(texel.y) << 16);
      }
    }
  }
}
