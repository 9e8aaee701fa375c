// The shadow map: the light view fitted to the visible receivers (focus stage, survey §4.1) and the casters'
// linear depth (R32F) and window depth (D32F) rendered from the light's centre (shadow_map stage). Every other
// light-space structure is built from it. Its results are FrameResources' lightView, shadowMapLinear and
// shadowMapDepth (the root of the light-space stage, read by every shadow-map technique's shader).
#pragma once

#include "lightspace/Cascades.h"
#include "lightspace/FittedVirtualShadowMap.h"
#include "lightspace/PartitionViews.h"
#include "lightspace/PerspectiveWarp.h"
#include "structures/LightSpaceStructure.h"

#include <optional>

class vtkTextureObject;

namespace sl
{

const LightSpaceStructure& shadowMapStructure();

// The depth the map stores for the comparison (survey §5, "depth biasing"): the nearest caster's (first), or one
// combined from the nearest and the second-nearest surface at the texel, the second found by depth peeling (a second
// pass keeping the nearest depth strictly behind the first layer's at the same texel; DepthLayers.h has the rules).
enum class ShadowMapDepthLayer
{
  First,    // the nearest caster (Williams 1978); with caster_faces = back, the nearest back face (Wang & Molnar 1994)
  Midpoint, // (z1 + z2) / 2 (Woo 1992)
  Dual,     // the midpoint with the offset past z1 limited to dual_max_offset_texels (Weiskopf & Ertl 2003)
  PolygonId, // the nearest triangle's id besides z1 (Hourcade & Nicolas 1985): techniques that compare ids (hard)
};

const char* depthLayerName(ShadowMapDepthLayer layer);

// What a layered build (depth_layer = midpoint or dual) leaves besides the combined map, for the export: the two
// peeled layers' linear depth (R32F), one pair per view for views that partition the pixels.
struct ShadowMapLayersData : LightSpaceData
{
  std::vector<vtkSmartPointer<vtkTextureObject>> first;
  std::vector<vtkSmartPointer<vtkTextureObject>> second;
  // depth_layer = polygon_id: the nearest triangle's id per texel (R32UI) and the id each camera pixel sees (R32UI).
  vtkSmartPointer<vtkTextureObject> polygonIds;
  vtkSmartPointer<vtkTextureObject> receiverPolygonIds;
};
// Whether `technique`'s shader compares polygon ids (depth_layer = polygon_id; the others refuse it in one line).
bool comparesPolygonIds(const TechniqueDescriptor& technique);
// Whether `technique` flags the pixels a midpoint or dual map lights only by its layer gap (an approximation named
// "depth layer gap", ApproximationRules.h's markDepthLayerGap); the others refuse those depth layers in one line.
bool declaresDepthLayerGap(const TechniqueDescriptor& technique);

// The parameters its build reads, typed.
struct ShadowMapSettings
{
  int resolution = 0;        // shadow_map_size; 0 while automaticResolution (the focus stage chooses)
  bool automaticResolution = false; // shadow_map_size = auto (AutomaticMapSize.h)
  double automaticTexelsPerPixel = 2.0; // auto_texels_per_pixel: the density auto serves under an area light
  double automaticTexelsPerPixelHard = 4.0; // auto_texels_per_pixel_hard: under a point, spot or directional light
  double marginTexels = 1.0; // the technique's filter width w (LightSpaceRequest): ceil(w / 2) + 1, else 1
  bool secondDepth = false;  // caster_faces = back (Wang & Molnar 1994, survey §5)
  ShadowMapDepthLayer depthLayer = ShadowMapDepthLayer::First; // depth_layer (survey §5)
  double dualMaxOffsetTexels = 4.0;          // dual_max_offset_texels (depth_layer = dual)
  WarpSettings warp;         // warp, warp_n (survey §4.2), read only from techniques that list them
  CascadeSettings cascades;  // cascades, split_scheme, split_lambda, cascade_selection, cascade_blend, cascade_snap
                             // (survey §4.3.1), read only from techniques that list them
  FvsmSettings fvsm;         // fvsm, fvsm_tile_size, fvsm_max_level, fvsm_max_tiles (survey §4.3.3), likewise
  // cube_map (survey §2, CubeFaces.h); none for a technique that does not list it (no cube maps)
  std::optional<CubeMapMode> cubeMap;

  // Whether a frame with `light` may run as views that partition the pixels (the renderer's stage pipeline, before
  // GL): cascades > 1, fvsm, or a point light whose technique may use cube faces.
  bool mayPartition(const Light& light) const;
  // The density shadow_map_size = auto serves for `light` (the scene's light, not a sub-light sample): a light
  // without area casts hard edges everywhere, which no penumbra softens (the shadow map's page, "Four under a light without area").
  double automaticTexelsPerPixelFor(const Light& light) const;

  // Throws InputError when the filter's margin leaves no texel for the receivers (2 x margin >= shadow_map_size).
  static ShadowMapSettings from(const ParameterValues& values, const LightSpaceRequest& request = {});
};
// The settings of a frame of `technique` with `values`: its filter from the technique's LightSpaceRequest.
ShadowMapSettings shadowMapSettings(const TechniqueDescriptor& technique, const ParameterValues& values);
ShadowMapSettings shadowMapSettings(const FrameResources& frame);

// A point light one map cannot cover (fitLightView's refusal): the message names the way out, the techniques with cube
// shadow maps (FrameResources::cubeMapTechniques) or, for one of them, its setting cube_map=off.
void adviseBeyondOneMap(const FrameResources& frame, FocusSettings& focus);

// Views that partition the pixels (survey §4.3, PartitionViews.h): the categorical buffer the structure adds to a
// partitioned frame, per kind: `cascade` (cascades > 1, survey §4.3.1; labels partitionViewLabel's), `fvsm_tile`
// (fvsm, survey §4.3.3; likewise) or `cube_face` (survey §2; labels cubeFaceName's, -1 where the pixel is uncovered or
// its face has no map).
const BufferSpec& partitionBufferSpec(PartitionKind kind);
// fvsm (survey §4.3.3): fvsm_level, fvsm_required_resolution and fvsm_unmet beside `fvsm_tile`.
const std::vector<BufferSpec>& fvsmBufferSpecs();

} // namespace sl
