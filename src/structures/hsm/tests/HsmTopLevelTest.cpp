// The N-buffers and the dual-grid MSSM built only up to a top level (issue 33: structures built at the level of detail
// the frame reads; lightspace/HierarchicalShadowMap.h, minMaxTopLevel). Every range query of a hierarchy built to its
// top level equals brute force, and equals the full hierarchy's; below the top level the tiling is unchanged; the
// whole map costs at most (2^4 + 1)^2 squares. The frame's top level follows Eq. 1's kernel of the farthest receiver
// (Yang et al. 2009) and is every level where the technique does not bound its queries.
#include "lightspace/HierarchicalShadowMap.h"
#include "structures/hsm/HsmStructure.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

namespace sl
{
namespace
{

// Blocks of random depth (so that ranges depend on where a rectangle lies), texel noise on top, and a few empty
// texels at 2 x far.
ImageF blockyDepthMap(int size, unsigned seed)
{
  std::mt19937 generator(seed);
  std::uniform_real_distribution<float> depth(1.0f, 5.0f);
  std::uniform_real_distribution<float> noise(0.0f, 0.01f);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const int block = 1 + static_cast<int>(generator() % 13u);
  std::vector<float> blocks(static_cast<std::size_t>((size / block + 1) * (size / block + 1)));
  for (float& value : blocks)
  {
    value = depth(generator);
  }
  ImageF map(size, size, 1);
  for (int y = 0; y < size; ++y)
  {
    for (int x = 0; x < size; ++x)
    {
      const float base = blocks[static_cast<std::size_t>((y / block) * (size / block + 1) + x / block)];
      map.at(x, y) = unit(generator) < 0.002f ? 20.0f : base + noise(generator);
    }
  }
  return map;
}

// (min, max) over the samples [lo, hi], those outside the map at `outside`.
glm::dvec2 bruteForceRange(const ImageF& depth, glm::ivec2 lo, glm::ivec2 hi, float outside)
{
  glm::dvec2 range(1e300, -1e300);
  for (int y = lo.y; y <= hi.y; ++y)
  {
    for (int x = lo.x; x <= hi.x; ++x)
    {
      const bool inside = x >= 0 && y >= 0 && x < depth.width && y < depth.height;
      const double z = inside ? depth.at(x, y) : outside;
      range = { std::min(range.x, z), std::max(range.y, z) };
    }
  }
  return range;
}

// Random rectangles of [first, last] per axis, plus the whole extent and its single rows and columns.
std::vector<std::pair<glm::ivec2, glm::ivec2>> rectangles(int first, int last, unsigned seed)
{
  std::mt19937 generator(seed);
  std::uniform_int_distribution<int> coordinate(first, last);
  std::vector<std::pair<glm::ivec2, glm::ivec2>> result = { { glm::ivec2(first), glm::ivec2(last) },
    { glm::ivec2(first, last), glm::ivec2(last) }, { glm::ivec2(last, first), glm::ivec2(last) } };
  for (int k = 0; k < 300; ++k)
  {
    const glm::ivec2 a(coordinate(generator), coordinate(generator));
    const glm::ivec2 b(coordinate(generator), coordinate(generator));
    result.push_back({ glm::min(a, b), glm::max(a, b) });
  }
  return result;
}

int shorterSideLevel(glm::ivec2 lo, glm::ivec2 hi)
{
  const int shorter = std::min(hi.x - lo.x + 1, hi.y - lo.y + 1);
  return static_cast<int>(std::floor(std::log2(shorter)));
}

TEST(HsmTopLevel, NBufferRangesBuiltToATopLevelAreExact)
{
  for (const int n : { 64, 100, 128 })
  {
    const ImageF depth = blockyDepthMap(n, 7u + static_cast<unsigned>(n));
    const HierarchicalShadowMap full = HierarchicalShadowMap::build(depth, HsmLayout::NBuffers);
    const int levelCount = hsmLevelCount(n);
    for (int top = levelCount - minMaxMaxLevelsLeftOut; top <= levelCount; ++top)
    {
      const HierarchicalShadowMap capped = HierarchicalShadowMap::build(depth, HsmLayout::NBuffers, top);
      ASSERT_EQ(capped.topLevel(), top);
      int wholeMapReads = 0;
      for (const auto& [lo, hi] : rectangles(0, n - 1, 3u * static_cast<unsigned>(top)))
      {
        int reads = 0;
        int fullReads = 0;
        const glm::dvec2 range = capped.range(lo, hi, &reads);
        EXPECT_EQ(range, bruteForceRange(depth, lo, hi, 20.0f)) << n << " top " << top;
        EXPECT_EQ(range, full.range(lo, hi, &fullReads)) << n << " top " << top;
        if (shorterSideLevel(lo, hi) <= top)
        {
          EXPECT_EQ(reads, fullReads) << "below the top level the tiling is the full hierarchy's";
        }
        if (lo == glm::ivec2(0) && hi == glm::ivec2(n - 1))
        {
          wholeMapReads = reads;
        }
      }
      const int side = 1 << std::min(top, shorterSideLevel(glm::ivec2(0), glm::ivec2(n - 1)));
      const int squaresPerAxis = (n + side - 1) / side;
      EXPECT_EQ(wholeMapReads, squaresPerAxis * squaresPerAxis) << n << " top " << top;
      EXPECT_LE(wholeMapReads, ((1 << minMaxMaxLevelsLeftOut) + 1) * ((1 << minMaxMaxLevelsLeftOut) + 1));
    }
  }
}

TEST(HsmTopLevel, DualGridRangesBuiltToATopLevelAreExact)
{
  const float outside = 40.0f;
  for (const int n : { 63, 96, 128 })
  {
    const ImageF depth = blockyDepthMap(n, 11u + static_cast<unsigned>(n));
    const HierarchicalShadowMap full = HierarchicalShadowMap::buildDual(depth, outside);
    const int levelCount = dualMssmLevelCount(n);
    ASSERT_EQ(full.topLevel(), levelCount);
    for (int top = levelCount - minMaxMaxLevelsLeftOut; top <= levelCount; ++top)
    {
      const HierarchicalShadowMap capped = HierarchicalShadowMap::buildDual(depth, outside, top);
      ASSERT_EQ(capped.topLevel(), top);
      // Cells -1 .. N - 1; cell c holds the samples c .. c + 1.
      for (const auto& [cellLo, cellHi] : rectangles(-1, n - 1, 5u * static_cast<unsigned>(top)))
      {
        int reads = 0;
        int fullReads = 0;
        const glm::dvec2 range = capped.dualRange(cellLo, cellHi, &reads);
        EXPECT_EQ(range, bruteForceRange(depth, cellLo, cellHi + 1, outside)) << n << " top " << top;
        EXPECT_EQ(range, full.dualRange(cellLo, cellHi, &fullReads)) << n << " top " << top;
        if (shorterSideLevel(cellLo, cellHi) <= top)
        {
          EXPECT_EQ(reads, fullReads);
        }
      }
      // Every level up to the top is the full hierarchy's, texel for texel.
      for (int level = 0; level <= top; ++level)
      {
        EXPECT_EQ(capped.levels[static_cast<std::size_t>(level)].data, full.levels[static_cast<std::size_t>(level)].data)
          << n << " level " << level;
      }
    }
  }
}

TEST(HsmTopLevel, TopLevelIsTheLevelReadWithinFourOfTheTop)
{
  EXPECT_EQ(minMaxTopLevel(10, 7), 7);
  EXPECT_EQ(minMaxTopLevel(10, 2), 6);
  EXPECT_EQ(minMaxTopLevel(10, 13), 10);
  EXPECT_EQ(minMaxTopLevel(3, 1), 1);
  EXPECT_EQ(minMaxTopLevel(3, 0), 0);
}

// A frame's top level from its light view: Eq. 1's half-width at d = far with the plane at near,
// 0.5 s (far - near) / (near far), in texels of the window's narrower tangent per texel.
TEST(HsmTopLevel, FrameTopLevelFollowsTheFarthestReceiversKernel)
{
  LightView view;
  view.projection = LightProjection::Perspective;
  view.window = { -0.5, 0.5, -0.25, 0.25 }; // tangents per texel: 1 / 1024 (x), 0.5 / 1024 (y)
  view.nearDepth = 1.0;
  view.farDepth = 3.0;
  view.resolution = 1024;
  Light light;
  light.type = LightType::Area;
  light.size = 0.3;
  // Half-width 0.5 * 0.3 * 2 / 3 = 0.1 in tangent: 204.8 texels of 0.5 / 1024, so the widest query is
  // 2 * 205 + 4 = 414 texels: floor(log2) = 8 for the N-buffers' tiling, ceil = 9 for the dual grid's traversal.
  EXPECT_EQ(minMaxTopLevel(HsmLayout::NBuffers, view, light, true), 8);
  EXPECT_EQ(minMaxTopLevel(HsmLayout::DualMssm, view, light, true), 9);
  // Unbounded queries, the mip-map and the YSM: every level.
  EXPECT_EQ(minMaxTopLevel(HsmLayout::NBuffers, view, light, false), 10);
  EXPECT_EQ(minMaxTopLevel(HsmLayout::DualMssm, view, light, false), 11);
  EXPECT_EQ(minMaxTopLevel(HsmLayout::MipMap, view, light, true), 10);
  EXPECT_EQ(minMaxTopLevel(HsmLayout::Ysm, view, light, true), 10);
  // A light ten times smaller: 21 texels, 2 * 21 + 4 = 46 wide: level 5 is below the floor of 10 - 4.
  light.size = 0.03;
  EXPECT_EQ(minMaxTopLevel(HsmLayout::NBuffers, view, light, true), 6);
  EXPECT_EQ(minMaxTopLevel(HsmLayout::DualMssm, view, light, true), 7);
  // A light as wide as the window: beyond the map, every level.
  light.size = 3.0;
  EXPECT_EQ(minMaxTopLevel(HsmLayout::NBuffers, view, light, true), 10);
  EXPECT_EQ(minMaxTopLevel(HsmLayout::DualMssm, view, light, true), 11);
  // Degenerate views bound nothing: a near depth of 0 (an infinite kernel), an empty window (0 / 0).
  view.nearDepth = 0.0;
  EXPECT_EQ(minMaxTopLevel(HsmLayout::NBuffers, view, light, true), 10);
  view.nearDepth = 1.0;
  view.window = { 0.0, 0.0, 0.0, 0.0 };
  light.size = 0.0;
  EXPECT_EQ(minMaxTopLevel(HsmLayout::DualMssm, view, light, true), 11);
}

} // namespace
} // namespace sl
