// Microrects' CPU build (lightspace/Microrects.h; Schwarz & Stamminger 2008 §5.2): Fig. 5's 1-D example and the
// diagonal rule worked by hand, and the definition's invariants on every level of random maps with ties (every
// microrect absorbed exactly once, the own reference point and no other inside each extent, extent and depth the
// bounding rectangle and min of the members), the overlap counts against brute force, and the lookup snippet's
// promise of no loops. The GPU build is compared with this one bit for bit in tests/render/MicrorectGpuTest.cpp.
#include "gl/ShaderLibrary.h"
#include "lightspace/HierarchicalShadowMap.h"
#include "lightspace/Microrects.h"

#include "support/RandomMaps.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <iostream>
#include <limits>
#include <map>
#include <random>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace sl
{
namespace
{

using Members = std::vector<glm::ivec2>;

std::set<std::pair<int, int>> asSet(const Members& members)
{
  std::set<std::pair<int, int>> set;
  for (const glm::ivec2& member : members)
  {
    set.insert({ member.x, member.y });
  }
  return set;
}

const Members& membersOf(const Microrects& microrects, int level, glm::ivec2 index)
{
  const glm::ivec2 size = microrects.levelSize(level);
  return microrects.members[static_cast<std::size_t>(level)][static_cast<std::size_t>(index.x + index.y * size.x)];
}

ImageF rowMap(const std::vector<float>& depths)
{
  ImageF map(static_cast<int>(depths.size()), 1, 1);
  map.data = depths;
  return map;
}

// Fig. 5 (§5.2), one row of 8 texels: every second microrect B joins the neighbour (A or C) of the
// smaller depth difference; extent = union, depth = min. The depths force each case: level 1 has B -> C twice
// (the figure's B, C -> N), B -> A by a smaller difference, and B -> A because C is past the end; level 2 has a
// tie (ties go to A) and a missing C again.
TEST(Microrects, Fig5RowJoinsEachBWithThePartnerOfSmallerDepthDifference)
{
  const Microrects microrects = Microrects::build(rowMap({ 1.0f, 4.0f, 4.5f, 7.5f, 7.0f, 7.25f, 9.0f, 8.0f }), true);
  ASSERT_EQ(microrects.levelCount(), 3);
  struct Expected
  {
    int level;
    int index;
    int lo;
    int hi;
    float depth;
    std::vector<int> members; // level-(level - 1) indices
  };
  const std::vector<Expected> expected = {
    { 1, 0, 0, 0, 1.0f, { 0 } },          // B = 1 (4.0): |4 - 1| = 3 > |4 - 4.5| = 0.5, joins C = 2
    { 1, 1, 1, 2, 4.0f, { 2, 1 } },       // C = 2 takes B = 1 in pass 2 (as its F)
    { 1, 2, 3, 5, 7.0f, { 4, 5, 3 } },    // B = 5 (7.25): |0.25| < |1.75| joins A = 4; B = 3: |0.5| < |3| joins C = 4
    { 1, 3, 6, 7, 8.0f, { 6, 7 } },       // B = 7 has no C: joins A = 6
    { 2, 0, 0, 2, 1.0f, { 0, 1 } },       // B = m1 (4.0): |4 - 1| = |4 - 7| = 3, a tie: A
    { 2, 1, 3, 7, 7.0f, { 2, 3 } },       // B = m3 has no C: joins A = m2
    { 3, 0, 0, 7, 1.0f, { 0, 1 } },       // the last B has no C
  };
  for (const Expected& e : expected)
  {
    const Microrect microrect = microrects.at(e.level, { e.index, 0 });
    const std::string label = "level " + std::to_string(e.level) + " microrect " + std::to_string(e.index);
    EXPECT_EQ(microrect.lo, glm::ivec2(e.lo, 0)) << label;
    EXPECT_EQ(microrect.hi, glm::ivec2(e.hi, 0)) << label;
    EXPECT_EQ(microrect.depth, e.depth) << label;
    Members members;
    for (const int member : e.members)
    {
      members.push_back({ member, 0 });
    }
    EXPECT_EQ(asSet(membersOf(microrects, e.level, { e.index, 0 })), asSet(members)) << label;
  }
  // The levels have the sizes of the HSM mip levels and nothing else.
  EXPECT_EQ(microrects.levelSize(1), glm::ivec2(4, 1));
  EXPECT_EQ(microrects.levelSize(2), glm::ivec2(2, 1));
  EXPECT_EQ(microrects.levelSize(3), glm::ivec2(1, 1));
}

// The 2-D rule (§5.2, Fig. 6) worked by hand on 4 x 4 maps. Level 1 keeps (0, 0), (2, 0), (0, 2), (2, 2) of
// level 0. Depths (x right, y up): 9 everywhere but A = (0, 0) = 1, E = (1, 1) = 1, (2, 1) = 4, (2, 2) = 4, and
// B = (1, 0), D = (0, 1) set per variant to 1.5 (joins A: |0.5| against |1.5 - 9|) or 8.5 (joins C = (2, 0) or
// G = (0, 2), both 9). Then:
//  - level-1 (0, 0) takes E = (1, 1) in pass 1 only if it took both B and D (only then does its rectangle
//    contain E); otherwise (2, 2) takes E in pass 2 as its E';
//  - a B or D that (0, 0) did not take goes to (2, 0) as its F, or to (0, 2) as its H, in pass 2;
//  - level-1 (1, 0) = (2, 0) (depth 9) takes B' = (3, 0) (no C), not D' = (2, 1) (|4 - 9| > |4 - 4|: G' = (2, 2)),
//    and E' = (3, 1) although its rectangle [2, 3] x [0, 0] does not contain it: (4, 2) does not exist;
//  - (2, 2) takes (2, 1) in pass 2 as its H; (1, 2) (9: |9 - 9| against |9 - 4|) joins (0, 2) in pass 1.
TEST(Microrects, DiagonalJoinsAWhenContainedElseItsOtherRetainedNeighbour)
{
  struct Variant
  {
    float b;
    float d;
    Members first;   // members of level-1 (0, 0)
    Members right;   // (1, 0)
    Members up;      // (0, 1)
    Members diagonal; // (1, 1)
    glm::ivec2 rightLo;
    glm::ivec2 diagonalLo;
    float diagonalDepth;
  };
  const Members right = { { 2, 0 }, { 3, 0 }, { 3, 1 } };
  const Members up = { { 0, 2 }, { 1, 2 }, { 0, 3 }, { 1, 3 } };
  const Members diagonal = { { 2, 2 }, { 3, 2 }, { 2, 3 }, { 3, 3 }, { 2, 1 } };
  const auto plus = [](Members members, const Members& more) {
    members.insert(members.end(), more.begin(), more.end());
    return members;
  };
  const std::vector<Variant> variants = {
    { 1.5f, 1.5f, { { 0, 0 }, { 1, 0 }, { 0, 1 }, { 1, 1 } }, right, up, diagonal, { 2, 0 }, { 2, 1 }, 4.0f },
    { 1.5f, 8.5f, { { 0, 0 }, { 1, 0 } }, right, plus(up, { { 0, 1 } }), plus(diagonal, { { 1, 1 } }), { 2, 0 }, { 1, 1 }, 1.0f },
    { 8.5f, 1.5f, { { 0, 0 }, { 0, 1 } }, plus(right, { { 1, 0 } }), up, plus(diagonal, { { 1, 1 } }), { 1, 0 }, { 1, 1 }, 1.0f },
    { 8.5f, 8.5f, { { 0, 0 } }, plus(right, { { 1, 0 } }), plus(up, { { 0, 1 } }), plus(diagonal, { { 1, 1 } }), { 1, 0 },
      { 1, 1 }, 1.0f },
  };
  for (const Variant& variant : variants)
  {
    ImageF map(4, 4, 1, 9.0f);
    map.at(0, 0) = 1.0f;
    map.at(1, 1) = 1.0f;
    map.at(2, 1) = 4.0f;
    map.at(2, 2) = 4.0f;
    map.at(1, 0) = variant.b;
    map.at(0, 1) = variant.d;
    const Microrects microrects = Microrects::build(map, true);
    std::ostringstream label;
    label << "B = " << variant.b << ", D = " << variant.d;
    EXPECT_EQ(asSet(membersOf(microrects, 1, { 0, 0 })), asSet(variant.first)) << label.str();
    EXPECT_EQ(asSet(membersOf(microrects, 1, { 1, 0 })), asSet(variant.right)) << label.str();
    EXPECT_EQ(asSet(membersOf(microrects, 1, { 0, 1 })), asSet(variant.up)) << label.str();
    EXPECT_EQ(asSet(membersOf(microrects, 1, { 1, 1 })), asSet(variant.diagonal)) << label.str();
    // (1, 0)'s extent [., 3] x [0, 1] overlaps (1, 1)'s, which holds (2, 1) (§5.2: overlaps are allowed).
    EXPECT_EQ(microrects.at(1, { 1, 0 }).lo, variant.rightLo) << label.str();
    EXPECT_EQ(microrects.at(1, { 1, 0 }).hi, glm::ivec2(3, 1)) << label.str();
    EXPECT_EQ(microrects.at(1, { 1, 1 }).lo, variant.diagonalLo) << label.str();
    EXPECT_EQ(microrects.at(1, { 1, 1 }).hi, glm::ivec2(3, 3)) << label.str();
    EXPECT_EQ(microrects.at(1, { 1, 1 }).depth, variant.diagonalDepth) << label.str();
  }
}

using test::randomMapWithTies;

// Every invariant of the definition (Microrects.h) on every level of a build with its members tracked.
void expectInvariants(const Microrects& microrects, const ImageF& map, const std::string& label)
{
  const int n = map.width;
  ASSERT_EQ(microrects.levelCount(), hsmLevelCount(n)) << label;
  // Level 0 = micropatches.
  int wrongMicropatches = 0;
  for (int y = 0; y < n; ++y)
  {
    for (int x = 0; x < n; ++x)
    {
      const Microrect m = microrects.at(0, { x, y });
      wrongMicropatches += (m.lo != glm::ivec2(x, y) || m.hi != glm::ivec2(x, y) || m.depth != map.at(x, y)) ? 1 : 0;
    }
  }
  EXPECT_EQ(wrongMicropatches, 0) << label;

  for (int level = 1; level <= microrects.levelCount(); ++level)
  {
    const glm::ivec2 size = microrects.levelSize(level);
    const glm::ivec2 finerSize = microrects.levelSize(level - 1);
    EXPECT_EQ(size, glm::ivec2(hsmLevelSize(HsmLayout::MipMap, n, level))) << label << " level " << level;
    std::vector<int> absorbedCount(static_cast<std::size_t>(finerSize.x * finerSize.y), 0);
    int outsideMap = 0, ownReferenceOutside = 0, otherReferenceInside = 0, memberNotACandidate = 0;
    int retainedNotFirst = 0, extentNotBoundingRectangle = 0, depthNotMemberMin = 0, depthBelowRectangleMin = 0;
    int over16Bits = 0;
    double areaSum = 0.0;
    int widest = 0;
    const int step = 1 << level;
    for (int y = 0; y < size.y; ++y)
    {
      for (int x = 0; x < size.x; ++x)
      {
        const Microrect m = microrects.at(level, { x, y });
        const glm::ivec2 reference = Microrects::referencePoint(level, { x, y });
        outsideMap += (glm::any(glm::lessThan(m.lo, glm::ivec2(0))) || glm::any(glm::greaterThanEqual(m.hi, glm::ivec2(n))) ||
                        glm::any(glm::greaterThan(m.lo, m.hi)))
          ? 1
          : 0;
        over16Bits += glm::any(glm::greaterThan(m.hi, glm::ivec2(65535))) ? 1 : 0;
        ownReferenceOutside +=
          (glm::any(glm::lessThan(reference, m.lo)) || glm::any(glm::greaterThan(reference, m.hi))) ? 1 : 0;
        // Level-`level` reference points inside the extent: multiples of 2^level per axis, inside the level.
        const glm::ivec2 firstInside = (m.lo + step - 1) / step;
        const glm::ivec2 lastInside = glm::min(m.hi / step, size - 1);
        const glm::ivec2 inside = glm::max(lastInside - firstInside + 1, glm::ivec2(0));
        otherReferenceInside += (inside.x * inside.y != 1) ? 1 : 0;

        const Members& members = membersOf(microrects, level, { x, y });
        retainedNotFirst += (members.empty() || members.front() != 2 * glm::ivec2(x, y)) ? 1 : 0;
        glm::ivec2 lo(std::numeric_limits<int>::max()), hi(std::numeric_limits<int>::min());
        float depth = std::numeric_limits<float>::infinity();
        for (const glm::ivec2& member : members)
        {
          const glm::ivec2 offset = member - 2 * glm::ivec2(x, y);
          memberNotACandidate += (glm::any(glm::lessThan(offset, glm::ivec2(-1))) || glm::any(glm::greaterThan(offset, glm::ivec2(1))) ||
                                   glm::any(glm::lessThan(member, glm::ivec2(0))) ||
                                   glm::any(glm::greaterThanEqual(member, finerSize)))
            ? 1
            : 0;
          if (glm::all(glm::greaterThanEqual(member, glm::ivec2(0))) && glm::all(glm::lessThan(member, finerSize)))
          {
            ++absorbedCount[static_cast<std::size_t>(member.x + member.y * finerSize.x)];
            const Microrect finer = microrects.at(level - 1, member);
            lo = glm::min(lo, finer.lo);
            hi = glm::max(hi, finer.hi);
            depth = std::min(depth, finer.depth);
          }
        }
        extentNotBoundingRectangle += (lo != m.lo || hi != m.hi) ? 1 : 0;
        depthNotMemberMin += depth != m.depth ? 1 : 0;
        float rectangleMin = std::numeric_limits<float>::infinity();
        for (int ty = m.lo.y; ty <= m.hi.y; ++ty)
        {
          for (int tx = m.lo.x; tx <= m.hi.x; ++tx)
          {
            rectangleMin = std::min(rectangleMin, map.at(tx, ty));
          }
        }
        depthBelowRectangleMin += m.depth < rectangleMin ? 1 : 0;
        const glm::ivec2 extent = m.hi - m.lo + 1;
        areaSum += extent.x * extent.y;
        widest = std::max(widest, std::max(extent.x, extent.y));
      }
    }
    int notOnce = 0;
    for (const int count : absorbedCount)
    {
      notOnce += count != 1 ? 1 : 0;
    }
    const std::string where = label + " level " + std::to_string(level);
    EXPECT_EQ(outsideMap, 0) << where;
    EXPECT_EQ(over16Bits, 0) << where;
    EXPECT_EQ(ownReferenceOutside, 0) << where;
    EXPECT_EQ(otherReferenceInside, 0) << where << ": extents holding another level-" << level << " reference point";
    EXPECT_EQ(retainedNotFirst, 0) << where;
    EXPECT_EQ(memberNotACandidate, 0) << where;
    EXPECT_EQ(notOnce, 0) << where << ": level-" << level - 1 << " microrects not absorbed exactly once";
    EXPECT_EQ(extentNotBoundingRectangle, 0) << where;
    EXPECT_EQ(depthNotMemberMin, 0) << where;
    EXPECT_EQ(depthBelowRectangleMin, 0) << where;
    const double micropatchArea = static_cast<double>(step) * step;
    if (n < 512)
    {
      continue;
    }
    std::cout << "[ measured ] " << where << ": mean extent " << areaSum / (size.x * size.y) << " texels ("
              << "micropatch " << micropatchArea << "), widest " << widest << "\n";
  }
}

TEST(Microrects, InvariantsOnEveryLevelOfRandomMapsWithTies)
{
  for (const int size : { 128, 200, 512 })
  {
    for (const bool blocks : { false, true })
    {
      const ImageF map = randomMapWithTies(size, 7u + static_cast<unsigned>(size), blocks);
      const std::string label = std::to_string(size) + "^2 " + (blocks ? "blocks" : "independent texels");
      expectInvariants(Microrects::build(map, true), map, label);
    }
  }
}

TEST(Microrects, TiesDecideTheSameWithAndWithoutMemberTracking)
{
  const ImageF map = randomMapWithTies(200, 3u, false);
  const Microrects tracked = Microrects::build(map, true);
  const Microrects plain = Microrects::build(map);
  EXPECT_TRUE(plain.members.empty());
  EXPECT_EQ(plain.extentAtlas().data, tracked.extentAtlas().data);
  EXPECT_EQ(plain.depthAtlas().data, tracked.depthAtlas().data);
}

// The atlases hold every level at hsmAtlasOffset (the HSM mip-map layout) and 0 elsewhere; reading them back
// gives the build again.
TEST(Microrects, AtlasesHoldEveryLevelAtTheHsmOffsets)
{
  for (const int size : { 1, 2, 3, 37, 200 })
  {
    const ImageF map = randomMapWithTies(size, 11u, true);
    const Microrects built = Microrects::build(map);
    const Image<std::uint32_t> extents = built.extentAtlas();
    const ImageF depths = built.depthAtlas();
    const Microrects read = Microrects::fromAtlases(map, extents, depths);
    ASSERT_EQ(read.levelCount(), built.levelCount()) << size;
    int differing = 0;
    std::size_t written = 0;
    for (int level = 0; level <= built.levelCount(); ++level)
    {
      const glm::ivec2 levelSize = built.levelSize(level);
      written += level > 0 ? static_cast<std::size_t>(levelSize.x * levelSize.y) : 0;
      for (int y = 0; y < levelSize.y; ++y)
      {
        for (int x = 0; x < levelSize.x; ++x)
        {
          const Microrect a = built.at(level, { x, y });
          const Microrect b = read.at(level, { x, y });
          differing += (a.lo != b.lo || a.hi != b.hi || a.depth != b.depth) ? 1 : 0;
        }
      }
    }
    EXPECT_EQ(differing, 0) << size;
    // Levels never overlap in the atlas: the texels with a non-zero extent or depth are at most the levels' count
    // (a microrect (0, 0, 0, 0) of depth 0 cannot occur: depths are >= 1 here).
    std::size_t nonZero = 0;
    for (std::size_t i = 0; i < depths.data.size(); ++i)
    {
      nonZero += depths.data[i] != 0.0f ? 1 : 0;
    }
    EXPECT_EQ(nonZero, written) << size;
  }
}

// microrect_overlap_k: a difference array against counting every extent's texels.
TEST(Microrects, OverlapCountsEqualBruteForceAndCoverTheMap)
{
  const ImageF map = randomMapWithTies(200, 5u, true);
  const Microrects microrects = Microrects::build(map);
  for (int level = 1; level <= microrects.levelCount(); ++level)
  {
    ImageF bruteForce(200, 200, 1, 0.0f);
    for (const Microrect& m : microrects.levels[static_cast<std::size_t>(level)])
    {
      for (int y = m.lo.y; y <= m.hi.y; ++y)
      {
        for (int x = m.lo.x; x <= m.hi.x; ++x)
        {
          bruteForce.at(x, y) += 1.0f;
        }
      }
    }
    const ImageF counts = microrects.overlapCount(level);
    EXPECT_EQ(counts.data, bruteForce.data) << "level " << level;
    // Every texel is represented at every level (each microrect is absorbed by one whose extent contains its own).
    const auto [least, most] = std::minmax_element(counts.data.begin(), counts.data.end());
    EXPECT_GE(*least, 1.0f) << "level " << level;
    std::cout << "[ measured ] 200^2 blocks level " << level << ": texels covered by up to " << *most
              << " microrects\n";
  }
}

// The lookup runs once per micro-occluder in a technique's shader: llvmpipe caps loop iterations per invocation,
// so neither it nor the atlas layout it includes may loop.
TEST(Microrects, LookupSnippetHasNoLoops)
{
  for (const std::string path : { "common/MicrorectLookup.glsl", "common/MipAtlasLayout.glsl" })
  {
    std::string code;
    std::istringstream lines(embeddedShaderText(path));
    std::string line;
    while (std::getline(lines, line))
    {
      code += line.substr(0, line.find("//")) + "\n";
    }
    EXPECT_FALSE(std::regex_search(code, std::regex(R"(\b(for|while|do)\b)"))) << path;
  }
  // The signature techniques code against.
  EXPECT_NE(embeddedShaderText("common/MicrorectLookup.glsl")
              .find("void microrectAt(int level, ivec2 index, out ivec4 extent, out float depth)"),
    std::string::npos);
}

} // namespace
} // namespace sl
