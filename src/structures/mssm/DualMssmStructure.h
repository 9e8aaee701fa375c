// The multi-scale shadow map on the dual grid of 2 x 2 sample blocks (Yang et al. 2009 §4.2; yfgl09): RG32F
// (min, max) of the 2^k x 2^k dual cells starting at each cell, levels 0..L in the layers of an (N + 1)^2 x (L + 1)
// texture (lightspace/HierarchicalShadowMap.h). Built by the HSM's pass (structures/hsm/vtkSLHsmPass) in its
// dual-grid layout; stage hierarchical_shadow_map. No parameters.
#pragma once

#include "structures/LightSpaceStructure.h"

namespace sl
{

const LightSpaceStructure& dualMssmStructure();

} // namespace sl
