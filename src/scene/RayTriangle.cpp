#include "scene/RayTriangle.h"

#include <cmath>

namespace sl
{

std::optional<RayTriangleHit> intersectRayTriangle(const glm::dvec3& origin, const glm::dvec3& direction,
  const glm::dvec3& a, const glm::dvec3& edge1, const glm::dvec3& edge2, double minAbsDeterminant)
{
  const glm::dvec3 p = glm::cross(direction, edge2);
  const double determinant = glm::dot(edge1, p);
  if (determinant == 0.0 || std::abs(determinant) < minAbsDeterminant)
  {
    return std::nullopt;
  }
  const double inverse = 1.0 / determinant;
  const glm::dvec3 s = origin - a;
  const double u = glm::dot(s, p) * inverse;
  if (u < 0.0 || u > 1.0)
  {
    return std::nullopt;
  }
  const glm::dvec3 q = glm::cross(s, edge1);
  const double v = glm::dot(direction, q) * inverse;
  if (v < 0.0 || u + v > 1.0)
  {
    return std::nullopt;
  }
  return RayTriangleHit{ glm::dot(edge2, q) * inverse, u, v };
}

} // namespace sl
