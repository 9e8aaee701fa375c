// Multi-view shadow maps (Yang et al. 2009 §5): the light split into S x S sub-lights, each with its own
// focused shadow map and MSSM, visibilities averaged; available to every technique with a `sublights`
// parameter (gbp07, yfgl09).
#include "support/TestSupport.h"

#include "metrics/ErrorMetrics.h"
#include "reference/ReferenceRenderer.h"
#include "techniques/Registry.h"
#include "techniques/SoftShadowSupport.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

namespace sl
{
namespace
{

std::string vectorJson(const glm::dvec3& v)
{
  return "[" + std::to_string(v.x) + ", " + std::to_string(v.y) + ", " + std::to_string(v.z) + "]";
}

TEST(MultiView, VisibilityIsTheMeanOfEachSubLightsOwnFrame)
{
  // Each sub-light's frame must be exactly the frame of a scene whose light is that sub-light (its own focus,
  // shadow map, MSSM and kernels), and `visibility` their mean.
  const std::filesystem::path file = test::datasetPath("stacked-occluders");
  const Scene scene = loadScene(file);
  for (const std::string technique : { "gbp07", "yfgl09" })
  {
    const FrameResult frame = test::renderDataset(scene, technique, 64, 48, { "shadow_map_size=128", "sublights=2" });
    const NamedImage* subLights = frame.find("sublight_visibility");
    ASSERT_NE(subLights, nullptr);
    ASSERT_EQ(subLights->image.components, 4);
    const std::vector<Light> parts = splitIntoSubLights(scene.lights.front(), 2);
    ImageF mean(64, 48, 1);
    double maxSubLightDifference = 0.0;
    for (std::size_t k = 0; k < parts.size(); ++k)
    {
      // std::to_string keeps 6 decimals: the sub-light's centre and size are exact in this scene (1.2 / 2).
      const Scene alone = loadScene(file, { "/lights/0/center=" + vectorJson(parts[k].center),
                                            "/lights/0/size=" + std::to_string(parts[k].size) });
      const FrameResult single = test::renderDataset(alone, technique, 64, 48, { "shadow_map_size=128" });
      const ImageF& expected = single.find("visibility")->image;
      for (std::size_t i = 0; i < expected.data.size(); ++i)
      {
        const double actual = subLights->image.data[i * 4 + k];
        maxSubLightDifference = std::max(maxSubLightDifference, std::abs(actual - expected.data[i]));
        mean.data[i] += 0.25f * expected.data[i];
      }
    }
    double maxMeanDifference = 0.0;
    int penumbra = 0;
    for (std::size_t i = 0; i < mean.data.size(); ++i)
    {
      maxMeanDifference = std::max(maxMeanDifference, std::abs(static_cast<double>(frame.find("visibility")->image.data[i]) - mean.data[i]));
      penumbra += mean.data[i] > 0.02f && mean.data[i] < 0.98f ? 1 : 0;
    }
    std::cout << "[ measured ] " << technique << " sublights=2 on stacked-occluders: max |sub-light - own frame| "
              << maxSubLightDifference << ", max |visibility - mean| " << maxMeanDifference << ", " << penumbra
              << " penumbra pixels\n";
    EXPECT_LE(maxSubLightDifference, 1e-6) << technique;
    EXPECT_LE(maxMeanDifference, 1e-6) << technique;
    EXPECT_GT(penumbra, 300) << technique;
  }
}

TEST(MultiView, ProbeRefusesMoreThanOneSubLightAndReplaysOne)
{
  // A frame keeps one light-space export (the first sub-light's shadow map), so `shadowlab probe` cannot replay
  // S x S sub-lights: it says so (InputError) instead of replaying the wrong map; with sublights=1 it replays.
  const Scene scene = test::loadDataset("stacked-occluders");
  for (const std::string technique : { "gbp07", "yfgl09" })
  {
    const FrameResult frame = test::renderDataset(scene, technique, 32, 24, { "shadow_map_size=128", "sublights=2" });
    ProbeRecorder recorder;
    EXPECT_THROW(findTechnique(technique).probe({ &frame, &scene, 0 }, { 16, 12 }, recorder), InputError) << technique;
    const FrameResult single = test::renderDataset(scene, technique, 32, 24, { "shadow_map_size=128", "sublights=1" });
    const ProbeOutcome outcome = findTechnique(technique).probe({ &single, &scene, 0 }, { 16, 12 }, recorder);
    EXPECT_TRUE(outcome.evaluated) << technique;
    if (outcome.ambiguity.empty())
    {
      EXPECT_NEAR(outcome.visibility, single.find("visibility")->image.at(16, 12), outcome.tolerance) << technique;
    }
  }
}

TEST(MultiView, SubLightsReduceTheSingleShadowMapErrorAgainstTheRayTracedReference)
{
  // §5 / Fig. 11: one shadow map from the light's centre misses the lower of two stacked occluders where the
  // upper hides it from the centre (shadows underestimated); sub-lights see it from their own centres.
  const Scene scene = test::loadDataset("stacked-occluders");
  ReferenceSettings settings;
  settings.samples = 256;
  const FrameResult one = test::renderDataset(scene, "yfgl09", 64, 48, { "shadow_map_size=256" });
  const ImageF reference = renderReference(test::referenceInputs(one, scene), settings).visibility;
  const ImageF& coverage = one.find("coverage")->image;
  double previous = 1e300;
  for (const int perSide : { 1, 2, 4 })
  {
    const FrameResult frame = test::renderDataset(scene, "yfgl09", 64, 48, { "shadow_map_size=256", "sublights=" + std::to_string(perSide) });
    const ErrorMetrics metrics = computeErrorMetrics(frame.find("visibility")->image, reference, coverage, coverage);
    std::cout << "[ measured ] yfgl09 on stacked-occluders, S = " << perSide << ": RMSE " << metrics.covered.rmse
              << ", penumbra RMSE " << metrics.penumbra.rmse << "\n";
    EXPECT_LT(metrics.covered.rmse, previous) << "S = " << perSide;
    previous = metrics.covered.rmse;
  }
}

} // namespace
} // namespace sl
