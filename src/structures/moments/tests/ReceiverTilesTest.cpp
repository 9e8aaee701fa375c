// ReceiverTiles (structures/moments/ReceiverTiles.h): growing by a reach covers every texel within that reach of a
// marked texel, the rectangles cover exactly the marked tiles' texels (partial tiles at the map's edge included), and
// boxBlurReach is BoxBlur.glsl's farthest tap.
#include "structures/moments/ReceiverTiles.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <random>

namespace sl
{
namespace
{

bool receiverTileTexelMarked(const ReceiverTiles& tiles, int x, int y)
{
  return tiles.marked(x / tiles.tileTexels(), y / tiles.tileTexels());
}

ReceiverTiles randomReceiverTiles(std::mt19937& generator, int mapSize, int tileTexels, double fraction)
{
  ReceiverTiles tiles(mapSize, tileTexels);
  std::bernoulli_distribution draw(fraction);
  for (int y = 0; y < tiles.tilesPerSide(); ++y)
  {
    for (int x = 0; x < tiles.tilesPerSide(); ++x)
    {
      if (draw(generator))
      {
        tiles.mark(x, y);
      }
    }
  }
  return tiles;
}

TEST(ReceiverTiles, RectanglesCoverExactlyTheMarkedTexels)
{
  std::mt19937 generator(33u);
  for (const int mapSize : { 64, 100, 257 })
  {
    for (const double fraction : { 0.0, 0.1, 0.5, 1.0 })
    {
      const ReceiverTiles tiles = randomReceiverTiles(generator, mapSize, 8, fraction);
      Image<int> covered(mapSize, mapSize, 1, 0);
      for (const TileRect& rect : tiles.rectangles())
      {
        ASSERT_GE(rect.x, 0);
        ASSERT_GE(rect.y, 0);
        ASSERT_LE(rect.x + rect.width, mapSize);
        ASSERT_LE(rect.y + rect.height, mapSize);
        for (int y = rect.y; y < rect.y + rect.height; ++y)
        {
          for (int x = rect.x; x < rect.x + rect.width; ++x)
          {
            ++covered.at(x, y);
          }
        }
      }
      const ImageF mask = tiles.texelMask();
      int marked = 0;
      for (int y = 0; y < mapSize; ++y)
      {
        for (int x = 0; x < mapSize; ++x)
        {
          const int expected = receiverTileTexelMarked(tiles, x, y) ? 1 : 0;
          marked += expected;
          ASSERT_EQ(covered.at(x, y), expected)
            << "texel " << x << "," << y << " of " << mapSize << "^2, fraction " << fraction;
          ASSERT_EQ(mask.at(x, y), static_cast<float>(expected));
        }
      }
      EXPECT_EQ(tiles.texelCount(), marked);
    }
  }
  EXPECT_EQ(ReceiverTiles::wholeMap(100, 8).texelCount(), 100 * 100);
  EXPECT_EQ(ReceiverTiles::wholeMap(100, 8).markedCount(), 13 * 13);
}

TEST(ReceiverTiles, GrowingCoversEveryTexelWithinReach)
{
  std::mt19937 generator(34u);
  const int mapSize = 90;
  for (const int tileTexels : { 8, 16 })
  {
    for (const auto& [reachX, reachY] : { std::pair{ 0, 0 }, std::pair{ 0, 2 }, std::pair{ 7, 0 }, std::pair{ 9, 31 } })
    {
      const ReceiverTiles tiles = randomReceiverTiles(generator, mapSize, tileTexels, 0.08);
      const ReceiverTiles grown = tiles.grown(reachX, reachY);
      // Every texel a separable pass reads from a marked texel (the box reachX x reachY around it) is in `grown`.
      int missing = 0;
      for (int y = 0; y < mapSize; ++y)
      {
        for (int x = 0; x < mapSize; ++x)
        {
          if (!receiverTileTexelMarked(tiles, x, y))
          {
            continue;
          }
          for (int dy = -reachY; dy <= reachY; ++dy)
          {
            for (int dx = -reachX; dx <= reachX; ++dx)
            {
              const int readX = std::clamp(x + dx, 0, mapSize - 1);
              const int readY = std::clamp(y + dy, 0, mapSize - 1);
              missing += receiverTileTexelMarked(grown, readX, readY) ? 0 : 1;
            }
          }
        }
      }
      EXPECT_EQ(missing, 0) << "tile " << tileTexels << ", reach " << reachX << " x " << reachY;
      // No farther than one tile per started tile of reach: the growth is not the whole map.
      for (int y = 0; y < grown.tilesPerSide(); ++y)
      {
        for (int x = 0; x < grown.tilesPerSide(); ++x)
        {
          if (!grown.marked(x, y))
          {
            continue;
          }
          bool near = false;
          const int tilesX = (reachX + tileTexels - 1) / tileTexels;
          const int tilesY = (reachY + tileTexels - 1) / tileTexels;
          for (int ny = std::max(0, y - tilesY); ny <= std::min(grown.tilesPerSide() - 1, y + tilesY); ++ny)
          {
            for (int nx = std::max(0, x - tilesX); nx <= std::min(grown.tilesPerSide() - 1, x + tilesX); ++nx)
            {
              near = near || tiles.marked(nx, ny);
            }
          }
          EXPECT_TRUE(near) << "tile " << x << "," << y << " grown from nothing within reach";
        }
      }
    }
  }
}

TEST(ReceiverTiles, BoxBlurReachIsTheFarthestTap)
{
  for (int width = 1; width <= 63; ++width)
  {
    // BoxBlur.glsl: taps first .. first + width - 1, first = -(width - 1) / 2.
    const int first = -(width - 1) / 2;
    const int last = first + width - 1;
    EXPECT_EQ(boxBlurReach(width), std::max(std::abs(first), std::abs(last))) << "width " << width;
  }
}

TEST(ReceiverTiles, FlagsFromTheGpuLayout)
{
  ReceiverTiles tiles(64, 16); // 4 x 4 tiles
  std::vector<std::uint32_t> flags(17, 0);
  flags[5] = 1; // tile (1, 1)
  tiles.markFromFlags(flags);
  EXPECT_EQ(tiles.markedCount(), 1);
  EXPECT_TRUE(tiles.marked(1, 1));
  flags[16] = 1; // the whole-map word
  tiles.markFromFlags(flags);
  EXPECT_EQ(tiles.markedCount(), 16);
  EXPECT_EQ(ReceiverTiles::tileTexelsFor(256), 8);
  EXPECT_EQ(ReceiverTiles::tileTexelsFor(1024), 16);
  EXPECT_EQ(ReceiverTiles::tileTexelsFor(4096), 32);
}

TEST(ReceiverTiles, PlanIsSparseOnlyWhenCheaperAndBuildsWhatItBlurs)
{
  ReceiverTiles read(256, 16);
  read.mark(3, 4);
  read.mark(4, 4);
  // Two listed texels in tile (3, 4): 2 x 25 fetches against (6 + 2) tiles x 256 texels x 5.
  const std::vector<std::uint32_t> listed = { 50u | (70u << 16), 51u | (70u << 16) };
  const ReceiverPrefilterPlan plan = planReceiverPrefilter(read, 5, listed);
  EXPECT_TRUE(plan.blur.sparse);
  EXPECT_EQ(plan.blur.readTexelCount, 2);
  const ImageF built = plan.builtMask();
  double builtTexels = 0.0;
  for (const float value : built.data)
  {
    builtTexels += value;
  }
  EXPECT_EQ(builtTexels, 2.0);
  EXPECT_EQ(built.at(50, 70), 1.0f);
  EXPECT_EQ(built.at(51, 70), 1.0f);
  // No horizontal pass; the source over the receivers' tiles grown by 2 along y and x (what the boxes read).
  EXPECT_EQ(plan.horizontalTiles, 0);
  EXPECT_EQ(plan.sourceTiles, 12);

  // As many fetches as the passes': the tiles are blurred, and built.
  const long long passFetches = (6 + 2) * 256 * 5;
  const long long breakEven = (passFetches + 24) / 25; // the fewest listed texels whose 25 fetches each are not fewer
  EXPECT_TRUE(sparseBlurIsCheaper(breakEven - 1, 5, 6 * 256, 2 * 256));
  EXPECT_FALSE(sparseBlurIsCheaper(breakEven, 5, 6 * 256, 2 * 256));
  const std::vector<std::uint32_t> many(static_cast<std::size_t>(breakEven), 50u | (70u << 16));
  const ReceiverPrefilterPlan tiled = planReceiverPrefilter(read, 5, many);
  EXPECT_FALSE(tiled.blur.sparse);
  EXPECT_EQ(tiled.horizontalTiles, 6); // the receivers' tiles grown by 2 along y
  EXPECT_EQ(tiled.builtMask().data, read.texelMask().data);
  // A build whose own rule finds the sparse path cheaper (the Fourier basis) turns it back, and over tiles again.
  ReceiverPrefilterPlan turned = tiled;
  planSparse(turned);
  EXPECT_TRUE(turned.blur.sparse);
  EXPECT_EQ(turned.horizontalTiles, 0);
  EXPECT_EQ(turned.builtMask().at(50, 70), 1.0f);
  EXPECT_EQ(turned.builtMask().at(52, 70), 0.0f);
  planOverTiles(turned, 5);
  EXPECT_FALSE(turned.blur.sparse);
  EXPECT_EQ(turned.horizontalTiles, 6);
  // No list (it overflowed) or no blur: tiles.
  EXPECT_FALSE(planReceiverPrefilter(read, 5).blur.sparse);
  ReceiverPrefilterPlan unlisted = planReceiverPrefilter(read, 5);
  planSparse(unlisted);
  EXPECT_FALSE(unlisted.blur.sparse);
  const ReceiverPrefilterPlan unblurred = planReceiverPrefilter(read, 1, listed);
  EXPECT_FALSE(unblurred.blur.sparse);
  EXPECT_EQ(unblurred.sourceTiles, 2);
  EXPECT_EQ(unblurred.builtMask().data, read.texelMask().data);

  // Tiles over more than wholeDrawFraction of the map: one draw of the whole map, and all of it built.
  ReceiverTiles most(64, 16); // 4 x 4 tiles
  for (int tile = 0; tile < 9; ++tile)
  {
    most.mark(tile % 4, tile / 4);
  }
  const ReceiverPrefilterPlan whole = planReceiverPrefilter(most, 5);
  ASSERT_EQ(whole.blur.vertical.size(), 1u);
  EXPECT_EQ(whole.blur.vertical[0].width * whole.blur.vertical[0].height, 64 * 64);
  EXPECT_EQ(whole.builtMask().data, ReceiverTiles::wholeMap(64, 16).texelMask().data);
  // Listing pays only with fewer than 2 / w listed texels per map texel (4 per pixel).
  EXPECT_TRUE(receiverTexelListCanPay(256 * 256, 2048, 5));
  EXPECT_FALSE(receiverTexelListCanPay(256 * 256, 512, 5));
  EXPECT_FALSE(receiverTexelListCanPay(16, 2048, 1));
  EXPECT_TRUE(receiverRegionCanPay(256 * 256, 1024));
  EXPECT_FALSE(receiverRegionCanPay(256 * 256, 512));
}

} // namespace
} // namespace sl
