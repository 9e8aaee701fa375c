// Parameters every shadow-map technique shares (declared once, listed by each descriptor).
//   shadow_map_size       texels per side of the (square) shadow map
//   caster_faces          front: first-depth shadow map; back: second-depth (Wang & Molnar 1994, survey §5)
//   bias_constant_texels  constant depth bias, in shadow-map texel footprints at the receiver (survey §5)
//   bias_slope_texels     slope-scaled bias: texel footprints per unit tan(angle to light) (survey §5)
//   bias_max_slope        clamp on tan(angle to light), so grazing receivers do not push the bias to infinity
// Units are texel footprints (world size of one texel at the receiver's depth), so one setting works at
// any scene scale and map resolution; see lightspace/ShadowMapMath.h.
#pragma once

#include "frame/TechniqueDescriptor.h"

#include <string>
#include <vector>

namespace sl
{

std::vector<ParameterSpec> shadowMapParameters();
std::vector<LightType> shadowMapLights(); // area (from its centre), point, spot, directional
// The perspective warp of the shadow map (survey §4.2), for the techniques whose lookups stay valid under it (a
// texel's footprint from the warped matrix, linear depth unchanged): hard and pcf list them with addParameters.
//   warp    none | psm | lispsm | tsm (lightspace/PerspectiveWarp.h)
//   warp_n  the warp's n in world units; 0: the rule of `warp` (LiSPSM: n_opt / sin γ)
std::vector<ParameterSpec> shadowMapWarpParameters();
// Z-partitioning of the shadow map (survey §4.3.1, lightspace/Cascades.h), for the same techniques (their lookups are
// per pixel against one map, which the cascade loop picks per pixel): hard and pcf list them with addParameters.
//   cascades           1-8 maps (1: one map, as without the parameters)
//   split_scheme       uniform | log | practical, with split_lambda (practical's weight of log)
//   cascade_selection  depth | containment
//   cascade_blend      the band blended into the next cascade (fraction of a slice; 0: hard switch)
//   cascade_snap       off | on: whole-texel windows (stable under camera motion)
std::vector<ParameterSpec> shadowMapCascadeParameters();
// Adaptive partitioning of the shadow map (survey §4.3.3, fitted virtual shadow maps, lightspace/FittedVirtualShadowMap.h),
// for the same techniques (per-pixel lookups against the one tile map the pixel's quadtree leaf owns):
//   fvsm            off | on (not with cascades > 1 nor a warp)
//   fvsm_tile_size  texels per side of each tile's map
//   fvsm_max_level  deepest quadtree level: 2^level tiles per side of the focused window (5: 32 x 32, Fig. 16)
//   fvsm_max_tiles  the most tiles (maps) a frame may use
std::vector<ParameterSpec> shadowMapFvsmParameters();
// Cube shadow maps for point lights (survey §2, lightspace/CubeFaces.h), for the same techniques (one map per pixel,
// picked by the face loop): hard and pcf list it.
//   cube_map  off | auto | on: six face maps, where one map cannot cover the receivers (auto) or always (on)
std::vector<ParameterSpec> shadowMapCubeParameters();

// A shadow-map technique's descriptor before its own parameters and buffers: its identity, shadowMapParameters
// (shadow_map_size = auto by default), the shadow-map structure and shadowMapLights.
TechniqueDescriptor describeShadowMapTechnique(std::string name, std::string title, std::string paper);
// The same with shadow_map_size = auto at most `largestAutomaticMapSize` (TechniqueDescriptor).
TechniqueDescriptor describeShadowMapTechnique(
  std::string name, std::string title, std::string paper, int largestAutomaticMapSize);

// Buffers every technique that compares against one shadow map can publish, declared once.
BufferSpec texelRatioBuffer(); // survey Eq. 2's aliasing error m
BufferSpec depthBiasBuffer();  // the bias applied at the pixel (survey §5)

struct BiasSettings;
BiasSettings biasSettings(const ParameterValues& values);
// The bias at the shadow-map parameters' defaults: what `pcf` applies unless told otherwise. The moment techniques'
// light_leak compares its PCF with it, whatever bias the technique itself uses (vsm's is 0).
BiasSettings defaultBiasSettings();

} // namespace sl
