#include "structures/moments/MomentMapStructure.h"

#include "core/Error.h"
#include "frame/FrameResult.h"
#include "gl/GlResources.h"
#include "structures/moments/vtkSLMomentMapPass.h"
#include "structures/shadowmap/ShadowMapStructure.h"
#include "passes/PassUtilities.h"

#include <vtkTextureObject.h>

namespace sl
{

MomentMapSettings MomentMapSettings::from(const ParameterValues& values, const LightSpaceRequest& request)
{
  MomentMapSettings settings;
  settings.esmExponent = request.momentExponent;
  settings.mipmap = values.has("prefilter") && values.choice("prefilter") == "mipmap";
  settings.blurTexels = values.has("prefilter_texels") && !settings.mipmap ? values.getInt("prefilter_texels") : 1;
  return settings;
}

MomentMapSettings momentMapSettings(const TechniqueDescriptor& technique, const ParameterValues& values)
{
  return MomentMapSettings::from(values, technique.lightSpaceRequestFor(values));
}

MomentMapSettings momentMapSettings(const FrameResources& frame)
{
  SL_CHECK(frame.technique != nullptr);
  return momentMapSettings(*frame.technique, frame.parameters);
}

namespace
{

const MomentMapData& momentData(const FrameResources& frame)
{
  return frame.structureData<MomentMapData>(momentMapStructure().name);
}

std::vector<NamedImage> exportMoments(const FrameResources& frame, FrameResult&)
{
  const ImageF moments = readFloatTexture(momentData(frame).moments, 4);
  const char* names[3] = { "moment_mean", "moment_second", "moment_exponential" };
  const char* docs[3] = { "prefiltered E[z] (linear depth)", "prefiltered E[z^2]", "prefiltered E[exp(c z_n)] (esm)" };
  std::vector<NamedImage> images;
  for (int c = 0; c < 3; ++c)
  {
    images.push_back({ names[c], moments.channels(c, 1), "", docs[c] });
  }
  return images;
}

} // namespace

const LightSpaceStructure& momentMapStructure()
{
  static const LightSpaceStructure structure = [] {
    LightSpaceStructure s;
    s.name = "moment_map";
    s.doc = "(z, z^2, exp(c z_n)) of the shadow map, box-blurred or mip-mapped (survey §6)";
    s.builtFrom = { &shadowMapStructure() };
    s.parameters = {
      { "prefilter", 0, 0, 1, "", "blur: separable box blur of the moments; mipmap: trilinear mip-map lookup at log2(width)", { "blur", "mipmap" }, true },
      { "prefilter_texels", 5, 1, 63, "texels", "width of the box the moments are averaged over (odd widths are centred)", {}, true },
    };
    s.createBuildPasses = [] {
      return std::vector<vtkSmartPointer<vtkSLStagePass>>{ vtkSmartPointer<vtkSLMomentMapPass>::New() };
    };
    s.exportImages = exportMoments;
    s.gpuBytes = [](const FrameResources& frame) {
      const MomentMapData& data = momentData(frame);
      return textureBytes(data.moments, 16, data.mipmapped);
    };
    s.shaderDefines = [](const FrameResources&) { return ShaderDefines{}; };
    s.bind = [](vtkShaderProgram* program, const FrameResources& frame) {
      return std::vector<vtkTextureObject*>{ bindTexture(program, "momentMap", momentData(frame).moments) };
    };
    return s;
  }();
  return structure;
}

} // namespace sl
