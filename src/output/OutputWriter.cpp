#include "output/OutputWriter.h"

#include "core/Error.h"
#include "lightspace/FittedVirtualShadowMap.h"
#include "io/ImageIO.h"
#include "output/ParaViewScript.h"
#include "vis/BufferHeatMap.h"
#include "vis/HeatMap.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace sl
{
namespace
{

// One heat map per buffer that drawsHeatMap (vis/BufferHeatMap.h): frame buffers over their declared pixels
// (bufferValueMask: grey where the quantity does not apply), light-space ones (`frameBuffers` null) over every texel.
// Appends to `drawn` how each was drawn, for open_in_paraview.py (`file`: the .vti that holds the buffers).
void writeHeatMaps(const std::vector<NamedImage>& images, const std::vector<NamedImage>* frameBuffers,
  const std::filesystem::path& dir, const std::string& prefix, const std::string& file,
  std::vector<DrawnHeatMap>& drawn)
{
  for (const NamedImage& named : images)
  {
    if (!drawsHeatMap(named))
    {
      continue;
    }
    const ImageU8 mask = frameBuffers ? bufferValueMask(named, *frameBuffers) : ImageU8();
    const ImageU8* maskOrAll = frameBuffers ? &mask : nullptr;
    DrawnHeatMap heatMap{ &named, file, "", bufferHeatMapOptions(named, maskOrAll), {} };
    heatMap.scale = writeHeatMapPng(heatMapValues(named), maskOrAll, heatMap.options, dir / (prefix + named.name + ".png"));
    if (frameBuffers)
    {
      // The array bufferValueMask read: shadow_tested for a quantity declared on shadow-tested pixels, else coverage.
      const bool onShadowTested = named.domain == BufferDomain::ShadowTested && findNamed(*frameBuffers, "shadow_tested");
      heatMap.appliesWhere = onShadowTested ? "shadow_tested" : findNamed(*frameBuffers, "coverage") ? "coverage" : "";
    }
    drawn.push_back(std::move(heatMap));
  }
}

} // namespace

nlohmann::json bufferSummary(const NamedImage& named, const ImageU8* valueMask)
{
  double minimum = 0.0;
  double maximum = 0.0;
  double sum = 0.0;
  std::size_t count = 0;
  std::size_t nonFinite = 0;
  std::size_t domainPixels = 0;
  const ImageF& image = named.image;
  // Only the pixels the buffer has a value at (bufferValueMask: covered, and shadow-tested for a quantity declared
  // there): the 0 a shader writes where no shadow test ran is no value, and would pull min and mean to 0.
  const auto inDomain = [&](std::size_t i) {
    return !valueMask || (valueMask->data[i] != 0 && valueMask->data[i] != kNotApplicablePixel);
  };
  for (std::size_t i = 0; i < image.pixelCount(); ++i)
  {
    if (!inDomain(i))
    {
      continue;
    }
    ++domainPixels;
    for (int c = 0; c < image.components; ++c)
    {
      const double value = image.data[i * image.components + c];
      if (!std::isfinite(value))
      {
        ++nonFinite;
        continue;
      }
      minimum = count == 0 ? value : std::min(minimum, value);
      maximum = count == 0 ? value : std::max(maximum, value);
      sum += value;
      ++count;
    }
  }
  nlohmann::json statistics = { { "components", image.components }, { "min", minimum }, { "max", maximum },
    { "mean", count ? sum / static_cast<double>(count) : 0.0 }, { "non_finite", nonFinite }, { "unit", named.unit },
    { "doc", named.doc }, { "domain_pixels", domainPixels } };
  if (named.kind == BufferKind::Categorical && image.components == 1)
  {
    // Pixels per category (covered pixels, the not-applicable ones included: a "not tested" class counts them), by label: how many were lit, penumbra, cut short, ...
    std::vector<std::size_t> pixels(named.categoryLabels.size(), 0);
    for (std::size_t i = 0; i < image.pixelCount(); ++i)
    {
      const float value = image.data[i];
      if ((!valueMask || valueMask->data[i] != 0) && value >= 0.0f && value < static_cast<float>(pixels.size()) &&
        value == std::floor(value))
      {
        ++pixels[static_cast<std::size_t>(value)];
      }
    }
    nlohmann::json counts = nlohmann::json::object();
    for (std::size_t code = 0; code < pixels.size(); ++code)
    {
      counts[named.categoryLabels[code]] = pixels[code];
    }
    statistics["category_pixels"] = counts;
  }
  return statistics;
}

nlohmann::json frameStats(const FrameResult& frame, const OutputContext& context)
{
  SL_CHECK_MSG(frame.descriptor, "frame of technique ", frame.technique, " has no descriptor");
  const TechniqueDescriptor& technique = *frame.descriptor;
  nlohmann::json parameters = nlohmann::json::object();
  for (const ParameterSpec& spec : technique.parameters)
  {
    if (spec.file)
    {
      parameters[spec.name] = frame.parameters.file(spec.name);
    }
    else if (frame.parameters.automatic(spec.name))
    {
      parameters[spec.name] = spec.automatic; // the value chosen: light_view (shadow_map_size_chosen)
    }
    else if (spec.choices.empty())
    {
      parameters[spec.name] = frame.parameters.get(spec.name);
    }
    else
    {
      parameters[spec.name] = frame.parameters.choice(spec.name);
    }
  }
  nlohmann::json stages = nlohmann::json::array();
  double totalGpuMs = 0.0;
  for (const StageTiming& stage : frame.stages)
  {
    stages.push_back({ { "stage", stage.stage }, { "gpu_ms", stage.gpuMs }, { "wall_ms", stage.wallMs } });
    totalGpuMs += stage.gpuMs;
  }
  nlohmann::json stats = {
    { "technique", technique.name },
    { "title", technique.title },
    { "paper", technique.paper },
    { "parameters", parameters },
    { "scene", context.sceneFile.string() },
    { "light_index", context.lightIndex },
    { "resolution", { frame.resolution.x, frame.resolution.y } },
    { "gl_renderer", frame.glRenderer },
    { "gl_version", frame.glVersion },
    { "egl_platform", frame.eglPlatform },
    { "egl_device", { { "index", frame.eglDeviceIndex }, { "description", frame.eglDevice } } },
    { "stages", stages },
    { "total_gpu_ms", totalGpuMs },
    { "frame_wall_ms", frame.frameWallMs },
    { "dropped_degenerate_triangles", context.droppedDegenerateTriangles },
    { "technique_statistics", frame.techniqueStatistics },
  };
  nlohmann::json structures = nlohmann::json::array();
  for (const std::string& name : frame.lightStructureNames)
  {
    structures.push_back(name);
  }
  stats["light_structures"] = structures;
  nlohmann::json structureBytes = nlohmann::json::object();
  for (const auto& [name, bytes] : frame.lightStructureGpuBytes)
  {
    structureBytes[name] = bytes;
  }
  stats["light_structure_gpu_bytes"] = structureBytes;
  nlohmann::json structureBuilds = nlohmann::json::object();
  for (const auto& [name, build] : frame.lightStructureBuilds)
  {
    structureBuilds[name] = { { "reused", build.reused }, { "build_ms", build.buildGpuMs },
      { "build_ms_when_built", build.buildGpuMsWhenBuilt } };
  }
  stats["light_structure_builds"] = structureBuilds; // GPU ms; a reused build (an unchanged input) costs 0
  if (!frame.samplePositions.empty())
  {
    nlohmann::json positions = nlohmann::json::array();
    for (const glm::dvec2& position : frame.samplePositions)
    {
      positions.push_back({ position.x, position.y });
    }
    stats["sample_positions"] = positions;
  }
  if (frame.lightView)
  {
    const LightView& view = *frame.lightView;
    stats["light_view"] = {
      { "projection", view.projection == LightProjection::Perspective ? "perspective" : "orthographic" },
      { "resolution", view.resolution },
      { "near_depth", view.nearDepth },
      { "far_depth", view.farDepth },
      { "window", { view.window.x, view.window.y, view.window.z, view.window.w } },
      { "receiver_samples", view.receiverSampleCount },
    };
    if (view.warp.active())
    {
      // Survey §4.2: P's free parameter and the angle that sets LiSPSM's falloff (n null: degraded to uniform).
      const PerspectiveWarp& warp = view.warp;
      const auto finiteOr = [](double value) { return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(); };
      stats["light_view"]["warp"] = { { "kind", warpName(warp.kind) }, { "n", finiteOr(warp.n) },
        { "n_opt", finiteOr(warp.nOpt) }, { "gamma_deg", warp.gammaDeg }, { "z_near", warp.zNear },
        { "z_far", warp.zFar }, { "near", finiteOr(warp.nearDistance) }, { "far", finiteOr(warp.farDistance) } };
    }
  }
  if (const std::optional<int> size = frame.shadowMapSize())
  {
    stats["shadow_map_size_chosen"] = *size; // as rendered, given or chosen (shadow_map_size = auto)
  }
  if (frame.automaticMapSize)
  {
    const AutomaticMapSize& choice = *frame.automaticMapSize;
    stats["shadow_map_size_automatic"] = { { "quantile", kAutomaticMapQuantile }, { "texels_per_pixel", choice.texelsPerPixel },
      { "required_texels", choice.requiredTexels }, { "receiver_samples", choice.samples },
      { "pixel_stride", choice.pixelStride }, { "capped", choice.capped } };
  }
  if (frame.partitions && frame.partitions->kind == PartitionKind::FvsmTiles)
  {
    // Survey §4.3.3: the quadtree's tiles (rectangles in light x/y, the units of `window`), the pre-pass's samples and
    // how many pixels' required resolution was not met; the top-level light_view is tile 0's.
    const FittedVirtualShadowMap& fvsm = *frame.partitions->fvsm;
    const FvsmQuadtree& tree = fvsm.quadtree;
    nlohmann::json tiles = nlohmann::json::array();
    for (std::size_t k = 0; k < tree.tiles.size(); ++k)
    {
      const FvsmTile& tile = tree.tiles[k];
      const LightView& view = frame.partitions->views[k];
      tiles.push_back({ { "level", tile.level }, { "cell", { tile.cell.x, tile.cell.y } },
        { "rect", { tile.rect.x, tile.rect.y, tile.rect.z, tile.rect.w } },
        { "window", { view.window.x, view.window.y, view.window.z, view.window.w } },
        { "required_resolution", tile.requiredResolution }, { "effective_resolution", tile.effectiveResolution },
        { "met", tile.met() }, { "receiver_samples", tile.samples } });
    }
    const NamedImage* unmet = findNamed(frame.buffers, "fvsm_unmet");
    int unmetPixels = 0;
    for (std::size_t i = 0; unmet && i < unmet->image.data.size(); ++i)
    {
      unmetPixels += unmet->image.data[i] > 0.5f ? 1 : 0;
    }
    const int tileSize = tree.settings.tileSize;
    stats["light_view"]["fvsm"] = { { "tile_size", tileSize }, { "max_level", tree.settings.maxLevel },
      { "max_tiles", tree.settings.maxTiles }, { "grid_size", tree.gridSize },
      { "root_rect", { tree.rootRect.x, tree.rootRect.y, tree.rootRect.z, tree.rootRect.w } },
      { "tile_count", tree.tiles.size() },
      { "total_texels", static_cast<double>(frame.partitions->viewCount()) * tileSize * tileSize },
      { "budget_reached", tree.budgetReached }, { "level_reached", tree.levelReached },
      { "prepass_samples", fvsm.prepass.samples }, { "unmet_pixels", unmetPixels }, { "tiles", tiles } };
  }
  if (frame.partitions && frame.partitions->kind == PartitionKind::CubeFaces)
  {
    // Survey §2: the faces that own visible receivers, each with its map (window in tangents of the face's axis: a
    // face's map reaches past +-1, its 90-degree pyramid, only by the focus's margin); the top-level light_view is the
    // first face's.
    const PartitionSet& faces = *frame.partitions;
    nlohmann::json list = nlohmann::json::array();
    for (int k = 0; k < faces.viewCount(); ++k)
    {
      const LightView& view = faces.views[static_cast<std::size_t>(k)];
      const int face = faces.viewFaces[static_cast<std::size_t>(k)];
      const glm::dvec3 axis = cubeFaceAxis(face);
      list.push_back({ { "face", cubeFaceName(face) }, { "map", "shadow_map_depth" + partitionViewSuffix(faces, k) },
        { "axis", { axis.x, axis.y, axis.z } }, { "resolution", view.resolution },
        { "texel_world_size_at_unit_depth", view.texelWorldSize(1.0) }, { "light_near_depth", view.nearDepth },
        { "light_far_depth", view.farDepth },
        { "window", { view.window.x, view.window.y, view.window.z, view.window.w } },
        { "receiver_samples", view.receiverSampleCount } });
    }
    stats["light_view"]["cube_faces"] = list;
  }
  if (frame.partitions && frame.partitions->kind == PartitionKind::Cascades)
  {
    // Survey §4.3.1: the split depths (eye depth) and each cascade's map; the top-level light_view is cascade 0's.
    const PartitionSet& cascades = *frame.partitions;
    nlohmann::json list = nlohmann::json::array();
    for (std::size_t k = 0; k < cascades.views.size(); ++k)
    {
      const LightView& view = cascades.views[k];
      nlohmann::json entry = { { "near", cascades.splits[k] }, { "far", cascades.splits[k + 1] },
        { "resolution", view.resolution }, { "texel_world_size", view.texelWorldSize(0.0) },
        { "light_near_depth", view.nearDepth }, { "light_far_depth", view.farDepth },
        { "window", { view.window.x, view.window.y, view.window.z, view.window.w } },
        { "receiver_samples", view.receiverSampleCount } };
      if (view.warp.active())
      {
        entry["warp_n"] = std::isfinite(view.warp.n) ? nlohmann::json(view.warp.n) : nlohmann::json();
      }
      list.push_back(entry);
    }
    stats["light_view"]["cascades"] = list;
    const CascadeSettings& settings = cascades.cascadeSettings;
    stats["light_view"]["split_scheme"] = splitSchemeName(settings.scheme);
    stats["light_view"]["split_lambda"] = settings.lambda;
    stats["light_view"]["cascade_selection"] = cascadeSelectionName(settings.selection);
    stats["light_view"]["cascade_blend"] = settings.blend;
    stats["light_view"]["cascade_snap"] = settings.snap;
  }
  stats["buffers"] = bufferSummaries(frame.buffers);
  nlohmann::json lightSpace = nlohmann::json::object();
  for (const NamedImage& named : frame.lightSpace)
  {
    lightSpace[named.name] = bufferSummary(named, nullptr);
  }
  stats["light_space"] = lightSpace;
  nlohmann::json objectSpace = nlohmann::json::object();
  for (const NamedPolyData& exported : frame.objectSpace)
  {
    objectSpace[exported.name] = { { "file", exported.name + ".vtp" }, { "points", exported.data->GetNumberOfPoints() },
      { "cells", exported.data->GetNumberOfCells() }, { "doc", exported.doc } };
  }
  if (!objectSpace.empty())
  {
    stats["object_space"] = objectSpace;
  }
  return stats;
}

nlohmann::json bufferSummaries(const std::vector<NamedImage>& buffers)
{
  nlohmann::json summaries = nlohmann::json::object();
  const bool hasCoverage = findNamed(buffers, "coverage") != nullptr;
  for (const NamedImage& named : buffers)
  {
    const bool overDomain = hasCoverage && named.name != "coverage";
    const ImageU8 mask = overDomain ? bufferValueMask(named, buffers) : ImageU8();
    const bool maskFits = mask.width == named.image.width && mask.height == named.image.height;
    summaries[named.name] = bufferSummary(named, overDomain && maskFits ? &mask : nullptr);
    summaries[named.name]["domain"] = !(overDomain && maskFits) ? "all pixels"
      : named.domain == BufferDomain::ShadowTested && findNamed(buffers, "shadow_tested") ? "shadow_tested"
                                                                                           : "covered";
  }
  return summaries;
}

void writeBufferFiles(const std::vector<NamedImage>& buffers, const std::vector<NamedImage>& lightSpace,
  const ImageU8* image, const std::filesystem::path& dir)
{
  writeVti(dir / "buffers.vti", buffers);
  if (!lightSpace.empty())
  {
    writeVti(dir / "light_space.vti", lightSpace);
  }
  if (image && !image->empty())
  {
    writePng(dir / "image.png", *image);
  }
  if (const NamedImage* visibility = findNamed(buffers, "visibility"))
  {
    writeExr(dir / "visibility.exr", visibility->image);
  }
  const NamedImage* coverage = findNamed(buffers, "coverage");
  SL_CHECK(coverage);
  std::vector<DrawnHeatMap> drawn;
  writeHeatMaps(buffers, &buffers, dir, "heatmap_", "buffers.vti", drawn);
  writeHeatMaps(lightSpace, nullptr, dir, "heatmap_", "light_space.vti", drawn);
  writeFileChecked(dir / "open_in_paraview.py",
    paraViewScript(drawn, glm::ivec2(coverage->image.width, coverage->image.height)));
}

void writeJson(const nlohmann::json& json, const std::filesystem::path& path)
{
  // Strings that are not UTF-8 (file names are any bytes on Linux) are written with U+FFFD, never refused
  // after the frame was rendered.
  writeFileChecked(path, json.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
}

void writeFrameOutputs(const FrameResult& frame, const OutputContext& context, const OutputTarget& target)
{
  writeDirectoryAtomically(target, [&](const std::filesystem::path& dir) {
    writeBufferFiles(frame.buffers, frame.lightSpace, &frame.image, dir);
    for (const NamedPolyData& exported : frame.objectSpace)
    {
      writeVtp(dir / (exported.name + ".vtp"), exported.data);
    }
    writeJson(frameStats(frame, context), dir / "stats.json");
  });
}

} // namespace sl
