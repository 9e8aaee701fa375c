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

  nlohmann::json parameters = nlohmann::json::object();
  for (const ParameterSpec& spec : last.parameters.specs())
  {
    parameters[spec.name] = spec.file ? nlohmann::json(last.parameters.file(spec.name))
      : spec.choices.empty()          ? nlohmann::json(last.parameters.get(spec.name))
                                      : nlohmann::json(last.parameters.choice(spec.name));
  }
  nlohmann::json stages = nlohmann::json::object();
  for (const StageTiming& stage : last.stages)
  {
    stages[stage.stage] = { { "gpu_ms", median(stageGpu[stage.stage]) }, { "wall_ms", median(stageWall[stage.stage]) } };
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
    { "stages", stages },
    { "frame_gpu_ms", median(frameGpu) },
    { "frame_wall_ms", median(frameWall) },
    { "technique_statistics", last.techniqueStatistics },
    { "work_counter_sums", workCounterSums(last) },
  };
  if (!options.referenceFile.empty())
  {
    const std::vector<NamedImage> reference = readVti(options.referenceFile);
    const ErrorMetrics metrics = computeErrorMetrics(last.find("visibility")->image,
      requireArray(reference, "visibility", options.referenceFile), last.find("coverage")->image,
      requireArray(reference, "coverage", options.referenceFile));
    result["error"] = metricsJson(metrics);
  }
  if (profileSettings)
  {
    result["depth_profile"] = depthProfileJson(depthProfile(last, *profileSettings));
  }
  writeJson(result, options.resultFile);
  return 0;
}

} // namespace sl
