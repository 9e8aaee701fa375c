// pcss: the GLSL against its CPU implementation, and against closed forms in the configuration where
// PCSS's planarity assumption holds exactly (a square occluder parallel to the light and the ground).
#include "metrics/ErrorMetrics.h"
#include "reference/ReferenceRenderer.h"
#include "support/TestSupport.h"
#include "frame/ProbeRecord.h"
#include "techniques/Registry.h"
#include "techniques/PcssReference.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <optional>

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
  const PcssSettings settings = PcssSettings::from(frame.parameters);
  const ImageF& visibility = frame.find("visibility")->image;
  const ImageF& blocker = frame.find("avg_blocker_depth")->image;
  const ImageF& penumbra = frame.find("penumbra_kernel_texels")->image;
  Agreement agreement;
  for (int y = 0; y < visibility.height; ++y)
  {
    for (int x = 0; x < visibility.width; ++x)
    {
      const PcssSample cpu = pcssReference(inputs, settings, x, y);
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

// The probe (TechniqueDescriptor::probe) records the kernels and averages the GPU computed at the pixel: the
// blocker search's taps and the blockers' mean are avg_blocker_depth, the penumbra kernel w_p is the GPU's
// penumbra_kernel_texels, the filter's occluding taps weigh 1 - visibility; on a lit (no blocker), a penumbra
// and an umbra pixel.
TEST(Pcss, ProbeRecordsTheKernelsAndTapsTheGpuUsed)
{
  const Scene scene = test::loadDataset("stacked-occluders");
  const FrameResult frame = test::renderDataset(scene, "pcss", 96, 80, { "shadow_map_size=512" });
  const ShadowMapInputs inputs = test::shadowMapInputs(frame, scene);
  const PcssSettings settings = PcssSettings::from(frame.parameters);
  std::vector<glm::ivec2> pixels(3, glm::ivec2(-1)); // lit without blockers, penumbra, umbra
  for (int y = 0; y < 80; ++y)
  {
    for (int x = 0; x < 96; ++x)
    {
      const PcssSample cpu = pcssReference(inputs, settings, x, y);
      if (!cpu.sample.evaluated || cpu.kernelEdgeMargin < 1e-4 || cpu.sample.depthMargin < 2e-6 ||
        cpu.sample.reachMargin < 1e-5 || cpu.sample.texelEdgeMargin < 1e-4)
      {
        continue;
      }
      const int kind = !cpu.foundBlockers ? 0 : cpu.sample.visibility == 0.0 ? 2 : cpu.sample.visibility < 1.0 ? 1 : -1;
      if (kind >= 0 && pixels[kind].x < 0)
      {
        pixels[kind] = { x, y };
      }
    }
  }
  const auto gpu = [&](const char* buffer, glm::ivec2 pixel) {
    return static_cast<double>(frame.find(buffer)->image.at(pixel.x, pixel.y));
  };
  for (int kind = 0; kind < 3; ++kind)
  {
    const glm::ivec2 pixel = pixels[kind];
    ASSERT_GE(pixel.x, 0) << "no pixel of kind " << kind;
    const std::string label = format("pixel ", pixel.x, ",", pixel.y);
    ProbeRecorder recorder;
    const ProbeOutcome outcome = findTechnique("pcss").probe({ &frame, &scene, 0 }, pixel, recorder);
    const ProbeRecord& record = recorder.record();
    ASSERT_TRUE(outcome.evaluated) << label;
    EXPECT_TRUE(outcome.ambiguity.empty()) << label << ": " << outcome.ambiguity;
    EXPECT_EQ(outcome.visibility, pcssReference(inputs, settings, pixel.x, pixel.y).sample.visibility) << label;
    EXPECT_LE(std::abs(outcome.visibility - gpu("visibility", pixel)), outcome.tolerance) << label;
    const auto quantity = [&](const char* name) {
      const ProbeQuantity* found = record.find(name);
      EXPECT_NE(found, nullptr) << label << ": " << name << " not recorded";
      return found != nullptr ? found->value.at(0) : -1.0;
    };
    const auto kernel = [&](const char* role) {
      const auto found = std::find_if(record.kernels.begin(), record.kernels.end(), [&](const ProbeKernel& k) { return k.role == role; });
      return found != record.kernels.end() ? std::optional<ProbeKernel>(*found) : std::nullopt;
    };
    // Blocker search: its kernel is the GPU's w_i, every tap recorded, the blockers' mean depth the GPU's.
    EXPECT_NEAR(quantity("blocker_kernel_texels"), gpu("blocker_kernel_texels", pixel), 1e-4 * gpu("blocker_kernel_texels", pixel)) << label;
    const std::optional<ProbeKernel> search = kernel("blocker search");
    ASSERT_TRUE(search.has_value()) << label;
    EXPECT_NEAR(std::max(search->hi.x - search->lo.x, search->hi.y - search->lo.y), quantity("blocker_kernel_texels"), 1e-9) << label;
    int searchTaps = 0;
    int blockers = 0;
    double blockerSum = 0.0;
    double occludingFilterWeight = 0.0;
    int filterTaps = 0;
    for (const ProbeTexel& texel : record.texels)
    {
      EXPECT_EQ(texel.occluding, texel.role == "blocker search" ? texel.storedDepth < texel.comparedDepth
                                                                : !(texel.comparedDepth <= texel.storedDepth)) << label;
      if (texel.role == "blocker search")
      {
        ++searchTaps;
        blockers += texel.occluding ? 1 : 0;
        blockerSum += texel.occluding ? texel.storedDepth : 0.0;
        EXPECT_GE(texel.texel.x + 1.0, search->lo.x) << label;
        EXPECT_LE(texel.texel.x, search->hi.x) << label;
      }
      else
      {
        ASSERT_EQ(texel.role, "filter tap") << label;
        ++filterTaps;
        occludingFilterWeight += texel.occluding ? texel.weight : 0.0;
      }
    }
    EXPECT_EQ(searchTaps, gpu("blocker_samples", pixel)) << label;
    EXPECT_EQ(searchTaps, quantity("blocker_samples")) << label;
    EXPECT_EQ(blockers, quantity("blockers_found")) << label;
    if (kind == 0)
    {
      EXPECT_EQ(blockers, 0) << label;
      EXPECT_EQ(filterTaps, 0) << label << ": no blocker, no filter step";
      EXPECT_EQ(outcome.visibility, 1.0) << label;
      continue;
    }
    // Penumbra estimate and filter: w_p is the GPU's kernel, the filter's taps its pcf_samples.
    EXPECT_NEAR(blockerSum / blockers, quantity("avg_blocker_depth"), 1e-12 * blockerSum) << label;
    EXPECT_NEAR(quantity("avg_blocker_depth"), gpu("avg_blocker_depth", pixel), 1e-4 * gpu("avg_blocker_depth", pixel)) << label;
    EXPECT_NEAR(quantity("penumbra_width"), gpu("penumbra_width", pixel), 2e-3 * gpu("penumbra_width", pixel) + 1e-6) << label;
    const std::optional<ProbeKernel> penumbra = kernel("penumbra");
    ASSERT_TRUE(penumbra.has_value()) << label;
    const double penumbraTexels = std::max(penumbra->hi.x - penumbra->lo.x, penumbra->hi.y - penumbra->lo.y);
    EXPECT_NEAR(penumbraTexels, gpu("penumbra_kernel_texels", pixel), 2e-3 * penumbraTexels + 1e-3) << label;
    EXPECT_EQ(filterTaps, gpu("pcf_samples", pixel)) << label;
    EXPECT_NEAR(occludingFilterWeight, 1.0 - outcome.visibility, 1e-12) << label;
  }
}

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
