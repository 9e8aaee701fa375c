// The moment map: (z, z^2, exp(c z_n), 1) of the shadow map (RGBA32F), prefiltered by a separable box blur or
// mip-mapped (survey §6; VSM, ESM). Built by vtkSLMomentMapPass (stage moment_map).
#pragma once

#include "structures/LightSpaceStructure.h"

namespace sl
{

const LightSpaceStructure& momentMapStructure();

// The parameters its build reads, typed.
struct MomentMapSettings
{
  double esmExponent = 0.0; // the technique's LightSpaceRequest::momentExponent (esm), else 0 (the third moment unused)
  bool mipmap = false;      // prefilter = mipmap
  int blurTexels = 1;       // prefilter_texels for prefilter = blur; 1 = no blur

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
};

} // namespace sl
