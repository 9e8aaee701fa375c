// Technique `hard`: shadow mapping with one depth comparison per pixel (Williams 1978), with the survey's
// depth biasing (Scherzer et al. 2011, §5): constant + slope-scaled bias, or second-depth shadow maps.
//
// Parameters (see ShadowMapParameters.h): shadow_map_size [texels], caster_faces (front|back),
// bias_constant_texels, bias_slope_texels [texel footprints], bias_max_slope; warp (none|psm|lispsm|tsm), warp_n
// [world] (survey §4.2, lightspace/PerspectiveWarp.h; directional lights); cascades, split_scheme, split_lambda,
// cascade_selection, cascade_blend, cascade_snap (survey §4.3.1, lightspace/Cascades.h; directional lights);
// cube_map (off|auto|on; survey §2, lightspace/CubeFaces.h; point lights).
// Buffers: kernel_texels (1: one texel), texel_ratio (survey Eq. 2, screen pixels per texel),
// depth_bias [world], depth_margin [world] = receiver depth - bias - stored depth (> 0: shadowed).
#pragma once

#include "techniques/ShadowMapReference.h"
#include "frame/TechniqueDescriptor.h"

namespace sl
{

TechniqueDescriptor hardTechnique();

// CPU reference (double precision) of HardVisibility.glsl at pixel (x, y).
// hard's parameters, typed (parsed once, by from()): the shadow map's own are ShadowMapSettings.
struct HardSettings
{
  BiasSettings bias;

  static HardSettings from(const ParameterValues& values);
};

ReferenceSample hardReference(const ShadowMapInputs& inputs, const BiasSettings& bias, int x, int y,
  ProbeRecorder* recorder = nullptr);

} // namespace sl
