// savsm and its summed-area table: the table's box moments against exact double sums for both precisions
// (the survey's §6.4 question, measured and printed), the GLSL against the CPU implementation, and the
// closed form where Chebyshev over two depths is exact (planar occluder).
#include "support/TestSupport.h"
#include "techniques/ShadowMapParameters.h"
#include "techniques/savsm/SavsmTechnique.h"
#include "lightspace/sat/SummedAreaTable.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>

namespace sl
{
namespace
{

TEST(SummedAreaTable, BoxMomentsOfBothPrecisionsAgainstExactSums)
{
  const Scene scene = test::loadDataset("stacked-occluders");
  const FrameResult integer =
    test::renderDataset(scene, "savsm", 64, 64, { "shadow_map_size=512", "sat_precision=int32" });
  const FrameResult floating =
    test::renderDataset(scene, "savsm", 64, 64, { "shadow_map_size=512", "sat_precision=float_centred" });
  ASSERT_TRUE(integer.integerSummedAreaTable.has_value());
  const ImageF& shadowMap = test::lightSpaceArray(integer, "shadow_map_depth");
  const double nearDepth = integer.lightView->nearDepth;
  const double farDepth = integer.lightView->farDepth;
  const ImageF floatTable = test::floatSummedAreaTable(floating);
  std::mt19937 generator(7u);
  std::uniform_int_distribution<int> coordinate(0, 511);
  double integerMeanError = 0.0;
  double integerVarianceError = 0.0;
  double floatMeanError = 0.0;
  double floatVarianceError = 0.0;
  double integerQuantisedMeanError = 0.0;
  for (int box = 0; box < 300; ++box)
  {
    glm::ivec2 a(coordinate(generator), coordinate(generator));
    glm::ivec2 b(coordinate(generator), coordinate(generator));
    const glm::ivec2 lo = glm::min(a, b);
    const glm::ivec2 hi = glm::max(a, b);
    const BoxMoments exact = exactBoxMoments(shadowMap, lo, hi, nearDepth, farDepth, false);
    const BoxMoments quantised = exactBoxMoments(shadowMap, lo, hi, nearDepth, farDepth, true);
    const BoxMoments fromInteger = boxMomentsFromIntegerTable(*integer.integerSummedAreaTable, lo, hi, nearDepth, farDepth);
    const BoxMoments fromFloat = boxMomentsFromFloatTable(floatTable, lo, hi, nearDepth, farDepth);
    // The integer table sums exactly: its box moments are the quantised depths' moments.
    integerQuantisedMeanError = std::max(integerQuantisedMeanError, std::abs(fromInteger.mean - quantised.mean));
    integerMeanError = std::max(integerMeanError, std::abs(fromInteger.mean - exact.mean));
    integerVarianceError = std::max(integerVarianceError, std::abs(fromInteger.variance - exact.variance));
    floatMeanError = std::max(floatMeanError, std::abs(fromFloat.mean - exact.mean));
    floatVarianceError = std::max(floatVarianceError, std::abs(fromFloat.variance - exact.variance));
  }
  std::cout << "[ measured ] SAT box moments over 300 random boxes of a 512^2 map (depth range "
            << farDepth - nearDepth << "): int32 (" << std::log2(satFixedPointScale(512) + 1.0)
            << "-bit fixed point) max mean error " << integerMeanError << ", variance " << integerVarianceError
            << "; float_centred max mean error " << floatMeanError << ", variance " << floatVarianceError << "\n";
  EXPECT_LT(integerQuantisedMeanError, 1e-9) << "int32 box sums must be exact";
  // Quantisation to b bits bounds the int32 error by half a step of the depth range.
  EXPECT_LE(integerMeanError, 0.5 * (farDepth - nearDepth) / satFixedPointScale(512) + 1e-12);
  EXPECT_LT(floatMeanError, 1e-2) << "float SAT precision far worse than expected";
}

TEST(Savsm, MatchesTheCpuImplementation)
{
  for (const std::string dataset : { "stacked-occluders", "contact" })
  {
    const Scene scene = test::loadDataset(dataset);
    const FrameResult frame = test::renderDataset(scene, "savsm", 96, 80, { "shadow_map_size=512", "sat_precision=int32" });
    const ShadowMapInputs inputs = test::shadowMapInputs(frame, scene);
    const ImageF& visibility = frame.find("visibility")->image;
    int compared = 0;
    int skipped = 0;
    int partial = 0;
    double maxDifference = 0.0;
    for (int y = 0; y < 80; ++y)
    {
      for (int x = 0; x < 96; ++x)
      {
        const SavsmSample cpu = savsmReference(inputs, frame.parameters, x, y);
        if (!cpu.sample.evaluated)
        {
          continue;
        }
        const ShadowLookup lookup = prepareShadowLookup(inputs, biasSettings(frame.parameters), x, y);
        const double d = lookup.sm.depthLin;
        // Float on the GPU: kernel edges at texel centres, tests at their boundary, small variances (see
        // PcssTest and MomentTest) are counted, not compared.
        if (cpu.kernelEdgeMargin < 1e-4 || cpu.sample.depthMargin < 2e-6 || cpu.sample.texelEdgeMargin < 1e-4 ||
          cpu.sample.reachMargin < 1e-5 || (cpu.foundBlockers && cpu.variance < 1e-3 * d * d))
        {
          ++skipped;
          continue;
        }
        ++compared;
        partial += (cpu.sample.visibility > 0.0 && cpu.sample.visibility < 1.0) ? 1 : 0;
        maxDifference = std::max(maxDifference, std::abs(visibility.at(x, y) - cpu.sample.visibility));
        EXPECT_NEAR(visibility.at(x, y), cpu.sample.visibility, 2e-3) << dataset << " pixel " << x << "," << y;
      }
    }
    std::cout << "[ measured ] savsm " << dataset << ": compared " << compared << " (partial " << partial
              << "), skipped " << skipped << ", max |gpu - cpu| " << maxDifference << "\n";
    EXPECT_GT(compared, 2000) << dataset;
    EXPECT_GT(partial, 200) << dataset;
  }
}

TEST(Savsm, ExactForAParallelPlanarOccluder)
{
  // Two depths in every penumbra kernel: Chebyshev equals the PCF there, so savsm is as exact as pcss.
  const Scene scene = test::loadDataset("planar-occluder");
  for (const std::string precision : { "int32", "float_centred" })
  {
    const FrameResult frame = test::renderDataset(scene, "savsm", 128, 128, { "sat_precision=" + precision });
    const double rmse = test::groundErrorAgainst(frame, [](double x, double z) {
      return test::parallelSquaresVisibility(1.0, 3.0, 1.0, 1.0, x, z);
    }).rmse;
    std::cout << "[ measured ] savsm (" << precision << ") on planar-occluder against the closed form: RMSE " << rmse << "\n";
    EXPECT_LT(rmse, 0.02) << precision;
  }
}

} // namespace
} // namespace sl
