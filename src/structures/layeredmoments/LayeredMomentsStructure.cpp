#include "structures/layeredmoments/LayeredMomentsStructure.h"

#include "core/Error.h"
#include "frame/FrameResult.h"
#include "gl/GlResources.h"
#include "passes/PassUtilities.h"
#include "structures/layeredmoments/vtkSLLayeredMomentsPass.h"
#include "structures/moments/MomentMapStructure.h"
#include "structures/shadowmap/ShadowMapStructure.h"

#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>

namespace sl
{

LayeredMomentsSettings LayeredMomentsSettings::from(const ParameterValues& values)
{
  LayeredMomentsSettings settings;
  settings.layers = values.getInt("layers");
  settings.blurTexels = values.getInt("prefilter_texels");
  settings.placement =
    choiceOf<LayerPlacement>(values, "layer_placement", { { "uniform", LayerPlacement::Uniform }, { "gaps", LayerPlacement::Gaps } });
  settings.receiversOnly = values.has("prefilter_region") && values.choice("prefilter_region") == "receivers";
  return settings;
}

bool layeredSparseBlurFits(int blurTexels, int layers)
{
  const long long width = blurTexels;
  return width * width * (layers + 1) + width * (2 * layers + 1) + 2 * layers < 65535;
}

std::vector<double> layeredEndsOf(const std::map<std::string, double>& statistics)
{
  std::vector<double> ends;
  for (auto found = statistics.find(format("layer_end_", 0)); found != statistics.end();
       found = statistics.find(format("layer_end_", ends.size())))
  {
    ends.push_back(found->second);
  }
  return ends;
}

void layeredEndStatistics(const std::vector<double>& ends, std::map<std::string, double>& statistics)
{
  for (std::size_t i = 0; i < ends.size(); ++i)
  {
    statistics[format("layer_end_", i)] = ends[i];
  }
}

namespace
{

const LayeredMomentsData& layeredMomentsData(const FrameResources& frame)
{
  return frame.structureData<LayeredMomentsData>(layeredMomentsStructure().name);
}

std::vector<NamedImage> exportLayeredMoments(const FrameResources& frame, FrameResult& result)
{
  const LayeredMomentsData& data = layeredMomentsData(frame);
  const std::vector<ImageF> slices = readFloatTextureLayers(data.moments, 2);
  const int mapSize = frame.lightView.resolution;
  const ImageF built = prefilterBuiltMask(data.region, mapSize);
  std::vector<NamedImage> images;
  for (std::size_t layer = 0; layer < slices.size(); ++layer)
  {
    // The texels outside the receivers' tiles hold whatever an earlier frame left there: 0, not data.
    images.push_back({ format("layer", layer, "_mean"), builtChannel(slices[layer], 0, built), "",
      format("layer ", layer, ": prefiltered E[phi(z)], the depth warped into the layer (Lauritzen & McCool 2008)") });
    images.push_back({ format("layer", layer, "_second_moment"), builtChannel(slices[layer], 1, built), "",
      format("layer ", layer, ": prefiltered E[phi(z)^2]") });
  }
  images.push_back(prefilterBuiltArray("layered_moment_built", built, "every layer of the layered moment map"));
  addPrefilterRegionStatistics(data.region, "layered_moments", result);
  return images;
}

std::vector<vtkTextureObject*> bindLayeredMoments(vtkShaderProgram* program, const FrameResources& frame)
{
  const LayeredMomentsData& data = layeredMomentsData(frame);
  if (program->IsUniformUsed("layeredLayers"))
  {
    program->SetUniformi("layeredLayers", data.layers);
  }
  if (program->IsUniformUsed("layeredEnds"))
  {
    const std::vector<float> ends(data.ends.begin(), data.ends.end());
    program->SetUniform1fv("layeredEnds", static_cast<int>(ends.size()), ends.data());
  }
  return { bindTexture(program, "layeredMoments", data.moments) };
}

} // namespace

const LightSpaceStructure& layeredMomentsStructure()
{
  static const LightSpaceStructure structure = [] {
    LightSpaceStructure s;
    s.name = "layered_moments";
    s.doc = "(phi_i(z), phi_i(z)^2) of the shadow map per depth layer i, box-blurred (Lauritzen & McCool 2008)";
    s.builtFrom = { &shadowMapStructure() };
    s.parameters = {
      { "layers", 4, 1, 16, "", "depth layers: disjoint intervals of the light's depth range (Lauritzen & McCool 2008)", {}, true },
      { "layer_placement", 1, 0, 1, "", "where the layers' boundaries lie: uniform, equal intervals; gaps (ShadowLab's, not LM08's placement), in the widest empty runs of the shadow map's depth histogram (256 bins over [near, far], counted on the GPU), so that surfaces separated in depth fall into different layers", { "uniform", "gaps" }, true },
    };
    s.sharedParameters = { "prefilter_texels", "prefilter_region" };
    s.createBuildPasses = [] {
      return std::vector<vtkSmartPointer<vtkSLStagePass>>{ vtkSmartPointer<vtkSLLayeredMomentsPass>::New() };
    };
    s.exportImages = exportLayeredMoments;
    s.gpuBytes = [](const FrameResources& frame) { return textureBytes(layeredMomentsData(frame).moments, 8); };
    s.shaderDefines = [](const FrameResources&) { return ShaderDefines{}; };
    s.bind = bindLayeredMoments;
    s.largestMapSize = [](const ParameterValues&, int max3dTextureSize) { return max3dTextureSize; };
    return s;
  }();
  return structure;
}

} // namespace sl
