#include "structures/shadowmap/ShadowMapStructure.h"

#include "core/Error.h"
#include "frame/FrameResult.h"
#include "gl/GlResources.h"
#include "structures/shadowmap/SamplingErrorBuffers.h"
#include "structures/shadowmap/vtkSLFocusPass.h"
#include "structures/shadowmap/vtkSLLightDepthPass.h"
#include "passes/PassUtilities.h"

#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>

#include <cmath>
#include <iterator>

namespace sl
{

ShadowMapSettings ShadowMapSettings::from(const ParameterValues& values, const LightSpaceRequest& request)
{
  ShadowMapSettings settings;
  settings.resolution = values.getInt("shadow_map_size");
  // A filter reaches width/2 texels past a receiver; one more for the bilinear footprint. The moment techniques'
  // prefilter box reaches as far as pcf's kernel (and clamps at the map's edge without the margin), and the same
  // width focuses the same map: vsm and pcf over one box read the same texels (the light_leak lesson).
  const bool filtered = !request.filterParameter.empty();
  settings.marginTexels = filtered ? std::ceil(0.5 * request.filterTexels) + 1.0 : 1.0;
  if (2.0 * settings.marginTexels >= settings.resolution)
  {
    throw InputError(format("--set ", request.filterParameter, "=", request.filterTexels,
      ": the filter reaches ", settings.marginTexels, " texels past the receivers on each side, which leaves none of a ",
      settings.resolution, "-texel shadow map for them; use a larger shadow_map_size or a narrower filter"));
  }
  settings.secondDepth = values.has("caster_faces") && values.choice("caster_faces") == "back";
  if (values.has("warp"))
  {
    settings.warp.kind = choiceOf<WarpKind>(values, "warp",
      { { "none", WarpKind::None }, { "psm", WarpKind::Psm }, { "lispsm", WarpKind::Lispsm }, { "tsm", WarpKind::Tsm } });
    settings.warp.n = values.get("warp_n");
  }
  if (values.has("cascades"))
  {
    CascadeSettings& cascades = settings.cascades;
    cascades.count = values.getInt("cascades");
    cascades.scheme = choiceOf<SplitScheme>(values, "split_scheme",
      { { "uniform", SplitScheme::Uniform }, { "log", SplitScheme::Log }, { "practical", SplitScheme::Practical } });
    cascades.lambda = values.get("split_lambda");
    cascades.selection = choiceOf<CascadeSelection>(values, "cascade_selection",
      { { "depth", CascadeSelection::Depth }, { "containment", CascadeSelection::Containment } });
    cascades.blend = values.get("cascade_blend");
    cascades.snap = values.choice("cascade_snap") == "on";
  }
  if (values.has("cube_map"))
  {
    settings.cubeMap = choiceOf<CubeMapMode>(
      values, "cube_map", { { "off", CubeMapMode::Off }, { "auto", CubeMapMode::Auto }, { "on", CubeMapMode::On } });
  }
  return settings;
}

void adviseBeyondOneMap(const FrameResources& frame, FocusSettings& focus)
{
  if (frame.parameters.has("cube_map") && frame.parameters.choice("cube_map") == "off")
  {
    focus.beyondOneMapPrefix = "--set cube_map=off: ";
    focus.beyondOneMapAdvice = ": use cube_map=auto or on (survey §2: cube shadow maps)";
  }
  else if (!frame.cubeMapTechniques.empty())
  {
    focus.beyondOneMapAdvice =
      ": render it with cube shadow maps (techniques " + frame.cubeMapTechniques + ") or use a spot or area light";
  }
}

bool ShadowMapSettings::mayPartition(const Light& light) const
{
  return cascades.active() || (light.type == LightType::Point && cubeMap && *cubeMap != CubeMapMode::Off);
}

ShadowMapSettings shadowMapSettings(const TechniqueDescriptor& technique, const ParameterValues& values)
{
  return ShadowMapSettings::from(values, technique.lightSpaceRequestFor(values));
}

ShadowMapSettings shadowMapSettings(const FrameResources& frame)
{
  SL_CHECK(frame.technique != nullptr);
  const ShadowMapSettings settings = shadowMapSettings(*frame.technique, frame.parameters);
  if (frame.light)
  {
    // The renderer asks before any GL (ShadowRenderer's setFrameInputs); fitLightView refuses the same.
    requireWarpableLight(settings.warp.kind, frame.light->type);
    requireCascadableLight(settings.cascades, frame.light->type);
    requireCubeMapLight(settings.cubeMap.value_or(CubeMapMode::Off), frame.light->type);
  }
  return settings;
}

namespace
{

// Views that partition the pixels (survey §4.3, PartitionViews.h): the per-pixel categorical buffer of the kind
// (`cascade`), the sampling error of each pixel's view, then each view's two maps, suffixed as partitionViewSuffix
// names them (_c<k>).
std::vector<NamedImage> exportPartitions(const FrameResources& frame, FrameResult& result)
{
  const PartitionSet& partitions = *frame.partitions;
  const ImageF selection = readFloatTexture(frame.viewSelection, 4);
  const ImageF primaryView = selection.channels(0, 1);
  const BufferSpec& spec = partitionBufferSpec(partitions.kind);
  std::vector<std::string> labels;
  if (partitions.kind == PartitionKind::CubeFaces)
  {
    // By face, not by view (the selection's fourth channel): a face without a map keeps its code.
    for (int face = 0; face < kCubeFaceCount; ++face)
    {
      labels.push_back(cubeFaceName(face));
    }
    result.buffers.push_back({ spec.name, selection.channels(3, 1), spec.unit, spec.doc, spec.kind, labels });
  }
  else
  {
    for (int k = 0; k < partitions.viewCount(); ++k)
    {
      labels.push_back(partitionViewLabel(partitions, k));
    }
    result.buffers.push_back({ spec.name, primaryView, spec.unit, spec.doc, spec.kind, labels });
  }
  std::vector<NamedImage> samplingError = samplingErrorBuffers(frame, result, &primaryView);
  result.buffers.insert(result.buffers.end(), std::make_move_iterator(samplingError.begin()),
    std::make_move_iterator(samplingError.end()));
  std::vector<NamedImage> images;
  for (std::size_t k = 0; k < frame.viewShadowMapLinear.size(); ++k)
  {
    const int view = static_cast<int>(k);
    const std::string suffix = partitionViewSuffix(partitions, view);
    const std::string label = partitionViewLabel(partitions, view);
    images.push_back({ "shadow_map_depth" + suffix, readFloatTexture(frame.viewShadowMapLinear[k], 1), "world units",
      format(label, "'s map: linear depth of the nearest caster along the light axis (empty texels hold 2 x far)") });
    images.push_back({ "shadow_map_window_depth" + suffix, readDepthTexture(frame.viewShadowMapDepth[k]), "",
      format(label, "'s hardware depth buffer, window coordinates in [0, 1]") });
  }
  return images;
}

std::vector<NamedImage> exportShadowMap(const FrameResources& frame, FrameResult& result)
{
  if (frame.partitions)
  {
    return exportPartitions(frame, result);
  }
  // The map's sampling error at the visible receivers is per pixel: it joins the frame's buffers.
  std::vector<NamedImage> samplingError = samplingErrorBuffers(frame, result);
  result.buffers.insert(result.buffers.end(), std::make_move_iterator(samplingError.begin()),
    std::make_move_iterator(samplingError.end()));
  // Built in place: an initializer list would copy both maps (16 MiB each at the default size) once more.
  std::vector<NamedImage> images(2);
  images[0] = { "shadow_map_depth", readFloatTexture(frame.shadowMapLinear, 1), "world units",
    "linear depth of the nearest caster along the light axis (empty texels hold 2 x far)" };
  images[1] = { "shadow_map_window_depth", readDepthTexture(frame.shadowMapDepth), "",
    "hardware depth buffer of the shadow map, window coordinates in [0, 1]" };
  return images;
}

std::vector<vtkTextureObject*> bindShadowMap(vtkShaderProgram* program, const FrameResources& frame)
{
  std::vector<vtkTextureObject*> bound;
  const LightView& view = frame.lightView;
  if (program->IsUniformUsed("shadowMapLinear"))
  {
    bound.push_back(bindTexture(program, "shadowMapLinear", frame.shadowMapLinear));
  }
  setMatrix(program, "lightClipFromWorld", view.clipFromWorld);
  setMatrix(program, "lightViewFromWorld", view.viewFromWorld);
  setIntIfUsed(program, "shadowMapSize", view.resolution);
  setIntIfUsed(program, "lightIsPerspective", view.projection == LightProjection::Perspective ? 1 : 0);
  setIntIfUsed(program, "lightWarped", view.warp.active() ? 1 : 0);
  if (program->IsUniformUsed("lightDepthToClip"))
  {
    // windowDepth: clip.z = -P22 d + P32, clip.w = -P23 d + P33 for linear depth d (z_view = -d).
    const glm::dmat4& projection = view.clipFromView;
    const float depthToClip[4] = { static_cast<float>(projection[2][2]), static_cast<float>(projection[3][2]),
      static_cast<float>(projection[2][3]), static_cast<float>(projection[3][3]) };
    program->SetUniform4f("lightDepthToClip", depthToClip);
  }
  // texelWorldSize(depthLin) = shadowTexelExtent * depthLin (perspective) or shadowTexelExtent.
  setFloatIfUsed(program, "shadowTexelExtent",
    view.projection == LightProjection::Perspective ? view.texelWorldSize(1.0) : view.texelWorldSize(0.0));
  return bound;
}

} // namespace

const BufferSpec& partitionBufferSpec(PartitionKind kind)
{
  static const BufferSpec cascade{ "cascade", "",
    "the cascade whose map the pixel read (survey §4.3.1, Fig. 15's colour coding); with cascade_blend, the first of "
    "the two it blends",
    BufferKind::Categorical };
  static const BufferSpec cubeFace{ "cube_face", "",
    "the cube face whose map the pixel read (survey §2): 0 +x, 1 -x, 2 +y, 3 -y, 4 +z, 5 -z, the dominant axis of "
    "p - light centre; -1 where uncovered or where the face has no map (the light reaches none of its receivers)",
    BufferKind::Categorical };
  switch (kind)
  {
    case PartitionKind::Cascades:
      return cascade;
    case PartitionKind::CubeFaces:
      return cubeFace;
  }
  SL_CHECK_MSG(false, "no buffer for partition kind ", partitionKindName(kind));
  return cascade;
}

const LightSpaceStructure& shadowMapStructure()
{
  static const LightSpaceStructure structure = [] {
    LightSpaceStructure s;
    s.name = "shadow_map";
    s.doc = "linear (R32F) and window (D32F) depth from the light's centre, focused on the visible receivers (survey §4.1); "
            "publishes its sampling error per pixel (texel_ratio_s/_t, perspective_factor, projection_factor: survey §3)";
    s.parameters = {
      { "shadow_map_size", 2048, 16, 8192, "texels", "texels per side of the shadow map (focused on visible receivers, survey §4.1)", {}, true },
      { "caster_faces", 0, 0, 1, "", "front = first-depth map; back = second-depth map (Wang & Molnar 1994, survey §5; needs closed casters)", { "front", "back" }, true },
    };
    s.createBuildPasses = [] {
      return std::vector<vtkSmartPointer<vtkSLStagePass>>{ vtkSmartPointer<vtkSLFocusPass>::New(),
        vtkSmartPointer<vtkSLLightDepthPass>::New() };
    };
    s.exportImages = exportShadowMap;
    s.gpuBytes = [](const FrameResources& frame) {
      if (frame.partitions)
      {
        std::size_t bytes = textureBytes(frame.viewSelection, 16);
        for (std::size_t k = 0; k < frame.viewShadowMapLinear.size(); ++k)
        {
          bytes += textureBytes(frame.viewShadowMapLinear[k], 4) + textureBytes(frame.viewShadowMapDepth[k], 4);
        }
        return bytes;
      }
      return textureBytes(frame.shadowMapLinear, 4) + textureBytes(frame.shadowMapDepth, 4);
    };
    s.shaderDefines = [](const FrameResources&) { return ShaderDefines{}; };
    s.bind = bindShadowMap;
    return s;
  }();
  return structure;
}

} // namespace sl
