// vsm and esm: the GLSL against the CPU implementation (prefilter = blur), and VSM's defining property:
// with two depths in the filter region (a planar occluder over a planar receiver) the Chebyshev bound is
// exact, so its light-leak buffer is zero; with more depths (stacked occluders) it bleeds light.
#include "support/TestSupport.h"
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
    int compared = 0;
    int illConditioned = 0;
    int partial = 0;
    double maxVsm = 0.0;
    double maxEsm = 0.0;
    for (int y = 0; y < 80; ++y)
    {
      for (int x = 0; x < 96; ++x)
      {
        const VsmSample cpu = vsmReference(vsmInputs, vsm.parameters, x, y);
        const double gpu = vsm.find("visibility")->image.at(x, y);
        if (!cpu.sample.evaluated)
        {
          EXPECT_EQ(gpu, cpu.sample.visibility) << dataset << " " << x << "," << y;
          continue;
        }
        const ShadowLookup lookup = prepareShadowLookup(vsmInputs, biasSettings(vsm.parameters), x, y);
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
        const ReferenceSample esmCpu = esmReference(esmInputs, esm.parameters, x, y);
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
