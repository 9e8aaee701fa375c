// shadowlab bench-run (hidden, started by `bench`): one configuration in its own process.
#include "cli/Commands.h"

#include "core/Error.h"
#include "io/ImageIO.h"
#include "output/OutputWriter.h"
#include "metrics/Comparison.h"
#include "metrics/DepthProfile.h"
#include "metrics/ErrorMetrics.h"
#include "pipeline/ShadowRenderer.h"
#include "scene/Scene.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>

namespace sl
{
namespace
{

double median(std::vector<double> values)
{
  SL_CHECK(!values.empty());
  std::sort(values.begin(), values.end());
  const std::size_t middle = values.size() / 2;
  return values.size() % 2 ? values[middle] : 0.5 * (values[middle - 1] + values[middle]);
}

// `<key>` (the median, the number every reader of bench.json already takes), `<key>_min` and `<key>_max` over the
// --repeat frames into `target`: the spread says how far one frame's time can be trusted.
void putTimingSpread(nlohmann::json& target, const std::string& key, const std::vector<double>& values)
{
  target[key] = median(values);
  target[key + "_min"] = *std::min_element(values.begin(), values.end());
  target[key + "_max"] = *std::max_element(values.begin(), values.end());
}

// The nearest-rank 99th percentile of |error| over `errors` (0 for none), as viewStatistics ranks: unlike the largest
// error, which one misplaced silhouette pixel sets to 1 in almost every frame, it tells techniques apart.
double percentile99(std::vector<double> errors)
{
  if (errors.empty())
  {
    return 0.0;
  }
  std::sort(errors.begin(), errors.end());
  const std::size_t rank = static_cast<std::size_t>(std::ceil(0.99 * static_cast<double>(errors.size())));
  return errors[std::max<std::size_t>(rank, 1) - 1];
}

// metricsJson plus each set's p99_abs_error (the penumbra: the reference strictly inside (0, 1), ErrorMetrics.h).
nlohmann::json benchErrorJson(const Comparison& comparison)
{
  std::vector<double> coveredErrors;
  std::vector<double> penumbraErrors;
  for (std::size_t i = 0; i < comparison.error.pixelCount(); ++i)
  {
    if (comparison.mask.data[i] > 0.5f)
    {
      const double magnitude = std::abs(static_cast<double>(comparison.error.data[i]));
      coveredErrors.push_back(magnitude);
      const float referenceValue = comparison.reference.data[i];
      if (referenceValue > 0.0f && referenceValue < 1.0f)
      {
        penumbraErrors.push_back(magnitude);
      }
    }
  }
  nlohmann::json json = metricsJson(comparison.metrics);
  json["covered"]["p99_abs_error"] = percentile99(std::move(coveredErrors));
  json["penumbra"]["p99_abs_error"] = percentile99(std::move(penumbraErrors));
  return json;
}

// `image` shrunk by box filtering to at most `longestSide` pixels across, counting only the pixels `mask` marks
// (an empty mask marks all); a thumbnail pixel none of whose pixels is marked is 0 and unmarked in `thumbnailMask`.
ImageF benchThumbnail(const ImageF& image, const ImageF& mask, int longestSide, ImageF* thumbnailMask)
{
  const int factor = std::max(1, (std::max(image.width, image.height) + longestSide - 1) / longestSide);
  const int width = std::max(1, image.width / factor);
  const int height = std::max(1, image.height / factor);
  ImageF thumbnail(width, height, 1, 0.0f);
  if (thumbnailMask)
  {
    *thumbnailMask = ImageF(width, height, 1, 0.0f);
  }
  for (int y = 0; y < height; ++y)
  {
    for (int x = 0; x < width; ++x)
    {
      double sum = 0.0;
      int marked = 0;
      for (int dy = 0; dy < factor; ++dy)
      {
        for (int dx = 0; dx < factor; ++dx)
        {
          const std::size_t source = static_cast<std::size_t>(y * factor + dy) * image.width + (x * factor + dx);
          if (mask.empty() || mask.data[source] > 0.5f)
          {
            sum += image.data[source];
            ++marked;
          }
        }
      }
      const std::size_t target = static_cast<std::size_t>(y) * width + x;
      thumbnail.data[target] = marked > 0 ? static_cast<float>(sum / marked) : 0.0f;
      if (thumbnailMask)
      {
        thumbnailMask->data[target] = marked > 0 ? 1.0f : 0.0f;
      }
    }
  }
  return thumbnail;
}

// The image-wide total of each work counter the technique publishes (buffers its descriptor sums over
// sub-lights, e.g. yfgl09's visited_nodes), over covered pixels like stats.json's means: Yang et al. 2009's
// Eq. 9 is a statement about this total, which a mean over pixels hides.
nlohmann::json workCounterSums(const FrameResult& frame)
{
  nlohmann::json sums = nlohmann::json::object();
  const NamedImage* coverage = frame.find("coverage");
  for (const BufferSpec& spec : frame.descriptor->buffers)
  {
    const NamedImage* counter = frame.find(spec.name);
    if (spec.subLightCombine != SubLightCombine::Sum || !counter)
    {
      continue;
    }
    const ImageF& image = counter->image;
    double sum = 0.0;
    for (std::size_t i = 0; i < image.pixelCount(); ++i)
    {
      if (coverage && coverage->image.data[i] <= 0.5f)
      {
        continue;
      }
      for (int c = 0; c < image.components; ++c)
      {
        sum += image.data[i * image.components + c];
      }
    }
    sums[spec.name] = sum;
  }
  return sums;
}

// The comma-separated buffer names of --view-stats; an empty item is refused.
std::vector<std::string> viewStatisticBuffers(const std::string& list)
{
  std::vector<std::string> names;
  for (std::size_t start = 0; !list.empty();)
  {
    const std::size_t comma = list.find(',', start);
    names.push_back(list.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (names.back().empty())
    {
      throw InputError("--view-stats " + list + ": an empty item in the comma-separated list");
    }
    if (comma == std::string::npos)
    {
      break;
    }
    start = comma + 1;
  }
  return names;
}

// A buffer's distribution over the view (--view-stats): its largest value, 99th percentile (nearest rank) and mean
// over the covered pixels whose value is finite and not 0 (the sampling-error buffers' 0 marks a pixel the map does
// not test, as in metrics/DepthProfile.h), and the eye depths (`depth`) those pixels span. The largest is the
// survey's storage-factor reading of Fig. 18 (the worst undersampling in the view); the 99th percentile says
// whether it is one pixel's.
nlohmann::json viewStatistics(const FrameResult& frame, const std::string& name)
{
  const NamedImage* named = frame.find(name);
  if (named == nullptr || named->image.components != 1)
  {
    throw InputError("--view-stats " + name + ": technique " + frame.technique + " (with these settings) has no "
      "one-component buffer of that name");
  }
  const ImageF& image = named->image;
  const ImageF& coverage = frame.find("coverage")->image;
  const ImageF& depth = frame.find("depth")->image;
  std::vector<double> values;
  double sum = 0.0;
  double depthMin = std::numeric_limits<double>::infinity();
  double depthMax = 0.0;
  for (std::size_t i = 0; i < image.pixelCount(); ++i)
  {
    const double value = image.data[i];
    if (coverage.data[i] <= 0.5f || !std::isfinite(value) || value == 0.0)
    {
      continue;
    }
    values.push_back(value);
    sum += value;
    depthMin = std::min(depthMin, static_cast<double>(depth.data[i]));
    depthMax = std::max(depthMax, static_cast<double>(depth.data[i]));
  }
  if (values.empty())
  {
    return { { "pixels", 0 } };
  }
  std::sort(values.begin(), values.end());
  const std::size_t rank = static_cast<std::size_t>(std::ceil(0.99 * static_cast<double>(values.size())));
  return { { "pixels", values.size() }, { "max", values.back() }, { "p99", values[std::max<std::size_t>(rank, 1) - 1] },
    { "mean", sum / static_cast<double>(values.size()) }, { "depth_min", depthMin }, { "depth_max", depthMax } };
}

} // namespace

int runBenchConfiguration(const BenchRunOptions& options)
{
  if (options.repeat < 1)
  {
    throw InputError("--repeat " + std::to_string(options.repeat) + ": must be >= 1");
  }
  const std::optional<DepthProfileSettings> profileSettings = options.depthProfile.empty()
    ? std::nullopt
    : std::optional(depthProfileSettings(options.depthProfile, options.depthBins, options.depthRange));
  const std::vector<std::string> viewStatisticNames = viewStatisticBuffers(options.viewStats);
  const Scene scene = loadScene(options.sceneFile, options.sceneOverrides);
  RenderRequest request;
  request.technique = options.technique;
  request.settings = options.settings;
  request.resolution = parseResolution(options.resolution);
  ShadowRenderer renderer;
  renderer.render(scene, request); // warm-up: shader compilation, allocations, driver caches

  std::map<std::string, std::vector<double>> stageGpu;
  std::map<std::string, std::vector<double>> stageWall;
  std::vector<double> frameGpu;
  std::vector<double> frameWall;
  FrameResult last;
  for (int frame = 0; frame < options.repeat; ++frame)
  {
    // Cold: every light-space structure built, as before reuse existed (the figures stay comparable).
    renderer.forgetLightSpaceBuilds();
    last = renderer.render(scene, request);
    double gpu = 0.0;
    for (const StageTiming& stage : last.stages)
    {
      stageGpu[stage.stage].push_back(stage.gpuMs);
      stageWall[stage.stage].push_back(stage.wallMs);
      gpu += stage.gpuMs;
    }
    frameGpu.push_back(gpu);
    frameWall.push_back(last.frameWallMs);
  }

  // Then as many warm frames: the scene and light unchanged, each structure's build reused (ShadowRenderer's
  // light-space reuse, as in the viewer), so the run tells a cold frame from a warm one.
  std::vector<double> warmFrameGpu;
  for (int frame = 0; frame < options.repeat; ++frame)
  {
    const FrameResult warm = renderer.render(scene, request);
    double gpu = 0.0;
    for (const StageTiming& stage : warm.stages)
    {
      gpu += stage.gpuMs;
    }
    warmFrameGpu.push_back(gpu);
  }

  nlohmann::json parameters = nlohmann::json::object();
  for (const ParameterSpec& spec : last.parameters.specs())
  {
    parameters[spec.name] = spec.file ? nlohmann::json(last.parameters.file(spec.name))
      : last.parameters.automatic(spec.name) ? nlohmann::json(spec.automatic)
      : spec.choices.empty()          ? nlohmann::json(last.parameters.get(spec.name))
                                      : nlohmann::json(last.parameters.choice(spec.name));
  }
  nlohmann::json stages = nlohmann::json::object();
  for (const StageTiming& stage : last.stages)
  {
    nlohmann::json timing = nlohmann::json::object();
    putTimingSpread(timing, "gpu_ms", stageGpu[stage.stage]);
    putTimingSpread(timing, "wall_ms", stageWall[stage.stage]);
    stages[stage.stage] = timing;
  }
  nlohmann::json structureBytes = nlohmann::json::object();
  std::size_t structureBytesTotal = 0;
  for (const auto& [name, bytes] : last.lightStructureGpuBytes)
  {
    structureBytes[name] = bytes;
    structureBytesTotal += bytes;
  }
  nlohmann::json result = {
    { "scene", options.sceneFile },
    { "scene_overrides", options.sceneOverrides },
    { "technique", options.technique },
    { "settings", options.settings },
    { "parameters", parameters },
    { "resolution", { last.resolution.x, last.resolution.y } },
    { "repeat", options.repeat },
    { "gl_renderer", last.glRenderer },
    { "gl_version", last.glVersion },
    { "egl_device", { { "index", last.eglDeviceIndex }, { "description", last.eglDevice } } },
    { "stages", stages },
    { "frame_gpu_ms_samples", frameGpu },
    { "technique_statistics", last.techniqueStatistics },
    { "work_counter_sums", workCounterSums(last) },
    { "light_structure_gpu_bytes", structureBytes },
    { "light_structure_gpu_bytes_total", structureBytesTotal },
  };
  if (const std::optional<int> size = last.shadowMapSize())
  {
    result["shadow_map_size_chosen"] = *size; // given, or chosen by shadow_map_size = auto
  }
  putTimingSpread(result, "frame_gpu_ms", frameGpu);
  putTimingSpread(result, "frame_wall_ms", frameWall);
  putTimingSpread(result, "warm_frame_gpu_ms", warmFrameGpu);
  // Small copies of the visibility (and, against a reference, of the reference and the error) beside the result,
  // <result>.thumbnail.vti: bench lays them out as its per-scene strip and removes them.
  const int thumbnailSide = 96;
  const ImageF& coverage = last.find("coverage")->image;
  ImageF visibleMask;
  std::vector<NamedImage> thumbnails{ { "visibility", benchThumbnail(last.find("visibility")->image, coverage,
    thumbnailSide, &visibleMask) } };
  thumbnails.push_back({ "visibility_mask", visibleMask });
  if (!options.referenceFile.empty())
  {
    const std::vector<NamedImage> reference = readVti(options.referenceFile);
    const ImageF& referenceCoverage = requireArray(reference, "coverage", options.referenceFile);
    const Comparison comparison = compareImages(last.find("visibility")->image,
      requireArray(reference, "visibility", options.referenceFile), coverage, referenceCoverage);
    result["error"] = benchErrorJson(comparison);
    ImageF errorMask;
    thumbnails.push_back({ "error", benchThumbnail(comparison.error, comparison.mask, thumbnailSide, &errorMask) });
    thumbnails.push_back({ "error_mask", errorMask });
    ImageF referenceMask;
    thumbnails.push_back({ "reference", benchThumbnail(comparison.reference, referenceCoverage, thumbnailSide,
      &referenceMask) });
    thumbnails.push_back({ "reference_mask", referenceMask });
  }
  std::filesystem::path thumbnailFile = options.resultFile;
  thumbnailFile.replace_extension(".thumbnail.vti");
  writeVti(thumbnailFile, thumbnails);
  if (profileSettings)
  {
    result["depth_profile"] = depthProfileJson(depthProfile(last, *profileSettings));
  }
  if (!viewStatisticNames.empty())
  {
    nlohmann::json statistics = nlohmann::json::object();
    for (const std::string& name : viewStatisticNames)
    {
      statistics[name] = viewStatistics(last, name);
    }
    result["view_stats"] = statistics;
  }
  writeJson(result, options.resultFile);
  return 0;
}

} // namespace sl
