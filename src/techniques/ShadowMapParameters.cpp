#include "techniques/ShadowMapParameters.h"

#include "lightspace/ShadowMapMath.h"

namespace sl
{

std::vector<ParameterSpec> shadowMapParameters()
{
  return {
    { "shadow_map_size", 2048, 16, 8192, "texels", "texels per side of the shadow map (focused on visible receivers, survey §4.1)", {}, true },
    { "caster_faces", 0, 0, 1, "", "front = first-depth map; back = second-depth map (Wang & Molnar 1994, survey §5; needs closed casters)", { "front", "back" }, true },
    { "bias_constant_texels", 0.5, 0, 64, "texel footprints", "constant depth bias (survey §5)", {}, false },
    { "bias_slope_texels", 1.0, 0, 64, "texel footprints", "slope-scaled depth bias, times tan(angle between normal and light) (survey §5)", {}, false },
    { "bias_max_slope", 10.0, 0, 1000, "", "clamp of tan(angle between normal and light) in the slope bias", {}, false },
  };
}

std::vector<LightType> shadowMapLights()
{
  return { LightType::Area, LightType::Point, LightType::Spot, LightType::Directional };
}

BiasSettings biasSettings(const ParameterValues& values)
{
  BiasSettings bias;
  bias.constantTexels = values.get("bias_constant_texels");
  bias.slopeTexels = values.get("bias_slope_texels");
  bias.maxSlope = values.get("bias_max_slope");
  return bias;
}

} // namespace sl
