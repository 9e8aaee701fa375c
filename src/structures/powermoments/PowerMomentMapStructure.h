// The power-moment map of moment shadow mapping (Peters & Klein 2015): per shadow-map texel the four power
// moments b = (z, z^2, z^3, z^4) of the normalised depth z = (d - near) / (far - near) in [0, 1] (RGBA32F),
// prefiltered like the moment map of vsm and esm (separable box blur or mip-map). Built by
// vtkSLPowerMomentMapPass (stage power_moment_map).
#pragma once

#include "structures/LightSpaceStructure.h"
#include "structures/moments/ReceiverTiles.h"

#include <optional>

namespace sl
{

const LightSpaceStructure& powerMomentMapStructure();

// The parameters its build reads, typed.
struct PowerMomentMapSettings
{
  bool mipmap = false; // prefilter = mipmap
  int blurTexels = 1;  // prefilter_texels for prefilter = blur; 1 = no blur
  bool receiversOnly = false; // prefilter_region = receivers with prefilter = blur

  // The depth in the moments' [0, 1] of a linear depth (clamped to the light's range), as the build maps it.
  static double normalisedDepth(double depth, double nearDepth, double farDepth);

  static PowerMomentMapSettings from(const ParameterValues& values);
};

// What the build leaves in the frame (FrameResources::structureData<PowerMomentMapData>("power_moment_map")).
struct PowerMomentMapData : LightSpaceData
{
  vtkSmartPointer<vtkTextureObject> moments; // RGBA32F (z, z^2, z^3, z^4); with a mip chain when mipmapped
  bool mipmapped = false;
  // prefilter_region = receivers: the moment map's plan; the texels it did not build are not data. None: all built.
  std::optional<ReceiverPrefilterPlan> region;
};

} // namespace sl
