// vsm and esm: the GLSL against the CPU implementation (prefilter = blur), and VSM's defining property:
// with two depths in the filter region (a planar occluder over a planar receiver) the Chebyshev bound is
// exact, so its light-leak buffer is zero; with more depths (stacked occluders) it bleeds light.
#include "support/TestSupport.h"
#include "frame/ProbeRecord.h"
#include "techniques/Registry.h"
#include "techniques/ShadowMapParameters.h"
#include "techniques/esm/EsmTechnique.h"
#include "techniques/vsm/VsmTechnique.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

namespace sl
{
namespace
{

// Tolerances: the GPU averages the moments in float. VSM's variance E[z^2] - E[z]^2 cancels
// catastrophically when it is small (float error ~1e-7 z^2 per term, ~1e-5 after the blur), so pixels whose
// variance is below 1e-3 d^2 are counted, not compared; elsewhere 2e-3. ESM's exp(c z_n) sums are well conditioned: 1e-4. Depth tests
// within float rounding of their boundary (box taps) are also counted, not compared.
TEST(MomentTechniques, MatchTheCpuImplementations)
{
  for (const std::string dataset : { "stacked-occluders", "bunny", "contact" })
  {
    const Scene scene = test::loadDataset(dataset);
    const std::vector<std::string> settings{ "shadow_map_size=256", "prefilter_texels=7", "light_bleeding_reduction=0" };
    const FrameResult vsm = test::renderDataset(scene, "vsm", 96, 80, settings);
    const FrameResult esm =
      test::renderDataset(scene, "esm", 96, 80, { "shadow_map_size=256", "prefilter_texels=7", "esm_exponent=30" });
    const ShadowMapInputs vsmInputs = test::shadowMapInputs(vsm, scene);
    const ShadowMapInputs esmInputs = test::shadowMapInputs(esm, scene);
    const VsmSettings vsmSettings = VsmSettings::from(vsm.parameters);
    const EsmSettings esmSettings = EsmSettings::from(esm.parameters);
    int compared = 0;
    int illConditioned = 0;
    int partial = 0;
    double maxVsm = 0.0;
    double maxEsm = 0.0;
    for (int y = 0; y < 80; ++y)
    {
      for (int x = 0; x < 96; ++x)
      {
        const VsmSample cpu = vsmReference(vsmInputs, vsmSettings, x, y);
        const double gpu = vsm.find("visibility")->image.at(x, y);
        if (!cpu.sample.evaluated)
        {
          EXPECT_EQ(gpu, cpu.sample.visibility) << dataset << " " << x << "," << y;
          continue;
        }
        const ShadowLookup lookup = prepareShadowLookup(vsmInputs, vsmSettings.bias, x, y);
        const double d = lookup.sm.depthLin;
        if (cpu.variance < 1e-3 * d * d || cpu.sample.reachMargin < 1e-5)
        {
          ++illConditioned;
        }
        else
        {
          ++compared;
          partial += (cpu.sample.visibility > 0.0 && cpu.sample.visibility < 1.0) ? 1 : 0;
          maxVsm = std::max(maxVsm, std::abs(gpu - cpu.sample.visibility));
          EXPECT_NEAR(gpu, cpu.sample.visibility, 2e-3) << dataset << " vsm pixel " << x << "," << y;
        }
        const ReferenceSample esmCpu = esmReference(esmInputs, esmSettings, x, y);
        const double esmGpu = esm.find("visibility")->image.at(x, y);
        if (esmCpu.evaluated && esmCpu.reachMargin >= 1e-5)
        {
          maxEsm = std::max(maxEsm, std::abs(esmGpu - esmCpu.visibility));
          EXPECT_NEAR(esmGpu, esmCpu.visibility, 1e-4) << dataset << " esm pixel " << x << "," << y;
        }
      }
    }
    std::cout << "[ measured ] " << dataset << ": vsm compared " << compared << " (partial " << partial
              << "), ill-conditioned variance " << illConditioned << ", max |gpu - cpu| " << maxVsm << "; esm max |gpu - cpu| "
              << maxEsm << "\n";
    EXPECT_GT(compared, 300) << dataset;
    EXPECT_GT(partial, 20) << dataset << ": prefiltering must soften the shadow edges";
  }
}

// The probes of vsm and esm (TechniqueDescriptor::probe) record the moment box the blur averaged and the GPU's
// buffers: the recorded mean is the box texels' mean, p_max, kernel_texels and light_leak are the GPU's at the
// pixel, and the light-leak PCF's occluding texels weigh 1 - box_pcf; on a lit, a penumbra and an umbra pixel
// the probes' replays agree with the GPU within their tolerance.
TEST(MomentTechniques, ProbesRecordTheBoxMomentsAndTheGpuBuffers)
{
  const Scene scene = test::loadDataset("stacked-occluders");
  for (const std::string technique : { "vsm", "esm" })
  {
    const FrameResult frame = test::renderDataset(scene, technique, 96, 80, { "shadow_map_size=256", "prefilter_texels=5" });
    std::vector<glm::ivec2> pixels(3, glm::ivec2(-1)); // lit, penumbra, umbra: found by the probe itself
    std::vector<ProbeRecord> records(3);
    std::vector<ProbeOutcome> outcomes(3);
    int probed = 0;
    for (int y = 0; y < 80 && probed < 3; ++y)
    {
      for (int x = 0; x < 96 && probed < 3; ++x)
      {
        ProbeRecorder recorder;
        const ProbeOutcome outcome = findTechnique(technique).probe({ &frame, &scene, 0 }, { x, y }, recorder);
        if (!outcome.evaluated || !outcome.ambiguity.empty())
        {
          continue;
        }
        // Umbra below 0.02: esm's exponential reaches 0 only in float underflow.
        const int kind = outcome.visibility >= 1.0 ? 0 : outcome.visibility < 0.02 ? 2 : 1;
        if (pixels[kind].x < 0)
        {
          pixels[kind] = { x, y };
          records[kind] = recorder.record();
          outcomes[kind] = outcome;
          ++probed;
        }
      }
    }
    for (int kind = 0; kind < 3; ++kind)
    {
      const glm::ivec2 pixel = pixels[kind];
      ASSERT_GE(pixel.x, 0) << technique << ": no unambiguous pixel of kind " << kind;
      const std::string label = format(technique, " pixel ", pixel.x, ",", pixel.y);
      const ProbeRecord& record = records[kind];
      const auto quantity = [&](const char* name) {
        const ProbeQuantity* found = record.find(name);
        EXPECT_NE(found, nullptr) << label << ": " << name << " not recorded";
        return found != nullptr ? found->value.at(0) : -1.0;
      };
      const auto gpu = [&](const char* buffer) { return static_cast<double>(frame.find(buffer)->image.at(pixel.x, pixel.y)); };
      EXPECT_LE(std::abs(outcomes[kind].visibility - gpu("visibility")), outcomes[kind].tolerance) << label;
      EXPECT_EQ(quantity("kernel_texels"), gpu("kernel_texels")) << label;
      double boxSum = 0.0;
      double boxWeight = 0.0;
      int boxTexels = 0;
      double occluding = 0.0;
      for (const ProbeTexel& texel : record.texels)
      {
        if (texel.role == "moment box")
        {
          boxSum += texel.storedDepth;
          boxWeight += texel.weight;
          ++boxTexels;
        }
        else
        {
          ASSERT_EQ(texel.role, "light-leak pcf") << label;
          occluding += texel.occluding ? texel.weight : 0.0;
        }
      }
      EXPECT_EQ(boxTexels, 25) << label;
      EXPECT_NEAR(boxWeight, 1.0, 1e-12) << label;
      EXPECT_NEAR(occluding, 1.0 - quantity("box_pcf"), 1e-12) << label;
      const double tolerance = outcomes[kind].tolerance;
      if (technique == "vsm")
      {
        EXPECT_NEAR(quantity("mean"), boxSum / boxTexels, 1e-12 * boxSum) << label;
        EXPECT_NEAR(quantity("p_max"), gpu("p_max"), tolerance) << label;
      }
      else
      {
        EXPECT_EQ(quantity("visibility"), outcomes[kind].visibility) << label;
      }
      // light_leak, or the range its tied comparisons allow.
      glm::dvec2 leak(0.0);
      if (const ProbeQuantity* exact = record.find("light_leak"))
      {
        EXPECT_EQ(quantity("light_leak_tied_comparisons"), 0.0) << label;
        leak = glm::dvec2(exact->value.at(0));
      }
      else
      {
        const ProbeQuantity* range = record.find("light_leak_range");
        ASSERT_NE(range, nullptr) << label << ": neither light_leak nor light_leak_range";
        EXPECT_GT(quantity("light_leak_tied_comparisons"), 0.0) << label;
        leak = glm::dvec2(range->value.at(0), range->value.at(1));
      }
      EXPECT_GE(gpu("light_leak"), leak.x - tolerance) << label;
      EXPECT_LE(gpu("light_leak"), leak.y + tolerance) << label;
      std::cout << "[ measured ] " << label << ": GPU " << gpu("visibility") << ", probe " << outcomes[kind].visibility
                << ", light_leak GPU " << gpu("light_leak") << " probe [" << leak.x << ", " << leak.y << "]\n";
    }
  }
}

double maxLightLeakOnGround(const FrameResult& frame, double& fractionAbove)
{
  const ImageF& position = frame.find("position")->image;
  const ImageF& coverage = frame.find("coverage")->image;
  const ImageF& leak = frame.find("light_leak")->image;
  double maximum = 0.0;
  int ground = 0;
  int above = 0;
  for (int y = 0; y < position.height; ++y)
  {
    for (int x = 0; x < position.width; ++x)
    {
      if (coverage.at(x, y) < 0.5f || std::abs(position.at(x, y, 1)) > 1e-4)
      {
        continue;
      }
      ++ground;
      maximum = std::max(maximum, static_cast<double>(std::abs(leak.at(x, y))));
      above += std::abs(leak.at(x, y)) > 0.02f ? 1 : 0;
    }
  }
  fractionAbove = static_cast<double>(above) / std::max(1, ground);
  return maximum;
}

TEST(MomentTechniques, ChebyshevIsExactForTwoDepthsAndBleedsForMore)
{
  const std::vector<std::string> settings{ "shadow_map_size=256", "prefilter_texels=9", "light_bleeding_reduction=0" };
  double planarFraction = 0.0;
  const FrameResult planar = test::renderDataset(test::loadDataset("planar-occluder"), "vsm", 128, 128, settings);
  const double planarMax = maxLightLeakOnGround(planar, planarFraction);
  double stackedFraction = 0.0;
  const FrameResult stacked = test::renderDataset(test::loadDataset("stacked-occluders"), "vsm", 128, 128, settings);
  const double stackedMax = maxLightLeakOnGround(stacked, stackedFraction);
  std::cout << "[ measured ] vsm light leak on the ground: planar-occluder max " << planarMax << " (" << planarFraction * 100
            << "% > 0.02), stacked-occluders max " << stackedMax << " (" << stackedFraction * 100 << "% > 0.02)\n";
  EXPECT_LT(planarMax, 0.01) << "two depths: p_max equals the PCF result";
  EXPECT_GT(stackedMax, 0.1) << "stacked occluders: VSM must bleed light between them";
}

} // namespace
} // namespace sl
