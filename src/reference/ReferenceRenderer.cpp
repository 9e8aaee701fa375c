#include "reference/ReferenceRenderer.h"

#include "frame/FrameResult.h"

#include "core/Error.h"
#include "lightspace/LightView.h"
#include "reference/EmbreeScene.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <exception>
#include <limits>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

namespace sl
{

ReferenceInputs referenceInputsOf(const FrameResult& frame, const Scene& scene, int lightIndex)
{
  if (lightIndex < 0 || lightIndex >= static_cast<int>(scene.lights.size()))
  {
    throw InputError(format("--light ", lightIndex, ": the scene has ", scene.lights.size(), " light(s)"));
  }
  ReferenceInputs inputs;
  inputs.scene = &scene;
  inputs.light = &scene.lights[static_cast<std::size_t>(lightIndex)];
  inputs.position = frame.find("position")->image;
  inputs.normal = frame.find("normal")->image;
  inputs.coverage = frame.find("coverage")->image;
  inputs.receives = frame.find("receives_shadows")->image;
  return inputs;
}

namespace
{

// Shadow rays stop this relative distance short of the light, so the light's own plane (or a caster lying
// exactly in it) never blocks them.
constexpr double kLightEndShortening = 1e-6;
constexpr double kDefaultRayOffsetPerRadius = 1e-4;
// The progress callback is called at most this many times (plus a final 1.0).
constexpr int kProgressReports = 32;
// lightSampleMask packs this many sample bits into one float component (exact: < 2^24).
constexpr int kMaskBitsPerComponent = 16;

void validate(const ReferenceSettings& settings, const Light& light)
{
  if (settings.lightSampleSet)
  {
    const LightSampleSetSettings& set = *settings.lightSampleSet;
    // The CLI's own checks (pattern, count, seed), so a set built in code gets the same InputError, not an abort.
    lightSampleSetSettings(lightSamplePatternName(set), set.count, set.seed);
    if (light.type != LightType::Area)
    {
      throw InputError(format("--light-samples ", lightSamplePatternName(set), ": the light is a ",
        lightTypeName(light.type), " light; a light-sample set needs an area light"));
    }
  }
  if (settings.samples < 1)
  {
    throw InputError(format("--samples ", settings.samples, ": must be >= 1"));
  }
  if (settings.threads < 0)
  {
    throw InputError(format("--threads ", settings.threads, ": must be >= 0 (0 = all cores)"));
  }
  if (!std::isfinite(settings.rayOffset))
  {
    throw InputError(format("--ray-offset ", settings.rayOffset, ": must be a finite number (< 0: default)"));
  }
}

void checkInputs(const ReferenceInputs& inputs)
{
  SL_CHECK(inputs.scene != nullptr && inputs.light != nullptr);
  const int width = inputs.position.width;
  const int height = inputs.position.height;
  const auto sameSize = [&](const ImageF& image) { return image.width == width && image.height == height; };
  SL_CHECK_MSG(sameSize(inputs.normal) && sameSize(inputs.coverage) && sameSize(inputs.receives),
    "reference inputs differ in size: position ", width, "x", height, ", normal ", inputs.normal.width, "x",
    inputs.normal.height, ", coverage ", inputs.coverage.width, "x", inputs.coverage.height, ", receives ",
    inputs.receives.width, "x", inputs.receives.height);
  SL_CHECK(inputs.position.components >= 3 && inputs.normal.components >= 3);
  SL_CHECK(inputs.coverage.components >= 1 && inputs.receives.components >= 1);
}

struct PixelResult
{
  double visibility = 0.0;
  double standardError = 0.0;
};

// The estimate from `visible` of `sampleCount` samples, with the Bernoulli standard error (see the header).
PixelResult estimate(int visible, int sampleCount)
{
  const double visibility = static_cast<double>(visible) / sampleCount;
  const double standardError =
    sampleCount > 1 ? std::sqrt(visibility * (1.0 - visibility) / (sampleCount - 1)) : 0.5;
  return { visibility, standardError };
}

// Where a pixel's per-sample results go (light-sample sets only): its components of sampleCrossings and
// lightSampleMask.
struct SampleOutputs
{
  float* crossings = nullptr; // N values
  float* mask = nullptr;      // N / 16 values
};

// Everything a worker needs to shade one pixel; read-only during tracing.
struct Tracer
{
  const ReferenceInputs& inputs;
  const Light& light;
  const EmbreeScene& casters;
  const std::optional<LightSampler>& sampler; // area lights without a light-sample set only
  const std::optional<LightSampleSet>& sampleSet;
  double rayOffset;

  // With a light-sample set: counts the crossings of every sample of covered pixel (x, y) into `outputs`, sets
  // the mask bits of the hidden ones, and returns how many are hidden.
  int countSampleSet(int x, int y, const glm::dvec3& pWs, const glm::dvec3& nWs, std::uint64_t& rays,
    const SampleOutputs& outputs) const
  {
    const glm::dvec3 origin = pWs + rayOffset * nWs;
    const int sampleCount = sampleSet->count();
    int hidden = 0;
    std::uint32_t maskBits = 0;
    for (int i = 0; i < sampleCount; ++i)
    {
      const glm::dvec3 onLight = sampleSet->point(light, x, y, i);
      ++rays;
      const int crossed = casters.crossings(origin, onLight - origin, 0.0, 1.0 - kLightEndShortening);
      outputs.crossings[i] = static_cast<float>(crossed);
      // Hidden by the surface itself (on or below the tangent plane) or by at least one caster.
      if (glm::dot(nWs, onLight - pWs) <= 0.0 || crossed > 0)
      {
        ++hidden;
        maskBits |= 1u << (i % kMaskBitsPerComponent);
      }
      if ((i + 1) % kMaskBitsPerComponent == 0)
      {
        outputs.mask[i / kMaskBitsPerComponent] = static_cast<float>(maskBits);
        maskBits = 0;
      }
    }
    return hidden;
  }

  PixelResult pixel(int x, int y, std::uint64_t& rays, const SampleOutputs& outputs) const
  {
    if (inputs.coverage.at(x, y) <= 0.5f)
    {
      return { 0.0, 0.0 };
    }
    const glm::dvec3 pWs(inputs.position.at(x, y, 0), inputs.position.at(x, y, 1), inputs.position.at(x, y, 2));
    const glm::dvec3 nWs(inputs.normal.at(x, y, 0), inputs.normal.at(x, y, 1), inputs.normal.at(x, y, 2));
    // The per-sample arrays are computed at every covered pixel, whatever the pixel rules below decide.
    const int hiddenSamples = sampleSet ? countSampleSet(x, y, pWs, nWs, rays, outputs) : 0;
    if (inputs.receives.at(x, y) <= 0.5f)
    {
      return { 1.0, 0.0 };
    }
    if (!lightCanReach(light, pWs, nWs))
    {
      return { 0.0, 0.0 };
    }
    if (sampleSet)
    {
      return estimate(sampleSet->count() - hiddenSamples, sampleSet->count());
    }
    const glm::dvec3 origin = pWs + rayOffset * nWs;
    switch (light.type)
    {
      case LightType::Directional:
        ++rays;
        return { casters.occluded(origin, -light.direction, 0.0, std::numeric_limits<double>::infinity()) ? 0.0 : 1.0,
          0.0 };
      case LightType::Point:
      case LightType::Spot:
        ++rays;
        return { casters.occluded(origin, light.center - origin, 0.0, 1.0 - kLightEndShortening) ? 0.0 : 1.0, 0.0 };
      case LightType::Area:
        break;
    }
    const int sampleCount = sampler->sampleCount();
    int visible = 0;
    for (int i = 0; i < sampleCount; ++i)
    {
      const glm::dvec3 onLight = sampler->point(x, y, i);
      if (glm::dot(nWs, onLight - pWs) <= 0.0)
      {
        continue; // below the tangent plane: the surface itself hides this part of the light
      }
      ++rays;
      if (!casters.occluded(origin, onLight - origin, 0.0, 1.0 - kLightEndShortening))
      {
        ++visible;
      }
    }
    return estimate(visible, sampleCount);
  }
};

double secondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

} // namespace

double referenceRayOffset(const Scene& scene, const ReferenceSettings& settings)
{
  if (settings.rayOffset >= 0.0)
  {
    return settings.rayOffset;
  }
  const Bounds bounds = scene.bounds();
  return bounds.empty() ? 0.0 : kDefaultRayOffsetPerRadius * bounds.radius();
}

ReferenceResult renderReference(const ReferenceInputs& inputs, const ReferenceSettings& settings,
  const std::function<void(double fractionDone)>& progress)
{
  checkInputs(inputs);
  validate(settings, *inputs.light);
  const auto start = std::chrono::steady_clock::now();
  const Light& light = *inputs.light;
  const int width = inputs.position.width;
  const int height = inputs.position.height;

  ReferenceResult result;
  result.visibility = ImageF(width, height, 1, 0.0f);
  result.standardError = ImageF(width, height, 1, 0.0f);

  const EmbreeScene casters(*inputs.scene);
  std::optional<LightSampler> sampler;
  std::optional<LightSampleSet> sampleSet;
  if (settings.lightSampleSet)
  {
    sampleSet.emplace(*settings.lightSampleSet);
    result.sampleCrossings = ImageF(width, height, sampleSet->count(), 0.0f);
    result.lightSampleMask = ImageF(width, height, sampleSet->count() / kMaskBitsPerComponent, 0.0f);
  }
  else if (light.type == LightType::Area)
  {
    sampler.emplace(light, settings.samples, settings.sampling, settings.seed);
  }
  const Tracer tracer{ inputs, light, casters, sampler, sampleSet, referenceRayOffset(*inputs.scene, settings) };

  const int rowBegin = std::clamp(settings.rowBegin, 0, height);
  const int rowEnd = settings.rowEnd < 0 ? height : std::clamp(settings.rowEnd, rowBegin, height);
  const int tracedRows = rowEnd - rowBegin;
  const unsigned hardwareThreads = std::max(1u, std::thread::hardware_concurrency());
  const int threadCount =
    std::max(1, std::min(tracedRows, settings.threads > 0 ? settings.threads : static_cast<int>(hardwareThreads)));

  const auto traceStart = std::chrono::steady_clock::now();
  std::atomic<int> nextRow{ rowBegin };
  std::atomic<bool> stop{ false };
  std::atomic<std::uint64_t> raysTraced{ 0 };
  std::mutex mutex;
  std::condition_variable rowFinished;
  int rowsDone = 0;                // guarded by mutex
  std::exception_ptr workerError;  // guarded by mutex

  const auto work = [&]() {
    std::uint64_t rays = 0;
    try
    {
      for (int y = nextRow++; y < rowEnd && !stop; y = nextRow++)
      {
        for (int x = 0; x < width; ++x)
        {
          SampleOutputs outputs;
          if (sampleSet)
          {
            outputs.crossings = &result.sampleCrossings.at(x, y, 0);
            outputs.mask = &result.lightSampleMask.at(x, y, 0);
          }
          const PixelResult pixel = tracer.pixel(x, y, rays, outputs);
          result.visibility.at(x, y) = static_cast<float>(pixel.visibility);
          result.standardError.at(x, y) = static_cast<float>(pixel.standardError);
        }
        {
          const std::lock_guard<std::mutex> lock(mutex);
          ++rowsDone;
        }
        rowFinished.notify_one();
      }
    }
    catch (...)
    {
      const std::lock_guard<std::mutex> lock(mutex);
      if (!workerError)
      {
        workerError = std::current_exception();
      }
      stop = true;
    }
    raysTraced += rays;
    rowFinished.notify_one();
  };

  std::vector<std::thread> workers;
  workers.reserve(static_cast<std::size_t>(threadCount));
  const auto joinAll = [&]() {
    for (std::thread& worker : workers)
    {
      if (worker.joinable())
      {
        worker.join();
      }
    }
  };
  try
  {
    for (int i = 0; i < threadCount; ++i)
    {
      workers.emplace_back(work);
    }
    if (progress && tracedRows > 0)
    {
      const int rowsPerReport = std::max(1, (tracedRows + kProgressReports - 1) / kProgressReports);
      int reported = 0;
      while (true)
      {
        int done;
        {
          std::unique_lock<std::mutex> lock(mutex);
          const int target = std::min(tracedRows, reported + rowsPerReport);
          rowFinished.wait(lock, [&]() { return rowsDone >= target || stop; });
          done = rowsDone;
        }
        if (stop || done >= tracedRows)
        {
          break;
        }
        reported = done;
        progress(static_cast<double>(done) / tracedRows);
      }
    }
  }
  catch (...)
  {
    stop = true; // the progress callback cancelled (or a thread could not start)
    joinAll();
    throw;
  }
  joinAll();
  if (workerError)
  {
    std::rethrow_exception(workerError);
  }
  if (progress)
  {
    progress(1.0);
  }

  const double traceSeconds = secondsSince(traceStart);
  result.raysTraced = raysTraced;
  result.seconds = secondsSince(start);
  result.raysPerSecond = traceSeconds > 0.0 ? static_cast<double>(result.raysTraced) / traceSeconds : 0.0;
  return result;
}

ReferenceResult renderMultisampleReference(const std::vector<ReferenceInputs>& perSample,
  const ReferenceSettings& settings, const std::function<void(double fractionDone)>& progress)
{
  SL_CHECK(!perSample.empty());
  if (settings.lightSampleSet)
  {
    throw InputError("--light-samples: per-sample facts of one surface point; not available with --msaa (multisample mode)");
  }
  const auto start = std::chrono::steady_clock::now();
  const int samples = static_cast<int>(perSample.size());
  std::vector<ReferenceResult> traced;
  for (int s = 0; s < samples; ++s)
  {
    const auto sampleProgress = [&](double fraction) {
      if (progress)
      {
        progress((s + fraction) / samples);
      }
    };
    traced.push_back(renderReference(perSample[static_cast<std::size_t>(s)], settings, sampleProgress));
  }
  const int width = traced.front().visibility.width;
  const int height = traced.front().visibility.height;
  ReferenceResult result;
  result.visibility = ImageF(width, height, 1, 0.0f);
  result.standardError = ImageF(width, height, 1, 0.0f);
  double traceSeconds = 0.0;
  for (const ReferenceResult& one : traced)
  {
    SL_CHECK(one.visibility.width == width && one.visibility.height == height);
    result.raysTraced += one.raysTraced;
    traceSeconds += one.raysPerSecond > 0.0 ? static_cast<double>(one.raysTraced) / one.raysPerSecond : 0.0;
  }
  for (int y = 0; y < height; ++y)
  {
    for (int x = 0; x < width; ++x)
    {
      if (perSample.front().coverage.at(x, y) <= 0.5f)
      {
        continue;
      }
      double sum = 0.0;
      double squaredErrors = 0.0;
      int covered = 0;
      for (int s = 0; s < samples; ++s)
      {
        if (perSample[static_cast<std::size_t>(s)].coverage.at(x, y) > 0.5f)
        {
          const ReferenceResult& one = traced[static_cast<std::size_t>(s)];
          sum += one.visibility.at(x, y);
          squaredErrors += static_cast<double>(one.standardError.at(x, y)) * one.standardError.at(x, y);
          ++covered;
        }
      }
      result.visibility.at(x, y) = static_cast<float>(sum / covered);
      result.standardError.at(x, y) = static_cast<float>(std::sqrt(squaredErrors) / covered);
    }
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.raysPerSecond = traceSeconds > 0.0 ? static_cast<double>(result.raysTraced) / traceSeconds : 0.0;
  return result;
}

} // namespace sl
