#include "techniques/ContourBackprojection.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace sl
{
namespace
{

double cross(const glm::dvec2& u, const glm::dvec2& v)
{
  return u.x * v.y - u.y * v.x;
}

// Corner k's position in the unit cell, counter-clockwise from the lower left, and the midpoint of side k
// (between corners k and k + 1).
const std::array<glm::dvec2, 4> cellCorners = { glm::dvec2(0, 0), glm::dvec2(1, 0), glm::dvec2(1, 1), glm::dvec2(0, 1) };
const std::array<glm::dvec2, 4> sideMidpoints = { glm::dvec2(0.5, 0), glm::dvec2(1, 0.5), glm::dvec2(0.5, 1), glm::dvec2(0, 0.5) };

} // namespace

int marchingSquaresEdges(const std::array<bool, 4>& occluding, const std::array<double, 4>& depths,
  const glm::dvec2& cellOrigin, std::array<ContourEdge, 2>& edges)
{
  // Each run of occluding corners, walking counter-clockwise, enters at the side whose second corner is its
  // first occluding one and leaves at the side after its last; the edge runs leave -> enter, which puts the
  // run (the occluder) on its left. A saddle has two runs of one corner each.
  int count = 0;
  for (int leave = 0; leave < 4; ++leave)
  {
    const int next = (leave + 1) % 4;
    if (!(occluding[static_cast<std::size_t>(leave)] && !occluding[static_cast<std::size_t>(next)]))
    {
      continue;
    }
    int enter = (leave + 3) % 4;
    while (occluding[static_cast<std::size_t>(enter)])
    {
      enter = (enter + 3) % 4;
    }
    // Side `enter` joins corner `enter` (free) and `enter + 1` (occluding); side `leave` joins `leave`
    // (occluding) and `leave + 1` (free).
    ContourEdge& edge = edges[static_cast<std::size_t>(count++)];
    edge.a = cellOrigin + sideMidpoints[static_cast<std::size_t>(leave)];
    edge.b = cellOrigin + sideMidpoints[static_cast<std::size_t>(enter)];
    edge.depthA = depths[static_cast<std::size_t>(leave)];
    edge.depthB = depths[static_cast<std::size_t>((enter + 1) % 4)];
  }
  return count;
}

bool insideReconstructedOccluder(const std::array<bool, 4>& occluding, const glm::dvec2& cellOrigin,
  const glm::dvec2& position)
{
  std::array<ContourEdge, 2> edges;
  const int count = marchingSquaresEdges(occluding, { 0.0, 0.0, 0.0, 0.0 }, cellOrigin, edges);
  bool inside = occluding[0];
  const glm::dvec2 start = cellOrigin + cellCorners[0];
  for (int e = 0; e < count; ++e)
  {
    const ContourEdge& edge = edges[static_cast<std::size_t>(e)];
    // Proper crossing of [start, position] and [a, b].
    const double d1 = cross(edge.b - edge.a, start - edge.a);
    const double d2 = cross(edge.b - edge.a, position - edge.a);
    const double d3 = cross(position - start, edge.a - start);
    const double d4 = cross(position - start, edge.b - start);
    if (((d1 > 0.0) != (d2 > 0.0)) && ((d3 > 0.0) != (d4 > 0.0)))
    {
      inside = !inside;
    }
  }
  return inside;
}

glm::dvec2 backProject(const glm::dvec2& tangent, double depth, const glm::dvec2& receiverXy, double receiverDepth)
{
  // The line from p through X = (tangent depth, depth) meets depth 0 at p + (X - p) p_z / (p_z - X_z).
  const glm::dvec2 occluderXy = tangent * depth;
  return receiverXy + (occluderXy - receiverXy) * (receiverDepth / (receiverDepth - depth));
}

double clippedSquareArea(double halfSize, const std::array<glm::dvec3, 3>& planes, int planeCount)
{
  std::vector<glm::dvec2> polygon = { { -halfSize, -halfSize }, { halfSize, -halfSize }, { halfSize, halfSize },
    { -halfSize, halfSize } };
  for (int k = 0; k < planeCount && !polygon.empty(); ++k)
  {
    const glm::dvec2 normal(planes[static_cast<std::size_t>(k)]);
    const double offset = planes[static_cast<std::size_t>(k)].z;
    std::vector<glm::dvec2> clipped;
    for (std::size_t i = 0; i < polygon.size(); ++i)
    {
      const glm::dvec2& current = polygon[i];
      const glm::dvec2& following = polygon[(i + 1) % polygon.size()];
      const double currentSide = glm::dot(normal, current) - offset;
      const double followingSide = glm::dot(normal, following) - offset;
      if (currentSide <= 0.0)
      {
        clipped.push_back(current);
      }
      if ((currentSide <= 0.0) != (followingSide <= 0.0))
      {
        clipped.push_back(current + (following - current) * (currentSide / (currentSide - followingSide)));
      }
    }
    polygon = clipped;
  }
  double twiceArea = 0.0;
  for (std::size_t i = 0; i < polygon.size(); ++i)
  {
    twiceArea += cross(polygon[i], polygon[(i + 1) % polygon.size()]);
  }
  return 0.5 * std::abs(twiceArea);
}

namespace
{

// Where the ray from O through d (d != 0) leaves the square [-h, h]^2.
glm::dvec2 squareBoundaryHit(const glm::dvec2& d, double halfSize)
{
  return d * (halfSize / std::max(std::abs(d.x), std::abs(d.y)));
}

// The square's corner reached first walking counter-clockwise along its boundary from the side that the ray
// through d meets: sides 0..3 = right, top, left, bottom; their counter-clockwise ends (h, h), (-h, h),
// (-h, -h), (h, -h).
glm::dvec2 nextSquareCorner(const glm::dvec2& d, int step, double halfSize)
{
  const int side = std::abs(d.x) >= std::abs(d.y) ? (d.x > 0.0 ? 0 : 2) : (d.y > 0.0 ? 1 : 3);
  const int corner = (side + step) % 4;
  return halfSize * glm::dvec2(corner == 0 || corner == 3 ? 1.0 : -1.0, corner <= 1 ? 1.0 : -1.0);
}

// One edge u -> v of a convex polygon clipped to {x: beyond(x) >= 0}: its shoelace term, and where the
// boundary leaves and re-enters the half-plane (the chord between them closes the clipped polygon).
void clipEdgeBeyondLine(const glm::dvec2& u, const glm::dvec2& v, const glm::dvec2& away, double offset, double& twiceArea,
  glm::dvec2& exitPoint, glm::dvec2& entryPoint)
{
  const double su = glm::dot(away, u) - offset;
  const double sv = glm::dot(away, v) - offset;
  if (su >= 0.0 && sv >= 0.0)
  {
    twiceArea += cross(u, v);
  }
  else if (su >= 0.0)
  {
    exitPoint = u + (v - u) * (su / (su - sv));
    twiceArea += cross(u, exitPoint);
  }
  else if (sv >= 0.0)
  {
    entryPoint = u + (v - u) * (su / (su - sv));
    twiceArea += cross(entryPoint, v);
  }
}

} // namespace

double sectorBeyondEdgeArea(const glm::dvec2& first, const glm::dvec2& second, double halfSize)
{
  // P = square ∩ sector: O, the ray hits F and G, and the corners met between them (at most two: the sector
  // is narrower than pi). An absent corner is replaced by G, a zero-length edge.
  const glm::dvec2 hitFirst = squareBoundaryHit(first, halfSize);
  const glm::dvec2 hitSecond = squareBoundaryHit(second, halfSize);
  const auto inSector = [&](const glm::dvec2& c) { return cross(first, c) >= 0.0 && cross(c, second) >= 0.0; };
  glm::dvec2 corner1 = nextSquareCorner(first, 0, halfSize);
  glm::dvec2 corner2 = nextSquareCorner(first, 1, halfSize);
  if (!inSector(corner1))
  {
    corner1 = hitSecond;
    corner2 = hitSecond;
  }
  else if (!inSector(corner2))
  {
    corner2 = hitSecond;
  }
  // P ∩ {dot(away, x - first) >= 0}, away = right of first -> second, the side O is not on.
  const glm::dvec2 direction = second - first;
  const glm::dvec2 away(direction.y, -direction.x);
  const double offset = glm::dot(away, first);
  const glm::dvec2 origin(0.0);
  double twiceArea = 0.0;
  glm::dvec2 exitPoint(0.0);
  glm::dvec2 entryPoint(0.0);
  clipEdgeBeyondLine(origin, hitFirst, away, offset, twiceArea, exitPoint, entryPoint);
  clipEdgeBeyondLine(hitFirst, corner1, away, offset, twiceArea, exitPoint, entryPoint);
  clipEdgeBeyondLine(corner1, corner2, away, offset, twiceArea, exitPoint, entryPoint);
  clipEdgeBeyondLine(corner2, hitSecond, away, offset, twiceArea, exitPoint, entryPoint);
  clipEdgeBeyondLine(hitSecond, origin, away, offset, twiceArea, exitPoint, entryPoint);
  twiceArea += cross(exitPoint, entryPoint); // O lies outside: the boundary crosses the line twice or never
  return 0.5 * std::abs(twiceArea);
}

double radialEdgeArea(const glm::dvec2& a, const glm::dvec2& b, double halfSize)
{
  // The sector of rays from O through the edge, oriented counter-clockwise from `first` to `second`.
  const double sweep = cross(a, b);
  if (std::abs(sweep) <= 1e-300)
  {
    return 0.0; // the edge is seen edge-on from O: no sector
  }
  const glm::dvec2 first = sweep > 0.0 ? a : b;
  const glm::dvec2 second = sweep > 0.0 ? b : a;
  const double area = sectorBeyondEdgeArea(first, second, halfSize);
  // Crossing outwards enters the occluder when O is on the edge's right (the occluder on its left).
  return cross(b - a, -a) < 0.0 ? area : -area;
}

} // namespace sl
