// Layout of the min-max hierarchical shadow map (VSSM Alg. 1 L4, §6.1), shared by its build
// (hsm/HsmBuild.glsl, hsm/YsmMssmBuild.glsl) and its lookup (common/HsmLookup.glsl). HSM_LAYOUT_* come from
// the `hsm` parameter. The Y shadow map (HSM_LAYOUT_YSM, SS08 §6) holds the mip-map levels in the same
// atlas, plus its MSSM part (HsmLookup.glsl).
// CPU mirror: src/lightspace/HierarchicalShadowMap.cpp (hsmLevelSize, hsmAtlasOffset).
#include "common/MipAtlasLayout.glsl"

uniform int hsmMapSize; // N, the shadow map's side

// Texels per side of level k (k >= 1).
int hsmLevelSize(int level)
{
#if HSM_LAYOUT == HSM_LAYOUT_MIPMAP || HSM_LAYOUT == HSM_LAYOUT_YSM
  return (hsmMapSize + (1 << level) - 1) >> level;
#elif HSM_LAYOUT == HSM_LAYOUT_DUAL
  return hsmMapSize + 1; // texel t holds dual cell t - 1
#else
  return hsmMapSize;
#endif
}

// Mip-map (and YSM) atlas: level 1 at the origin, levels 2.. stacked in a column to its right. Closed form,
// no loop (common/MipAtlasLayout.glsl): llvmpipe counts every loop iteration of an invocation, and ss08 reads a
// node per micro-occluder.
ivec2 hsmAtlasOffset(int level)
{
  return mipAtlasOffset(hsmMapSize, level);
}
