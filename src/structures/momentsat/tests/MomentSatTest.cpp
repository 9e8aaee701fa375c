// The moment summed-area table (structures/momentsat) on llvmpipe: the GPU's 64-bit words equal the CPU mirror's
// (lightspace/MomentSummedAreaTable) bit for bit, random box sums equal direct uint64 sums of the quantised texels,
// and the box means the lookup decodes in float lie within float rounding of the double means of the texels' moments.
#include "support/TestSupport.h"
#include "lightspace/MomentSummedAreaTable.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>

namespace sl
{
namespace
{

// MomentSatLookup.glsl's box mean in float: (float(high) 2^32 + float(low)) / 2^b / float(texels), per component.
double momentSatFloatMean(std::uint64_t sum, double texels, double scale)
{
  const float high = static_cast<float>(static_cast<std::uint32_t>(sum >> 32));
  const float low = static_cast<float>(static_cast<std::uint32_t>(sum & 0xFFFFFFFFu));
  return static_cast<double>((high * 4294967296.0f + low) / static_cast<float>(scale) / static_cast<float>(texels));
}

// `maxKernel` > 0: moment_sat_precision = int32 for boxes up to maxKernel^2 texels (random boxes drawn within it).
void checkMomentSatAt(int mapSize, int boxes, int maxKernel = 0)
{
  const Scene scene = test::loadDataset("stacked-occluders");
  std::vector<std::string> settings{ "shadow_map_size=" + std::to_string(mapSize) };
  if (maxKernel > 0)
  {
    settings.push_back("moment_sat_precision=int32");
    settings.push_back("moment_sat_max_kernel_texels=" + std::to_string(maxKernel));
  }
  const MomentSatFormat format = maxKernel > 0 ? int32MomentSatFormat(maxKernel) : MomentSatFormat{};
  const FrameResult frame = test::renderDataset(scene, "msmsoft", 32, 32, settings);
  ASSERT_TRUE(frame.momentSummedAreaTable.has_value());
  ASSERT_EQ(frame.momentSummedAreaTable->components, format.wide ? 8 : 4);
  const ImageF& shadowMap = test::lightSpaceArray(frame, "shadow_map_depth");
  const double nearDepth = frame.lightView->nearDepth;
  const double farDepth = frame.lightView->farDepth;
  const Image<std::uint64_t> gpu = momentSummedAreaTableFromWords(*frame.momentSummedAreaTable);
  const MomentSatTable cpu = momentSummedAreaTable(shadowMap, nearDepth, farDepth, format);
  ASSERT_EQ(gpu.width, mapSize);
  // int32: the GPU holds the exact sums modulo 2^32.
  const std::uint64_t wordMask = format.wide ? ~std::uint64_t{ 0 } : 0xFFFFFFFFu;
  std::size_t differingWords = 0;
  for (std::size_t i = 0; i < gpu.data.size(); ++i)
  {
    differingWords += gpu.data[i] != (cpu.sums.data[i] & wordMask) ? 1 : 0;
  }
  EXPECT_EQ(differingWords, 0u) << mapSize << "^2: the GPU's table differs from the CPU mirror's";

  // The texels' quantised moments and their double moments (z in double, unquantised).
  Image<std::uint32_t> quantised(mapSize, mapSize, 4);
  const float nearFloat = static_cast<float>(nearDepth);
  const float farFloat = static_cast<float>(farDepth);
  for (int y = 0; y < mapSize; ++y)
  {
    for (int x = 0; x < mapSize; ++x)
    {
      const std::array<std::uint32_t, 4> texel = momentSatTexel(shadowMap.at(x, y), nearFloat, farFloat, format.bits);
      for (int k = 0; k < 4; ++k)
      {
        quantised.at(x, y, k) = texel[static_cast<std::size_t>(k)];
      }
    }
  }
  std::mt19937 generator(11u + static_cast<unsigned>(mapSize));
  std::uniform_int_distribution<int> coordinate(0, mapSize - 1);
  // int32: boxes of at most maxKernel x maxKernel texels (the sizes it sums exactly).
  std::uniform_int_distribution<int> extent(1, maxKernel > 0 ? maxKernel : mapSize);
  int differingSums = 0;
  double largestMeanError = 0.0;     // |float decode - double mean of the double moments|
  double largestRelativeError = 0.0; // the same relative to the mean, over means above 1e-3
  for (int box = 0; box < boxes; ++box)
  {
    const glm::ivec2 a(coordinate(generator), coordinate(generator));
    const glm::ivec2 b = maxKernel > 0 ? glm::min(a + glm::ivec2(extent(generator), extent(generator)) - 1, mapSize - 1)
                                       : glm::ivec2(coordinate(generator), coordinate(generator));
    const glm::ivec2 lo = glm::min(a, b);
    const glm::ivec2 hi = glm::max(a, b);
    MomentSums direct{};
    glm::dvec4 exact(0.0);
    for (int y = lo.y; y <= hi.y; ++y)
    {
      for (int x = lo.x; x <= hi.x; ++x)
      {
        const double z = std::clamp((shadowMap.at(x, y) - nearDepth) / (farDepth - nearDepth), 0.0, 1.0);
        exact += glm::dvec4(z, z * z, z * z * z, z * z * z * z);
        for (int k = 0; k < 4; ++k)
        {
          direct[static_cast<std::size_t>(k)] += quantised.at(x, y, k);
        }
      }
    }
    const double texels = static_cast<double>(hi.x - lo.x + 1) * (hi.y - lo.y + 1);
    exact /= texels;
    MomentSums fromTable = momentBoxSum(gpu, lo, hi);
    for (std::uint64_t& sum : fromTable)
    {
      sum &= wordMask; // int32: exact modulo 2^32, and the box's sum is below 2^32
    }
    differingSums += fromTable != direct ? 1 : 0;
    for (int k = 0; k < 4; ++k)
    {
      const double error =
        std::abs(momentSatFloatMean(fromTable[static_cast<std::size_t>(k)], texels, format.scale()) - exact[k]);
      largestMeanError = std::max(largestMeanError, error);
      largestRelativeError = exact[k] > 1e-3 ? std::max(largestRelativeError, error / exact[k]) : largestRelativeError;
      // Float rounding: the texel's z in float (a few ulps, times k for z^k, and near's rounding to float relative
      // to the range), the decode's two roundings, and the quantisation step 2^-bits.
      EXPECT_LE(error, 16.0 * 0x1p-24 * (exact[k] + nearDepth / (farDepth - nearDepth)) + 1.0 / format.scale()) << mapSize << "^2 box " << box << " moment " << k + 1;
    }
  }
  std::cout << "[ measured ] moment SAT " << mapSize << "^2 ("
            << (format.wide ? std::string("int64") : "int32, " + std::to_string(format.bits) + " bits") << "): GPU table words differing from the CPU mirror: "
            << differingWords << "; " << boxes << " random boxes: sums differing from direct uint64 sums " << differingSums
            << ", largest |float box mean - double mean| " << largestMeanError << " (relative " << largestRelativeError
            << ")\n";
  EXPECT_EQ(differingSums, 0) << mapSize << "^2: box sums must be exact";

  // The exported per-texel moments: each texel's decoded one-texel box.
  const ImageF& texelZ2 = test::lightSpaceArray(frame, "moment_sat_texel_2");
  double largestTexelError = 0.0;
  for (int y = 0; y < mapSize; y += 7)
  {
    for (int x = 0; x < mapSize; x += 5)
    {
      largestTexelError =
        std::max(largestTexelError, std::abs(texelZ2.at(x, y) - quantised.at(x, y, 1) / format.scale()));
    }
  }
  EXPECT_LE(largestTexelError, 1e-7) << "moment_sat_texel_2 must be the texel's quantised z^2";
}

TEST(MomentSat, BoxSumsAreExactAt512)
{
  checkMomentSatAt(512, 200);
}

TEST(MomentSat, BoxSumsAreExactAt2048)
{
  checkMomentSatAt(2048, 40);
}

// The authors' 32-bit form: 16 bits per texel for boxes up to 256^2, 20 for 64^2; sums wrap, boxes within it exact.
TEST(MomentSat, Int32BoxSumsAreExactWithinTheirLargestKernel)
{
  checkMomentSatAt(512, 200, 256);
  checkMomentSatAt(512, 200, 64);
}

// The fractional rectangle: its mean is the area-weighted mean of the texels it touches (checked against a direct
// double sum), equals the integer box's at integer edges, and is continuous across a texel edge.
TEST(MomentSat, FractionalBoxIsTheAreaWeightedMean)
{
  Image<float> map(16, 16, 1);
  std::mt19937 generator(5u);
  std::uniform_real_distribution<float> depth(1.0f, 9.0f);
  for (float& value : map.data)
  {
    value = depth(generator);
  }
  const MomentSatTable table = momentSummedAreaTable(map, 1.0, 9.0);
  std::uniform_real_distribution<double> position(-2.0, 18.0);
  double largest = 0.0;
  for (int trial = 0; trial < 200; ++trial)
  {
    glm::dvec2 a(position(generator), position(generator));
    glm::dvec2 b(position(generator), position(generator));
    const glm::dvec2 boxMin = glm::min(a, b);
    const glm::dvec2 boxMax = glm::max(a, b);
    const glm::dvec2 clampedMin = glm::clamp(boxMin, 0.0, 16.0);
    const glm::dvec2 clampedMax = glm::clamp(boxMax, 0.0, 16.0);
    if (!(clampedMax.x > clampedMin.x && clampedMax.y > clampedMin.y))
    {
      continue;
    }
    glm::dvec4 sum(0.0);
    double area = 0.0;
    for (int y = 0; y < 16; ++y)
    {
      for (int x = 0; x < 16; ++x)
      {
        const double coverX = std::max(0.0, std::min(clampedMax.x, x + 1.0) - std::max(clampedMin.x, double(x)));
        const double coverY = std::max(0.0, std::min(clampedMax.y, y + 1.0) - std::max(clampedMin.y, double(y)));
        const std::array<std::uint32_t, 4> q = momentSatTexel(map.at(x, y), 1.0f, 9.0f);
        sum += coverX * coverY * glm::dvec4(q[0], q[1], q[2], q[3]) / table.format.scale();
        area += coverX * coverY;
      }
    }
    const glm::dvec4 mean = momentFractionalBoxMean(table, boxMin, boxMax);
    for (int k = 0; k < 4; ++k)
    {
      largest = std::max(largest, std::abs(mean[k] - sum[k] / area));
    }
  }
  EXPECT_LT(largest, 1e-12);
  const glm::dvec4 integer = momentBoxMean(table, { 3, 4 }, { 9, 12 });
  const glm::dvec4 fractional = momentFractionalBoxMean(table, { 3.0, 4.0 }, { 10.0, 13.0 });
  const glm::dvec4 nudged = momentFractionalBoxMean(table, { 3.0 - 1e-9, 4.0 }, { 10.0, 13.0 + 1e-9 });
  for (int k = 0; k < 4; ++k)
  {
    EXPECT_NEAR(fractional[k], integer[k], 1e-14);
    EXPECT_NEAR(nudged[k], integer[k], 1e-8) << "continuous across a texel edge";
  }
}

} // namespace
} // namespace sl
