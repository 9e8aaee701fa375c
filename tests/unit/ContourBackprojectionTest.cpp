// Contour back-projection (GBP07) against closed forms: the radial integration of a closed occluder
// polygon's edges equals its exact overlap with the square light, and marching squares orients every edge
// with the occluder on its left and agrees with its own inside test.
#include "techniques/ContourBackprojection.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace sl
{
namespace
{

double cross(const glm::dvec2& u, const glm::dvec2& v)
{
  return u.x * v.y - u.y * v.x;
}

TEST(ContourBackprojection, RadialIntegrationOfATriangleEqualsItsOverlapWithTheLight)
{
  std::mt19937 generator(5u);
  std::uniform_real_distribution<double> coordinate(-2.0, 2.0);
  const double halfSize = 0.75;
  int partial = 0;
  for (int trial = 0; trial < 2000; ++trial)
  {
    std::array<glm::dvec2, 3> v = { glm::dvec2(coordinate(generator), coordinate(generator)),
      glm::dvec2(coordinate(generator), coordinate(generator)), glm::dvec2(coordinate(generator), coordinate(generator)) };
    if (cross(v[1] - v[0], v[2] - v[0]) < 0.0)
    {
      std::swap(v[1], v[2]); // counter-clockwise: the inside on each edge's left
    }
    if (std::abs(cross(v[1] - v[0], v[2] - v[0])) < 1e-3)
    {
      continue;
    }
    // Exact overlap: the square clipped by the triangle's three half-planes (inside = left of each edge).
    std::array<glm::dvec3, 3> planes;
    for (int k = 0; k < 3; ++k)
    {
      const glm::dvec2 a = v[static_cast<std::size_t>(k)];
      const glm::dvec2 b = v[static_cast<std::size_t>((k + 1) % 3)];
      const glm::dvec2 right(b.y - a.y, a.x - b.x);
      planes[static_cast<std::size_t>(k)] = glm::dvec3(right, glm::dot(right, a));
    }
    const double exact = clippedSquareArea(halfSize, planes, 3);
    bool centreInside = true;
    for (int k = 0; k < 3; ++k)
    {
      centreInside = centreInside && cross(v[static_cast<std::size_t>((k + 1) % 3)] - v[static_cast<std::size_t>(k)], -v[static_cast<std::size_t>(k)]) > 0.0;
    }
    double radial = centreInside ? 4.0 * halfSize * halfSize : 0.0;
    for (int k = 0; k < 3; ++k)
    {
      radial += radialEdgeArea(v[static_cast<std::size_t>(k)], v[static_cast<std::size_t>((k + 1) % 3)], halfSize);
    }
    partial += (exact > 1e-6 && exact < 4.0 * halfSize * halfSize - 1e-6) ? 1 : 0;
    ASSERT_NEAR(radial, exact, 1e-12) << "trial " << trial;
  }
  EXPECT_GT(partial, 300);
}

TEST(ContourBackprojection, MarchingSquaresEdgesKeepTheOccluderOnTheirLeft)
{
  const glm::dvec2 origin(10.5, 20.5);
  const std::array<glm::dvec2, 4> corners = { glm::dvec2(0, 0), glm::dvec2(1, 0), glm::dvec2(1, 1), glm::dvec2(0, 1) };
  for (int mask = 0; mask < 16; ++mask)
  {
    std::array<bool, 4> occluding;
    int occluders = 0;
    for (int k = 0; k < 4; ++k)
    {
      occluding[static_cast<std::size_t>(k)] = ((mask >> k) & 1) != 0;
      occluders += occluding[static_cast<std::size_t>(k)] ? 1 : 0;
    }
    std::array<ContourEdge, 2> edges;
    const int count = marchingSquaresEdges(occluding, { 1.0, 2.0, 3.0, 4.0 }, origin, edges);
    const bool saddle = mask == 5 || mask == 10;
    EXPECT_EQ(count, occluders == 0 || occluders == 4 ? 0 : (saddle ? 2 : 1)) << "mask " << mask;
    for (int e = 0; e < count; ++e)
    {
      const ContourEdge& edge = edges[static_cast<std::size_t>(e)];
      for (int k = 0; k < 4; ++k)
      {
        // Every occluding corner is on the left of, or behind, the edge; every free corner on its right
        // or behind (a saddle's other run).
        const double side = cross(edge.b - edge.a, origin + corners[static_cast<std::size_t>(k)] - edge.a);
        const double near = glm::length(origin + corners[static_cast<std::size_t>(k)] - 0.5 * (edge.a + edge.b));
        if (near < 0.75)
        {
          EXPECT_EQ(side > 0.0, occluding[static_cast<std::size_t>(k)]) << "mask " << mask << " corner " << k;
        }
      }
      // Endpoint depths are those of occluding corners.
      EXPECT_TRUE(occluding[static_cast<std::size_t>(edge.depthA) - 1]) << "mask " << mask;
      EXPECT_TRUE(occluding[static_cast<std::size_t>(edge.depthB) - 1]) << "mask " << mask;
    }
    // The inside test agrees with each corner's status just inside the cell.
    for (int k = 0; k < 4; ++k)
    {
      const glm::dvec2 nearCorner = origin + 0.5 + 0.9 * (corners[static_cast<std::size_t>(k)] - 0.5);
      EXPECT_EQ(insideReconstructedOccluder(occluding, origin, nearCorner), occluding[static_cast<std::size_t>(k)])
        << "mask " << mask << " corner " << k;
    }
  }
}

TEST(ContourBackprojection, BackProjectionThroughTheOccluderReachesTheLightPlane)
{
  // Receiver at depth 3 under the light centre, occluder point at depth 1 and tangent 0.1: the ray through
  // them meets depth 0 at x = 0 + (0.1 - 0) * 3 / 2 = 0.15.
  const glm::dvec2 onLight = backProject(glm::dvec2(0.1, -0.2), 1.0, glm::dvec2(0.0), 3.0);
  EXPECT_NEAR(onLight.x, 0.15, 1e-15);
  EXPECT_NEAR(onLight.y, -0.3, 1e-15);
}

} // namespace
} // namespace sl
