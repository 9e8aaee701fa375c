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

namespace sl
{

const LightSpaceStructure& shadowMapStructure();

// The parameters its build reads, typed.
struct ShadowMapSettings
{
  int resolution = 2048;     // shadow_map_size
  double marginTexels = 1.0; // the technique's filter width w (LightSpaceRequest): ceil(w / 2) + 1, else 1
  bool secondDepth = false;  // caster_faces = back (Wang & Molnar 1994, survey §5)
  WarpSettings warp;         // warp, warp_n (survey §4.2), read only from techniques that list them
  CascadeSettings cascades;  // cascades, split_scheme, split_lambda, cascade_selection, cascade_blend, cascade_snap
                             // (survey §4.3.1), read only from techniques that list them
  FvsmSettings fvsm;         // fvsm, fvsm_tile_size, fvsm_max_level, fvsm_max_tiles (survey §4.3.3), likewise

  // Throws InputError when the filter's margin leaves no texel for the receivers (2 x margin >= shadow_map_size).
  static ShadowMapSettings from(const ParameterValues& values, const LightSpaceRequest& request = {});
};
// The settings of a frame of `technique` with `values`: its filter from the technique's LightSpaceRequest.
ShadowMapSettings shadowMapSettings(const TechniqueDescriptor& technique, const ParameterValues& values);
ShadowMapSettings shadowMapSettings(const FrameResources& frame);

// Views that partition the pixels (survey §4.3, PartitionViews.h): the categorical buffer the structure adds to a
// partitioned frame, per kind: `cascade` (cascades > 1, survey §4.3.1), `fvsm_tile` (fvsm, survey §4.3.3); its labels
// are partitionViewLabel's.
const BufferSpec& partitionBufferSpec(PartitionKind kind);
// fvsm (survey §4.3.3): fvsm_level, fvsm_required_resolution and fvsm_unmet beside `fvsm_tile`.
const std::vector<BufferSpec>& fvsmBufferSpecs();

} // namespace sl
