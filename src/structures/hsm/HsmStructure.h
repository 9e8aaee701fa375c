// The min-max hierarchical shadow map (VSSM §6.1, Alg. 1 L4; Guennebaud et al. 2006): RG32F (min, max) depth of
// levels 1..L, as a mip-map atlas (conservative ranges), as N-buffers (exact ranges over the 2^k square at every
// texel, Schwarz & Stamminger 2007; L times the memory) or as the Y shadow map (the mip-map atlas plus a ~256^2
// MSSM part from one of its levels, Schwarz & Stamminger 2008 §6, Table 1: + 4 MiB at 1024^2 and 2048^2).
// Layouts: lightspace/HierarchicalShadowMap.h. Built by
// vtkSLHsmPass (stage hierarchical_shadow_map), which also builds the dual-grid MSSM (structures/mssm).
#pragma once

#include "lightspace/HierarchicalShadowMap.h"
#include "structures/LightSpaceStructure.h"

namespace sl
{

const LightSpaceStructure& hierarchicalShadowMapStructure();

// The parameters its build reads, typed.
struct HierarchicalShadowMapSettings
{
  HsmLayout layout = HsmLayout::MipMap; // hsm = mipmap | nbuffers | ysm
};
HierarchicalShadowMapSettings hierarchicalShadowMapSettings(const ParameterValues& values);
// The CPU build of the hierarchy those parameters ask for, from a read-back shadow map: what the twins and probe
// replays traverse where the GPU traversed vtkSLHsmPass's.
HierarchicalShadowMap buildHierarchicalShadowMap(const ImageF& shadowMapLinear, const ParameterValues& values);

// What the build leaves in the frame (this structure's and the dual-grid MSSM's).
struct MinMaxDepthData : LightSpaceData
{
  vtkSmartPointer<vtkTextureObject> texture; // RG32F: 2-D atlas (mip-map, YSM) or 3-D (N-buffers, dual grid)
  HsmLayout layout = HsmLayout::MipMap;
  // YSM only: the MSSM part, RG32F M x M x ceil(log2 M) (layer j - 1 = its level j), over HSM level ysmBaseLevel.
  vtkSmartPointer<vtkTextureObject> mssmPart;
  int ysmBaseLevel = 0;
};

// Shared with the dual-grid MSSM: the structure's export, memory and binding for a built MinMaxDepthData.
std::vector<NamedImage> exportMinMaxDepth(const MinMaxDepthData& data, int mapSize);
std::size_t minMaxDepthBytes(const MinMaxDepthData& data);
std::vector<vtkTextureObject*> bindMinMaxDepth(vtkShaderProgram* program, const MinMaxDepthData& data, int mapSize);

} // namespace sl
