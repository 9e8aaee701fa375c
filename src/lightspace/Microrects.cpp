#include "lightspace/Microrects.h"

#include "core/Error.h"
#include "lightspace/HierarchicalShadowMap.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace sl
{
namespace
{

std::size_t flatIndex(glm::ivec2 index, glm::ivec2 size)
{
  return static_cast<std::size_t>(index.x) + static_cast<std::size_t>(index.y) * static_cast<std::size_t>(size.x);
}

} // namespace

glm::ivec2 Microrects::levelSize(int level) const
{
  SL_CHECK(level >= 0 && level <= levelCount());
  return { ((mapSize - 1) >> level) + 1, ((mapHeight - 1) >> level) + 1 };
}

Microrect Microrects::at(int level, glm::ivec2 index) const
{
  const glm::ivec2 size = levelSize(level);
  SL_CHECK_MSG(index.x >= 0 && index.y >= 0 && index.x < size.x && index.y < size.y, "microrect (", index.x, ", ",
    index.y, ") is outside level ", level, " (", size.x, " x ", size.y, ")");
  return levels[static_cast<std::size_t>(level)][flatIndex(index, size)];
}

glm::ivec2 Microrects::referencePoint(int level, glm::ivec2 index)
{
  return index * (1 << level);
}

Microrects Microrects::build(const ImageF& shadowMapLinear, bool trackMembers)
{
  SL_CHECK(shadowMapLinear.components == 1 && shadowMapLinear.width > 0 && shadowMapLinear.height > 0);
  Microrects result;
  result.mapSize = shadowMapLinear.width;
  result.mapHeight = shadowMapLinear.height;
  const int levelCount = hsmLevelCount(std::max(result.mapSize, result.mapHeight));
  result.levels.resize(static_cast<std::size_t>(levelCount) + 1);
  if (trackMembers)
  {
    result.members.resize(static_cast<std::size_t>(levelCount) + 1);
  }

  // Level 0: the micropatches.
  std::vector<Microrect>& base = result.levels[0];
  base.reserve(shadowMapLinear.pixelCount());
  for (int y = 0; y < result.mapHeight; ++y)
  {
    for (int x = 0; x < result.mapSize; ++x)
    {
      base.push_back({ { x, y }, { x, y }, shadowMapLinear.at(x, y) });
    }
  }

  for (int level = 1; level <= levelCount; ++level)
  {
    const std::vector<Microrect>& finer = result.levels[static_cast<std::size_t>(level - 1)];
    const glm::ivec2 finerSize = result.levelSize(level - 1);
    const glm::ivec2 size = result.levelSize(level);
    const auto exists = [&](glm::ivec2 index) {
      return index.x >= 0 && index.y >= 0 && index.x < finerSize.x && index.y < finerSize.y;
    };
    const auto finerAt = [&](glm::ivec2 index) -> const Microrect& { return finer[flatIndex(index, finerSize)]; };

    std::vector<Microrect>& built = result.levels[static_cast<std::size_t>(level)];
    built.resize(static_cast<std::size_t>(size.x) * static_cast<std::size_t>(size.y));
    std::vector<std::vector<glm::ivec2>>* members = nullptr;
    if (trackMembers)
    {
      members = &result.members[static_cast<std::size_t>(level)];
      members->resize(built.size());
    }
    std::vector<std::uint8_t> claims(built.size(), 0);

    // Level-(i-1) microrect `index` joins `merged`, microrect `self` of level i: the bounding rectangle of the
    // extents, the min of the depths (§5.2); the member is recorded when members are tracked.
    const auto absorbInto = [&](Microrect& merged, std::size_t self, glm::ivec2 index) {
      const Microrect& member = finerAt(index);
      merged.lo = glm::min(merged.lo, member.lo);
      merged.hi = glm::max(merged.hi, member.hi);
      merged.depth = std::min(merged.depth, member.depth);
      if (members)
      {
        (*members)[self].push_back(index);
      }
    };
    // Pass 1 (§5.2): each retained A = (2x, 2y) absorbs B and D by the smaller depth difference, then E if
    // the rectangle so far contains it (or E has no other retained neighbour).
    for (int y = 0; y < size.y; ++y)
    {
      for (int x = 0; x < size.x; ++x)
      {
        const std::size_t self = flatIndex({ x, y }, size);
        const glm::ivec2 a(2 * x, 2 * y);
        Microrect merged = finerAt(a);
        const float depthA = merged.depth;
        const auto absorb = [&](glm::ivec2 index) { absorbInto(merged, self, index); };
        // B joins A unless C exists and is strictly closer in depth (ties to A, the negative-side partner).
        // In float, as the GPU computes it.
        const auto joinsA = [&](glm::ivec2 candidate, glm::ivec2 otherPartner) {
          if (!exists(otherPartner))
          {
            return true;
          }
          const float depth = finerAt(candidate).depth;
          return std::fabs(depth - depthA) <= std::fabs(depth - finerAt(otherPartner).depth);
        };
        absorb(a);
        const glm::ivec2 b = a + glm::ivec2(1, 0);
        if (exists(b) && joinsA(b, a + glm::ivec2(2, 0)))
        {
          absorb(b);
          claims[self] |= MicrorectClaims::kB;
        }
        const glm::ivec2 d = a + glm::ivec2(0, 1);
        if (exists(d) && joinsA(d, a + glm::ivec2(0, 2)))
        {
          absorb(d);
          claims[self] |= MicrorectClaims::kD;
        }
        const glm::ivec2 e = a + glm::ivec2(1, 1);
        if (exists(e))
        {
          const Microrect& diagonal = finerAt(e);
          const bool contained = glm::all(glm::lessThanEqual(merged.lo, diagonal.lo)) &&
            glm::all(glm::lessThanEqual(diagonal.hi, merged.hi));
          if (contained || !exists(a + glm::ivec2(2, 2)))
          {
            absorb(e);
            claims[self] |= MicrorectClaims::kE;
          }
        }
        built[self] = merged;
      }
    }

    // Pass 2 (§5.2): each retained P = (2x, 2y) absorbs F, H and E' unless their own retained microrect
    // claimed them in pass 1.
    for (int y = 0; y < size.y; ++y)
    {
      for (int x = 0; x < size.x; ++x)
      {
        const std::size_t self = flatIndex({ x, y }, size);
        const glm::ivec2 p(2 * x, 2 * y);
        Microrect& merged = built[self];
        const auto absorbUnclaimed = [&](glm::ivec2 owner, std::uint8_t claim, glm::ivec2 index) {
          if (claims[flatIndex(owner, size)] & claim)
          {
            return;
          }
          absorbInto(merged, self, index);
        };
        if (x > 0)
        {
          absorbUnclaimed({ x - 1, y }, MicrorectClaims::kB, p - glm::ivec2(1, 0)); // F
        }
        if (y > 0)
        {
          absorbUnclaimed({ x, y - 1 }, MicrorectClaims::kD, p - glm::ivec2(0, 1)); // H
        }
        if (x > 0 && y > 0)
        {
          absorbUnclaimed({ x - 1, y - 1 }, MicrorectClaims::kE, p - glm::ivec2(1, 1)); // E'
        }
      }
    }
  }
  return result;
}

Microrects Microrects::fromAtlases(
  const ImageF& shadowMapLinear, const Image<std::uint32_t>& extentAtlas, const ImageF& depthAtlas)
{
  const int n = shadowMapLinear.width;
  SL_CHECK(shadowMapLinear.height == n && shadowMapLinear.components == 1);
  SL_CHECK(extentAtlas.width == n && extentAtlas.height == n && extentAtlas.components == 4);
  SL_CHECK(depthAtlas.width == n && depthAtlas.height == n && depthAtlas.components == 1);
  Microrects result;
  result.mapSize = n;
  result.mapHeight = n;
  const int levelCount = hsmLevelCount(n);
  result.levels.resize(static_cast<std::size_t>(levelCount) + 1);
  for (int y = 0; y < n; ++y)
  {
    for (int x = 0; x < n; ++x)
    {
      result.levels[0].push_back({ { x, y }, { x, y }, shadowMapLinear.at(x, y) });
    }
  }
  for (int level = 1; level <= levelCount; ++level)
  {
    const glm::ivec2 size = result.levelSize(level);
    const glm::ivec2 offset = hsmAtlasOffset(n, level);
    std::vector<Microrect>& microrects = result.levels[static_cast<std::size_t>(level)];
    for (int y = 0; y < size.y; ++y)
    {
      for (int x = 0; x < size.x; ++x)
      {
        const int ax = offset.x + x;
        const int ay = offset.y + y;
        Microrect microrect;
        microrect.lo = { static_cast<int>(extentAtlas.at(ax, ay, 0)), static_cast<int>(extentAtlas.at(ax, ay, 1)) };
        microrect.hi = { static_cast<int>(extentAtlas.at(ax, ay, 2)), static_cast<int>(extentAtlas.at(ax, ay, 3)) };
        microrect.depth = depthAtlas.at(ax, ay);
        microrects.push_back(microrect);
      }
    }
  }
  return result;
}

Image<std::uint32_t> Microrects::extentAtlas() const
{
  SL_CHECK_MSG(mapSize == mapHeight, "the microrect atlas needs a square map");
  Image<std::uint32_t> atlas(mapSize, mapSize, 4, 0u);
  for (int level = 1; level <= levelCount(); ++level)
  {
    const glm::ivec2 size = levelSize(level);
    const glm::ivec2 offset = hsmAtlasOffset(mapSize, level);
    for (int y = 0; y < size.y; ++y)
    {
      for (int x = 0; x < size.x; ++x)
      {
        const Microrect microrect = at(level, { x, y });
        const int coordinates[4] = { microrect.lo.x, microrect.lo.y, microrect.hi.x, microrect.hi.y };
        for (int c = 0; c < 4; ++c)
        {
          atlas.at(offset.x + x, offset.y + y, c) = static_cast<std::uint32_t>(coordinates[c]);
        }
      }
    }
  }
  return atlas;
}

ImageF Microrects::depthAtlas() const
{
  SL_CHECK_MSG(mapSize == mapHeight, "the microrect atlas needs a square map");
  ImageF atlas(mapSize, mapSize, 1, 0.0f);
  for (int level = 1; level <= levelCount(); ++level)
  {
    const glm::ivec2 size = levelSize(level);
    const glm::ivec2 offset = hsmAtlasOffset(mapSize, level);
    for (int y = 0; y < size.y; ++y)
    {
      for (int x = 0; x < size.x; ++x)
      {
        atlas.at(offset.x + x, offset.y + y) = at(level, { x, y }).depth;
      }
    }
  }
  return atlas;
}

ImageF Microrects::overlapCount(int level) const
{
  SL_CHECK(level >= 0 && level <= levelCount());
  return microrectOverlapCount(levels[static_cast<std::size_t>(level)], mapSize, mapHeight);
}

ImageF microrectOverlapCount(const std::vector<Microrect>& microrects, int width, int height)
{
  // +1 at (lo), -1 past each edge, +1 past both: the 2-D prefix sum is then the coverage count.
  const std::size_t stride = static_cast<std::size_t>(width) + 1;
  std::vector<int> difference(stride * (static_cast<std::size_t>(height) + 1), 0);
  const auto cell = [&](int x, int y) -> int& {
    return difference[static_cast<std::size_t>(x) + static_cast<std::size_t>(y) * stride];
  };
  for (const Microrect& microrect : microrects)
  {
    SL_CHECK_MSG(microrect.lo.x >= 0 && microrect.lo.y >= 0 && microrect.hi.x < width && microrect.hi.y < height &&
        microrect.lo.x <= microrect.hi.x && microrect.lo.y <= microrect.hi.y,
      "microrect extent (", microrect.lo.x, ", ", microrect.lo.y, ") .. (", microrect.hi.x, ", ", microrect.hi.y,
      ") is not a rectangle inside the ", width, " x ", height, " map");
    ++cell(microrect.lo.x, microrect.lo.y);
    --cell(microrect.hi.x + 1, microrect.lo.y);
    --cell(microrect.lo.x, microrect.hi.y + 1);
    ++cell(microrect.hi.x + 1, microrect.hi.y + 1);
  }
  ImageF counts(width, height, 1, 0.0f);
  std::vector<int> row(static_cast<std::size_t>(width) + 1, 0); // column sums of the rows so far
  for (int y = 0; y < height; ++y)
  {
    int running = 0;
    for (int x = 0; x < width; ++x)
    {
      row[static_cast<std::size_t>(x)] += cell(x, y);
      running += row[static_cast<std::size_t>(x)];
      counts.at(x, y) = static_cast<float>(running);
    }
  }
  return counts;
}

} // namespace sl
