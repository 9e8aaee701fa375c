// reference-sm against closed forms: on planar-occluder (square light of side 1 at height 3, square
// occluder of side 1 at height 1, both centred over the origin and parallel to the ground), the occluded
// fraction at a ground point p is the overlap of the light square with the occluder's projection through p
// onto the light plane: the occluder scaled by (H - 0) / (h - 0) = 3 about p.
#include "metrics/ErrorMetrics.h"
#include "reference/ReferenceRenderer.h"
#include "support/TestSupport.h"
#include "frame/ProbeRecord.h"
#include "techniques/Registry.h"
#include "techniques/referencesm/ReferenceSmTechnique.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>

namespace sl
{
namespace
{

// Visible fraction of the light from ground point (x, z) in planar-occluder.
double planarOccluderVisibility(double x, double z)
{
  return test::parallelSquaresVisibility(1.0, 3.0, 1.0, 1.0, x, z);
}

TEST(ReferenceSm, ConvergesToTheClosedFormOverlapOnThePlanarOccluder)
{
  const Scene scene = test::loadDataset("planar-occluder");
  test::GroundError previous;
  previous.penumbraRmse = 1e300;
  for (const int samples : { 16, 64, 256 })
  {
    const FrameResult frame = test::renderDataset(
      scene, "reference-sm", 128, 128, { "samples=" + std::to_string(samples), "shadow_map_size=1024" });
    const test::GroundError errors = test::groundErrorAgainst(frame, planarOccluderVisibility);
    std::cout << "[ measured ] reference-sm K=" << samples << ": RMSE " << errors.rmse << " (penumbra "
              << errors.penumbraRmse << " over " << errors.penumbra << " px), max " << errors.maxError << "\n";
    EXPECT_GT(errors.penumbra, 1000) << "the view must show a wide penumbra";
    EXPECT_LT(errors.penumbraRmse, previous.penumbraRmse) << "error must drop as K grows (K=" << samples << ")";
    previous = errors;
  }
  // At K = 256 the Hammersley estimate of a smooth overlap is within a few thousandths, plus the shadow
  // map's discretisation at the penumbra's ends.
  EXPECT_LT(previous.rmse, 0.01);
}

TEST(ReferenceSm, OneSampleOfAPointLightIsTheHardShadow)
{
  const Scene scene = test::loadDataset("sphere-point");
  const FrameResult reference = test::renderDataset(scene, "reference-sm", 96, 96, { "shadow_map_size=512" });
  const FrameResult hard = test::renderDataset(scene, "hard", 96, 96, { "shadow_map_size=512" });
  const ImageF& a = reference.find("visibility")->image;
  const ImageF& b = hard.find("visibility")->image;
  int differing = 0;
  for (std::size_t i = 0; i < a.data.size(); ++i)
  {
    differing += std::abs(a.data[i] - b.data[i]) > 1e-6f ? 1 : 0;
  }
  // Same light view up to the focus margin (reference-sm uses 1 texel, hard 1 texel too): identical maps.
  EXPECT_EQ(differing, 0);
  EXPECT_EQ(reference.find("sample_count")->image.at(48, 48), 1.0f);
}

TEST(ReferenceSm, AgreesWithTheRayTracedReferenceWithinItsDiscretisationError)
{
  // The two references of the project: K accumulated shadow maps on the GPU, and Embree shadow rays from
  // the same G-buffer points. On receivers they differ by the maps' discretisation and bias (and K vs the
  // ray count), most at penumbra ends; the bounds below hold that difference (measured on llvmpipe, with
  // slack) and are far below any real technique's error (pcf's RMSE is ~0.1 here). On the bunny the
  // comparison is over the ground: on its own curved, tessellated surface the smooth shading normals and
  // flat facets make self-shadowing near the terminator differ between depth bias and ray offset (printed).
  struct Case
  {
    const char* dataset;
    bool groundOnly;
    double maxRmse;
    double maxPenumbraRmse;
  };
  for (const Case& c : { Case{ "planar-occluder", false, 0.01, 0.02 }, Case{ "stacked-occluders", false, 0.015, 0.03 },
         Case{ "bunny", true, 0.01, 0.03 } })
  {
    const Scene scene = test::loadDataset(c.dataset);
    const FrameResult gpu =
      test::renderDataset(scene, "reference-sm", 128, 128, { "samples=256", "shadow_map_size=1024" });
    const ReferenceInputs inputs = test::referenceInputs(gpu, scene);
    ReferenceSettings settings;
    settings.samples = 1024;
    const ReferenceResult rays = renderReference(inputs, settings);
    ImageF compared = inputs.coverage;
    ImageF elsewhere = inputs.coverage;
    for (int y = 0; y < compared.height; ++y)
    {
      for (int x = 0; x < compared.width; ++x)
      {
        const bool ground = std::abs(inputs.position.at(x, y, 1)) < 1e-3f;
        compared.at(x, y) *= (!c.groundOnly || ground) ? 1.0f : 0.0f;
        elsewhere.at(x, y) *= ground ? 0.0f : 1.0f;
      }
    }
    const ImageF& visibility = gpu.find("visibility")->image;
    const ErrorMetrics metrics = computeErrorMetrics(visibility, rays.visibility, compared, compared);
    std::cout << "[ measured ] reference-sm (K=256) vs Embree (1024 rays) on " << c.dataset
              << (c.groundOnly ? " (ground)" : "") << ": RMSE " << metrics.covered.rmse << ", penumbra RMSE "
              << metrics.penumbra.rmse << " over " << metrics.penumbra.pixels << " px, max " << metrics.covered.maxAbsError;
    if (c.groundOnly)
    {
      const ErrorMetrics caster = computeErrorMetrics(visibility, rays.visibility, elsewhere, elsewhere);
      std::cout << "; on the caster's own surface RMSE " << caster.covered.rmse << " over " << caster.covered.pixels << " px";
    }
    std::cout << "\n";
    EXPECT_GT(metrics.penumbra.pixels, 100u) << c.dataset;
    EXPECT_LT(metrics.covered.rmse, c.maxRmse) << c.dataset;
    EXPECT_LT(metrics.penumbra.rmse, c.maxPenumbraRmse) << c.dataset;
  }
}

// The probe's replay (ReferenceSmReplay: the K samples' hard tests, each map's texel replayed by a ray through its
// centre, views fitted on the CPU) against the GPU on every covered pixel of two datasets: |GPU - replay| within the
// pixel's tolerance (K 2^-24 of float accumulation plus 1/K per sample the replay marks uncertain), and edge_samples
// equal to the replay's count up to the samples whose edge decision it marks uncertain. The measured
// maximum and the share of pixels with uncertain samples are printed: they are the probe's honest tolerance.
TEST(ReferenceSm, ProbeReplaysTheKHardTestsOfEveryPixel)
{
  struct Case
  {
    const char* dataset;
    std::vector<std::string> settings;
  };
  for (const Case& c : { Case{ "stacked-occluders", { "samples=16", "shadow_map_size=512" } },
         Case{ "fence", { "samples=8", "shadow_map_size=512", "seed=3" } },
         Case{ "contact", { "samples=8", "shadow_map_size=256", "caster_faces=back", "bias_constant_texels=0", "bias_slope_texels=0" } } })
  {
    const Scene scene = test::loadDataset(c.dataset);
    const FrameResult frame = test::renderDataset(scene, "reference-sm", 64, 64, c.settings);
    const ImageF& visibility = frame.find("visibility")->image;
    const ImageF& edgeSamples = frame.find("edge_samples")->image;
    ReferenceSmReplay replay(frame, scene);
    int withEdge = 0;
    int edgeBeyond = 0;
    std::string firstEdge;
    int evaluated = 0;
    int partial = 0;
    int withUncertain = 0;
    int uncertainSamples = 0;
    int beyond = 0;
    double maxDifference = 0.0;
    double maxCertainDifference = 0.0;
    std::string first;
    for (int y = 0; y < 64; ++y)
    {
      for (int x = 0; x < 64; ++x)
      {
        const ReferenceSmReplay::Pixel pixel = replay.replay({ x, y });
        const double difference = std::abs(pixel.visibility - visibility.at(x, y));
        evaluated += pixel.evaluated ? 1 : 0;
        partial += pixel.visibility > 0.0 && pixel.visibility < 1.0 ? 1 : 0;
        withUncertain += pixel.uncertain > 0 ? 1 : 0;
        uncertainSamples += pixel.uncertain;
        maxDifference = std::max(maxDifference, difference);
        if (pixel.uncertain == 0)
        {
          maxCertainDifference = std::max(maxCertainDifference, difference);
        }
        withEdge += pixel.edge > 0 ? 1 : 0;
        if (std::abs(pixel.edge - edgeSamples.at(x, y)) > pixel.edgeUncertain && edgeBeyond++ == 0)
        {
          firstEdge = format("pixel ", x, ",", y, ": GPU ", edgeSamples.at(x, y), " edge samples, replay ", pixel.edge,
            " (", pixel.edgeUncertain, " uncertain)");
        }
        if (difference > pixel.tolerance && beyond++ == 0)
        {
          first = format("pixel ", x, ",", y, ": GPU ", visibility.at(x, y), ", replay ", pixel.visibility, " (", pixel.lit,
            " lit, ", pixel.uncertain, " uncertain of ", replay.sampleCount(), ")");
        }
      }
    }
    std::cout << "[ measured ] reference-sm replay on " << c.dataset << " (K = " << replay.sampleCount() << "): "
              << evaluated << " pixels, " << partial << " partial, " << withUncertain << " with uncertain samples ("
              << uncertainSamples << " samples), max |GPU - replay| " << maxDifference << " (" << maxCertainDifference
              << " where no sample is uncertain), " << beyond << " beyond the pixel's tolerance; " << withEdge
              << " pixels with edge samples, " << edgeBeyond << " counted otherwise than the replay\n";
    EXPECT_EQ(beyond, 0) << c.dataset << ": " << first;
    EXPECT_EQ(edgeBeyond, 0) << c.dataset << ": " << firstEdge;
    EXPECT_GT(withEdge, 20) << c.dataset << ": penumbrae hold edges within a texel";
    EXPECT_GT(evaluated, 64 * 64 / 4) << c.dataset;
    EXPECT_GT(partial, 20) << c.dataset;
    EXPECT_LT(withUncertain, evaluated / 10) << c.dataset << ": the margins excuse too much";
  }
}

// Through the registry's probe: each light sample recorded (light coordinates inside the light, blocked or not),
// the lit ones making the visibility, and the buffers sample_count and visibility_stderr the GPU's; on a lit, a
// penumbra and an umbra pixel.
TEST(ReferenceSm, ProbeRecordsEveryLightSample)
{
  const Scene scene = test::loadDataset("planar-occluder");
  const FrameResult frame = test::renderDataset(scene, "reference-sm", 64, 64, { "samples=16", "shadow_map_size=512" });
  const ImageF& visibility = frame.find("visibility")->image;
  std::vector<glm::ivec2> pixels(3, glm::ivec2(-1));
  for (int y = 0; y < 64; ++y)
  {
    for (int x = 0; x < 64; ++x)
    {
      const float v = visibility.at(x, y);
      const int kind = v == 1.0f ? 0 : v == 0.0f ? 2 : 1;
      if (frame.find("coverage")->image.at(x, y) > 0.5f && pixels[kind].x < 0 && (x + 2 * y) % 5 == 0)
      {
        pixels[kind] = { x, y };
      }
    }
  }
  const Light& light = scene.lights[0];
  for (const glm::ivec2 pixel : pixels)
  {
    ASSERT_GE(pixel.x, 0);
    const std::string label = format("pixel ", pixel.x, ",", pixel.y);
    ProbeRecorder recorder;
    const ProbeOutcome outcome = findTechnique("reference-sm").probe({ &frame, &scene, 0 }, pixel, recorder);
    const ProbeRecord& record = recorder.record();
    ASSERT_TRUE(outcome.evaluated) << label;
    EXPECT_LE(std::abs(outcome.visibility - visibility.at(pixel.x, pixel.y)), outcome.tolerance) << label;
    ASSERT_EQ(record.lightSamples.size(), 16u) << label;
    int unblocked = 0;
    for (const ProbeLightSample& sample : record.lightSamples)
    {
      unblocked += sample.blocked ? 0 : 1;
      EXPECT_LE(std::max(std::abs(sample.position.x), std::abs(sample.position.y)), 0.5 * light.size + 1e-12) << label;
    }
    EXPECT_EQ(unblocked / 16.0, outcome.visibility) << label;
    EXPECT_EQ(record.find("sample_count")->value.at(0), frame.find("sample_count")->image.at(pixel.x, pixel.y)) << label;
    if (std::abs(outcome.visibility - visibility.at(pixel.x, pixel.y)) < 1e-4)
    {
      EXPECT_NEAR(record.find("visibility_stderr")->value.at(0),
        frame.find("visibility_stderr")->image.at(pixel.x, pixel.y), 1e-3) << label;
    }
  }
}

} // namespace
} // namespace sl
