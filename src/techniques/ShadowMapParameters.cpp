#include "techniques/ShadowMapParameters.h"

#include "core/Error.h"
#include "lightspace/ShadowMapMath.h"
#include "structures/shadowmap/ShadowMapStructure.h"

#include <utility>

namespace sl
{

std::vector<ParameterSpec> shadowMapParameters()
{
  // The shadow map's own parameters (its structure declares them), then the depth bias the techniques apply.
  std::vector<ParameterSpec> parameters = shadowMapStructure().parameters;
  parameters.insert(parameters.end(), {
    { "bias_constant_texels", 0.5, 0, 64, "texel footprints", "constant depth bias (survey §5)", {}, false },
    { "bias_slope_texels", 1.0, 0, 64, "texel footprints", "slope-scaled depth bias, times tan(angle between normal and light) (survey §5)", {}, false },
    { "bias_max_slope", 10.0, 0, 1000, "", "clamp of tan(angle between normal and light) in the slope bias", {}, false },
  });
  return parameters;
}

std::vector<LightType> shadowMapLights()
{
  return { LightType::Area, LightType::Point, LightType::Spot, LightType::Directional };
}

std::vector<ParameterSpec> shadowMapWarpParameters()
{
  return {
    { "warp", 0, 0, 3, "", "perspective warp of the map (survey §4.2): none, psm (n = z_n), lispsm (n_opt = z_n + sqrt(z_n z_f), over sin gamma) or tsm (80 % rule); directional lights", { "none", "psm", "lispsm", "tsm" }, true },
    { "warp_n", 0, 0, 1e9, "world units", "the warp's free parameter n (survey Fig. 9), its projection centre's distance to the focused body; 0: the rule of `warp`", {}, false },
  };
}

std::vector<ParameterSpec> shadowMapCascadeParameters()
{
  return {
    { "cascades", 1, 1, 8, "maps", "z-partitioning (survey §4.3.1, PSSM/CSM): equal-size maps, one per slice of the visible receivers' eye depth range, each focused on its slice; 1: one map; directional lights", {}, true },
    { "split_scheme", 1, 0, 2, "", "split depths over the visible receivers' eye depths [z_n, z_f]: uniform C_i = z_n + (z_f - z_n) i/m, log C_i = z_n (z_f/z_n)^(i/m), practical = split_lambda log + (1 - split_lambda) uniform (PSSM)", { "uniform", "log", "practical" }, true },
    { "split_lambda", 0.5, 0, 1, "", "practical split's weight of the log split (0: uniform, 1: log)", {}, false },
    { "cascade_selection", 0, 0, 1, "", "which map a pixel reads: depth (the slice of its eye depth) or containment (the finest map that holds it, survey §4.3.1)", { "depth", "containment" }, true },
    { "cascade_blend", 0, 0, 1, "", "band blended into the next cascade: fraction of a slice (depth) or of a map's half-width (containment); 0: hard switch", {}, false },
    { "cascade_snap", 1, 0, 1, "", "texel snapping: each cascade's texel size rounded to 2^(k/4) and its window to whole texels, so shadow edges stay put as the camera moves (unwarped cascades)", { "off", "on" }, true },
  };
}

std::vector<ParameterSpec> shadowMapFvsmParameters()
{
  return {
    { "fvsm", 0, 0, 1, "", "fitted virtual shadow maps (survey §4.3.3): a quadtree of fixed-size tile maps over the focused window, refined where a receiver needs more than one texel per pixel (read-back pre-pass); directional and spot/area lights; not with cascades or a warp", { "off", "on" }, true },
    { "fvsm_tile_size", 256, 16, 4096, "texels", "texels per side of each fvsm tile's map", {}, true },
    { "fvsm_max_level", 5, 0, 8, "", "deepest fvsm quadtree level: at most 2^level x 2^level tiles over the focused window (5: 32 x 32, the survey's Fig. 16)", {}, true },
    { "fvsm_max_tiles", 64, 1, 256, "maps", "the most fvsm tiles (maps) one frame may use; pixels left coarser than they need are flagged (fvsm_unmet)", {}, true },
  };
}

std::vector<ParameterSpec> shadowMapCubeParameters()
{
  return {
    { "cube_map", 1, 0, 2, "", "point lights (survey §2): six 90-degree face maps, each focused on the receivers its face owns and read by the dominant axis of p - light centre; auto: only where one map cannot cover the visible receivers (some more than 80 degrees off its axis), on: always, off: one map (refused there)", { "off", "auto", "on" }, true },
  };
}

namespace
{

TechniqueDescriptor shadowMapDescriptor(
  std::string name, std::string title, std::string paper, std::vector<ParameterSpec> parameters)
{
  TechniqueDescriptor descriptor = describeTechnique(std::move(name), std::move(title), std::move(paper));
  descriptor.parameters = std::move(parameters);
  descriptor.lightStructures = { &shadowMapStructure() };
  descriptor.supportedLights = shadowMapLights();
  return descriptor;
}

} // namespace

TechniqueDescriptor describeShadowMapTechnique(std::string name, std::string title, std::string paper)
{
  return shadowMapDescriptor(std::move(name), std::move(title), std::move(paper), shadowMapParameters());
}

TechniqueDescriptor describeShadowMapTechnique(
  std::string name, std::string title, std::string paper, int largestAutomaticMapSize)
{
  TechniqueDescriptor descriptor = describeShadowMapTechnique(std::move(name), std::move(title), std::move(paper));
  descriptor.largestAutomaticMapSize = largestAutomaticMapSize;
  return descriptor;
}

BufferSpec texelRatioBuffer()
{
  return onShadowTestedPixels({ "texel_ratio", "pixels/texel",
    "aliasing error m (survey Eq. 2): screen pixels spanned by one shadow-map texel along its most stretched "
    "direction; > 1 means undersampling" });
}

BufferSpec depthBiasBuffer()
{
  return onShadowTestedPixels({ "depth_bias", "world units", "depth bias applied at the pixel (constant + slope-scaled)" });
}

BiasSettings biasSettings(const ParameterValues& values)
{
  BiasSettings bias;
  bias.constantTexels = values.get("bias_constant_texels");
  bias.slopeTexels = values.get("bias_slope_texels");
  bias.maxSlope = values.get("bias_max_slope");
  return bias;
}

BiasSettings defaultBiasSettings()
{
  BiasSettings bias;
  for (const ParameterSpec& spec : shadowMapParameters())
  {
    if (spec.name == "bias_constant_texels")
    {
      bias.constantTexels = spec.defaultValue;
    }
    else if (spec.name == "bias_slope_texels")
    {
      bias.slopeTexels = spec.defaultValue;
    }
    else if (spec.name == "bias_max_slope")
    {
      bias.maxSlope = spec.defaultValue;
    }
  }
  return bias;
}

} // namespace sl
