#include "lightspace/HierarchicalShadowMap.h"

#include "core/Error.h"

#include <algorithm>
#include <cmath>

namespace sl
{

int hsmLevelCount(int mapSize)
{
  int levels = 0;
  while ((1 << levels) < mapSize)
  {
    ++levels;
  }
  return levels;
}

int dualMssmLevelCount(int mapSize)
{
  return hsmLevelCount(mapSize + 1);
}

int hsmLevelSize(HsmLayout layout, int mapSize, int level)
{
  switch (layout)
  {
    case HsmLayout::NBuffers: return mapSize;
    case HsmLayout::DualMssm: return mapSize + 1;
    case HsmLayout::MipMap:
    case HsmLayout::Ysm: break;
  }
  return (mapSize + (1 << level) - 1) >> level;
}

int ysmBaseLevel(int mapSize)
{
  // b = floor(log2 (N / 256)), at least 0 (SS08: n - 1 = log2 (N / 256), §6).
  int level = 0;
  while ((ysmMssmPartTargetSize << (level + 1)) <= mapSize)
  {
    ++level;
  }
  return level;
}

int ysmMssmPartSize(int mapSize)
{
  return hsmLevelSize(HsmLayout::MipMap, mapSize, ysmBaseLevel(mapSize));
}

int ysmMssmPartLevelCount(int mapSize)
{
  return hsmLevelCount(ysmMssmPartSize(mapSize));
}

int minMaxTopLevel(int levelCount, int levelRead)
{
  return std::clamp(levelRead, std::max(levelCount - minMaxMaxLevelsLeftOut, 0), levelCount);
}

glm::ivec2 hsmAtlasOffset(int mapSize, int level)
{
  glm::ivec2 offset(0, 0);
  if (level >= 2)
  {
    offset.x = hsmLevelSize(HsmLayout::MipMap, mapSize, 1);
    for (int finer = 2; finer < level; ++finer)
    {
      offset.y += hsmLevelSize(HsmLayout::MipMap, mapSize, finer);
    }
  }
  return offset;
}

ImageF HierarchicalShadowMap::atlas() const
{
  SL_CHECK(layout == HsmLayout::MipMap || layout == HsmLayout::Ysm);
  ImageF result(mapSize, mapSize, 2);
  for (std::size_t level = 1; level < levels.size(); ++level)
  {
    const ImageF& image = levels[level];
    const glm::ivec2 offset = hsmAtlasOffset(mapSize, static_cast<int>(level));
    for (int y = 0; y < image.height; ++y)
    {
      for (int x = 0; x < image.width; ++x)
      {
        for (int c = 0; c < 2; ++c)
        {
          result.at(offset.x + x, offset.y + y, c) = image.at(x, y, c);
        }
      }
    }
  }
  return result;
}

namespace
{

// N-buffer level `level` (>= 1) of a square grid from its level - 1 (`finer`): texel (x, y) holds the range of
// the four level - 1 squares at (x, y) + 2^(level-1) {0, 1}^2, clamped to the grid (Décoret 2005).
ImageF nBufferLevel(const ImageF& finer, int level)
{
  const int size = finer.width;
  const int stride = 1 << (level - 1);
  ImageF coarser(size, size, 2);
  for (int y = 0; y < size; ++y)
  {
    for (int x = 0; x < size; ++x)
    {
      float low = finer.at(x, y, 0);
      float high = finer.at(x, y, 1);
      for (int child = 1; child < 4; ++child)
      {
        const int cx = std::min(x + (child & 1) * stride, size - 1);
        const int cy = std::min(y + (child >> 1) * stride, size - 1);
        low = std::min(low, finer.at(cx, cy, 0));
        high = std::max(high, finer.at(cx, cy, 1));
      }
      coarser.at(x, y, 0) = low;
      coarser.at(x, y, 1) = high;
    }
  }
  return coarser;
}

// The inclusive rectangle [first, last] of an N-buffer grid tiled by its largest squares not wider than the
// rectangle's shorter side nor above `topLevel`: squares start every `side` texels and the last one of each axis ends
// exactly at `last` (overlaps are harmless for min and max), so the tiling is exact; at most 2 squares along the
// shorter side unless the top level is narrower. GLSL: hsmTiledRange.
template <typename VisitSquare>
void tileWithSquares(glm::ivec2 first, glm::ivec2 last, int topLevel, VisitSquare&& visitSquare)
{
  const glm::ivec2 extent = last - first + 1;
  int level = 0;
  while (level < topLevel && (2 << level) <= std::min(extent.x, extent.y))
  {
    ++level;
  }
  const int side = 1 << level;
  for (int y = first.y;; y += side)
  {
    const int sy = std::min(y, last.y - side + 1);
    for (int x = first.x;; x += side)
    {
      const int sx = std::min(x, last.x - side + 1);
      visitSquare(level, sx, sy);
      if (sx + side > last.x)
      {
        break;
      }
    }
    if (sy + side > last.y)
    {
      break;
    }
  }
}

int builtTopLevel(int levelCount, int topLevel)
{
  return topLevel < 0 ? levelCount : std::min(topLevel, levelCount);
}

} // namespace

HierarchicalShadowMap HierarchicalShadowMap::build(const ImageF& shadowMapLinear, HsmLayout layout, int topLevel)
{
  SL_CHECK(layout != HsmLayout::DualMssm); // buildDual
  SL_CHECK_MSG(shadowMapLinear.width == shadowMapLinear.height, "the HSM needs a square shadow map");
  // The mip-map's levels above k hold less than a third of level k, and the YSM's MSSM part is built from a fixed
  // level: only the N-buffers are built to a top level.
  SL_CHECK(topLevel < 0 || layout == HsmLayout::NBuffers);
  HierarchicalShadowMap hsm;
  hsm.layout = layout;
  hsm.mapSize = shadowMapLinear.width;
  const int levelCount = builtTopLevel(hsmLevelCount(hsm.mapSize), topLevel);
  ImageF base(hsm.mapSize, hsm.mapSize, 2);
  for (int y = 0; y < hsm.mapSize; ++y)
  {
    for (int x = 0; x < hsm.mapSize; ++x)
    {
      base.at(x, y, 0) = shadowMapLinear.at(x, y);
      base.at(x, y, 1) = shadowMapLinear.at(x, y);
    }
  }
  hsm.levels.push_back(std::move(base));
  for (int level = 1; level <= levelCount; ++level)
  {
    const ImageF& finer = hsm.levels.back();
    const int size = hsmLevelSize(layout, hsm.mapSize, level);
    ImageF coarser(size, size, 2);
    // Mip-map: the four children 2x + {0, 1}; N-buffers: the four squares of half the side at offsets
    // {0, 2^(k-1)}. Either way clamped to the finer level, which keeps the range inside the map.
    const int stride = layout == HsmLayout::NBuffers ? 1 << (level - 1) : 1;
    for (int y = 0; y < size; ++y)
    {
      for (int x = 0; x < size; ++x)
      {
        const glm::ivec2 first = layout == HsmLayout::NBuffers ? glm::ivec2(x, y) : glm::ivec2(2 * x, 2 * y);
        float low = finer.at(std::min(first.x, finer.width - 1), std::min(first.y, finer.height - 1), 0);
        float high = finer.at(std::min(first.x, finer.width - 1), std::min(first.y, finer.height - 1), 1);
        for (int child = 1; child < 4; ++child)
        {
          const int cx = std::min(first.x + (child & 1) * stride, finer.width - 1);
          const int cy = std::min(first.y + (child >> 1) * stride, finer.height - 1);
          low = std::min(low, finer.at(cx, cy, 0));
          high = std::max(high, finer.at(cx, cy, 1));
        }
        coarser.at(x, y, 0) = low;
        coarser.at(x, y, 1) = high;
      }
    }
    hsm.levels.push_back(std::move(coarser));
  }
  if (layout == HsmLayout::Ysm)
  {
    // The MSSM part: N-buffers over the nodes of HSM level b, whose level 0 is that level (not stored).
    hsm.ysmBaseLevel = sl::ysmBaseLevel(hsm.mapSize);
    const int partLevels = ysmMssmPartLevelCount(hsm.mapSize);
    for (int level = 1; level <= partLevels; ++level)
    {
      const ImageF& finer = level == 1 ? hsm.levels[static_cast<std::size_t>(hsm.ysmBaseLevel)] : hsm.mssmPart.back();
      hsm.mssmPart.push_back(nBufferLevel(finer, level));
    }
  }
  return hsm;
}

HierarchicalShadowMap HierarchicalShadowMap::buildDual(const ImageF& shadowMapLinear, float outsideDepth, int topLevel)
{
  SL_CHECK_MSG(shadowMapLinear.width == shadowMapLinear.height, "the MSSM needs a square shadow map");
  HierarchicalShadowMap mssm;
  mssm.layout = HsmLayout::DualMssm;
  mssm.mapSize = shadowMapLinear.width;
  const int size = mssm.mapSize + 1;
  const auto sample = [&](int i, int j) {
    const bool inside = i >= 0 && j >= 0 && i < mssm.mapSize && j < mssm.mapSize;
    return inside ? shadowMapLinear.at(i, j) : outsideDepth;
  };
  // Level 0: texel t holds cell t - 1, i.e. the samples t - 1 and t per axis (Yang et al. 2009 §4.2).
  ImageF cells(size, size, 2);
  for (int y = 0; y < size; ++y)
  {
    for (int x = 0; x < size; ++x)
    {
      const float corners[4] = { sample(x - 1, y - 1), sample(x, y - 1), sample(x - 1, y), sample(x, y) };
      cells.at(x, y, 0) = std::min({ corners[0], corners[1], corners[2], corners[3] });
      cells.at(x, y, 1) = std::max({ corners[0], corners[1], corners[2], corners[3] });
    }
  }
  mssm.levels.push_back(std::move(cells));
  // Level k: the four level k - 1 squares at offsets {0, 2^(k-1)}, clamped to the last cell.
  for (int level = 1; level <= builtTopLevel(dualMssmLevelCount(mssm.mapSize), topLevel); ++level)
  {
    mssm.levels.push_back(nBufferLevel(mssm.levels.back(), level));
  }
  return mssm;
}

glm::dvec2 HierarchicalShadowMap::dualNode(int level, glm::ivec2 cell) const
{
  const ImageF& image = levels[static_cast<std::size_t>(level)];
  return { image.at(cell.x + 1, cell.y + 1, 0), image.at(cell.x + 1, cell.y + 1, 1) };
}

glm::dvec2 HierarchicalShadowMap::dualRange(glm::ivec2 cellLo, glm::ivec2 cellHi, int* fetches,
  std::vector<HsmQueryNode>* nodes) const
{
  SL_CHECK(layout == HsmLayout::DualMssm);
  glm::dvec2 result(1e300, -1e300);
  int reads = 0;
  tileWithSquares(cellLo, cellHi, topLevel(), [&](int level, int sx, int sy) {
    const glm::dvec2 node = dualNode(level, { sx, sy });
    result = { std::min(result.x, node.x), std::max(result.y, node.y) };
    ++reads;
    if (nodes)
    {
      // Cells [s, s + side - 1] hold the samples [s, s + side].
      nodes->push_back({ "dual-grid mssm", level, glm::max(glm::ivec2(sx, sy), glm::ivec2(0)),
        glm::min(glm::ivec2(sx, sy) + (1 << level), glm::ivec2(mapSize - 1)), node });
    }
  });
  if (fetches)
  {
    *fetches = reads;
  }
  return result;
}

glm::dvec2 HierarchicalShadowMap::node(int level, glm::ivec2 index) const
{
  SL_CHECK(layout != HsmLayout::DualMssm); // dualNode
  const glm::ivec2 texel = layout == HsmLayout::NBuffers ? index << level : index;
  const ImageF& image = levels[static_cast<std::size_t>(level)];
  return { image.at(texel.x, texel.y, 0), image.at(texel.x, texel.y, 1) };
}

glm::dvec2 HierarchicalShadowMap::range(glm::ivec2 lo, glm::ivec2 hi, int* fetches, std::vector<HsmQueryNode>* nodes) const
{
  if (layout == HsmLayout::DualMssm)
  {
    // Samples [lo, hi] are exactly the cells [lo, hi - 1]: rectangles at least 2 samples wide.
    SL_CHECK_MSG(hi.x > lo.x && hi.y > lo.y, "a dual-grid MSSM range needs at least 2 x 2 samples");
    return dualRange(lo, hi - 1, fetches, nodes);
  }
  glm::dvec2 result(1e300, -1e300);
  int reads = 0;
  // `first` and `side`: the texels the node covers (for `nodes` only).
  const auto visitImage = [&](const ImageF& image, int x, int y, const char* part, int level, glm::ivec2 first, int side) {
    const glm::dvec2 node(image.at(x, y, 0), image.at(x, y, 1));
    result.x = std::min(result.x, node.x);
    result.y = std::max(result.y, node.y);
    ++reads;
    if (nodes)
    {
      nodes->push_back({ part, level, first, glm::min(first + side - 1, glm::ivec2(mapSize - 1)), node });
    }
  };
  // Mip-map: node (x, y) of `level` covers [(x, y) 2^level, (x, y + 1) 2^level); N-buffers: the square at (x, y).
  const auto visit = [&](int level, int x, int y) {
    const bool nBuffers = layout == HsmLayout::NBuffers;
    visitImage(levels[static_cast<std::size_t>(level)], x, y, nBuffers ? "n-buffers" : "mip-map", level,
      nBuffers ? glm::ivec2(x, y) : glm::ivec2(x, y) << level, 1 << level);
  };
  const glm::ivec2 extent = hi - lo + 1;
  if (layout == HsmLayout::MipMap || layout == HsmLayout::Ysm)
  {
    // The first level whose nodes are at least as wide as the rectangle: it spans at most 2 nodes per axis.
    int level = 0;
    while ((1 << level) < std::max(extent.x, extent.y))
    {
      ++level;
    }
    level = std::min(level, static_cast<int>(levels.size()) - 1);
    if (layout == HsmLayout::Ysm && level > ysmBaseLevel)
    {
      // YSM (SS08 §6): the level-b nodes the rectangle touches, tiled exactly by the MSSM part (its level 0 is
      // HSM level b). They lie inside the level-k nodes the mip-map query reads, so the range is never looser.
      tileWithSquares(lo >> ysmBaseLevel, hi >> ysmBaseLevel, static_cast<int>(mssmPart.size()), [&](int partLevel, int x, int y) {
        visitImage(partLevel == 0 ? levels[static_cast<std::size_t>(ysmBaseLevel)]
                                  : mssmPart[static_cast<std::size_t>(partLevel - 1)], x, y,
          partLevel == 0 ? "mip-map" : "ysm mssm part", ysmBaseLevel + partLevel, glm::ivec2(x, y) << ysmBaseLevel,
          1 << (ysmBaseLevel + partLevel));
      });
    }
    else
    {
      const glm::ivec2 first = lo >> level;
      const glm::ivec2 last = hi >> level;
      for (int y = first.y; y <= last.y; ++y)
      {
        for (int x = first.x; x <= last.x; ++x)
        {
          visit(level, x, y);
        }
      }
    }
  }
  else
  {
    tileWithSquares(lo, hi, topLevel(), visit); // N-buffers: exact
  }
  if (fetches)
  {
    *fetches = reads;
  }
  return result;
}

} // namespace sl
