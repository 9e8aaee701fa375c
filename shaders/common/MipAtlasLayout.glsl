// The mip-map atlas of an N x N map without loops (llvmpipe counts loop iterations per invocation, and the
// microrect lookup runs once per micro-occluder): level k >= 1 has ceil(N / 2^k) texels per side; level 1 sits
// at the origin, levels 2.. are stacked in a column to its right. The layout of the HSM's mip-map atlas
// (common/HsmLayout.glsl, whose hsmAtlasOffset sums the same sizes in a loop) and of the microrect atlases
// (common/MicrorectLookup.glsl). CPU mirror: hsmLevelSize and hsmAtlasOffset (src/lightspace/HierarchicalShadowMap.cpp).

// Texels per side of level k >= 0: ceil(N / 2^k) = ((N - 1) >> k) + 1.
int mipAtlasLevelSize(int mapSize, int level)
{
  return ((mapSize - 1) >> level) + 1;
}

// Where level k >= 1 starts. With m = N - 1, y = sum_{j=2}^{k-1} ((m >> j) + 1), and sum_{j>=1} (v >> j) =
// v - bitCount(v) (Legendre) gives sum_{j=2}^{k-1} (m >> j) = S(m >> 1) - S(m >> (k - 1)), S(v) = v - bitCount(v).
ivec2 mipAtlasOffset(int mapSize, int level)
{
  if (level < 2)
  {
    return ivec2(0);
  }
  int m = mapSize - 1;
  int coarser = m >> (level - 1);
  int y = (level - 2) + ((m >> 1) - bitCount(m >> 1)) - (coarser - bitCount(coarser));
  return ivec2(mipAtlasLevelSize(mapSize, 1), y);
}
