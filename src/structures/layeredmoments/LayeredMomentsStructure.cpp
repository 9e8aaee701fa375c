#include "structures/layeredmoments/LayeredMomentsStructure.h"

#include "core/Error.h"
#include "frame/FrameResult.h"
#include "gl/GlResources.h"
#include "passes/PassUtilities.h"
#include "structures/layeredmoments/vtkSLLayeredMomentsPass.h"
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
  return settings;
}

namespace
{

const LayeredMomentsData& layeredMomentsData(const FrameResources& frame)
{
  return frame.structureData<LayeredMomentsData>(layeredMomentsStructure().name);
}

std::vector<NamedImage> exportLayeredMoments(const FrameResources& frame, FrameResult&)
{
  const std::vector<ImageF> slices = readFloatTextureLayers(layeredMomentsData(frame).moments, 2);
  std::vector<NamedImage> images;
  for (std::size_t layer = 0; layer < slices.size(); ++layer)
  {
    images.push_back({ format("layer", layer, "_mean"), slices[layer].channels(0, 1), "",
      format("layer ", layer, ": prefiltered E[phi(z)], the depth warped into the layer (Lauritzen & McCool 2008)") });
    images.push_back({ format("layer", layer, "_second_moment"), slices[layer].channels(1, 1), "",
      format("layer ", layer, ": prefiltered E[phi(z)^2]") });
  }
  return images;
}

std::vector<vtkTextureObject*> bindLayeredMoments(vtkShaderProgram* program, const FrameResources& frame)
{
  const LayeredMomentsData& data = layeredMomentsData(frame);
  if (program->IsUniformUsed("layeredLayers"))
  {
    program->SetUniformi("layeredLayers", data.layers);
  }
  setFloatIfUsed(program, "layeredDepthNear", frame.lightView.nearDepth);
  setFloatIfUsed(program, "layeredDepthFar", frame.lightView.farDepth);
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
      { "layers", 4, 1, 16, "", "depth layers: equal, disjoint intervals of the light's depth range (Lauritzen & McCool 2008)", {}, true },
    };
    s.createBuildPasses = [] {
      return std::vector<vtkSmartPointer<vtkSLStagePass>>{ vtkSmartPointer<vtkSLLayeredMomentsPass>::New() };
    };
    s.exportImages = exportLayeredMoments;
    s.gpuBytes = [](const FrameResources& frame) { return textureBytes(layeredMomentsData(frame).moments, 8); };
    s.shaderDefines = [](const FrameResources&) { return ShaderDefines{}; };
    s.bind = bindLayeredMoments;
    return s;
  }();
  return structure;
}

} // namespace sl
