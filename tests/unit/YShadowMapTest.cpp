// The Y shadow map (Schwarz & Stamminger 2008, SS08 §6, Table 1) on the CPU
// (HierarchicalShadowMap, layout Ysm): its base level and MSSM-part size, its MSSM part against brute force,
// its range query against brute force (conservative, exact on rectangles aligned to level-b blocks) and against
// the mip-map HSM's query (never looser), and its memory against Table 1's closed forms.
#include "lightspace/HierarchicalShadowMap.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <iomanip>
#include <iostream>
#include <random>
#include <sstream>

namespace sl
{
namespace
{

// A random N x N depth map with structure at every scale (so rectangle ranges depend on where the rectangle
// is): a few random waves, plus per-texel noise, plus a few empty texels (2 x far = 20, as the shadow map
// stores them).
ImageF randomDepthMap(int size, unsigned seed)
{
  std::mt19937 generator(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  ImageF depth(size, size, 1);
  double frequency[3][2];
  double phase[3];
  for (int wave = 0; wave < 3; ++wave)
  {
    frequency[wave][0] = (0.5 + 20.0 * unit(generator)) / size;
    frequency[wave][1] = (0.5 + 20.0 * unit(generator)) / size;
    phase[wave] = 6.28 * unit(generator);
  }
  for (int y = 0; y < size; ++y)
  {
    for (int x = 0; x < size; ++x)
    {
      double z = 5.0;
      for (int wave = 0; wave < 3; ++wave)
      {
        z += std::sin(6.28 * (frequency[wave][0] * x + frequency[wave][1] * y) + phase[wave]);
      }
      z += 0.05 * unit(generator);
      depth.at(x, y) = unit(generator) < 0.001 ? 20.0f : static_cast<float>(z);
    }
  }
  return depth;
}

glm::dvec2 bruteForceRange(const ImageF& depth, glm::ivec2 lo, glm::ivec2 hi)
{
  float low = depth.at(lo.x, lo.y);
  float high = low;
  for (int y = lo.y; y <= hi.y; ++y)
  {
    for (int x = lo.x; x <= hi.x; ++x)
    {
      low = std::min(low, depth.at(x, y));
      high = std::max(high, depth.at(x, y));
    }
  }
  return { low, high };
}

TEST(YShadowMap, BaseLevelGivesAbout256SquaredMssmPart)
{
  // b = max(0, floor(log2 (N / 256))) (SS08 §6: n - 1 = 2 at 1024^2, 3 at 2048^2), M = ceil(N / 2^b).
  for (const int n : { 1, 2, 100, 128, 255, 256, 300, 511, 512, 513, 1000, 1023, 1024, 1500, 2047, 2048, 4096 })
  {
    const int expectedBase = std::max(0, static_cast<int>(std::floor(std::log2(n / 256.0))));
    EXPECT_EQ(ysmBaseLevel(n), expectedBase) << n;
    const int expectedSize = static_cast<int>(std::ceil(n / std::pow(2.0, expectedBase)));
    EXPECT_EQ(ysmMssmPartSize(n), expectedSize) << n;
    EXPECT_EQ(ysmMssmPartLevelCount(n), static_cast<int>(std::ceil(std::log2(expectedSize)))) << n;
    EXPECT_EQ(hsmLevelSize(HsmLayout::Ysm, n, 3), hsmLevelSize(HsmLayout::MipMap, n, 3)) << "YSM levels are the mip-map's";
  }
  EXPECT_EQ(ysmBaseLevel(1024), 2);
  EXPECT_EQ(ysmBaseLevel(2048), 3);
  EXPECT_EQ(ysmMssmPartSize(1024), 256);
  EXPECT_EQ(ysmMssmPartSize(2048), 256);
  EXPECT_EQ(ysmBaseLevel(511), 0);
  EXPECT_EQ(ysmMssmPartSize(511), 511);
}

TEST(YShadowMap, HoldsTheMipMapHsmAndTheNBuffersOfLevelB)
{
  for (const int n : { 100, 1000 })
  {
    const ImageF depth = randomDepthMap(n, 5u + static_cast<unsigned>(n));
    const HierarchicalShadowMap ysm = HierarchicalShadowMap::build(depth, HsmLayout::Ysm);
    const HierarchicalShadowMap mip = HierarchicalShadowMap::build(depth, HsmLayout::MipMap);
    ASSERT_EQ(ysm.levels.size(), mip.levels.size());
    for (std::size_t level = 0; level < mip.levels.size(); ++level)
    {
      EXPECT_EQ(ysm.levels[level].data, mip.levels[level].data) << "level " << level << " at " << n;
    }
    EXPECT_EQ(ysm.atlas().data, mip.atlas().data);
    const int b = ysm.ysmBaseLevel;
    EXPECT_EQ(b, ysmBaseLevel(n));
    const int m = ysmMssmPartSize(n);
    ASSERT_EQ(static_cast<int>(ysm.mssmPart.size()), ysmMssmPartLevelCount(n));
    // Part level j at node t: the range of level-b nodes [t, t + 2^j) clipped to the grid, i.e. of the
    // shadow-map texels [t 2^b, (t + 2^j) 2^b) clipped to the map.
    const ImageF& base = ysm.levels[static_cast<std::size_t>(b)];
    int differing = 0;
    std::mt19937 generator(7u);
    std::uniform_int_distribution<int> coordinate(0, m - 1);
    for (int j = 1; j <= static_cast<int>(ysm.mssmPart.size()); ++j)
    {
      const ImageF& part = ysm.mssmPart[static_cast<std::size_t>(j - 1)];
      ASSERT_EQ(part.width, m);
      ASSERT_EQ(part.height, m);
      // 64 random texels per level, and the last one (its squares clipped to the grid on both axes).
      for (int sample = 0; sample <= 64; ++sample)
      {
        const int x = sample == 64 ? m - 1 : coordinate(generator);
        const int y = sample == 64 ? m - 1 : coordinate(generator);
        {
          const glm::ivec2 last = glm::min(glm::ivec2(x, y) + (1 << j) - 1, glm::ivec2(m - 1));
          float low = base.at(x, y, 0);
          float high = base.at(x, y, 1);
          for (int v = y; v <= last.y; ++v)
          {
            for (int u = x; u <= last.x; ++u)
            {
              low = std::min(low, base.at(u, v, 0));
              high = std::max(high, base.at(u, v, 1));
            }
          }
          const glm::dvec2 texels = bruteForceRange(depth, glm::ivec2(x, y) << b,
            glm::min(((last + 1) << b) - 1, glm::ivec2(n - 1)));
          differing += part.at(x, y, 0) != low || part.at(x, y, 1) != high ? 1 : 0;
          differing += part.at(x, y, 0) != texels.x || part.at(x, y, 1) != texels.y ? 1 : 0;
        }
      }
    }
    EXPECT_EQ(differing, 0) << n;
  }
}

// 300 random rectangles per map size, the longer side log-uniform in [1, N] and the other log-uniform up to it
// (so both branches of the query occur: k <= b, the mip-map query, and k > b, the MSSM part), plus 100
// rectangles aligned to level-b blocks.
TEST(YShadowMap, RangesAreConservativeNeverLooserThanTheMipMapAndExactWhenAligned)
{
  for (const int n : { 128, 1000, 1024, 2048 })
  {
    const ImageF depth = randomDepthMap(n, 17u + static_cast<unsigned>(n));
    const HierarchicalShadowMap ysm = HierarchicalShadowMap::build(depth, HsmLayout::Ysm);
    const HierarchicalShadowMap mip = HierarchicalShadowMap::build(depth, HsmLayout::MipMap);
    const int b = ysm.ysmBaseLevel;
    std::mt19937 generator(3u + static_cast<unsigned>(n));
    std::uniform_real_distribution<double> logSide(0.0, std::log2(static_cast<double>(n)));
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    int partQueries = 0;
    int exactQueries = 0;
    int tighterThanMip = 0;
    int maxReads = 0;
    long totalReads = 0;
    double ysmExcess = 0.0; // summed (query width - exact width)
    double mipExcess = 0.0;
    for (int query = 0; query < 300; ++query)
    {
      const double logLonger = logSide(generator);
      const double logShorter = logLonger * unit(generator);
      const bool wide = unit(generator) < 0.5;
      const glm::ivec2 side(static_cast<int>(std::exp2(wide ? logLonger : logShorter)),
        static_cast<int>(std::exp2(wide ? logShorter : logLonger)));
      const glm::ivec2 lo(static_cast<int>(unit(generator) * (n - side.x + 1)), static_cast<int>(unit(generator) * (n - side.y + 1)));
      const glm::ivec2 hi = glm::min(lo + side - 1, glm::ivec2(n - 1));
      const std::string label = std::to_string(n) + "^2 [" + std::to_string(lo.x) + "," + std::to_string(lo.y) + "]-[" +
        std::to_string(hi.x) + "," + std::to_string(hi.y) + "]";
      const glm::dvec2 exact = bruteForceRange(depth, lo, hi);
      int reads = 0;
      const glm::dvec2 range = ysm.range(lo, hi, &reads);
      const glm::dvec2 mipRange = mip.range(lo, hi);
      EXPECT_LE(range.x, exact.x) << label;
      EXPECT_GE(range.y, exact.y) << label;
      EXPECT_GE(range.x, mipRange.x) << label;
      EXPECT_LE(range.y, mipRange.y) << label;
      int mipLevel = 0;
      while ((1 << mipLevel) < std::max(side.x, side.y))
      {
        ++mipLevel;
      }
      if (mipLevel > b)
      {
        ++partQueries;
      }
      else
      {
        EXPECT_EQ(range, mipRange) << label << ": k <= b is the mip-map query";
      }
      exactQueries += range == exact ? 1 : 0;
      tighterThanMip += range != mipRange ? 1 : 0;
      maxReads = std::max(maxReads, reads);
      totalReads += reads;
      ysmExcess += (range.y - range.x) - (exact.y - exact.x);
      mipExcess += (mipRange.y - mipRange.x) - (exact.y - exact.x);
    }
    int alignedExact = 0;
    std::uniform_int_distribution<int> node(0, (n - 1) >> b);
    for (int query = 0; query < 100; ++query)
    {
      const int a = node(generator);
      const int c = node(generator);
      const int d = node(generator);
      const int e = node(generator);
      const glm::ivec2 lo = glm::ivec2(std::min(a, c), std::min(d, e)) << b;
      const glm::ivec2 hi = glm::min(((glm::ivec2(std::max(a, c), std::max(d, e)) + 1) << b) - 1, glm::ivec2(n - 1));
      const glm::dvec2 exact = bruteForceRange(depth, lo, hi);
      const glm::dvec2 range = ysm.range(lo, hi);
      EXPECT_EQ(range, exact) << n << "^2 aligned [" << lo.x << "," << lo.y << "]-[" << hi.x << "," << hi.y << "]";
      alignedExact += range == exact ? 1 : 0;
    }
    if (b == 0)
    {
      EXPECT_EQ(exactQueries, 300) << "b = 0: every rectangle is aligned";
    }
    else
    {
      EXPECT_GT(partQueries, 60) << n << ": the MSSM part must be exercised";
      EXPECT_LT(partQueries, 290) << n << ": the mip-map branch must be exercised";
      EXPECT_GT(tighterThanMip, 30) << n << ": the MSSM part must tighten some ranges";
    }
    std::cout << "[ measured ] YSM " << n << "^2 (b = " << b << ", part " << ysmMssmPartSize(n) << "^2 x "
              << ysm.mssmPart.size() << "): 300 random rectangles, " << partQueries << " through the MSSM part, "
              << exactQueries << " exact, " << tighterThanMip << " tighter than the mip-map HSM; mean excess width "
              << std::setprecision(4) << ysmExcess / 300 << " (mip-map HSM " << mipExcess / 300 << "); reads mean "
              << static_cast<double>(totalReads) / 300 << ", max " << maxReads << "; " << alignedExact
              << " / 100 aligned rectangles exact\n";
  }
}

TEST(YShadowMap, NodeIsTheAlignedBlocksRangeInEveryLayout)
{
  const int n = 200;
  const ImageF depth = randomDepthMap(n, 99u);
  for (const HsmLayout layout : { HsmLayout::MipMap, HsmLayout::NBuffers, HsmLayout::Ysm })
  {
    const HierarchicalShadowMap hsm = HierarchicalShadowMap::build(depth, layout);
    for (int level = 0; level <= hsmLevelCount(n); ++level)
    {
      const int nodes = hsmLevelSize(HsmLayout::MipMap, n, level);
      for (int y = 0; y < nodes; y += 3)
      {
        for (int x = 0; x < nodes; x += 2)
        {
          const glm::ivec2 lo = glm::ivec2(x, y) << level;
          const glm::ivec2 hi = glm::min(((glm::ivec2(x, y) + 1) << level) - 1, glm::ivec2(n - 1));
          ASSERT_EQ(hsm.node(level, { x, y }), bruteForceRange(depth, lo, hi))
            << "layout " << static_cast<int>(layout) << " level " << level << " node " << x << "," << y;
        }
      }
    }
  }
}

// Table 1 (SS08 §6) counts RG32F (8 B per texel) in MiB: HSM = 8 N^2 4/3 (level 0 included, the full mip
// pyramid), YSM = HSM + 8 M^2 log2 M with M = 256. The project keeps level 0 in the shadow map and packs levels
// 1..L in one N x N atlas (8 N^2 bytes on the GPU), and adds the MSSM part, RG32F M x M x ceil(log2 M): its GPU
// bytes are 8 N^2 + 8 M^2 ceil(log2 M) (checked on the GPU in LightSpaceStructureGpuTest). Here: the CPU twin
// holds exactly that part, and YSM - HSM is 4 MiB exactly at 1024^2 and 2048^2, as in Table 1.
TEST(YShadowMap, MemoryMatchesTable1)
{
  const double mib = 1024.0 * 1024.0;
  const auto twoDecimals = [](double value) {
    std::ostringstream text;
    text << std::fixed << std::setprecision(2) << value;
    return text.str();
  };
  struct Row
  {
    int n;
    const char* hsm;
    const char* ysm;
    const char* mssm;
  };
  for (const Row& row : { Row{ 1024, "10.67", "14.67", "88.00" }, Row{ 2048, "42.67", "46.67", "384.00" } })
  {
    const double n = row.n;
    const HierarchicalShadowMap ysm = HierarchicalShadowMap::build(randomDepthMap(row.n, 1u), HsmLayout::Ysm);
    std::size_t partBytes = 0;
    for (const ImageF& level : ysm.mssmPart)
    {
      partBytes += level.data.size() * sizeof(float); // 2 floats per texel, as the GPU's RG32F
    }
    const std::size_t m = static_cast<std::size_t>(ysmMssmPartSize(row.n));
    EXPECT_EQ(partBytes, 8 * m * m * static_cast<std::size_t>(ysmMssmPartLevelCount(row.n)));
    EXPECT_EQ(partBytes, std::size_t(4) << 20) << "YSM - HSM = 4 MiB at " << row.n << "^2 (Table 1)";
    const double paperHsm = 8.0 * n * n * 4.0 / 3.0;
    const double paperMssm = 8.0 * n * n * (std::log2(n) + 1.0);
    EXPECT_EQ(twoDecimals(paperHsm / mib), row.hsm);
    EXPECT_EQ(twoDecimals((paperHsm + static_cast<double>(partBytes)) / mib), row.ysm);
    EXPECT_EQ(twoDecimals(paperMssm / mib), row.mssm);
    const std::size_t projectMip = 8 * static_cast<std::size_t>(row.n) * static_cast<std::size_t>(row.n);
    std::cout << "[ measured ] YSM " << row.n << "^2: MSSM part " << partBytes / mib << " MiB; Table 1 closed forms HSM "
              << twoDecimals(paperHsm / mib) << ", YSM " << twoDecimals((paperHsm + static_cast<double>(partBytes)) / mib)
              << " MiB; project GPU bytes mip-map " << projectMip << ", YSM " << projectMip + partBytes << "\n";
  }
}

} // namespace
} // namespace sl
