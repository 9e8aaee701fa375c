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
  settings.automaticResolution = values.automatic("shadow_map_size");
  settings.resolution = settings.automaticResolution ? 0 : values.getInt("shadow_map_size");
  if (values.has("auto_texels_per_pixel"))
  {
    settings.automaticTexelsPerPixel = values.get("auto_texels_per_pixel");
  }
  if (values.has("auto_texels_per_pixel_hard"))
  {
    settings.automaticTexelsPerPixelHard = values.get("auto_texels_per_pixel_hard");
  }
  // A filter reaches width/2 texels past a receiver; one more for the bilinear footprint. The moment techniques'
  // prefilter box reaches as far as pcf's kernel (and clamps at the map's edge without the margin), and the same
  // width focuses the same map: vsm and pcf over one box read the same texels (the light_leak lesson).
  const bool filtered = !request.filterParameter.empty();
  settings.marginTexels = filtered ? std::ceil(0.5 * request.filterTexels) + 1.0 : 1.0;
  if (!settings.automaticResolution && 2.0 * settings.marginTexels >= settings.resolution)
  {
    throw InputError(format("--set ", request.filterParameter, "=", request.filterTexels,
      ": the filter reaches ", settings.marginTexels, " texels past the receivers on each side, which leaves none of a ",
      settings.resolution, "-texel shadow map for them; use a larger shadow_map_size or a narrower filter"));
  }
  settings.secondDepth = values.has("caster_faces") && values.choice("caster_faces") == "back";
  if (values.has("depth_layer"))
  {
    settings.depthLayer = choiceOf<ShadowMapDepthLayer>(values, "depth_layer",
      { { "first", ShadowMapDepthLayer::First }, { "midpoint", ShadowMapDepthLayer::Midpoint }, { "dual", ShadowMapDepthLayer::Dual },
        { "polygon_id", ShadowMapDepthLayer::PolygonId } });
    settings.dualMaxOffsetTexels = values.get("dual_max_offset_texels");
    if (settings.secondDepth && settings.depthLayer != ShadowMapDepthLayer::First)
    {
      // Both layers are peeled from every face; a back-face-only first layer would make the "second" the third.
      throw InputError(format("--set depth_layer=", values.choice("depth_layer"),
        ": peels its two layers from all faces; use it with caster_faces=front (caster_faces=back is the second-depth "
        "map of Wang & Molnar 1994)"));
    }
  }
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
  if (values.has("fvsm"))
  {
    FvsmSettings& fvsm = settings.fvsm;
    fvsm.enabled = values.choice("fvsm") == "on";
    fvsm.tileSize = values.getInt("fvsm_tile_size");
    fvsm.maxLevel = values.getInt("fvsm_max_level");
    fvsm.maxTiles = values.getInt("fvsm_max_tiles");
    requireFvsmCombination(fvsm, settings.cascades.count, settings.warp.kind != WarpKind::None);
    if (fvsm.enabled && 2.0 * settings.marginTexels >= fvsm.tileSize)
    {
      throw InputError(format("--set fvsm_tile_size=", fvsm.tileSize, ": the filter reaches ", settings.marginTexels,
        " texels past the receivers on each side, which leaves none of the tile for them; use a larger fvsm_tile_size"));
    }
  }
  if (values.has("cube_map"))
  {
    settings.cubeMap = choiceOf<CubeMapMode>(
      values, "cube_map", { { "off", CubeMapMode::Off }, { "auto", CubeMapMode::Auto }, { "on", CubeMapMode::On } });
  }
  if (settings.depthLayer == ShadowMapDepthLayer::PolygonId && (settings.cascades.active() || settings.fvsm.active()))
  {
    throw InputError("--set depth_layer=polygon_id: one map only; use cascades=1 and fvsm=off");
  }
  return settings;
}

const char* depthLayerName(ShadowMapDepthLayer layer)
{
  switch (layer)
  {
    case ShadowMapDepthLayer::First:
      return "first";
    case ShadowMapDepthLayer::Midpoint:
      return "midpoint";
    case ShadowMapDepthLayer::Dual:
      return "dual";
    case ShadowMapDepthLayer::PolygonId:
      return "polygon_id";
  }
  return "first";
}

bool declaresDepthLayerGap(const TechniqueDescriptor& technique)
{
  // Right or flagged: the techniques whose accuracy contract marks the "depth layer gap" (markDepthLayerGap).
  for (const Approximation& approximation : technique.accuracy.approximations)
  {
    if (approximation.name == "depth layer gap")
    {
      return true;
    }
  }
  return false;
}

bool comparesPolygonIds(const TechniqueDescriptor& technique)
{
  // The techniques whose shader reads shadowMapPolygonId (HardVisibility.glsl's SHADOW_MAP_POLYGON_ID branch).
  return technique.name == "hard";
}
void adviseBeyondOneMap(const FrameResources& frame, FocusSettings& focus)
{
  if (frame.parameters.has("fvsm") && frame.parameters.choice("fvsm") == "on")
  {
    // FVSM's quadtree subdivides one focused map's window (survey §4.3.3); it does not partition by cube face.
    focus.beyondOneMapPrefix = "--set fvsm=on: ";
    focus.beyondOneMapAdvice = ": fvsm tiles one map's window; use fvsm=off (cube shadow maps, survey §2)";
  }
  else if (frame.parameters.has("cube_map") && frame.parameters.choice("cube_map") == "off")
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

double ShadowMapSettings::automaticTexelsPerPixelFor(const Light& light) const
{
  return light.type == LightType::Area ? automaticTexelsPerPixel : automaticTexelsPerPixelHard;
}

bool ShadowMapSettings::mayPartition(const Light& light) const
{
  return cascades.active() || fvsm.active() || (light.type == LightType::Point && cubeMap && *cubeMap != CubeMapMode::Off);
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
    if (settings.depthLayer == ShadowMapDepthLayer::PolygonId && !comparesPolygonIds(*frame.technique))
    {
      throw InputError("--set depth_layer=polygon_id: " + frame.technique->name +
        " compares depths, not polygon ids; use it with -t hard");
    }
    if ((settings.depthLayer == ShadowMapDepthLayer::Midpoint || settings.depthLayer == ShadowMapDepthLayer::Dual) &&
      !declaresDepthLayerGap(*frame.technique))
    {
      throw InputError(format("--set depth_layer=", depthLayerName(settings.depthLayer), ": ", frame.technique->name,
        " does not flag the pixels lit only by the gap to the second layer (its accuracy contract); use -t hard or pcf"));
    }

  }
  return settings;
}

namespace
{

// fvsm (survey §4.3.3): per pixel its tile's level, the pre-pass's required resolution and whether the tile meets it
// (on the GPU's selection, `tile`); in light space the pre-pass's grid and the quadtree's level per cell, resampled
// (nearest) to the tile maps' size.
void exportFvsm(const FrameResources& frame, const ImageF& tile, FrameResult& result, std::vector<NamedImage>& lightSpace)
{
  const FittedVirtualShadowMap& fvsm = *frame.partitions->fvsm;
  const FvsmQuadtree& tree = fvsm.quadtree;
  ImageF level(tile.width, tile.height, 1), required(tile.width, tile.height, 1), unmet(tile.width, tile.height, 1);
  for (int y = 0; y < tile.height; ++y)
  {
    for (int x = 0; x < tile.width; ++x)
    {
      const double need = fvsm.prepass.requiredResolution[static_cast<std::size_t>(y) * tile.width + x];
      if (need < 0.0 || tree.tiles.empty())
      {
        continue;
      }
      const FvsmTile& own = tree.tiles.at(static_cast<std::size_t>(tile.at(x, y)));
      level.at(x, y) = static_cast<float>(own.level);
      required.at(x, y) = static_cast<float>(need);
      unmet.at(x, y) = resolutionMet(own.effectiveResolution, need) ? 0.0f : 1.0f;
    }
  }
  for (const BufferSpec& spec : fvsmBufferSpecs())
  {
    ImageF& image = spec.name == "fvsm_level" ? level : spec.name == "fvsm_required_resolution" ? required : unmet;
    result.buffers.push_back({ spec.name, std::move(image), spec.unit, spec.doc, spec.kind, {} });
  }
  const int size = frame.partitions->views.front().resolution;
  ImageF requiredGrid(size, size, 1), levelGrid(size, size, 1);
  for (int y = 0; y < size; ++y)
  {
    for (int x = 0; x < size; ++x)
    {
      const std::size_t cell =
        static_cast<std::size_t>(y * tree.gridSize / size) * tree.gridSize + static_cast<std::size_t>(x * tree.gridSize / size);
      requiredGrid.at(x, y) = static_cast<float>(tree.requiredGrid[cell]);
      const int leaf = tree.tileOfCell[cell];
      levelGrid.at(x, y) = leaf < 0 ? -1.0f : static_cast<float>(tree.tiles[static_cast<std::size_t>(leaf)].level);
    }
  }
  lightSpace.push_back({ "fvsm_required_resolution_grid", std::move(requiredGrid), "texels",
    format("fvsm pre-pass (survey §4.3.3): the largest required resolution (texels across the focused window) of the "
           "receivers in each cell of the ", tree.gridSize, " x ", tree.gridSize, " grid over it; 0: no receiver") });
  lightSpace.push_back({ "fvsm_level_grid", std::move(levelGrid), "",
    "fvsm quadtree level of the tile holding each grid cell (tile side = window / 2^level); -1: no tile (no receiver)" });
}

// depth_layer = midpoint or dual (survey §5): the two peeled layers the combined map came from, per view
// (suffixed as the views' maps are).
void exportDepthLayers(const FrameResources& frame, std::vector<NamedImage>& images)
{
  const auto found = frame.lightSpaceData.find(shadowMapStructure().name);
  if (found == frame.lightSpaceData.end())
  {
    return;
  }
  const auto& layers = dynamic_cast<const ShadowMapLayersData&>(*found->second);
  if (layers.polygonIds)
  {
    // Ids are below 2^24 (the build checks), so float holds them exactly.
    const auto asFloat = [](const Image<std::uint32_t>& ids) {
      ImageF image(ids.width, ids.height, 1);
      for (std::size_t i = 0; i < ids.data.size(); ++i)
      {
        image.data[i] = static_cast<float>(ids.data[i]);
      }
      return image;
    };
    images.push_back({ "shadow_map_polygon_id", asFloat(readUnsignedTextureExact(layers.polygonIds, 1)), "",
      "depth_layer = polygon_id (Hourcade & Nicolas 1985): id of the nearest caster triangle per texel (scene triangle "
      "index + 1; 0: none)" });
  }
  for (std::size_t k = 0; k < layers.first.size(); ++k)
  {
    if (!layers.first[k])
    {
      continue;
    }
    const std::string suffix = frame.partitions ? partitionViewSuffix(*frame.partitions, static_cast<int>(k)) : "";
    images.push_back({ "shadow_map_first_depth" + suffix, readFloatTexture(layers.first[k], 1), "world units",
      "depth layer 1: linear depth of the nearest caster along the light axis (empty texels hold 2 x far)" });
    images.push_back({ "shadow_map_second_depth" + suffix, readFloatTexture(layers.second[k], 1), "world units",
      "depth layer 2 (depth peeling): the nearest caster depth strictly behind layer 1 at the texel (2 x far: none)" });
  }
}

// Views that partition the pixels (survey §4.3, PartitionViews.h): the per-pixel categorical buffer of the kind
// (`cascade`, `fvsm_tile` with fvsm's own buffers), the sampling error of each pixel's view, then each view's two
// maps, suffixed as partitionViewSuffix names them (_c<k>, _t<k>).
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
  std::vector<NamedImage> images;
  if (partitions.kind == PartitionKind::FvsmTiles)
  {
    exportFvsm(frame, primaryView, result, images);
  }
  std::vector<NamedImage> samplingError = samplingErrorBuffers(frame, result, &primaryView);
  result.buffers.insert(result.buffers.end(), std::make_move_iterator(samplingError.begin()),
    std::make_move_iterator(samplingError.end()));
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
  exportDepthLayers(frame, images);
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
  const auto layersFound = frame.lightSpaceData.find(shadowMapStructure().name);
  if (layersFound != frame.lightSpaceData.end())
  {
    const auto& layers = dynamic_cast<const ShadowMapLayersData&>(*layersFound->second);
    if (layers.receiverPolygonIds)
    {
      const Image<std::uint32_t> ids = readUnsignedTextureExact(layers.receiverPolygonIds, 1);
      ImageF image(ids.width, ids.height, 1);
      for (std::size_t i = 0; i < ids.data.size(); ++i)
      {
        image.data[i] = static_cast<float>(ids.data[i]);
      }
      result.buffers.push_back({ "polygon_id", std::move(image), "",
        "depth_layer = polygon_id (Hourcade & Nicolas 1985): id of the triangle the pixel sees (scene triangle index + 1; "
        "0: background), compared with the shadow map's shadow_map_polygon_id", BufferKind::Categorical, {} });
    }
  }
  std::vector<NamedImage> images(2);
  const ShadowMapDepthLayer layer = shadowMapSettings(frame).depthLayer;
  images[0] = { "shadow_map_depth", readFloatTexture(frame.shadowMapLinear, 1), "world units",
    layer == ShadowMapDepthLayer::First || layer == ShadowMapDepthLayer::PolygonId
      ? "linear depth of the nearest caster along the light axis (empty texels hold 2 x far)"
      : format("the depth the receivers are compared with (depth_layer = ", depthLayerName(layer),
          ", survey §5): combined from shadow_map_first_depth and shadow_map_second_depth") };
  images[1] = { "shadow_map_window_depth", readDepthTexture(frame.shadowMapDepth), "",
    "hardware depth buffer of the shadow map, window coordinates in [0, 1]" };
  exportDepthLayers(frame, images);
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
  const auto layersFound = frame.lightSpaceData.find(shadowMapStructure().name);
  if (layersFound != frame.lightSpaceData.end() && program->IsUniformUsed("shadowMapPolygonId"))
  {
    const auto& layers = dynamic_cast<const ShadowMapLayersData&>(*layersFound->second);
    SL_CHECK_MSG(layers.polygonIds && layers.receiverPolygonIds, "depth_layer = polygon_id built no id maps");
    bound.push_back(bindTexture(program, "shadowMapPolygonId", layers.polygonIds));
    bound.push_back(bindTexture(program, "receiverPolygonId", layers.receiverPolygonIds));
  }
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
  static const BufferSpec fvsmTile{ "fvsm_tile", "",
    "the fvsm quadtree tile whose map the pixel read (survey §4.3.3; stats.json light_view.fvsm.tiles lists their "
    "rectangles and levels)",
    BufferKind::Categorical };
  static const BufferSpec cubeFace{ "cube_face", "",
    "the cube face whose map the pixel read (survey §2): 0 +x, 1 -x, 2 +y, 3 -y, 4 +z, 5 -z, the dominant axis of "
    "p - light centre; -1 where uncovered or where the face has no map (the light reaches none of its receivers)",
    BufferKind::Categorical };
  switch (kind)
  {
    case PartitionKind::Cascades:
      return cascade;
    case PartitionKind::FvsmTiles:
      return fvsmTile;
    case PartitionKind::CubeFaces:
      return cubeFace;
  }
  SL_CHECK_MSG(false, "no buffer for partition kind ", partitionKindName(kind));
  return cascade;
}

const std::vector<BufferSpec>& fvsmBufferSpecs()
{
  static const std::vector<BufferSpec> specs = {
    { "fvsm_level", "", "quadtree level of the pixel's fvsm tile (its side is the focused window's / 2^level); 0 where "
      "the map is not queried" },
    { "fvsm_required_resolution", "texels", "the fvsm pre-pass's required resolution: texels across the focused window "
      "for one texel per pixel (survey Eq. 2 per axis); 0 where the map is not queried" },
    { "fvsm_unmet", "", "1 where the pixel's fvsm tile is coarser than its required resolution (fvsm_max_level or "
      "fvsm_max_tiles reached), else 0" },
  };
  return specs;
}

const LightSpaceStructure& shadowMapStructure()
{
  static const LightSpaceStructure structure = [] {
    LightSpaceStructure s;
    s.name = "shadow_map";
    s.doc = "linear (R32F) and window (D32F) depth from the light's centre, focused on the visible receivers (survey §4.1); "
            "publishes its sampling error per pixel (texel_ratio_s/_t, perspective_factor, projection_factor: survey §3)";
    s.parameters = {
      { "shadow_map_size", kAutomaticValue, 16, 8192, "texels", "texels per side of the shadow map (focused on visible receivers, survey §4.1); auto: auto_texels_per_pixel (area lights) or auto_texels_per_pixel_hard (the others) texels per pixel on the visible receivers (resolution matching, survey §4.3.3), a power of two", {}, true, false, "auto" },
      { "auto_texels_per_pixel", 2.0, 0.25, 8.0, "texels per pixel", "shadow_map_size = auto under an area light: texels per pixel along each map axis that the chosen size gives at the 0.9 quantile of visible receivers (2: two samples per pixel, above the image's Nyquist rate as survey §3 asks of the initial sampling; 1: one texel per pixel, between under- and oversampling, §3.1)", {}, false },
      { "auto_texels_per_pixel_hard", 4.0, 0.25, 8.0, "texels per pixel", "shadow_map_size = auto under a point, spot or directional light: as auto_texels_per_pixel, for shadows that are hard everywhere (no penumbra hides where a filter or box given in texels puts the edge)", {}, false },
      { "caster_faces", 0, 0, 1, "", "front = first-depth map; back = second-depth map (Wang & Molnar 1994, survey §5; needs closed casters)", { "front", "back" }, true },
      { "depth_layer", 0, 0, 3, "", "the depth compared (survey §5): first = the nearest caster's; midpoint = (z1 + z2) / 2 of the nearest and the second-nearest (depth-peeled) surface (Woo 1992); dual = min((z1 + z2) / 2, z1 + dual_max_offset_texels texel footprints) (Weiskopf & Ertl 2003); polygon_id = the nearest triangle's id (32 bits), lit iff it is the receiver's own (Hourcade & Nicolas 1985; hard only; flagged where the receiver's 3 x 3 texels hold several ids)", { "first", "midpoint", "dual", "polygon_id" }, true },
      { "dual_max_offset_texels", 4.0, 0, 1e4, "texel footprints", "depth_layer = dual: the most the compared depth lies behind the nearest caster, in texel footprints at its depth (limits the effective caster thickness)", {}, false },
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
        const auto found = frame.lightSpaceData.find("shadow_map");
        if (found != frame.lightSpaceData.end())
        {
          const auto& layers = dynamic_cast<const ShadowMapLayersData&>(*found->second);
          for (std::size_t k = 0; k < layers.first.size(); ++k)
          {
            bytes += textureBytes(layers.first[k], 4) + textureBytes(layers.second[k], 4);
          }
        }
        return bytes;
      }
      std::size_t layerBytes = 0;
      const auto found = frame.lightSpaceData.find("shadow_map");
      if (found != frame.lightSpaceData.end())
      {
        const auto& layers = dynamic_cast<const ShadowMapLayersData&>(*found->second);
        for (std::size_t k = 0; k < layers.first.size(); ++k)
        {
          layerBytes += textureBytes(layers.first[k], 4) + textureBytes(layers.second[k], 4);
        }
        layerBytes += textureBytes(layers.polygonIds, 4) + textureBytes(layers.receiverPolygonIds, 4);
      }
      return layerBytes + textureBytes(frame.shadowMapLinear, 4) + textureBytes(frame.shadowMapDepth, 4);
    };
    s.shaderDefines = [](const FrameResources& frame) {
      const bool ids = frame.technique && comparesPolygonIds(*frame.technique) &&
        shadowMapSettings(frame).depthLayer == ShadowMapDepthLayer::PolygonId;
      return ShaderDefines{ { "SHADOW_MAP_POLYGON_ID", ids ? "1" : "0" } };
    };
    s.bind = bindShadowMap;
    return s;
  }();
  return structure;
}

} // namespace sl
