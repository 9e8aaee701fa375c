// The light-space structures a technique can ask for (TechniqueDescriptor::lightStructures). Each is described
// once in the structure registry (lightspace/LightSpaceStructure.h), built once per frame (per sub-light for
// multi-view) and exported in light_space.vti.
#pragma once

#include <string>

namespace sl
{

enum class LightStructure
{
  ShadowMap, // linear depth (R32F) + hardware depth (D32F) from the light's centre, focused (survey §4.1)
  MomentMap, // (z, z^2, exp(c z_n)) of the shadow map, prefiltered by a box blur or mip-mapped (survey §6)
  SummedAreaTable, // of the shadow map's (z, z^2): float (centred) or 32-bit integer (survey §6.4)
  HierarchicalShadowMap, // min-max depth pyramid, mip-map or N-buffers (VSSM §6.1)
  DualMultiScaleShadowMap, // the MSSM on the dual grid of 2 x 2 sample blocks (Yang et al. 2009 §4.2)
};
std::string lightStructureName(LightStructure structure);

} // namespace sl
