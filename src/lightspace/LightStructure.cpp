#include "lightspace/LightStructure.h"

namespace sl
{

std::string lightStructureName(LightStructure structure)
{
  switch (structure)
  {
    case LightStructure::ShadowMap: return "shadow_map";
    case LightStructure::MomentMap: return "moment_map";
    case LightStructure::SummedAreaTable: return "summed_area_table";
    case LightStructure::HierarchicalShadowMap: return "hierarchical_shadow_map";
    case LightStructure::DualMultiScaleShadowMap: return "dual_mssm";
  }
  return "unknown";
}

} // namespace sl
