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
  settings.receiversOnly =
    !settings.mipmap && values.has("prefilter_region") && values.choice("prefilter_region") == "receivers";
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

ImageF prefilterBuiltMask(const std::optional<ReceiverPrefilterPlan>& region, int mapSize)
{
  return region ? region->builtMask() : ImageF(mapSize, mapSize, 1, 1.0f);
}

ImageF builtChannel(const ImageF& image, int channel, const ImageF& builtMask)
{
  ImageF values = image.channels(channel, 1);
  SL_CHECK(values.width == builtMask.width && values.height == builtMask.height);
  for (std::size_t i = 0; i < values.data.size(); ++i)
  {
    values.data[i] = builtMask.data[i] != 0.0f ? values.data[i] : 0.0f;
  }
  return values;
}

NamedImage prefilterBuiltArray(const std::string& name, const ImageF& builtMask, const std::string& map)
{
  return { name, builtMask, "",
    "1 where " + map + " was built (prefilter_region = receivers: the tiles the receivers' lookups read, or those "
    "texels alone when the blur was sparse), 0 where not (its arrays hold 0 there, not data)" };
}

void addPrefilterRegionStatistics(const std::optional<ReceiverPrefilterPlan>& region, const std::string& prefix,
  FrameResult& result)
{
  if (!region)
  {
    return;
  }
  const ReceiverTiles& read = region->read;
  result.techniqueStatistics[prefix + "_tiles"] = static_cast<double>(read.tilesPerSide()) * read.tilesPerSide();
  result.techniqueStatistics[prefix + "_receiver_tiles"] = read.markedCount();
  result.techniqueStatistics[prefix + "_horizontal_tiles"] = region->horizontalTiles;
  result.techniqueStatistics[prefix + "_source_tiles"] = region->sourceTiles;
  // The texels listed as read (repeats included; 0 when the list overflowed), and whether the blur ran on them alone.
  result.techniqueStatistics[prefix + "_read_texels"] = static_cast<double>(region->readTexels.size());
  result.techniqueStatistics[prefix + "_sparse_blur"] = region->blur.sparse ? 1 : 0;
}

namespace
{

const MomentMapData& momentData(const FrameResources& frame)
{
  return frame.structureData<MomentMapData>(momentMapStructure().name);
}

std::vector<NamedImage> exportMoments(const FrameResources& frame, FrameResult& result)
{
  const MomentMapData& data = momentData(frame);
  const ImageF moments = readFloatTexture(data.moments, 4);
  const ImageF built = prefilterBuiltMask(data.region, moments.width);
  const char* names[3] = { "moment_mean", "moment_second", "moment_exponential" };
  const char* docs[3] = { "prefiltered E[z] (linear depth)", "prefiltered E[z^2]", "prefiltered E[exp(c z_n)] (esm)" };
  std::vector<NamedImage> images;
  for (int c = 0; c < 3; ++c)
  {
    images.push_back({ names[c], builtChannel(moments, c, built), "", docs[c] });
  }
  images.push_back(prefilterBuiltArray("moment_built", built, "the moment map"));
  addPrefilterRegionStatistics(data.region, "moment_map", result);
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
      { "prefilter_region", 0, 0, 1, "", "where prefilter = blur builds and blurs the moment map (vsm, esm), msm's power moments, convsm's Fourier basis and lvsm's layered moments: receivers (only where the frame's receivers read, the rest marked not built in moment_built, power_moment_built, fourier_built, layered_moment_built) or whole_map; prefilter = mipmap builds the whole map", { "receivers", "whole_map" }, true },
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
