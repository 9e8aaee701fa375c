// ss08's multisample support (Schwarz and Stamminger 2008 §7, Fig. 9): a 4x multisampled G-buffer whose
// first sample feeds the passes, soft shadows once per pixel, and the custom resolve (passes/vtkSLMsaaResolvePass.h,
// CPU twin frame/MsaaResolve.h), checked
//  - against its twin bit for bit, and at the extremes tau = 0 (every sample off the first's depth looks for the
//    closest depth) and tau = infinity (one visibility per pixel);
//  - where a pixel's samples agree, against the single-sampled render;
//  - on silhouette pixels, against the ray tracer's multisample mode (each sample position traced, averaged): the
//    neighbour rule beats one visibility per pixel (Fig. 9 right against left);
//  - the reference's per-sample G-buffers against the sample positions GL reports.
// Frames 128^2 (64^2 for the geometry check), shadow maps 256^2-512^2 (llvmpipe).
#include "frame/MsaaResolve.h"
#include "metrics/ErrorMetrics.h"
#include "probe/Probe.h"
#include "reference/ReferenceRenderer.h"
#include "support/TestSupport.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace sl
{
namespace
{

constexpr int kMsaaFrameSize = 128;
constexpr int kSamples = 4;
constexpr double kPerPixel = 1e30; // tau at which every sample takes its pixel's visibility

using test::bufferOf;

FrameResult renderSs08(const Scene& scene, const std::vector<std::string>& settings)
{
  std::vector<std::string> all = { "shadow_map_size=512" };
  all.insert(all.end(), settings.begin(), settings.end());
  return test::renderDataset(scene, "ss08", kMsaaFrameSize, kMsaaFrameSize, all);
}

FrameResult renderMultisampled(const Scene& scene, double tolerance)
{
  return renderSs08(scene, { "msaa=4", "msaa_depth_tolerance=" + std::to_string(tolerance) });
}

MsaaResolved twinOf(const FrameResult& frame, double tolerance)
{
  MsaaResolveInputs inputs;
  inputs.pixelVisibility = &bufferOf(frame, "msaa_pixel_visibility");
  inputs.firstCoverage = &bufferOf(frame, "coverage");
  inputs.firstDepth = &bufferOf(frame, "depth");
  inputs.sampleDepth = &bufferOf(frame, "msaa_sample_depth");
  return msaaResolve(inputs, tolerance);
}

int countMismatches(const ImageF& gpu, const ImageF& twin)
{
  EXPECT_EQ(gpu.data.size(), twin.data.size());
  int mismatches = 0;
  for (std::size_t i = 0; i < gpu.data.size() && i < twin.data.size(); ++i)
  {
    mismatches += gpu.data[i] == twin.data[i] ? 0 : 1;
  }
  return mismatches;
}

bool firstCovered(const FrameResult& frame, int x, int y)
{
  return bufferOf(frame, "coverage").at(x, y) > 0.5f;
}

// A silhouette pixel, decided from the geometry alone (not from tau): its first sample is covered and another
// sample is uncovered or lies more than 2 % deeper or nearer (another surface: Fig. 9's ear over the ground).
bool isSilhouette(const FrameResult& frame, int x, int y)
{
  if (!firstCovered(frame, x, y))
  {
    return false;
  }
  const ImageF& depths = bufferOf(frame, "msaa_sample_depth");
  const float first = depths.at(x, y, 0);
  for (int s = 1; s < kSamples; ++s)
  {
    const float depth = depths.at(x, y, s);
    if (depth == 0.0f || std::abs(depth - first) > 0.02f * first)
    {
      return true;
    }
  }
  return false;
}

class Ss08MsaaResolve : public testing::TestWithParam<double>
{
};

TEST_P(Ss08MsaaResolve, MatchesItsTwinBitForBitAndReducesAtTheExtremes)
{
  const double tolerance = GetParam();
  const Scene scene = test::loadDataset("bunny");
  const FrameResult frame = renderMultisampled(scene, tolerance);
  ASSERT_EQ(frame.samplePositions.size(), static_cast<std::size_t>(kSamples));
  for (std::size_t s = 0; s < frame.samplePositions.size(); ++s)
  {
    const glm::dvec2 position = frame.samplePositions[s];
    EXPECT_TRUE(position.x >= 0.0 && position.x < 1.0 && position.y >= 0.0 && position.y < 1.0) << "sample " << s;
    for (std::size_t t = 0; t < s; ++t)
    {
      EXPECT_NE(position, frame.samplePositions[t]) << "samples " << t << " and " << s;
    }
  }
  const MsaaResolved twin = twinOf(frame, tolerance);
  EXPECT_EQ(countMismatches(bufferOf(frame, "visibility"), twin.visibility), 0);
  EXPECT_EQ(countMismatches(bufferOf(frame, "msaa_sample_visibility"), twin.sampleVisibility), 0);
  EXPECT_EQ(countMismatches(bufferOf(frame, "msaa_distinct_samples"), twin.distinctSamples), 0);
  EXPECT_EQ(countMismatches(bufferOf(frame, "msaa_interpolated_samples"), twin.interpolatedSamples), 0);

  // The extremes, from the buffers themselves: tau = infinity gives each covered sample its pixel's visibility
  // (per pixel, Fig. 9 left); tau = 0 sends every sample whose depth is not the first's exactly to the closest depth.
  const ImageF& depths = bufferOf(frame, "msaa_sample_depth");
  const ImageF& distinct = bufferOf(frame, "msaa_distinct_samples");
  const ImageF& interpolated = bufferOf(frame, "msaa_interpolated_samples");
  int interpolatedTotal = 0;
  int pixelsWithDistinct = 0;
  for (int y = 0; y < kMsaaFrameSize; ++y)
  {
    for (int x = 0; x < kMsaaFrameSize; ++x)
    {
      interpolatedTotal += static_cast<int>(interpolated.at(x, y));
      pixelsWithDistinct += distinct.at(x, y) > 0.0f ? 1 : 0;
      if (!firstCovered(frame, x, y))
      {
        continue;
      }
      int offFirstDepth = 0;
      for (int s = 0; s < kSamples; ++s)
      {
        offFirstDepth += depths.at(x, y, s) != 0.0f && depths.at(x, y, s) != depths.at(x, y, 0) ? 1 : 0;
      }
      if (tolerance == kPerPixel)
      {
        ASSERT_EQ(distinct.at(x, y), 0.0f) << x << "," << y;
        ASSERT_NEAR(bufferOf(frame, "visibility").at(x, y), bufferOf(frame, "msaa_pixel_visibility").at(x, y), 1e-6)
          << x << "," << y;
      }
      if (tolerance == 0.0)
      {
        ASSERT_EQ(distinct.at(x, y), static_cast<float>(offFirstDepth)) << x << "," << y;
      }
    }
  }
  std::cout << "[ measured ] ss08 msaa=4 bunny, tau " << tolerance << ": " << pixelsWithDistinct
            << " pixels with distinct samples, " << interpolatedTotal << " samples interpolated\n";
  // The twin check means something only if the neighbour rule ran.
  EXPECT_GT(interpolatedTotal, 0);
  EXPECT_GT(pixelsWithDistinct, 0);
}

INSTANTIATE_TEST_SUITE_P(Tolerances, Ss08MsaaResolve, testing::Values(0.0, 0.001, kPerPixel),
  [](const testing::TestParamInfo<double>& info) {
    return info.param == 0.0 ? std::string("PerSample") : info.param == kPerPixel ? std::string("PerPixel") : "Default";
  });

class Ss08MsaaScene : public testing::TestWithParam<std::string>
{
};

TEST_P(Ss08MsaaScene, AgreeingPixelsEqualTheSingleSampledRender)
{
  const Scene scene = test::loadDataset(GetParam());
  const FrameResult single = renderSs08(scene, {});
  const FrameResult multi = renderSs08(scene, { "msaa=4" });
  const ImageF& depths = bufferOf(multi, "msaa_sample_depth");
  int agreeing = 0;
  int close = 0;
  int exact = 0;
  double squaredSum = 0.0;
  for (int y = 0; y < kMsaaFrameSize; ++y)
  {
    for (int x = 0; x < kMsaaFrameSize; ++x)
    {
      bool allCovered = firstCovered(multi, x, y) && firstCovered(single, x, y);
      for (int s = 0; s < kSamples; ++s)
      {
        allCovered = allCovered && depths.at(x, y, s) != 0.0f;
      }
      if (!allCovered || bufferOf(multi, "msaa_distinct_samples").at(x, y) != 0.0f)
      {
        continue;
      }
      ++agreeing;
      // Every sample took the pixel's visibility ...
      ASSERT_NEAR(bufferOf(multi, "visibility").at(x, y), bufferOf(multi, "msaa_pixel_visibility").at(x, y), 1e-6);
      // ... which was evaluated where the single-sampled render evaluates, up to where the rasteriser interpolates
      // the first sample's attributes (llvmpipe: within ~0.1 pixel of the centre).
      const double difference = bufferOf(multi, "visibility").at(x, y) - bufferOf(single, "visibility").at(x, y);
      squaredSum += difference * difference;
      close += std::abs(difference) <= 0.02 ? 1 : 0;
      exact += difference == 0.0 ? 1 : 0;
    }
  }
  ASSERT_GT(agreeing, kMsaaFrameSize * kMsaaFrameSize / 4);
  const double rmse = std::sqrt(squaredSum / agreeing);
  std::cout << "[ measured ] ss08 msaa=4 " << GetParam() << ": " << agreeing << " pixels whose samples agree; against the "
            << "single-sampled render " << exact << " equal, " << close << " within 0.02, RMSE " << rmse << "\n";
  EXPECT_GE(close, 0.98 * agreeing);
  EXPECT_LE(rmse, 0.03);
}

TEST_P(Ss08MsaaScene, NeighbourRuleLowersTheSilhouetteErrorAgainstTheMultisampledReference)
{
  const Scene scene = test::loadDataset(GetParam());
  const FrameResult perPixel = renderMultisampled(scene, kPerPixel);
  const FrameResult neighbours = renderSs08(scene, { "msaa=4" });
  std::vector<ReferenceInputs> inputs;
  for (const FrameResult& sample : test::renderSampleGBuffers(scene, kMsaaFrameSize, kMsaaFrameSize, kSamples))
  {
    inputs.push_back(test::referenceInputs(sample, scene));
  }
  ReferenceSettings settings;
  settings.samples = 256;
  const ReferenceResult reference = renderMultisampleReference(inputs, settings);

  double perPixelSquared = 0.0;
  double neighbourSquared = 0.0;
  double allPerPixel = 0.0;
  double allNeighbour = 0.0;
  int silhouettes = 0;
  int covered = 0;
  for (int y = 0; y < kMsaaFrameSize; ++y)
  {
    for (int x = 0; x < kMsaaFrameSize; ++x)
    {
      if (!firstCovered(neighbours, x, y))
      {
        continue;
      }
      const double truth = reference.visibility.at(x, y);
      const double perPixelError = bufferOf(perPixel, "visibility").at(x, y) - truth;
      const double neighbourError = bufferOf(neighbours, "visibility").at(x, y) - truth;
      allPerPixel += perPixelError * perPixelError;
      allNeighbour += neighbourError * neighbourError;
      ++covered;
      if (isSilhouette(neighbours, x, y))
      {
        perPixelSquared += perPixelError * perPixelError;
        neighbourSquared += neighbourError * neighbourError;
        ++silhouettes;
      }
    }
  }
  ASSERT_GT(silhouettes, 50);
  const double perPixelRmse = std::sqrt(perPixelSquared / silhouettes);
  const double neighbourRmse = std::sqrt(neighbourSquared / silhouettes);
  std::cout << "[ measured ] ss08 msaa=4 " << GetParam() << ", " << silhouettes << " silhouette pixels against the "
            << "multisampled reference: RMSE " << perPixelRmse << " with one visibility per pixel, " << neighbourRmse
            << " with the neighbour rule; all " << covered << " covered pixels: " << std::sqrt(allPerPixel / covered)
            << " and " << std::sqrt(allNeighbour / covered) << "\n";
  EXPECT_LT(neighbourRmse, 0.8 * perPixelRmse);
  EXPECT_LE(std::sqrt(allNeighbour / covered), std::sqrt(allPerPixel / covered));
}

INSTANTIATE_TEST_SUITE_P(Datasets, Ss08MsaaScene, testing::Values("bunny", "stacked-occluders"),
  [](const testing::TestParamInfo<std::string>& info) {
    std::string name = info.param;
    for (char& c : name)
    {
      c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
    }
    return name;
  });

TEST(Ss08Msaa, ProbeReplaysTheFirstSampleAndRecordsTheResolve)
{
  // On silhouette pixels the resolved visibility is not the twin's (samples took neighbours' values); the probe
  // compares the twin with the visibility before the resolve and records what each sample took.
  const Scene scene = test::loadDataset("bunny");
  const FrameResult frame = renderSs08(scene, { "msaa=4" });
  int probed = 0;
  for (int y = 0; y < kMsaaFrameSize && probed < 3; ++y)
  {
    for (int x = 0; x < kMsaaFrameSize && probed < 3; ++x)
    {
      if (!isSilhouette(frame, x, y) || bufferOf(frame, "msaa_interpolated_samples").at(x, y) == 0.0f ||
        bufferOf(frame, "visibility").at(x, y) == bufferOf(frame, "msaa_pixel_visibility").at(x, y))
      {
        continue;
      }
      const ProbeResult probe = probePixel(frame, scene, 0, { x, y });
      EXPECT_EQ(probe.gpuVisibility, bufferOf(frame, "msaa_pixel_visibility").at(x, y));
      EXPECT_TRUE(probe.agrees()) << x << "," << y << ": twin " << probe.outcome.visibility << ", gpu " << probe.gpuVisibility;
      int resolveQuantities = 0;
      for (const ProbeQuantity& quantity : probe.record.quantities)
      {
        if (quantity.group == "msaa resolve" && quantity.name == "resolved visibility")
        {
          EXPECT_EQ(quantity.value.at(0), bufferOf(frame, "visibility").at(x, y));
        }
        resolveQuantities += quantity.group == "msaa resolve" ? 1 : 0;
      }
      EXPECT_EQ(resolveQuantities, 2 * kSamples + 2) << x << "," << y;
      ++probed;
    }
  }
  EXPECT_EQ(probed, 3);
}

// The reference's per-sample G-buffer frames of `scene` and ss08's multisampled frame of it, size x size.
std::pair<std::vector<FrameResult>, FrameResult> sampleFramesBesideMultisampledFrame(const Scene& scene, int size)
{
  return { test::renderSampleGBuffers(scene, size, size, kSamples),
    test::renderDataset(scene, "ss08", size, size, { "shadow_map_size=256", "msaa=4" }) };
}

TEST(MultisampleReference, EachSampleGBufferSeesItsSamplePosition)
{
  // Frame s of renderSampleGBuffers holds at pixel (x, y) the surface on the camera ray through window position
  // (x + p_s.x, y + p_s.y) of the unshifted camera, and covers what sample s of the multisampled G-buffer covers.
  constexpr int size = 64;
  const Scene scene = test::loadDataset("bunny");
  const auto [samples, multi] = sampleFramesBesideMultisampledFrame(scene, size);
  ASSERT_EQ(samples.size(), static_cast<std::size_t>(kSamples));
  const CameraView& camera = multi.camera;
  const ImageF& depths = bufferOf(multi, "msaa_sample_depth");
  int coverageAgrees = 0;
  for (int s = 0; s < kSamples; ++s)
  {
    const glm::dvec2 position = multi.samplePositions[static_cast<std::size_t>(s)];
    const ImageF& points = bufferOf(samples[static_cast<std::size_t>(s)], "position");
    const ImageF& coverage = bufferOf(samples[static_cast<std::size_t>(s)], "coverage");
    double worstOffRay = 0.0;
    for (int y = 0; y < size; ++y)
    {
      for (int x = 0; x < size; ++x)
      {
        const bool covered = coverage.at(x, y) > 0.5f;
        coverageAgrees += covered == (depths.at(x, y, s) != 0.0f) ? 1 : 0;
        if (!covered)
        {
          continue;
        }
        const glm::dvec3 nearPoint = unprojectPixel(camera, x + position.x, y + position.y, -1.0);
        const glm::dvec3 direction = glm::normalize(unprojectPixel(camera, x + position.x, y + position.y, 1.0) - nearPoint);
        const glm::dvec3 point(points.at(x, y, 0), points.at(x, y, 1), points.at(x, y, 2));
        const glm::dvec3 offRay = (point - nearPoint) - glm::dot(point - nearPoint, direction) * direction;
        worstOffRay = std::max(worstOffRay, glm::length(offRay) / glm::length(point - nearPoint));
      }
    }
    // A pixel spans ~ 2 tan(fov / 2) / size radians; 1 % of one is far below the half-pixel error a missing
    // shift would make.
    const double pixelAngle = 2.0 * std::tan(glm::radians(scene.camera.viewAngleDeg) / 2.0) / size;
    EXPECT_LT(worstOffRay, 0.01 * pixelAngle) << "sample " << s;
  }
  const double agreement = static_cast<double>(coverageAgrees) / (kSamples * size * size);
  std::cout << "[ measured ] reference sample G-buffers: coverage agrees with the multisampled G-buffer's samples on "
            << 100.0 * agreement << " % of (pixel, sample) pairs\n";
  EXPECT_GE(agreement, 0.995);
}

TEST(MultisampleReference, EachSampleGBufferTestsAlphaAtThePixelCentre)
{
  // The multisampled G-buffer runs one fragment per pixel and primitive: a perforated caster's alpha test decides at
  // the pixel centre for all its samples, so sample s shows the caster or what lies behind it as the centre does. The
  // reference's sample frames must decide the same way, or they trace other surfaces than the frame shades (the
  // differential sweep's seed 4: V 1 on the `leaves` quad against 0.36 traced on the ground below its holes). Measured:
  // 1316 of 16 384 pairs with the alpha test at each sample's own position, 8 at the pixel centre (uv's derivatives).
  constexpr int size = 64;
  const auto [samples, multi] = sampleFramesBesideMultisampledFrame(test::loadDataset("fence"), size);
  ASSERT_EQ(samples.size(), static_cast<std::size_t>(kSamples));
  const ImageF& depths = bufferOf(multi, "msaa_sample_depth");
  int compared = 0;
  int otherSurface = 0;
  for (int s = 0; s < kSamples; ++s)
  {
    const ImageF& depth = bufferOf(samples[static_cast<std::size_t>(s)], "depth");
    const ImageF& coverage = bufferOf(samples[static_cast<std::size_t>(s)], "coverage");
    for (int y = 0; y < size; ++y)
    {
      for (int x = 0; x < size; ++x)
      {
        const double multiDepth = depths.at(x, y, s);
        if (coverage.at(x, y) > 0.5f && multiDepth != 0.0)
        {
          ++compared;
          // The same surface: within the depth change a fraction of a pixel makes; the fence stands 1 unit before the
          // ground, ~15 % of the view depth.
          otherSurface += std::abs(depth.at(x, y) - multiDepth) > 0.03 * multiDepth ? 1 : 0;
        }
      }
    }
  }
  std::cout << "[ measured ] fence, 4 samples: " << otherSurface << " of " << compared
            << " (pixel, sample) pairs show another surface in the reference's sample frame\n";
  EXPECT_GT(compared, kSamples * size * size / 2);
  EXPECT_LE(otherSurface, compared / 1000);
}

} // namespace
} // namespace sl
