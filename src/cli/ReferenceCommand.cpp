// shadowlab reference: the ray-traced ground truth (Embree) for the surface points the GPU pipeline
// shades. The G-buffer is rendered by the same pipeline (G-buffer stage only), then every covered pixel's
// visible fraction of the light is estimated with shadow rays (src/reference/ReferenceRenderer.h). With
// --light-samples, the samples are the shared light-sample set of technique `dcs` (lightspace/LightSampleSet.h)
// and every sample's crossing count and hidden bit are written too, to check dcs sample by sample.
#include "cli/Commands.h"

#include "cli/CommandProgress.h"
#include "cli/ReferenceTiles.h"
#include "core/Error.h"
#include "lightspace/LightSampleSet.h"
#include "output/OutputWriter.h"
#include "pipeline/ShadowRenderer.h"
#include "reference/ReferenceRenderer.h"
#include "scene/Scene.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <limits>
#include <optional>
#include <thread>

namespace sl
{

namespace
{

// The light-sample set --light-samples names, checked before anything is rendered (InputErrors of
// lightSampleSetSettings: "--light-samples spiral: ...", "--samples 10: ..."); none without the option.
std::optional<LightSampleSetSettings> lightSampleSetOf(const ReferenceOptions& options)
{
  if (options.lightSamples.empty())
  {
    if (options.lightSamplesGiven)
    {
      // `--light-samples ''` (an unset shell variable) would otherwise run the plain reference unnoticed.
      std::string names;
      for (const std::string& name : lightSamplePatternNames())
      {
        names += (names.empty() ? "" : ", ") + name;
      }
      throw InputError("--light-samples '': empty; expected one of " + names);
    }
    return std::nullopt;
  }
  if (options.seed > std::numeric_limits<std::uint32_t>::max())
  {
    throw InputError(
      format("--seed ", options.seed, ": must be < 2^32 with --light-samples (the sets' seeds are 32-bit)"));
  }
  const int count = options.samplesGiven ? options.samples : LightSampleSetSettings{}.count;
  try
  {
    return lightSampleSetSettings(options.lightSamples, count, static_cast<std::uint32_t>(options.seed));
  }
  catch (const InputError& error)
  {
    // lightSampleSetSettings names the count `--samples N`; name it as the user typed it.
    const std::string message = error.what();
    const std::string samplesPrefix = "--samples ";
    if (message.rfind(samplesPrefix, 0) != 0 || options.samplesOption == "--samples")
    {
      throw;
    }
    throw InputError(options.samplesOption + " " + message.substr(samplesPrefix.size()));
  }
}

} // namespace

int runReference(const ReferenceOptions& options, std::ostream& log)
{
  const std::optional<LightSampleSetSettings> sampleSet = lightSampleSetOf(options);
  if (options.samples < 1)
  {
    throw InputError(options.samplesOption + " " + std::to_string(options.samples) + ": must be >= 1");
  }
  if (options.sampling != "stratified" && options.sampling != "halton")
  {
    throw InputError("--sampling " + options.sampling + ": expected stratified or halton");
  }
  const int sampleCount = sampleSet ? sampleSet->count : options.samples;
  const std::string samplingName = sampleSet ? lightSamplePatternName(*sampleSet) : options.sampling;
  RenderRequest request;
  request.gbufferOnly = true;
  request.lightIndex = options.lightIndex;
  if (!options.resolution.empty())
  {
    request.resolution = parseResolution(options.resolution);
  }
  checkSceneOverrides(options.sceneOverrides);
  const Scene scene = loadScene(options.sceneFile, options.sceneOverrides);
  const OutputTarget output{ options.outDir, "reference", options.force, sceneInputs(scene, options.sceneFile) };
  checkOutputTarget(output);
  reportDroppedTriangles(scene, options.sceneFile, log);
  if (options.lightIndex < 0 || options.lightIndex >= static_cast<int>(scene.lights.size()))
  {
    throw InputError(format("--light ", options.lightIndex, ": the scene has ", scene.lights.size(), " light(s)"));
  }
  if (options.msaa != 1 && options.msaa != 4)
  {
    throw InputError(format("--msaa ", options.msaa, ": expected 1 or 4"));
  }
  if (options.msaa > 1 && sampleSet)
  {
    throw InputError("--light-samples: per-sample facts of one surface point; not available with --msaa 4");
  }
  if (!options.tile.empty())
  {
    parseRowTile(options.tile, std::numeric_limits<int>::max()); // its form, before anything is rendered
  }
  ShadowRenderer renderer;
  std::vector<FrameResult> sampleGBuffers = renderer.renderSampleGBuffers(scene, request, options.msaa);
  std::vector<ReferenceInputs> sampleInputs;
  for (const FrameResult& sampleGBuffer : sampleGBuffers)
  {
    sampleInputs.push_back(referenceInputsOf(sampleGBuffer, scene, options.lightIndex));
  }
  // The buffers written beside the reference: sample 0's G-buffer, the multisampled frame's coverage.
  FrameResult& gbuffer = sampleGBuffers.front();
  ReferenceSettings settings;
  settings.samples = options.samples;
  settings.sampling = options.sampling == "halton" ? LightSampling::Halton : LightSampling::Stratified;
  settings.seed = options.seed;
  settings.threads = options.threads;
  settings.lightSampleSet = sampleSet;
  std::optional<RowTile> tile;
  if (!options.tile.empty())
  {
    tile = parseRowTile(options.tile, gbuffer.resolution.y);
    settings.rowBegin = tile->rowBegin;
    settings.rowEnd = tile->rowEnd;
  }

  // Progress by rows (the renderer reports the fraction of rows done, about 33 times): on a terminal when the
  // trace is expected to take a few seconds, or with --progress (cli/CommandProgress.h).
  const ProgressSwitches switches{ options.progress, options.quiet };
  const std::size_t rows = static_cast<std::size_t>(tile ? tile->rowEnd - tile->rowBegin : gbuffer.resolution.y);
  Progress progress("reference", format(gbuffer.resolution.x, "x", gbuffer.resolution.y, " pixels x ", sampleCount,
      " samples", options.msaa > 1 ? format(" x ", options.msaa, " per pixel") : std::string()),
    "row", rows, commandProgressStream(switches, log), commandProgressSettings(switches));
  const auto rowsDone = [&progress, rows](double fraction) {
    progress.step(static_cast<std::size_t>(std::lround(fraction * static_cast<double>(rows))));
  };
  const ReferenceResult result = options.msaa > 1 ? renderMultisampleReference(sampleInputs, settings, rowsDone)
                                                 : renderReference(sampleInputs.front(), settings, rowsDone);
  progress.finish();

  std::vector<NamedImage> buffers;
  buffers.push_back({ "visibility", result.visibility, "", "ray-traced visible fraction of the light (ground truth)" });
  buffers.push_back({ "visibility_stderr", result.standardError, "", "standard error of the estimate (Bernoulli bound)" });
  if (sampleSet)
  {
    buffers.push_back({ "sample_crossings", result.sampleCrossings, "triangles",
      "per light sample (component i = sample i of the set): caster triangles crossed by the segment from the "
      "ray origin to the sample (depth complexity; 0 where uncovered)" });
    buffers.push_back({ "light_sample_mask", result.lightSampleMask, "bits",
      "16 samples per component: bit i % 16 of component i / 16 set when sample i is hidden (below the tangent "
      "plane or crossed); 0 where uncovered" });
  }
  for (NamedImage& named : gbuffer.buffers)
  {
    buffers.push_back(std::move(named));
  }
  nlohmann::json stats = {
    { "command", "reference" },
    { "scene", options.sceneFile },
    { "scene_overrides", options.sceneOverrides },
    { "light_index", options.lightIndex },
    { "resolution", { gbuffer.resolution.x, gbuffer.resolution.y } },
    { "samples", sampleCount },
    { "sampling", samplingName },
    { "seed", options.seed },
    { "threads", options.threads > 0 ? options.threads : static_cast<int>(std::thread::hardware_concurrency()) },
    { "ray_offset", referenceRayOffset(scene, settings) },
    { "msaa", options.msaa },
    { "rays_traced", result.raysTraced },
    { "seconds", result.seconds },
    { "rays_per_second", result.raysPerSecond },
    { "gl_renderer", gbuffer.glRenderer },
    { "egl_device", { { "index", gbuffer.eglDeviceIndex }, { "description", gbuffer.eglDevice } } },
  };
  if (sampleSet)
  {
    stats["light_samples"] = { { "pattern", samplingName }, { "count", sampleSet->count },
      { "seed", sampleSet->seed } };
  }
  if (tile)
  {
    // reference-merge reads it: which rows this directory traced (the others hold 0).
    stats["tile"] = { { "index", tile->index }, { "count", tile->count }, { "row_begin", tile->rowBegin },
      { "row_end", tile->rowEnd } };
  }
  stats["buffers"] = bufferSummaries(buffers);
  writeDirectoryAtomically(output, [&](const std::filesystem::path& dir) {
    writeBufferFiles(buffers, {}, nullptr, dir);
    writeJson(stats, dir / "stats.json");
  });
  if (!options.quiet)
  {
    log << "shadowlab: reference of " << printable(options.sceneFile) << " at " << gbuffer.resolution.x << "x"
        << gbuffer.resolution.y << ", " << sampleCount << " " << samplingName << " samples"
        << (sampleSet ? format(" (light-sample set, seed ", sampleSet->seed, ")") : std::string()) << ": " << std::fixed
        << std::setprecision(2) << result.seconds << " s, " << result.raysPerSecond * 1e-6 << " Mrays/s -> "
        << printable(options.outDir) << "\n";
  }
  return 0;
}

} // namespace sl
