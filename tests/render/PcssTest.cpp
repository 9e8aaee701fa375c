// pcss: the GLSL against its CPU implementation, and against closed forms in the configuration where
// PCSS's planarity assumption holds exactly (a square occluder parallel to the light and the ground).
#include "metrics/ErrorMetrics.h"
#include "reference/ReferenceRenderer.h"
#include "support/TestSupport.h"
#include "techniques/pcss/PcssTechnique.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

namespace sl
{
namespace
{

// Float rounding can move a kernel edge across a texel centre (one more or one less row of texels) or
// flip a comparison whose operands are within 2e-6 relative; such pixels are counted, not compared.
struct Agreement
{
  int evaluated = 0;
  int ambiguous = 0;
  int mismatched = 0;
  int partial = 0;
  double maxDifference = 0.0;
  std::string first;
};

Agreement compareWithCpu(const Scene& scene, const FrameResult& frame)
{
  const ShadowMapInputs inputs = test::shadowMapInputs(frame, scene);
  const ImageF& visibility = frame.find("visibility")->image;
  const ImageF& blocker = frame.find("avg_blocker_depth")->image;
  const ImageF& penumbra = frame.find("penumbra_kernel_texels")->image;
  Agreement agreement;
  for (int y = 0; y < visibility.height; ++y)
  {
    for (int x = 0; x < visibility.width; ++x)
    {
      const PcssSample cpu = pcssReference(inputs, frame.parameters, x, y);
      if (!cpu.sample.evaluated)
      {
        EXPECT_EQ(visibility.at(x, y), cpu.sample.visibility) << x << "," << y;
        continue;
      }
      ++agreement.evaluated;
      agreement.partial += (cpu.sample.visibility > 0.0 && cpu.sample.visibility < 1.0) ? 1 : 0;
      if (cpu.kernelEdgeMargin < 1e-4 || cpu.sample.depthMargin < 2e-6 || cpu.sample.reachMargin < 1e-5 ||
        cpu.sample.texelEdgeMargin < 1e-4)
      {
        ++agreement.ambiguous;
        continue;
      }
      const double difference = std::abs(visibility.at(x, y) - cpu.sample.visibility);
      agreement.maxDifference = std::max(agreement.maxDifference, difference);
      if (difference > 1e-5)
      {
        if (agreement.mismatched++ == 0)
        {
          agreement.first = format("pixel ", x, ",", y, " gpu ", visibility.at(x, y), " cpu ", cpu.sample.visibility,
            " (kernel edge margin ", cpu.kernelEdgeMargin, ")");
        }
      }
      // The GPU sums up to max_grid_taps^2 depths in float (relative error ~1e-5 at 1024 terms); the
      // penumbra kernel amplifies it by d / (d - z_avg).
      EXPECT_NEAR(blocker.at(x, y), cpu.averageBlockerDepth, 1e-4 * cpu.averageBlockerDepth + 1e-7) << x << "," << y;
      EXPECT_NEAR(penumbra.at(x, y), cpu.penumbraKernelTexels, 2e-3 * cpu.penumbraKernelTexels + 1e-3) << x << "," << y;
    }
  }
  return agreement;
}

class PcssGpuCpu : public ::testing::TestWithParam<std::string>
{
};

TEST_P(PcssGpuCpu, MatchesTheCpuImplementation)
{
  const Scene scene = test::loadDataset(GetParam());
  for (const std::vector<std::string>& settings :
    { std::vector<std::string>{ "shadow_map_size=512" },
      std::vector<std::string>{ "shadow_map_size=512", "blocker_search=poisson", "filter=poisson" },
      std::vector<std::string>{ "shadow_map_size=512", "max_grid_taps=8" } })
  {
    const FrameResult frame = test::renderDataset(scene, "pcss", 96, 80, settings);
    const Agreement agreement = compareWithCpu(scene, frame);
    std::cout << "[ measured ] pcss " << GetParam() << " " << settings.back() << ": evaluated " << agreement.evaluated
              << ", ambiguous " << agreement.ambiguous << ", partial " << agreement.partial << ", max |gpu - cpu| "
              << agreement.maxDifference << "\n";
    EXPECT_EQ(agreement.mismatched, 0) << settings.back() << ": " << agreement.first;
    EXPECT_LT(agreement.ambiguous, 96 * 80 / 50) << settings.back();
    EXPECT_GT(agreement.partial, 50) << settings.back() << ": PCSS must produce a penumbra";
  }
}

INSTANTIATE_TEST_SUITE_P(Datasets, PcssGpuCpu, ::testing::Values("bunny", "stacked-occluders", "near-light", "fence"),
  [](const ::testing::TestParamInfo<std::string>& info) {
    std::string name = info.param;
    std::replace(name.begin(), name.end(), '-', '_');
    return name;
  });

TEST(Pcss, ExactForParallelPlanarOccludersUpToDiscretisation)
{
  // planar-occluder: light 1 at height 3, occluder 1 at height 1; near-light: occluder 0.5 at 2.7, a
  // penumbra wider than the map's receivers' window (the focus stage must widen the frustum by the light's
  // footprint, or casters seen from the light's edges are missing).
  struct Case
  {
    const char* dataset;
    double occluderSize;
    double occluderHeight;
    double maxRmse;
  };
  for (const Case& c : { Case{ "planar-occluder", 1.0, 1.0, 0.02 }, Case{ "near-light", 0.5, 2.7, 0.03 } })
  {
    const Scene scene = test::loadDataset(c.dataset);
    const FrameResult frame = test::renderDataset(scene, "pcss", 128, 128);
    const test::GroundError error = test::groundErrorAgainst(frame, [&](double x, double z) {
      return test::parallelSquaresVisibility(1.0, 3.0, c.occluderSize, c.occluderHeight, x, z);
    });
    const double rmse = error.rmse;
    const int penumbra = error.penumbra;
    std::cout << "[ measured ] pcss on " << c.dataset << " against the closed form: RMSE " << rmse << " over "
              << error.ground << " ground pixels (" << penumbra << " in penumbra)\n";
    EXPECT_GT(penumbra, 1000) << c.dataset;
    EXPECT_LT(rmse, c.maxRmse) << c.dataset;
  }
}

TEST(Pcss, ReceiverPlaneBiasKeepsTheGrazingReceiverFromShadowingItself)
{
  // The light is ~80 degrees from the ground's normal: across PCSS's wide kernels the ground's own depth
  // falls far below the per-point bias. Against the ray-traced reference, receiver-plane bias (the default)
  // must keep the lit ground lit; without it the ground darkens (the test has teeth).
  const Scene scene = test::loadDataset("grazing");
  double rmse[2] = { 0.0, 0.0 };
  const char* settings[2] = { "receiver_plane_bias=on", "receiver_plane_bias=off" };
  for (int i = 0; i < 2; ++i)
  {
    const FrameResult frame = test::renderDataset(scene, "pcss", 128, 128, { settings[i] });
    const ReferenceInputs inputs = test::referenceInputs(frame, scene);
    ReferenceSettings referenceSettings;
    referenceSettings.samples = 256;
    const ReferenceResult rays = renderReference(inputs, referenceSettings);
    rmse[i] = computeErrorMetrics(frame.find("visibility")->image, rays.visibility, inputs.coverage, inputs.coverage)
                .covered.rmse;
    std::cout << "[ measured ] pcss " << settings[i] << " on grazing: RMSE " << rmse[i] << " vs Embree\n";
  }
  EXPECT_LT(rmse[0], 0.02);
  EXPECT_GT(rmse[1], 0.1);
}

TEST(Pcss, PointLightGivesTheHardShadow)
{
  const Scene scene = test::loadDataset("sphere-point");
  const FrameResult pcss = test::renderDataset(scene, "pcss", 96, 96, { "shadow_map_size=512" });
  const FrameResult hard = test::renderDataset(scene, "hard", 96, 96, { "shadow_map_size=512" });
  const ImageF& a = pcss.find("visibility")->image;
  const ImageF& b = hard.find("visibility")->image;
  int differing = 0;
  for (std::size_t i = 0; i < a.data.size(); ++i)
  {
    differing += a.data[i] != b.data[i] ? 1 : 0;
  }
  EXPECT_EQ(differing, 0);
}

} // namespace
} // namespace sl
