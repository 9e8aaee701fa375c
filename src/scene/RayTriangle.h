// Ray / triangle intersection in double precision (Moller & Trumbore 1997), written once for the CPU twins and
// references that walk the scene's triangles themselves: reference-sm's replay of its light-depth pass,
// shadow-volume's crossing count, the tests' brute-force ray caster. Each caller keeps its own range rule on t
// (a segment, an open interval, a ray) and its own face filter.
#pragma once

#include <glm/glm.hpp>

#include <optional>

namespace sl
{

// Where the line origin + t direction meets the triangle (a, a + edge1, a + edge2): the line parameter t and the
// barycentric coordinates u (weight of a + edge1) and v (weight of a + edge2). No range on t.
struct RayTriangleHit
{
  double t = 0.0;
  double u = 0.0;
  double v = 0.0;
};

// The hit, or none when the line misses the triangle (u < 0, v < 0 or u + v > 1; the triangle's edges count as
// inside) or runs parallel to its plane: a determinant edge1 . (direction x edge2) of 0 or of magnitude below
// `minAbsDeterminant` (0: only an exact 0 is parallel). Both faces are hit.
std::optional<RayTriangleHit> intersectRayTriangle(const glm::dvec3& origin, const glm::dvec3& direction,
  const glm::dvec3& a, const glm::dvec3& edge1, const glm::dvec3& edge2, double minAbsDeterminant = 0.0);

} // namespace sl
