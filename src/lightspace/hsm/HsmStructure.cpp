#include "lightspace/hsm/HsmStructure.h"

#include "gl/GlResources.h"
#include "lightspace/hsm/vtkSLHsmPass.h"
#include "lightspace/shadowmap/ShadowMapStructure.h"
#include "passes/PassUtilities.h"

#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>

namespace sl
{

HierarchicalShadowMapSettings hierarchicalShadowMapSettings(const ParameterValues& values)
{
  HierarchicalShadowMapSettings settings;
  settings.layout = values.choice("hsm") == "nbuffers" ? HsmLayout::NBuffers : HsmLayout::MipMap;
  return settings;
}

std::vector<NamedImage> exportMinMaxDepth(const MinMaxDepthData& data, int mapSize)
{
  // Mip-map: the atlas as stored (levels 1..L, HierarchicalShadowMap.h); N-buffers: one pair per level;
  // dual-grid MSSM: one pair per level, point (i, j) holding cell (i, j) (texel (i + 1, j + 1)).
  std::vector<NamedImage> images;
  const std::vector<ImageF> layers = readFloatTextureLayers(data.texture, 2);
  for (std::size_t layer = 0; layer < layers.size(); ++layer)
  {
    const std::string level = std::to_string(layer + 1);
    switch (data.layout)
    {
      case HsmLayout::MipMap:
      {
        const std::string what = "of each node, mip-map levels 1..L packed in an atlas (level 1 at the origin, the others stacked to its right)";
        images.push_back({ "hsm_min", layers[layer].channels(0, 1), "world units", "minimum depth " + what });
        images.push_back({ "hsm_max", layers[layer].channels(1, 1), "world units", "maximum depth " + what });
        break;
      }
      case HsmLayout::NBuffers:
      {
        const std::string what = "over the 2^" + level + " square at each texel (N-buffers level " + level + ")";
        images.push_back({ "hsm_min_" + level, layers[layer].channels(0, 1), "world units", "minimum depth " + what });
        images.push_back({ "hsm_max_" + level, layers[layer].channels(1, 1), "world units", "maximum depth " + what });
        break;
      }
      case HsmLayout::DualMssm:
      {
        const std::string dualLevel = std::to_string(layer);
        const std::string what = "of the 2^" + dualLevel + " x 2^" + dualLevel +
          " dual cells (2 x 2 sample blocks) starting at the cell whose first sample is this texel (dual-grid MSSM level " +
          dualLevel + ", Yang et al. 2009 §4.2; samples outside the map count as 2 x far)";
        const ImageF cells = layers[layer].crop(1, 1, mapSize, mapSize);
        images.push_back({ "mssm_dual_min_" + dualLevel, cells.channels(0, 1), "world units", "minimum depth " + what });
        images.push_back({ "mssm_dual_max_" + dualLevel, cells.channels(1, 1), "world units", "maximum depth " + what });
        break;
      }
    }
  }
  return images;
}

std::size_t minMaxDepthBytes(const MinMaxDepthData& data)
{
  return textureBytes(data.texture, 8);
}

std::vector<vtkTextureObject*> bindMinMaxDepth(vtkShaderProgram* program, const MinMaxDepthData& data, int mapSize)
{
  setIntIfUsed(program, "hsmMapSize", mapSize);
  return { bindTexture(program, "hsmTexture", data.texture) };
}

const LightSpaceStructure& hierarchicalShadowMapStructure()
{
  static const LightSpaceStructure structure = [] {
    LightSpaceStructure s;
    s.name = "hierarchical_shadow_map";
    s.doc = "min-max depth pyramid of the shadow map, mip-map or N-buffers (VSSM §6.1)";
    s.builtFrom = { &shadowMapStructure() };
    s.parameters = {
      { "hsm", 0, 0, 1, "", "min-max hierarchical shadow map: mipmap (conservative ranges) or nbuffers (exact ranges, L times the memory)", { "mipmap", "nbuffers" }, true },
    };
    s.createBuildPasses = [] {
      return std::vector<vtkSmartPointer<vtkSLStagePass>>{ vtkSmartPointer<vtkSLHsmPass>::New() };
    };
    const auto data = [](const FrameResources& frame) -> const MinMaxDepthData& {
      return frame.structureData<MinMaxDepthData>(hierarchicalShadowMapStructure().name);
    };
    s.exportImages = [data](const FrameResources& frame, FrameResult&) {
      return exportMinMaxDepth(data(frame), frame.lightView.resolution);
    };
    s.gpuBytes = [data](const FrameResources& frame) { return minMaxDepthBytes(data(frame)); };
    s.shaderDefines = [](const FrameResources& frame) {
      return vtkSLHsmPass::LayoutDefines(hierarchicalShadowMapSettings(frame.parameters).layout);
    };
    s.bind = [data](vtkShaderProgram* program, const FrameResources& frame) {
      return bindMinMaxDepth(program, data(frame), frame.lightView.resolution);
    };
    return s;
  }();
  return structure;
}

} // namespace sl
