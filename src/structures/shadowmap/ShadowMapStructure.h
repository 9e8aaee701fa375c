// The shadow map: the light view fitted to the visible receivers (focus stage, survey §4.1) and the casters'
// linear depth (R32F) and window depth (D32F) rendered from the light's centre (shadow_map stage). Every other
// light-space structure is built from it. Its results are FrameResources' lightView, shadowMapLinear and
// shadowMapDepth (the root of the light-space stage, read by every shadow-map technique's shader).
#pragma once

#include "structures/LightSpaceStructure.h"

namespace sl
{

const LightSpaceStructure& shadowMapStructure();

// The parameters its build reads, typed.
struct ShadowMapSettings
{
  int resolution = 2048;     // shadow_map_size
  double marginTexels = 1.0; // its filter's width w (kernel_texels, else prefilter_texels): ceil(w / 2) + 1, else 1
  bool secondDepth = false;  // caster_faces = back (Wang & Molnar 1994, survey §5)
};
// Throws InputError when the filter's margin leaves no texel for the receivers (2 x margin >= shadow_map_size).
ShadowMapSettings shadowMapSettings(const ParameterValues& values);

} // namespace sl
