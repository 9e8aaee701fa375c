#include "structures/moments/ReceiverTiles.h"

#include "core/Error.h"

#include <algorithm>

namespace sl
{

ReceiverTiles::ReceiverTiles(int mapSize, int tileTexels)
  : mapSize_(mapSize)
  , tileTexels_(tileTexels)
  , tilesPerSide_((mapSize + tileTexels - 1) / tileTexels)
  , marked_(static_cast<std::size_t>(tilesPerSide_) * static_cast<std::size_t>(tilesPerSide_), 0)
{
  SL_CHECK_MSG(mapSize > 0 && tileTexels > 0, "receiver tiles of a ", mapSize, "^2 map in ", tileTexels, "^2 tiles");
}

ReceiverTiles ReceiverTiles::wholeMap(int mapSize, int tileTexels)
{
  ReceiverTiles tiles(mapSize, tileTexels);
  std::fill(tiles.marked_.begin(), tiles.marked_.end(), 1);
  return tiles;
}

int ReceiverTiles::tileTexelsFor(int mapSize)
{
  return std::clamp(mapSize / 64, 8, 32);
}

bool ReceiverTiles::marked(int tileX, int tileY) const
{
  return marked_[static_cast<std::size_t>(tileY) * tilesPerSide_ + tileX] != 0;
}

void ReceiverTiles::mark(int tileX, int tileY)
{
  marked_[static_cast<std::size_t>(tileY) * tilesPerSide_ + tileX] = 1;
}

void ReceiverTiles::markFromFlags(const std::vector<std::uint32_t>& flags)
{
  SL_CHECK_MSG(flags.size() > marked_.size(), "receiver tile flags: ", flags.size(), " for ", marked_.size(), " tiles");
  const bool wholeMap = flags[marked_.size()] != 0;
  for (std::size_t i = 0; i < marked_.size(); ++i)
  {
    marked_[i] = wholeMap || flags[i] != 0 ? 1 : 0;
  }
}

int ReceiverTiles::markedCount() const
{
  return static_cast<int>(std::count(marked_.begin(), marked_.end(), std::uint8_t{ 1 }));
}

int ReceiverTiles::texelCount() const
{
  int texels = 0;
  for (const TileRect& rect : rectangles())
  {
    texels += rect.width * rect.height;
  }
  return texels;
}

ReceiverTiles ReceiverTiles::grown(int reachX, int reachY) const
{
  // A texel within `reach` of a marked tile lies at most ceil(reach / tile) tiles away from it.
  const int tilesX = (std::max(reachX, 0) + tileTexels_ - 1) / tileTexels_;
  const int tilesY = (std::max(reachY, 0) + tileTexels_ - 1) / tileTexels_;
  ReceiverTiles result(mapSize_, tileTexels_);
  for (int y = 0; y < tilesPerSide_; ++y)
  {
    for (int x = 0; x < tilesPerSide_; ++x)
    {
      if (!marked(x, y))
      {
        continue;
      }
      for (int ny = std::max(0, y - tilesY); ny <= std::min(tilesPerSide_ - 1, y + tilesY); ++ny)
      {
        for (int nx = std::max(0, x - tilesX); nx <= std::min(tilesPerSide_ - 1, x + tilesX); ++nx)
        {
          result.mark(nx, ny);
        }
      }
    }
  }
  return result;
}

std::vector<TileRect> ReceiverTiles::rectangles() const
{
  std::vector<TileRect> rects;
  for (int y = 0; y < tilesPerSide_; ++y)
  {
    int x = 0;
    while (x < tilesPerSide_)
    {
      if (!marked(x, y))
      {
        ++x;
        continue;
      }
      const int first = x;
      while (x < tilesPerSide_ && marked(x, y))
      {
        ++x;
      }
      TileRect rect;
      rect.x = first * tileTexels_;
      rect.y = y * tileTexels_;
      rect.width = std::min(x * tileTexels_, mapSize_) - rect.x;
      rect.height = std::min((y + 1) * tileTexels_, mapSize_) - rect.y;
      // One rectangle for the same run on consecutive rows of tiles: fewer draws.
      if (!rects.empty())
      {
        TileRect& previous = rects.back();
        if (previous.x == rect.x && previous.width == rect.width && previous.y + previous.height == rect.y)
        {
          previous.height += rect.height;
          continue;
        }
      }
      rects.push_back(rect);
    }
  }
  return rects;
}

ImageF ReceiverTiles::texelMask() const
{
  ImageF mask(mapSize_, mapSize_, 1);
  for (const TileRect& rect : rectangles())
  {
    for (int y = rect.y; y < rect.y + rect.height; ++y)
    {
      for (int x = rect.x; x < rect.x + rect.width; ++x)
      {
        mask.at(x, y, 0) = 1.0f;
      }
    }
  }
  return mask;
}

namespace
{

// `tiles`' rectangles, or the whole map in one when they cover more than wholeDrawFraction of it.
std::vector<TileRect> receiverDrawRectangles(const ReceiverTiles& tiles)
{
  const double all = static_cast<double>(tiles.tilesPerSide()) * tiles.tilesPerSide();
  if (tiles.markedCount() > wholeDrawFraction * all)
  {
    return { TileRect{ 0, 0, tiles.mapSize(), tiles.mapSize() } };
  }
  return tiles.rectangles();
}

} // namespace

ReceiverPrefilterPlan planReceiverPrefilter(
  const ReceiverTiles& read, int blurTexels, std::vector<std::uint32_t> readTexels)
{
  ReceiverPrefilterPlan plan;
  plan.read = read;
  if (blurTexels <= 1)
  {
    plan.source = receiverDrawRectangles(read);
    plan.built = plan.source;
    plan.sourceTiles = read.markedCount();
    return plan;
  }
  const int reach = boxBlurReach(blurTexels);
  const ReceiverTiles horizontal = read.grown(0, reach);
  const ReceiverTiles source = horizontal.grown(reach, 0);
  plan.blur.horizontal = receiverDrawRectangles(horizontal);
  plan.blur.vertical = receiverDrawRectangles(read);
  plan.built = plan.blur.vertical;
  plan.source = receiverDrawRectangles(source);
  plan.horizontalTiles = horizontal.markedCount();
  plan.sourceTiles = source.markedCount();
  const long long listed = static_cast<long long>(readTexels.size());
  plan.blur.readTexelCount = static_cast<int>(listed);
  plan.blur.sparse = listed > 0 && sparseBlurIsCheaper(listed, blurTexels, horizontal.texelCount(), read.texelCount());
  plan.horizontalTiles = plan.blur.sparse ? 0 : plan.horizontalTiles; // no horizontal pass
  plan.readTexels = std::move(readTexels);
  return plan;
}

void planOverTiles(ReceiverPrefilterPlan& plan, int blurTexels)
{
  if (plan.blur.sparse)
  {
    plan.blur.sparse = false;
    plan.horizontalTiles = plan.read.grown(0, boxBlurReach(blurTexels)).markedCount();
  }
}

void planSparse(ReceiverPrefilterPlan& plan)
{
  if (plan.blur.readTexelCount > 0)
  {
    plan.blur.sparse = true;
    plan.horizontalTiles = 0; // no horizontal pass
  }
}

ImageF ReceiverPrefilterPlan::builtMask() const
{
  ImageF mask(read.mapSize(), read.mapSize(), 1);
  if (!blur.sparse)
  {
    for (const TileRect& rect : built)
    {
      for (int y = rect.y; y < rect.y + rect.height; ++y)
      {
        for (int x = rect.x; x < rect.x + rect.width; ++x)
        {
          mask.at(x, y, 0) = 1.0f;
        }
      }
    }
    return mask;
  }
  for (const std::uint32_t packed : readTexels)
  {
    mask.at(static_cast<int>(packed & 0xFFFFu), static_cast<int>(packed >> 16), 0) = 1.0f;
  }
  return mask;
}

bool receiverRegionCanPay(long long pixels, int mapSize)
{
  return static_cast<long long>(mapSize) * mapSize >= receiverRegionTexelsPerPixel * pixels;
}

bool receiverTexelListCanPay(long long pixels, int mapSize, int blurTexels)
{
  const long long texels = static_cast<long long>(mapSize) * mapSize;
  return blurTexels > 1 && 4 * pixels * blurTexels < 2 * texels;
}

bool sparseBlurIsCheaper(long long listedTexels, int blurTexels, long long horizontalTexels, long long verticalTexels)
{
  const long long width = blurTexels;
  return listedTexels * width * width < (horizontalTexels + verticalTexels) * width;
}

int boxBlurReach(int boxTexels)
{
  return boxTexels <= 1 ? 0 : boxTexels / 2;
}

} // namespace sl
