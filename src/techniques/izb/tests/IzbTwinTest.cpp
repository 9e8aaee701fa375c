// The irregular z-buffer's CPU math (izb/IzbTwin.h): the conservative cover holds the texel of every point a
// triangle hides, it is tighter than the bounding box, and the per-sample test agrees with Moller-Trumbore wherever it
// does not call itself uncertain.
#include "scene/RayTriangle.h"
#include "techniques/izb/IzbTwin.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace sl
{
namespace
{

double izbUniform(std::mt19937_64& random, double low, double high)
{
  return std::uniform_real_distribution<double>(low, high)(random);
}

glm::dvec3 izbRandomPoint(std::mt19937_64& random, double extent)
{
  const double x = izbUniform(random, -extent, extent);
  const double y = izbUniform(random, -extent, extent);
  return { x, y, izbUniform(random, -extent, extent) };
}

// Every point of a random triangle, seen from the light, lands in a texel of the triangle's cover: the texel of a
// sample hidden by the triangle (a point on the light's line through the triangle point, farther from the light).
void expectCoverHoldsHiddenSamples(const Light& light, int gridSize, std::uint64_t seed)
{
  Bounds bounds;
  bounds.min = glm::dvec3(-3.0);
  bounds.max = glm::dvec3(3.0);
  const IzbGrid grid = IzbGrid::fit(light, bounds, gridSize);
  std::mt19937_64 random(seed);
  int checked = 0, missed = 0;
  std::size_t coverTexels = 0;
  for (int triangle = 0; triangle < 400; ++triangle)
  {
    // Small and large triangles, some straddling cube faces and some close to the light.
    const double size = triangle % 3 == 0 ? 2.5 : 0.3;
    const glm::dvec3 centre = izbRandomPoint(random, 2.5);
    const glm::dvec3 a = centre + izbRandomPoint(random, size);
    const glm::dvec3 b = centre + izbRandomPoint(random, size);
    const glm::dvec3 c = centre + izbRandomPoint(random, size);
    std::vector<std::uint32_t> texels;
    grid.triangleTexels(a, b, c, [](std::uint32_t) { return true; }, texels);
    std::sort(texels.begin(), texels.end());
    for (int sample = 0; sample < 200; ++sample)
    {
      double u = izbUniform(random, 0.0, 1.0), v = izbUniform(random, 0.0, 1.0);
      if (u + v > 1.0)
      {
        u = 1.0 - u;
        v = 1.0 - v;
      }
      const glm::dvec3 onTriangle = a + u * (b - a) + v * (c - a);
      const double beyond = izbUniform(random, 0.0, 3.0);
      const glm::dvec3 hidden = grid.directional ? onTriangle + beyond * grid.lightDirection
                                                 : onTriangle + beyond * (onTriangle - grid.lightPosition);
      const int texel = grid.place(hidden).texel;
      ++checked;
      if (!std::binary_search(texels.begin(), texels.end(), static_cast<std::uint32_t>(texel)))
      {
        ++missed;
      }
    }
    coverTexels += texels.size();
  }
  EXPECT_EQ(missed, 0) << missed << " of " << checked << " hidden samples fall in a texel outside the cover";
  EXPECT_GT(coverTexels, 0u);
}

TEST(IzbTwin, CoverHoldsEveryHiddenSampleDirectional)
{
  Light light;
  light.type = LightType::Directional;
  light.direction = glm::normalize(glm::dvec3(0.3, -1.0, 0.2));
  expectCoverHoldsHiddenSamples(light, 64, 1);
  light.direction = glm::dvec3(0.0, -1.0, 0.0);
  expectCoverHoldsHiddenSamples(light, 256, 2);
}

TEST(IzbTwin, CoverHoldsEveryHiddenSampleAroundAPointLight)
{
  Light light;
  light.type = LightType::Point;
  light.center = glm::dvec3(0.1, 0.2, -0.3); // inside the triangles' region: faces, edges and the light itself
  expectCoverHoldsHiddenSamples(light, 32, 3);
  expectCoverHoldsHiddenSamples(light, 128, 4);
}

TEST(IzbTwin, CoverOfAThinDiagonalTriangleIsFarBelowItsBoundingBox)
{
  Light light;
  light.type = LightType::Directional;
  light.direction = glm::dvec3(0.0, -1.0, 0.0);
  Bounds bounds;
  bounds.min = glm::dvec3(-1.0);
  bounds.max = glm::dvec3(1.0);
  const IzbGrid grid = IzbGrid::fit(light, bounds, 128);
  std::vector<std::uint32_t> texels;
  grid.triangleTexels(glm::dvec3(-0.9, 0.0, -0.9), glm::dvec3(0.9, 0.0, 0.9), glm::dvec3(0.88, 0.0, 0.9),
    [](std::uint32_t) { return true; }, texels);
  // The box spans ~115 x 115 texels; a sliver along its diagonal crosses about 2-3 texels per row.
  EXPECT_GT(texels.size(), 100u);
  EXPECT_LT(texels.size(), 500u) << "the edge test should cut the bounding box down to the diagonal";
}

// izbSampleTest against Moller-Trumbore (the ray tracer's test): identical wherever it is not uncertain, and
// uncertain only rarely on random configurations.
TEST(IzbTwin, SampleTestAgreesWithMollerTrumboreOutsideItsRoundingBand)
{
  std::mt19937_64 random(5);
  int disagreements = 0, uncertain = 0, shadowing = 0;
  constexpr int cases = 200000;
  for (int i = 0; i < cases; ++i)
  {
    IzbLight light;
    light.directional = i % 2 == 0;
    light.direction = glm::normalize(izbRandomPoint(random, 1.0));
    light.position = izbRandomPoint(random, 4.0);
    const glm::dvec3 a = izbRandomPoint(random, 2.0), b = izbRandomPoint(random, 2.0), c = izbRandomPoint(random, 2.0);
    const glm::dvec3 q = izbRandomPoint(random, 2.0);
    const IzbSampleTest test = izbSampleTest(a, b, c, q, light, 0.0);
    const glm::dvec3 toLight = light.directional ? -light.direction : light.position - q;
    const double tMax = light.directional ? 1e30 : 1.0;
    const auto hit = intersectRayTriangle(q, toLight, a, b - a, c - a, 1e-15);
    const bool occluded = hit && hit->t > 0.0 && hit->t < tMax;
    uncertain += test.uncertain ? 1 : 0;
    shadowing += occluded ? 1 : 0;
    if (!test.uncertain && test.shadows != occluded)
    {
      ++disagreements;
    }
    if (test.definite)
    {
      EXPECT_TRUE(test.shadows);
    }
  }
  EXPECT_EQ(disagreements, 0);
  EXPECT_GT(shadowing, cases / 50) << "the cases must exercise occlusion";
  EXPECT_LT(uncertain, cases / 1000) << uncertain << " uncertain of " << cases;
}

// A sample exactly on a triangle's edge (in light space) and one exactly in its plane are uncertain, not decided.
TEST(IzbTwin, SampleOnAnEdgeOrInThePlaneIsUncertain)
{
  IzbLight light;
  light.directional = true;
  light.direction = glm::dvec3(0.0, -1.0, 0.0);
  const glm::dvec3 a(0.0, 1.0, 0.0), b(1.0, 1.0, 0.0), c(0.0, 1.0, 1.0);
  const IzbSampleTest onEdge = izbSampleTest(a, b, c, glm::dvec3(0.5, 0.0, 0.0), light, 0.0);
  EXPECT_TRUE(onEdge.uncertain);
  const IzbSampleTest inPlane = izbSampleTest(a, b, c, glm::dvec3(0.2, 1.0, 0.2), light, 0.0);
  EXPECT_TRUE(inPlane.uncertain);
  const IzbSampleTest below = izbSampleTest(a, b, c, glm::dvec3(0.2, 0.0, 0.2), light, 0.0);
  EXPECT_TRUE(below.definite);
  const IzbSampleTest above = izbSampleTest(a, b, c, glm::dvec3(0.2, 2.0, 0.2), light, 0.0);
  EXPECT_FALSE(above.shadows);
  EXPECT_FALSE(above.uncertain);
}

// A sample under the shared diagonal of a quad split in two: each triangle alone is uncertain through that edge, the
// pair covers it (README.md, "Shared edges"); a triangle listed twice, or the edge met with opposite orientations
// (a fold seen edge-on), does not pair.
TEST(IzbTwin, TwoTrianglesSharingTheUncertainEdgeCoverTheSample)
{
  IzbLight light;
  light.directional = true;
  light.direction = glm::dvec3(0.0, -1.0, 0.0);
  const glm::dvec3 a(0.0, 1.0, 0.0), b(1.0, 1.0, 0.0), c(0.0, 1.0, 1.0), d(1.0, 1.0, 1.0);
  const std::uint32_t ib = 1, ic = 2; // vertex ids of b and c (a 0, d 3)
  const glm::dvec3 q(0.5, 0.0, 0.5);
  const IzbSampleTest first = izbSampleTest(a, b, c, q, light, 0.0);  // edges ab, bc, ca
  const IzbSampleTest second = izbSampleTest(b, d, c, q, light, 0.0); // edges bd, dc, cb
  ASSERT_TRUE(first.uncertain);
  ASSERT_TRUE(second.uncertain);
  ASSERT_EQ(first.loneEdge, 1);
  ASSERT_EQ(second.loneEdge, 2);
  EXPECT_EQ(first.orientation, second.orientation);
  const IzbEdgeEvent e1 = izbEdgeEvent(ib, ic, first.orientation);
  const IzbEdgeEvent e2 = izbEdgeEvent(ic, ib, second.orientation);
  EXPECT_TRUE(izbEdgePairCovers(2, e1.first ^ e2.first, e1.second ^ e2.second));
  EXPECT_FALSE(izbEdgePairCovers(2, e1.first ^ e1.first, e1.second ^ e1.second)) << "the same triangle twice";
  const IzbEdgeEvent flipped = izbEdgeEvent(ic, ib, -second.orientation);
  EXPECT_FALSE(izbEdgePairCovers(2, e1.first ^ flipped.first, e1.second ^ flipped.second)) << "a fold";
  EXPECT_FALSE(izbEdgePairCovers(3, e1.first ^ e2.first ^ e1.first, e1.second ^ e2.second ^ e1.second));
  // Off the diagonal the triangle holding the sample decides alone, definitely.
  const IzbSampleTest inside = izbSampleTest(a, b, c, glm::dvec3(0.3, 0.0, 0.3), light, 0.0);
  EXPECT_TRUE(inside.definite);
  EXPECT_EQ(inside.loneEdge, -1);
}

} // namespace
} // namespace sl
