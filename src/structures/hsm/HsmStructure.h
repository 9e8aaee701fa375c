// The min-max hierarchical shadow map (VSSM §6.1, Alg. 1 L4; Guennebaud et al. 2006): RG32F (min, max) depth of
// levels 1..L, as a mip-map atlas (conservative ranges), as N-buffers (exact ranges over the 2^k square at every
// texel, Schwarz & Stamminger 2007; L times the memory) or as the Y shadow map (the mip-map atlas plus a ~256^2
// MSSM part from one of its levels, Schwarz & Stamminger 2008 §6, Table 1: + 4 MiB at 1024^2 and 2048^2).
// Layouts: lightspace/HierarchicalShadowMap.h. Built by
// vtkSLHsmPass (stage hierarchical_shadow_map), which also builds the dual-grid MSSM (structures/mssm).
#pragma once

#include "lightspace/HierarchicalShadowMap.h"
#include "lightspace/LightView.h"
#include "scene/Scene.h"
#include "structures/LightSpaceStructure.h"

namespace sl
{

const LightSpaceStructure& hierarchicalShadowMapStructure();

// The parameters its build reads, typed.
struct HierarchicalShadowMapSettings
{
  HsmLayout layout = HsmLayout::MipMap; // hsm = mipmap | nbuffers | ysm
  bool levelsRead = true;               // hsm_levels = read | all
};
HierarchicalShadowMapSettings hierarchicalShadowMapSettings(const ParameterValues& values);
// hsm_levels (this structure's) and mssm_levels (the dual-grid MSSM's): read | all.
ParameterSpec hsmLevelsParameter(const std::string& name, const std::string& layout);

// The last level the N-buffers or the dual-grid MSSM of a frame is built to (HierarchicalShadowMap::topLevel): every
// level for the other layouts, with hsm_levels / mssm_levels = all, or where the technique does not bound its
// queries (LightSpaceRequest::minMaxQueriesWithinNearPlaneKernel); else minMaxTopLevel of the widest query it can
// make: Eq. 1's initial kernel (Yang et al. 2009) of a receiver at the map's far depth, 2 half-widths plus the
// kernel's texel, its ring and the dual grid's extra cell. `boundedQueries`: the technique's flag and the parameter.
int minMaxTopLevel(HsmLayout layout, const LightView& view, const Light& light, bool boundedQueries);
// The frame's: from its technique's LightSpaceRequest and `hsm_levels` (`mssm_levels` for the dual grid).
int minMaxTopLevel(HsmLayout layout, const FrameResources& frame);

// The CPU build of the hierarchy those parameters ask for, from a read-back shadow map: what the twins and probe
// replays traverse where the GPU traversed vtkSLHsmPass's. Every level; with the frame's light view and light and
// whether the technique bounds its queries (its LightSpaceRequest), up to the level vtkSLHsmPass built.
HierarchicalShadowMap buildHierarchicalShadowMap(const ImageF& shadowMapLinear, const ParameterValues& values);
HierarchicalShadowMap buildHierarchicalShadowMap(const ImageF& shadowMapLinear, const ParameterValues& values,
  const LightView& view, const Light& light, bool queriesWithinNearPlaneKernel);

// What the build leaves in the frame (this structure's and the dual-grid MSSM's).
struct MinMaxDepthData : LightSpaceData
{
  vtkSmartPointer<vtkTextureObject> texture; // RG32F: 2-D atlas (mip-map, YSM) or 3-D (N-buffers, dual grid)
  HsmLayout layout = HsmLayout::MipMap;
  // YSM only: the MSSM part, RG32F M x M x ceil(log2 M) (layer j - 1 = its level j), over HSM level ysmBaseLevel.
  vtkSmartPointer<vtkTextureObject> mssmPart;
  int ysmBaseLevel = 0;
  int topLevel = 0;   // the last level built (minMaxTopLevel)
  int levelCount = 0; // the levels the map has (hsmLevelCount, dualMssmLevelCount)
};

// Shared with the dual-grid MSSM: the structure's export (with stats.json <prefix>_top_level and _level_count),
// memory and binding for a built MinMaxDepthData.
std::vector<NamedImage> exportMinMaxDepth(const MinMaxDepthData& data, int mapSize, FrameResult& result,
  const std::string& statisticsPrefix);
std::size_t minMaxDepthBytes(const MinMaxDepthData& data);
std::vector<vtkTextureObject*> bindMinMaxDepth(vtkShaderProgram* program, const MinMaxDepthData& data, int mapSize);

} // namespace sl
