// The moment map: (z, z^2, exp(c z_n), 1) of the shadow map (RGBA32F), prefiltered by a separable box blur or
// mip-mapped (survey §6; VSM, ESM). Built by vtkSLMomentMapPass (stage moment_map).
#pragma once

#include "structures/LightSpaceStructure.h"
#include "structures/moments/ReceiverTiles.h"

#include <optional>

namespace sl
{

const LightSpaceStructure& momentMapStructure();

// The parameters its build reads, typed.
struct MomentMapSettings
{
  double esmExponent = 0.0; // the technique's LightSpaceRequest::momentExponent (esm), else 0 (the third moment unused)
  bool mipmap = false;      // prefilter = mipmap
  int blurTexels = 1;       // prefilter_texels for prefilter = blur; 1 = no blur
  // prefilter_region = receivers: built and blurred only over the tiles the receivers read (ReceiverTiles.h); never
  // with mipmap (the mip chain averages every texel).
  bool receiversOnly = false;

  static MomentMapSettings from(const ParameterValues& values, const LightSpaceRequest& request = {});
};
// The settings of a frame of `technique` with `values`: the exponent from the technique's LightSpaceRequest.
MomentMapSettings momentMapSettings(const TechniqueDescriptor& technique, const ParameterValues& values);
MomentMapSettings momentMapSettings(const FrameResources& frame);

// What the build leaves in the frame (FrameResources::structureData<MomentMapData>("moment_map")).
struct MomentMapData : LightSpaceData
{
  vtkSmartPointer<vtkTextureObject> moments; // RGBA32F; with a mip chain when mipmapped
  bool mipmapped = false;
  // prefilter_region = receivers: where each draw ran; the texels outside region->read are undefined. None: every
  // texel built.
  std::optional<ReceiverPrefilterPlan> region;
};

// For the exports of the prefiltered maps (moment map, power moments, Fourier basis, layered moments): 1 on the texels
// `region` built, 0 elsewhere (all 1 without a region); builtChannel is channel `channel` of `image` with every unbuilt
// texel 0 (not data); prefilterBuiltArray is the mask as the `<name>` array of `map`; the region's tile counts go to
// stats.json as <prefix>_tiles, _receiver_tiles, _horizontal_tiles, _source_tiles, _read_texels, _sparse_blur.
ImageF prefilterBuiltMask(const std::optional<ReceiverPrefilterPlan>& region, int mapSize);
ImageF builtChannel(const ImageF& image, int channel, const ImageF& builtMask);
NamedImage prefilterBuiltArray(const std::string& name, const ImageF& builtMask, const std::string& map);
void addPrefilterRegionStatistics(const std::optional<ReceiverPrefilterPlan>& region, const std::string& prefix,
  FrameResult& result);

} // namespace sl
