#include "structures/hsm/HsmStructure.h"

#include "frame/FrameResult.h"
#include "gl/GlResources.h"
#include "structures/hsm/vtkSLHsmPass.h"
#include "structures/shadowmap/ShadowMapStructure.h"
#include "passes/PassUtilities.h"

#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>

#include <algorithm>
#include <cmath>

namespace sl
{

HierarchicalShadowMapSettings hierarchicalShadowMapSettings(const ParameterValues& values)
{
  HierarchicalShadowMapSettings settings;
  const std::string choice = values.choice("hsm");
  settings.layout = choice == "nbuffers" ? HsmLayout::NBuffers : choice == "ysm" ? HsmLayout::Ysm : HsmLayout::MipMap;
  settings.levelsRead = values.choice("hsm_levels") == "read";
  return settings;
}

int minMaxTopLevel(HsmLayout layout, const LightView& view, const Light& light, bool boundedQueries)
{
  const bool dual = layout == HsmLayout::DualMssm;
  const int levelCount = dual ? dualMssmLevelCount(view.resolution) : hsmLevelCount(view.resolution);
  if (!boundedQueries || !(dual || layout == HsmLayout::NBuffers) || view.projection != LightProjection::Perspective)
  {
    return levelCount;
  }
  // kernelHalfTexels (common/SoftShadowKernels.glsl) at d = far, plane = near: the widest kernel of any receiver
  // the map holds; nearer receivers have narrower ones.
  const double lightSize = light.type == LightType::Area ? light.size : 0.0;
  const double halfTangent = 0.5 * lightSize * (view.farDepth - view.nearDepth) / (view.nearDepth * view.farDepth);
  const double texelTangent = std::min(view.window.y - view.window.x, view.window.w - view.window.z) / view.resolution;
  const double widestQueryTexels = 2.0 * std::ceil(halfTangent / texelTangent) + 4.0;
  if (!(widestQueryTexels < static_cast<double>(1 << 30)))
  {
    return levelCount; // a degenerate view (near depth 0, an empty window): no bound
  }
  // A range query tiles with squares no wider than its shorter side (floor); yfgl09's traversal starts from a node
  // as wide as its region (ceil).
  const double levelRead = dual ? std::ceil(std::log2(widestQueryTexels)) : std::floor(std::log2(widestQueryTexels));
  return sl::minMaxTopLevel(levelCount, static_cast<int>(levelRead));
}

int minMaxTopLevel(HsmLayout layout, const FrameResources& frame)
{
  const std::string parameter = layout == HsmLayout::DualMssm ? "mssm_levels" : "hsm_levels";
  const bool bounded = frame.technique->lightSpaceRequestFor(frame.parameters).minMaxQueriesWithinNearPlaneKernel &&
    frame.parameters.choice(parameter) == "read";
  return minMaxTopLevel(layout, frame.lightView, *frame.light, bounded);
}

HierarchicalShadowMap buildHierarchicalShadowMap(const ImageF& shadowMapLinear, const ParameterValues& values)
{
  return HierarchicalShadowMap::build(shadowMapLinear, hierarchicalShadowMapSettings(values).layout);
}

HierarchicalShadowMap buildHierarchicalShadowMap(const ImageF& shadowMapLinear, const ParameterValues& values,
  const LightView& view, const Light& light, bool queriesWithinNearPlaneKernel)
{
  const HierarchicalShadowMapSettings settings = hierarchicalShadowMapSettings(values);
  if (settings.layout != HsmLayout::NBuffers)
  {
    return HierarchicalShadowMap::build(shadowMapLinear, settings.layout);
  }
  return HierarchicalShadowMap::build(shadowMapLinear, settings.layout,
    minMaxTopLevel(settings.layout, view, light, queriesWithinNearPlaneKernel && settings.levelsRead));
}

std::vector<NamedImage> exportMinMaxDepth(const MinMaxDepthData& data, int mapSize, FrameResult& result,
  const std::string& statisticsPrefix)
{
  result.techniqueStatistics[statisticsPrefix + "_top_level"] = data.topLevel;
  result.techniqueStatistics[statisticsPrefix + "_level_count"] = data.levelCount;
  // Mip-map: the atlas as stored (levels 1..L, HierarchicalShadowMap.h); N-buffers: one pair per level;
  // dual-grid MSSM: one pair per level, point (i, j) holding cell (i, j) (texel (i + 1, j + 1)); YSM: the atlas,
  // then one pair per level of the MSSM part, point (i, j) holding the part's texel (i >> b, j >> b), i.e. the
  // square of level-b nodes starting at the node that holds shadow-map texel (i, j).
  std::vector<NamedImage> images;
  const std::vector<ImageF> layers = readFloatTextureLayers(data.texture, 2);
  for (std::size_t layer = 0; layer < layers.size(); ++layer)
  {
    const std::string level = std::to_string(layer + 1);
    switch (data.layout)
    {
      case HsmLayout::MipMap:
      case HsmLayout::Ysm:
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
  if (data.layout == HsmLayout::Ysm)
  {
    const std::vector<ImageF> part = readFloatTextureLayers(data.mssmPart, 2);
    const int b = data.ysmBaseLevel;
    for (int level = 1; level <= ysmMssmPartLevelCount(mapSize); ++level)
    {
      const ImageF& stored = part[static_cast<std::size_t>(level - 1)];
      ImageF perTexel(mapSize, mapSize, 2);
      for (int y = 0; y < mapSize; ++y)
      {
        for (int x = 0; x < mapSize; ++x)
        {
          perTexel.at(x, y, 0) = stored.at(x >> b, y >> b, 0);
          perTexel.at(x, y, 1) = stored.at(x >> b, y >> b, 1);
        }
      }
      const std::string k = std::to_string(level);
      const std::string what = "of the 2^" + k + " x 2^" + k + " HSM level-" + std::to_string(b) +
        " nodes starting at the node over this texel (Y shadow map's MSSM part, level " + k +
        "; Schwarz & Stamminger 2008 §6)";
      images.push_back({ "ysm_mssm_min_" + k, perTexel.channels(0, 1), "world units", "minimum depth " + what });
      images.push_back({ "ysm_mssm_max_" + k, perTexel.channels(1, 1), "world units", "maximum depth " + what });
    }
  }
  return images;
}

std::size_t minMaxDepthBytes(const MinMaxDepthData& data)
{
  // YSM: the atlas plus the MSSM part (SS08 Table 1).
  return textureBytes(data.texture, 8) + (data.mssmPart ? textureBytes(data.mssmPart, 8) : 0);
}

std::vector<vtkTextureObject*> bindMinMaxDepth(vtkShaderProgram* program, const MinMaxDepthData& data, int mapSize)
{
  setIntIfUsed(program, "hsmMapSize", mapSize);
  setIntIfUsed(program, "hsmTopLevel", data.topLevel);
  if (data.layout == HsmLayout::Ysm)
  {
    setIntIfUsed(program, "ysmBaseLevel", data.ysmBaseLevel);
    return { bindTexture(program, "hsmTexture", data.texture), bindTexture(program, "ysmMssmTexture", data.mssmPart) };
  }
  return { bindTexture(program, "hsmTexture", data.texture) };
}

ParameterSpec hsmLevelsParameter(const std::string& name, const std::string& layout)
{
  return { name, 0, 0, 1, "", "read: the " + layout + " built only up to the level of the widest range query the technique can make in this frame (Eq. 1's kernel of the farthest receiver; wider queries stay exact, tiled by more squares), where the technique bounds its queries; all: every level", { "read", "all" }, true };
}

const LightSpaceStructure& hierarchicalShadowMapStructure()
{
  static const LightSpaceStructure structure = [] {
    LightSpaceStructure s;
    s.name = "hierarchical_shadow_map";
    s.doc = "min-max depth pyramid of the shadow map, mip-map, N-buffers (VSSM §6.1) or Y shadow map (Schwarz & Stamminger 2008 §6)";
    s.builtFrom = { &shadowMapStructure() };
    s.parameters = {
      { "hsm", 0, 0, 2, "", "min-max hierarchical shadow map: mipmap (conservative ranges), nbuffers (exact ranges, L times the memory) or ysm (the mip-map plus N-buffers of its ~256^2 level: ranges exact on that level's blocks, + 4 MiB at 1024^2 and 2048^2; Schwarz & Stamminger 2008 §6)", { "mipmap", "nbuffers", "ysm" }, true },
      hsmLevelsParameter("hsm_levels", "N-buffers"),
    };
    s.createBuildPasses = [] {
      return std::vector<vtkSmartPointer<vtkSLStagePass>>{ vtkSmartPointer<vtkSLHsmPass>::New() };
    };
    const auto data = [](const FrameResources& frame) -> const MinMaxDepthData& {
      return frame.structureData<MinMaxDepthData>(hierarchicalShadowMapStructure().name);
    };
    s.exportImages = [data](const FrameResources& frame, FrameResult& result) {
      return exportMinMaxDepth(data(frame), frame.lightView.resolution, result, "hsm");
    };
    s.gpuBytes = [data](const FrameResources& frame) { return minMaxDepthBytes(data(frame)); };
    s.shaderDefines = [](const FrameResources& frame) {
      return vtkSLHsmPass::LayoutDefines(hierarchicalShadowMapSettings(frame.parameters).layout);
    };
    s.bind = [data](vtkShaderProgram* program, const FrameResources& frame) {
      return bindMinMaxDepth(program, data(frame), frame.lightView.resolution);
    };
    s.largestMapSize = [](const ParameterValues& values, int max3dTextureSize) {
      return hierarchicalShadowMapSettings(values).layout == HsmLayout::NBuffers ? max3dTextureSize : 1 << 30;
    };
    return s;
  }();
  return structure;
}

} // namespace sl
