// The summed-area table's banded build (gl/BandedPrefixSums.h): the GPU's table, built on llvmpipe in one band
// (256^2), two (1024^2) and eight (2048^2), against the CPU mirror (lightspace/SummedAreaTable.h) texel by texel. A band that
// started its columns from the wrong carry, or was copied to the wrong rows, would move every entry below it.
#include "gl/BandedPrefixSums.h"
#include "lightspace/SummedAreaTable.h"
#include "support/TestSupport.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <random>
#include <string>

namespace sl
{
namespace
{

// A texel's own entry, recovered from its table by the four corners (exact modulo 2^32).
std::uint32_t entryOf(const Image<std::uint32_t>& table, int x, int y, int component)
{
  std::uint32_t entry = table.at(x, y, component);
  if (x > 0)
  {
    entry -= table.at(x - 1, y, component);
  }
  if (y > 0)
  {
    entry -= table.at(x, y - 1, component);
  }
  if (x > 0 && y > 0)
  {
    entry += table.at(x - 1, y - 1, component);
  }
  return entry;
}

TEST(SatBuild, EveryBandEqualsTheCpuMirror)
{
  const Scene scene = test::loadDataset("stacked-occluders");
  std::string renderer;
  for (const int mapSize : { 256, 1024, 2048 })
  {
    const FrameResult frame = test::renderDataset(
      scene, "savsm", 32, 32, { "shadow_map_size=" + std::to_string(mapSize), "sat_precision=int32" });
    ASSERT_TRUE(frame.integerSummedAreaTable.has_value());
    renderer = frame.glRenderer;
    const int bandRows = BandedPrefixSums::bandRowsFor(mapSize, 2, BandedPrefixSums::bandBytesOfThisGl());
    const int bands = (mapSize + bandRows - 1) / bandRows;
    const Image<std::uint32_t>& gpu = *frame.integerSummedAreaTable;
    const Image<std::uint32_t> cpu = integerSummedAreaTable(
      test::lightSpaceArray(frame, "shadow_map_depth"), frame.lightView->nearDepth, frame.lightView->farDepth);
    ASSERT_EQ(gpu.width, mapSize);
    ASSERT_EQ(cpu.width, mapSize);
    // The GPU quantises z_n in float, the mirror in double: an entry exactly between two fixed-point steps may
    // round either way (SummedAreaTable.cpp), so entries may differ by one step, and rarely.
    std::size_t entriesOffByOne = 0;
    std::size_t entriesOffByMore = 0;
    for (int y = 0; y < mapSize; ++y)
    {
      for (int x = 0; x < mapSize; ++x)
      {
        for (int component = 0; component < 2; ++component)
        {
          const std::uint32_t difference = entryOf(gpu, x, y, component) - entryOf(cpu, x, y, component);
          entriesOffByOne += difference == 1u || difference == ~0u ? 1 : 0;
          entriesOffByMore += difference != 0u && difference != 1u && difference != ~0u ? 1 : 0;
        }
      }
    }
    std::cout << "[ measured ] " << mapSize << "^2 in " << bands << " band(s): " << entriesOffByOne
              << " entries one fixed-point step from the mirror's, " << entriesOffByMore << " further\n";
    EXPECT_EQ(entriesOffByMore, 0u) << mapSize << "^2";
    EXPECT_LE(entriesOffByOne, static_cast<std::size_t>(mapSize) * mapSize / 1000) << mapSize << "^2";
  }
  // llvmpipe builds 1024^2 in two bands and 2048^2 in eight (a GPU each in one).
  const std::size_t bandBytes = BandedPrefixSums::bandBytesOfThisGl();
  EXPECT_EQ(BandedPrefixSums::bandRowsFor(256, 2, BandedPrefixSums::kCpuBandBytes), 256);
  EXPECT_EQ(BandedPrefixSums::bandRowsFor(1024, 2, BandedPrefixSums::kCpuBandBytes), 512);
  EXPECT_EQ(BandedPrefixSums::bandRowsFor(2048, 2, BandedPrefixSums::kCpuBandBytes), 256);
  EXPECT_EQ(BandedPrefixSums::bandRowsFor(2048, 2, BandedPrefixSums::kGpuBandBytes), 2048);
  if (renderer.find("llvmpipe") != std::string::npos)
  {
    EXPECT_EQ(bandBytes, BandedPrefixSums::kCpuBandBytes) << renderer;
  }
  else
  {
    EXPECT_GE(bandBytes, BandedPrefixSums::kCpuBandBytes) << renderer;
    EXPECT_LE(bandBytes, BandedPrefixSums::kGpuBandBytes) << renderer;
  }
}

// float_centred over eight bands (llvmpipe): box moments from the GPU's float table against exact double sums, as
// SummedAreaTable.BoxMomentsOfBothPrecisionsAgainstExactSums measures them at 512^2 (one band).
TEST(SatBuild, FloatTableOfEightBandsGivesTheBoxMoments)
{
  const Scene scene = test::loadDataset("stacked-occluders");
  const FrameResult frame =
    test::renderDataset(scene, "savsm", 32, 32, { "shadow_map_size=2048", "sat_precision=float_centred" });
  const ImageF& shadowMap = test::lightSpaceArray(frame, "shadow_map_depth");
  const ImageF table = test::floatSummedAreaTable(frame);
  const double nearDepth = frame.lightView->nearDepth;
  const double farDepth = frame.lightView->farDepth;
  std::mt19937 generator(11u);
  std::uniform_int_distribution<int> coordinate(0, 2047);
  std::uniform_int_distribution<int> extent(0, 40);
  double largestMeanError = 0.0;
  for (int box = 0; box < 300; ++box)
  {
    // Boxes of up to 41 texels (kernels, not the whole map), anywhere, many across a band's edge.
    const glm::ivec2 lo(coordinate(generator), coordinate(generator));
    const glm::ivec2 hi = glm::min(lo + glm::ivec2(extent(generator), extent(generator)), glm::ivec2(2047));
    const BoxMoments exact = exactBoxMoments(shadowMap, lo, hi, nearDepth, farDepth, false);
    const BoxMoments fromTable = boxMomentsFromFloatTable(table, lo, hi, nearDepth, farDepth);
    largestMeanError = std::max(largestMeanError, std::abs(fromTable.mean - exact.mean));
  }
  std::cout << "[ measured ] float_centred 2048^2 in 8 bands: largest box-mean error " << largestMeanError
            << " over 300 boxes (depth range " << farDepth - nearDepth << ")\n";
  // float sums of up to 4M centred depths lose about 2^-24 of the corner magnitudes; a wrong band loses whole rows.
  EXPECT_LT(largestMeanError, 0.05 * (farDepth - nearDepth));
}

} // namespace
} // namespace sl
