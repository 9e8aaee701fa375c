#include "structures/powermoments/PowerMomentMapStructure.h"

#include "core/Error.h"
#include "frame/FrameResult.h"
#include "gl/GlResources.h"
#include "passes/PassUtilities.h"
#include "structures/moments/MomentMapStructure.h"
#include "structures/powermoments/vtkSLPowerMomentMapPass.h"
#include "structures/shadowmap/ShadowMapStructure.h"

#include <vtkTextureObject.h>

#include <algorithm>

namespace sl
{

PowerMomentMapSettings PowerMomentMapSettings::from(const ParameterValues& values)
{
  PowerMomentMapSettings settings;
  // The prefilter is the moment map's, read from its parameters (declared once, by momentMapStructure(); a
  // technique listing this structure declares them too).
  SL_CHECK_MSG(values.has("prefilter") && values.has("prefilter_texels"),
    "a technique listing power_moment_map must declare the moment map's prefilter parameters");
  settings.mipmap = values.choice("prefilter") == "mipmap";
  settings.blurTexels = settings.mipmap ? 1 : values.getInt("prefilter_texels");
  settings.receiversOnly =
    !settings.mipmap && values.has("prefilter_region") && values.choice("prefilter_region") == "receivers";
  return settings;
}

double PowerMomentMapSettings::normalisedDepth(double depth, double nearDepth, double farDepth)
{
  return std::clamp((depth - nearDepth) / (farDepth - nearDepth), 0.0, 1.0);
}

namespace
{

const PowerMomentMapData& powerMomentData(const FrameResources& frame)
{
  return frame.structureData<PowerMomentMapData>(powerMomentMapStructure().name);
}

std::vector<NamedImage> exportPowerMoments(const FrameResources& frame, FrameResult& result)
{
  const PowerMomentMapData& data = powerMomentData(frame);
  const ImageF moments = readFloatTexture(data.moments, 4);
  const ImageF built = prefilterBuiltMask(data.region, moments.width);
  const char* names[4] = { "power_moment_1", "power_moment_2", "power_moment_3", "power_moment_4" };
  const char* docs[4] = { "prefiltered E[z] (z = (d - near) / (far - near) in [0, 1])", "prefiltered E[z^2]",
    "prefiltered E[z^3]", "prefiltered E[z^4]" };
  std::vector<NamedImage> images;
  for (int c = 0; c < 4; ++c)
  {
    images.push_back({ names[c], builtChannel(moments, c, built), "", docs[c] });
  }
  images.push_back(prefilterBuiltArray("power_moment_built", built, "the power-moment map"));
  addPrefilterRegionStatistics(data.region, "power_moment_map", result);
  return images;
}

} // namespace

const LightSpaceStructure& powerMomentMapStructure()
{
  static const LightSpaceStructure structure = [] {
    LightSpaceStructure s;
    s.name = "power_moment_map";
    s.doc = "(z, z^2, z^3, z^4) of the normalised shadow-map depth, box-blurred or mip-mapped (Peters & Klein 2015)";
    s.builtFrom = { &shadowMapStructure() };
    s.sharedParameters = { "prefilter", "prefilter_texels", "prefilter_region" };
    s.createBuildPasses = [] {
      return std::vector<vtkSmartPointer<vtkSLStagePass>>{ vtkSmartPointer<vtkSLPowerMomentMapPass>::New() };
    };
    s.exportImages = exportPowerMoments;
    s.gpuBytes = [](const FrameResources& frame) {
      const PowerMomentMapData& data = powerMomentData(frame);
      return textureBytes(data.moments, 16, data.mipmapped);
    };
    s.shaderDefines = [](const FrameResources&) { return ShaderDefines{}; };
    s.bind = [](vtkShaderProgram* program, const FrameResources& frame) {
      return std::vector<vtkTextureObject*>{ bindTexture(program, "powerMomentMap", powerMomentData(frame).moments) };
    };
    return s;
  }();
  return structure;
}

} // namespace sl
