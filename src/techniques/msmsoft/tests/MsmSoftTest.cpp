// msmsoft on llvmpipe: the GLSL against the CPU twin (double precision, exact box sums) pixel by pixel on three
// datasets and on random configurations; the closed form of the blocker estimate (two depths in the search region:
// G_b is the occluder's fraction, z_avg its depth, up to epsilon and alpha); the probe; and the error against the ray
// tracer beside savsm's and pcss's.
//
// Exclusions (counted and printed): receivers whose search kernel edge lies within 1e-4 texel of a texel centre (the
// GPU's float may include or exclude a row of the integer search box), whose light-reach test is grazing, and where
// float rounding of the moments decides the value (MsmSoftSensitivity above msmSoftSensitivityLimit: a near-singular
// Hankel matrix, one or two depths in the box held apart only by the moment bias): visibility is compared where its
// sensitivity is small, G_b, z_avg and the kernel where theirs are.
#include "support/TestSupport.h"
#include "frame/ProbeRecord.h"
#include "lightspace/MomentSummedAreaTable.h"
#include "reference/ReferenceRenderer.h"
#include "scene/RandomScenes.h"
#include "scene/Scene.h"
#include "techniques/ProbeSupport.h"
#include "techniques/Registry.h"
#include "techniques/msmsoft/MsmSoftTechnique.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

namespace sl
{
namespace
{

struct MsmSoftAgreement
{
  int evaluated = 0;
  int compared = 0;
  int partial = 0;
  int edgeExcluded = 0;
  int sensitivityExcluded = 0;
  int overflowExcluded = 0;  // int32 table: a box beyond its exact size (the twin's flag)
  int overflowMismatched = 0; // the GPU's moment_sat_overflow differs from the twin's flag
  int blockersCompared = 0;           // G_b, z_avg and the kernel compared (their sensitivities small)
  double maxExcludedVisibility = 0.0; // |gpu - cpu| at the pixels excluded for sensitivity
  int reachExcluded = 0;
  int mismatched = 0;
  int leakMismatched = 0; // |light_leak| differs by > 2e-3 (a tap within float rounding of its texel's depth)
  double maxVisibility = 0.0;
  double maxIntensity = 0.0;
  double maxAverageDepth = 0.0; // relative to the depth
  double maxKernel = 0.0;       // relative
  double maxLeak = 0.0;
  std::string firstMismatch;
};

MsmSoftAgreement compareMsmSoftWithTwin(const FrameResult& frame, const Scene& scene)
{
  const ShadowMapInputs inputs = test::shadowMapInputs(frame, scene);
  const MsmSoftSettings settings = MsmSoftSettings::from(frame.parameters);
  const MomentSatTable table = momentSummedAreaTable(
    inputs.shadowMapLinear, inputs.lightView.nearDepth, inputs.lightView.farDepth, settings.satFormat);
  const ImageF& visibility = frame.find("visibility")->image;
  const ImageF& intensity = frame.find("blocker_intensity")->image;
  const ImageF& averageDepth = frame.find("avg_blocker_depth")->image;
  const ImageF& kernel = frame.find("penumbra_kernel_texels")->image;
  const ImageF& leak = frame.find("light_leak")->image;
  const ImageF& overflow = frame.find("moment_sat_overflow")->image;
  MsmSoftAgreement agreement;
  for (int y = 0; y < visibility.height; ++y)
  {
    for (int x = 0; x < visibility.width; ++x)
    {
      const MsmSoftSample cpu = msmSoftReference(inputs, settings, table, x, y);
      const double gpu = visibility.at(x, y);
      if (!cpu.sample.evaluated)
      {
        if (gpu != cpu.sample.visibility && agreement.mismatched++ == 0)
        {
          agreement.firstMismatch = format("pixel ", x, ",", y, " without a shadow test: gpu ", gpu, " cpu ", cpu.sample.visibility);
        }
        continue;
      }
      ++agreement.evaluated;
      agreement.overflowMismatched += (overflow.at(x, y) > 0.5f) != cpu.satOverflow ? 1 : 0;
      if (cpu.satOverflow)
      {
        ++agreement.overflowExcluded;
        continue;
      }
      if (cpu.searchEdgeMargin < 1e-4)
      {
        ++agreement.edgeExcluded;
        continue;
      }
      if (cpu.sample.reachMargin < 1e-5)
      {
        ++agreement.reachExcluded;
        continue;
      }
      const MsmSoftSensitivity& sensitivity = cpu.sensitivity;
      const double cpuKernel = 2.0 * std::max(cpu.filterHalfTexels.x, cpu.filterHalfTexels.y);
      if (sensitivity.blockerIntensity <= msmSoftSensitivityLimit && sensitivity.averageDepth <= msmSoftSensitivityLimit &&
        sensitivity.kernel <= msmSoftSensitivityLimit)
      {
        ++agreement.blockersCompared;
        agreement.maxIntensity = std::max(agreement.maxIntensity, std::abs(intensity.at(x, y) - std::min(cpu.blockers.intensity, 1.0)));
        agreement.maxAverageDepth = std::max(agreement.maxAverageDepth,
          std::abs(averageDepth.at(x, y) - cpu.averageBlockerDepth) / cpu.averageBlockerDepth);
        agreement.maxKernel = std::max(agreement.maxKernel, std::abs(kernel.at(x, y) - cpuKernel) / cpuKernel);
      }
      if (sensitivity.visibility > msmSoftSensitivityLimit)
      {
        ++agreement.sensitivityExcluded;
        agreement.maxExcludedVisibility = std::max(agreement.maxExcludedVisibility, std::abs(gpu - cpu.sample.visibility));
        continue;
      }
      ++agreement.compared;
      agreement.partial += cpu.sample.visibility > 0.01 && cpu.sample.visibility < 0.99 ? 1 : 0;
      const double difference = std::abs(gpu - cpu.sample.visibility);
      agreement.maxVisibility = std::max(agreement.maxVisibility, difference);
      const double leakDifference = std::abs(leak.at(x, y) - cpu.lightLeak);
      agreement.maxLeak = std::max(agreement.maxLeak, leakDifference);
      agreement.leakMismatched += leakDifference > 2e-3 ? 1 : 0;
      if (difference > msmSoftTwinTolerance && agreement.mismatched++ == 0)
      {
        agreement.firstMismatch = format("pixel ", x, ",", y, ": gpu ", gpu, " cpu ", cpu.sample.visibility, " (G_b ",
          cpu.blockers.intensity, ", kernel ", cpuKernel, ", D33 ", cpu.filter.pivot3, ")");
      }
    }
  }
  return agreement;
}

void printMsmSoftAgreement(const std::string& label, const MsmSoftAgreement& agreement)
{
  std::cout << "[ measured ] msmsoft vs twin, " << label << ": compared " << agreement.compared << " of "
            << agreement.evaluated << " (partial " << agreement.partial << "; excluded: search edge "
            << agreement.edgeExcluded << ", rounding sensitivity " << agreement.sensitivityExcluded << ", reach " << agreement.reachExcluded << ", int32 overflow " << agreement.overflowExcluded
            << " (GPU flag differs at " << agreement.overflowMismatched << ")"
            << "; excluded pixels differ by up to " << agreement.maxExcludedVisibility << "), max |gpu - cpu| visibility "
            << agreement.maxVisibility << "; over " << agreement.blockersCompared << " pixels G_b " << agreement.maxIntensity
            << ", z_avg (relative) " << agreement.maxAverageDepth << ", kernel (relative) " << agreement.maxKernel
            << ", light_leak " << agreement.maxLeak << " (" << agreement.leakMismatched << " over 2e-3)\n";
}

void expectAgreement(const MsmSoftAgreement& agreement, const std::string& label)
{
  EXPECT_EQ(agreement.mismatched, 0) << label << ": first " << agreement.firstMismatch;
  // The flag's box areas are integers in both; they differ only where float rounding moves the integer cover.
  EXPECT_LE(agreement.overflowMismatched, agreement.edgeExcluded + agreement.overflowExcluded / 100) << label;
  EXPECT_LT(agreement.maxIntensity, 1e-4) << label;
  EXPECT_LT(agreement.maxAverageDepth, 1e-4) << label;
  EXPECT_LT(agreement.maxKernel, 5e-4) << label;
  EXPECT_LE(agreement.leakMismatched, agreement.compared / 100 + 1) << label;
}

TEST(MsmSoft, MatchesTheCpuTwinOnThreeDatasets)
{
  for (const std::string dataset : { "stacked-occluders", "contact", "bunny" })
  {
    const Scene scene = test::loadDataset(dataset);
    const std::vector<std::string> settings{ "shadow_map_size=512" };
    const FrameResult frame = test::renderDataset(scene, "msmsoft", 96, 80, settings);
    test::expectFiniteBuffersAndVisibilityInRange(frame, dataset);
    const MsmSoftAgreement agreement = compareMsmSoftWithTwin(frame, scene);
    printMsmSoftAgreement(test::caseLabel(dataset, settings), agreement);
    expectAgreement(agreement, dataset);
    EXPECT_GT(agreement.compared, 2000) << dataset;
    EXPECT_GT(agreement.partial, 50) << dataset;
    // Lit receivers with a few blocker texels in the search box keep a tiny G_b, and z_avg there follows rounding;
    // one or two depths in a box leave D33 at the bias: the exclusions stay a minority.
    EXPECT_LT(agreement.edgeExcluded + agreement.sensitivityExcluded, agreement.evaluated / 4) << dataset;
    EXPECT_GT(agreement.blockersCompared, agreement.evaluated / 4) << dataset;
  }
}

TEST(MsmSoft, MatchesTheCpuTwinOnRandomConfigurations)
{
  int compared = 0;
  int configurations = 0;
  const char* momentBiases[4] = { "3e-5", "3e-4", "1e-6", "1e-3" };
  const char* fullyLitBiases[3] = { "1e-3", "1e-2", "1e-5" };
  for (std::uint64_t seed = 1; seed <= 40 && configurations < 6; ++seed)
  {
    const RandomScene random = randomScene(seed, 96);
    const Scene scene = parseScene(random.json, "msmsoft seed " + std::to_string(seed), ".");
    if (scene.lights.front().type == LightType::Directional)
    {
      continue; // msmsoft supports area, point and spot lights
    }
    ++configurations;
    const std::vector<std::string> settings{ "shadow_map_size=" + std::to_string(256 >> random.mapSizeHalvings),
      std::string("moment_bias=") + momentBiases[seed % 4], std::string("fully_lit_bias=") + fullyLitBiases[seed % 3],
      "min_kernel_texels=" + std::to_string(1 + seed % 3) };
    const FrameResult frame = test::renderDataset(scene, "msmsoft", scene.camera.resolution.x, scene.camera.resolution.y, settings);
    test::expectFiniteBuffersAndVisibilityInRange(frame, random.summary);
    const MsmSoftAgreement agreement = compareMsmSoftWithTwin(frame, scene);
    printMsmSoftAgreement(format("seed ", seed, " (", random.summary, ") ", test::caseLabel("", settings)), agreement);
    expectAgreement(agreement, format("seed ", seed, " ", random.summary));
    compared += agreement.compared;
  }
  EXPECT_EQ(configurations, 6);
  EXPECT_GT(compared, 1000) << "the random configurations must leave pixels to compare";
}

// One planar occluder at one depth over a planar receiver (planar-occluder: both parallel to the light, so each
// holds one linear depth): where the search box holds only those two depths, the canonical representation at z_f is
// the two-point distribution up to the moment bias, so G_b is the fraction p of occluder texels in the box and
// z_avg = (eps z_f + p z_o) / (eps + p). Checked on the GPU's buffers.
TEST(MsmSoft, BlockerEstimateOfOnePlanarOccluderIsExactUpToTheBiases)
{
  const Scene scene = test::loadDataset("planar-occluder");
  const FrameResult frame = test::renderDataset(scene, "msmsoft", 128, 128, { "shadow_map_size=256" });
  const ShadowMapInputs inputs = test::shadowMapInputs(frame, scene);
  const MsmSoftSettings settings = MsmSoftSettings::from(frame.parameters);
  const MomentSatTable table = momentSummedAreaTable(
    inputs.shadowMapLinear, inputs.lightView.nearDepth, inputs.lightView.farDepth, settings.satFormat);
  const ImageF& intensity = frame.find("blocker_intensity")->image;
  const ImageF& averageDepth = frame.find("avg_blocker_depth")->image;
  const double nearDepth = inputs.lightView.nearDepth;
  const double range = inputs.lightView.farDepth - nearDepth;
  int checked = 0;
  double largestIntensityError = 0.0;
  double largestDepthError = 0.0; // moment depth
  for (int y = 0; y < 128; ++y)
  {
    for (int x = 0; x < 128; ++x)
    {
      const MsmSoftSample cpu = msmSoftReference(inputs, settings, table, x, y);
      if (!cpu.sample.evaluated || cpu.searchEdgeMargin < 1e-4)
      {
        continue;
      }
      // The search box's depths: two values only (within float rounding), the occluder's in front of z_f.
      double occluderDepth = -1.0;
      double receiverDepth = -1.0;
      int occluders = 0;
      bool twoDepths = true;
      const double zf = cpu.fragmentDepth;
      for (int j = cpu.searchLo.y; j <= cpu.searchHi.y && twoDepths; ++j)
      {
        for (int i = cpu.searchLo.x; i <= cpu.searchHi.x; ++i)
        {
          const double z = std::clamp((inputs.shadowMapLinear.at(i, j) - nearDepth) / range, 0.0, 1.0);
          double& slot = z < zf ? occluderDepth : receiverDepth;
          occluders += z < zf ? 1 : 0;
          if (slot < 0.0)
          {
            slot = z;
          }
          else if (std::abs(slot - z) > 1e-6)
          {
            twoDepths = false;
            break;
          }
        }
      }
      const int texels = (cpu.searchHi.x - cpu.searchLo.x + 1) * (cpu.searchHi.y - cpu.searchLo.y + 1);
      if (!twoDepths || occluders == 0 || occluders == texels)
      {
        continue;
      }
      ++checked;
      const double p = static_cast<double>(occluders) / texels;
      const double epsilon = settings.fullyLitBias;
      const double expectedDepth = (epsilon * zf + p * occluderDepth) / (epsilon + p);
      largestIntensityError = std::max(largestIntensityError, std::abs(intensity.at(x, y) - p));
      largestDepthError =
        std::max(largestDepthError, std::abs((averageDepth.at(x, y) - nearDepth) / range - expectedDepth));
    }
  }
  std::cout << "[ measured ] msmsoft blocker estimate on planar-occluder (two depths in the search box, " << checked
            << " pixels): max |G_b - p| " << largestIntensityError << ", max |z_avg - (eps z_f + p z_o) / (eps + p)| "
            << largestDepthError << " (moment depth; alpha " << settings.momentBias << ")\n";
  ASSERT_GT(checked, 1000);
  // The moment bias moves the moments by alpha (at most 1 each); the weights and support move by O(alpha / p),
  // and the float moments add ~1e-6.
  EXPECT_LT(largestIntensityError, 100.0 * settings.momentBias + 1e-4);
  EXPECT_LT(largestDepthError, 100.0 * settings.momentBias + 1e-4);
}

// moment_sat_precision = int32 (the authors' form): fewer fixed-point bits and 32-bit sums that wrap. Where the
// boxes fit (at most moment_sat_max_kernel_texels squared texels) the GPU is the twin's, at its coarser fixed point;
// where they do not, moment_sat_overflow flags the pixel (and stats.json counts it).
TEST(MsmSoft, Int32TableMatchesTheTwinWhereItsBoxesFitAndFlagsTheRest)
{
  const Scene scene = test::loadDataset("stacked-occluders");
  for (const std::string maxKernel : { "64", "256" })
  {
    const std::vector<std::string> settings{ "shadow_map_size=512", "moment_sat_precision=int32",
      "moment_sat_max_kernel_texels=" + maxKernel };
    const FrameResult frame = test::renderDataset(scene, "msmsoft", 96, 80, settings);
    test::expectFiniteBuffersAndVisibilityInRange(frame, maxKernel);
    const MsmSoftAgreement agreement = compareMsmSoftWithTwin(frame, scene);
    printMsmSoftAgreement(test::caseLabel("stacked-occluders", settings), agreement);
    expectAgreement(agreement, maxKernel);
    // At 64 most search boxes exceed 64^2 texels and are flagged; at 256 (16 bits) the coarser fixed point leaves
    // more Hankel matrices near singular (README.md, Precision).
    EXPECT_GT(agreement.compared, maxKernel == "64" ? 300 : 1000) << maxKernel;
    const auto flagged = frame.techniqueStatistics.find("moment_sat_overflow_flagged_pixels");
    ASSERT_NE(flagged, frame.techniqueStatistics.end());
    EXPECT_NEAR(flagged->second, agreement.overflowExcluded, agreement.overflowMismatched) << maxKernel;
    if (maxKernel == "64")
    {
      EXPECT_GT(agreement.overflowExcluded, 100) << "stacked-occluders' search boxes exceed 64 x 64 texels at 512^2";
    }
  }
}

// The probe replays the twin: its visibility is the twin's and (unambiguous pixels) the GPU's within the tolerance,
// and it records the search and filter kernels and the quantities the buffers hold.
TEST(MsmSoft, ProbeRecordsTheKernelsAndTheGpuBuffers)
{
  const Scene scene = test::loadDataset("stacked-occluders");
  const FrameResult frame = test::renderDataset(scene, "msmsoft", 96, 80, { "shadow_map_size=512" });
  const ShadowMapInputs inputs = test::shadowMapInputs(frame, scene);
  const MsmSoftSettings settings = MsmSoftSettings::from(frame.parameters);
  const MomentSatTable table = momentSummedAreaTable(
    inputs.shadowMapLinear, inputs.lightView.nearDepth, inputs.lightView.farDepth, settings.satFormat);
  std::vector<glm::ivec2> pixels(3, glm::ivec2(-1)); // lit, penumbra, umbra
  for (int y = 0; y < 80; ++y)
  {
    for (int x = 0; x < 96; ++x)
    {
      const MsmSoftSample cpu = msmSoftReference(inputs, settings, table, x, y);
      if (!cpu.sample.evaluated || cpu.searchEdgeMargin < 1e-4 || cpu.sensitivity.visibility > msmSoftSensitivityLimit ||
        cpu.sensitivity.averageDepth > msmSoftSensitivityLimit || cpu.sensitivity.kernel > msmSoftSensitivityLimit)
      {
        continue;
      }
      const int kind = cpu.sample.visibility > 0.99 ? 0 : cpu.sample.visibility < 0.02 ? 2 : 1;
      if (pixels[kind].x < 0)
      {
        pixels[kind] = { x, y };
      }
    }
  }
  for (int kind = 0; kind < 3; ++kind)
  {
    const glm::ivec2 pixel = pixels[kind];
    ASSERT_GE(pixel.x, 0) << "no pixel of kind " << kind;
    const std::string label = format("pixel ", pixel.x, ",", pixel.y);
    ProbeRecorder recorder;
    const ProbeOutcome outcome = findTechnique("msmsoft").probe({ &frame, &scene, 0 }, pixel, recorder);
    const ProbeRecord& record = recorder.record();
    const auto gpu = [&](const char* buffer) { return static_cast<double>(frame.find(buffer)->image.at(pixel.x, pixel.y)); };
    const auto quantity = [&](const char* name) {
      const ProbeQuantity* found = record.find(name);
      EXPECT_NE(found, nullptr) << label << ": " << name << " not recorded";
      return found != nullptr ? found->value.at(0) : -1.0;
    };
    ASSERT_TRUE(outcome.evaluated) << label;
    EXPECT_EQ(outcome.visibility, msmSoftReference(inputs, settings, table, pixel.x, pixel.y).sample.visibility) << label;
    std::cout << "[ measured ] msmsoft probe " << label << ": GPU " << gpu("visibility") << ", probe " << outcome.visibility
              << (outcome.ambiguity.empty() ? "" : ", ambiguous: " + outcome.ambiguity) << "\n";
    EXPECT_TRUE(outcome.ambiguity.empty()) << label << ": " << outcome.ambiguity;
    EXPECT_LE(std::abs(outcome.visibility - gpu("visibility")), outcome.tolerance) << label;
    EXPECT_NEAR(quantity("blocker_kernel_texels"), gpu("blocker_kernel_texels"), 1e-4 * gpu("blocker_kernel_texels")) << label;
    EXPECT_NEAR(quantity("blocker_intensity"), gpu("blocker_intensity"), 1e-3) << label;
    EXPECT_NEAR(quantity("avg_blocker_depth"), gpu("avg_blocker_depth"), 1e-4 * gpu("avg_blocker_depth")) << label;
    EXPECT_NEAR(quantity("penumbra_kernel_texels"), gpu("penumbra_kernel_texels"), 1e-3 * gpu("penumbra_kernel_texels")) << label;
    std::vector<std::string> roles;
    double leakWeight = 0.0;
    for (const ProbeKernel& kernel : record.kernels)
    {
      roles.push_back(kernel.role);
    }
    for (const ProbeTexel& texel : record.texels)
    {
      leakWeight += texel.role == "light-leak pcf" ? texel.weight : 0.0;
    }
    for (const char* role : { "blocker search", "search SAT box", "penumbra", "light-leak cover" })
    {
      EXPECT_NE(std::find(roles.begin(), roles.end(), role), roles.end()) << label << ": no " << role << " kernel";
    }
    EXPECT_NEAR(leakWeight, 1.0, 1e-12) << label;
    EXPECT_NEAR(quantity("box_pcf"), gpu("visibility") - gpu("light_leak"), 2e-3) << label;
  }
}

struct ReferenceError
{
  double mean = 0.0;
  double rmse = 0.0;
  double maximum = 0.0;
  int pixels = 0;
};

ReferenceError errorAgainst(const FrameResult& frame, const ImageF& truth)
{
  const ImageF& visibility = frame.find("visibility")->image;
  const ImageF& coverage = frame.find("coverage")->image;
  ReferenceError error;
  double squares = 0.0;
  for (int y = 0; y < visibility.height; ++y)
  {
    for (int x = 0; x < visibility.width; ++x)
    {
      if (coverage.at(x, y) < 0.5f)
      {
        continue;
      }
      const double difference = std::abs(visibility.at(x, y) - truth.at(x, y));
      error.mean += difference;
      squares += difference * difference;
      error.maximum = std::max(error.maximum, difference);
      ++error.pixels;
    }
  }
  error.mean /= std::max(error.pixels, 1);
  error.rmse = std::sqrt(squares / std::max(error.pixels, 1));
  return error;
}

// Against the ray tracer on the area-light datasets, beside savsm and pcss at the same map: printed as one table.
// Asserted: the errors are finite and the flagged approximations leave msmsoft inside its contract's tolerance on
// average (mean error below 0.1).
TEST(MsmSoft, ErrorAgainstTheRayTracerBesideSavsmAndPcss)
{
  std::cout << "[ measured ] mean / RMSE / max |visibility - Embree (256 samples)| at 96x80, shadow_map_size=512:\n";
  for (const std::string dataset : { "stacked-occluders", "contact", "bunny", "planar-occluder" })
  {
    const Scene scene = test::loadDataset(dataset);
    std::string line = format("[ measured ]   ", dataset, ":");
    ImageF truth;
    for (const std::string technique : { "msmsoft", "savsm", "pcss" })
    {
      const FrameResult frame = test::renderDataset(scene, technique, 96, 80, { "shadow_map_size=512" });
      if (truth.empty())
      {
        ReferenceSettings reference;
        reference.samples = 256;
        truth = renderReference(test::referenceInputs(frame, scene), reference).visibility;
      }
      const ReferenceError error = errorAgainst(frame, truth);
      line += format(" ", technique, " ", error.mean, " / ", error.rmse, " / ", error.maximum, ";");
      EXPECT_TRUE(std::isfinite(error.rmse)) << dataset << " " << technique;
      if (technique == "msmsoft")
      {
        EXPECT_GT(error.pixels, 1000) << dataset;
        EXPECT_LT(error.mean, 0.1) << dataset;
      }
    }
    std::cout << line << "\n";
  }
}

} // namespace
} // namespace sl
