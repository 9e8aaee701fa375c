#include "objectspace/ShadowVolumeGeometry.h"

#include "core/Error.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace sl
{

VolumeLight VolumeLight::from(const Light& light)
{
  VolumeLight volumeLight;
  volumeLight.directional = light.type == LightType::Directional;
  volumeLight.position = light.center; // an area light is taken at its centre
  volumeLight.direction = glm::normalize(light.direction);
  return volumeLight;
}

namespace
{

// +1: the triangle's winding faces the light, -1: it faces away (flipped), 0: edge-on (rule 3).
int lightOrientation(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const VolumeLight& light)
{
  const glm::dvec3 normal = glm::cross(b - a, c - a);
  const glm::dvec3 toLight = light.directional ? -light.direction : light.position - a;
  const double scale = glm::length(normal) * glm::length(toLight);
  const double facing = glm::dot(normal, toLight);
  if (!(scale > 0.0) || std::abs(facing) < kEdgeOnSine * scale)
  {
    return 0;
  }
  return facing > 0.0 ? 1 : -1;
}

// The plane n . x = d of the triangle (a, b, c), n unit; (0, 0, 0, 0) when it has no area.
glm::vec4 planeThrough(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c)
{
  const glm::dvec3 normal = glm::cross(b - a, c - a);
  const double length = glm::length(normal);
  if (!(length > 0.0))
  {
    return glm::vec4(0.0f);
  }
  return glm::vec4(glm::vec3(normal / length), static_cast<float>(glm::dot(normal / length, a)));
}

// Where a caster vertex goes when extruded away from the light.
class Extruder
{
public:
  Extruder(const VolumeLight& light, VolumeExtrusion extrusion, double finiteScale)
    : light_(light)
    , extrusion_(extrusion)
    , finiteScale_(finiteScale)
  {
  }

  // The plane of the far cap of the light-oriented triangle (a, b, c): none (zeros) at infinity.
  glm::vec4 farCapPlane(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) const
  {
    if (extrusion_ == VolumeExtrusion::ToInfinity)
    {
      return glm::vec4(0.0f);
    }
    return planeThrough(farPoint(a), farPoint(b), farPoint(c));
  }

  // The plane of the side quad along the edge (from, to): it contains the light (or its direction).
  glm::vec4 sidePlane(const glm::vec3& from, const glm::vec3& to) const
  {
    const glm::dvec3 p(from), q(to);
    return light_.directional ? planeThrough(p, q, q + light_.direction) : planeThrough(light_.position, p, q);
  }

  glm::vec4 far(const glm::vec3& vertex) const
  {
    const glm::dvec3 p(vertex);
    if (extrusion_ == VolumeExtrusion::ToInfinity)
    {
      return light_.directional ? glm::vec4(glm::vec3(light_.direction), 0.0f) : glm::vec4(glm::vec3(p - light_.position), 0.0f);
    }
    return glm::vec4(glm::vec3(farPoint(vertex)), 1.0f);
  }

private:
  glm::dvec3 farPoint(const glm::vec3& vertex) const
  {
    const glm::dvec3 p(vertex);
    return light_.directional ? p + finiteScale_ * light_.direction : light_.position + finiteScale_ * (p - light_.position);
  }

  VolumeLight light_;
  VolumeExtrusion extrusion_;
  double finiteScale_;
};

// The finite extrusion's scale: K (directional, x + K d) or lambda (point, L + lambda (x - L)) such that the
// cut lies beyond every point of `bounds` on every ray through a light-oriented caster triangle.
//  - Directional: a receiver P behind caster point y is P = y + t d with t <= the bounds' diagonal.
//  - Point: P = L + mu (y - L) with |y - L| >= h, the distance from L to the triangle's plane, so
//    mu <= max |P - L| / min h.
// Twice those bounds leaves the cut well outside.
double finiteExtrusionScale(const std::vector<WeldedMesh>& casters, const VolumeLight& light, const Bounds& bounds)
{
  const double diagonal = bounds.empty() ? 0.0 : glm::length(bounds.max - bounds.min);
  if (light.directional)
  {
    return std::max(2.0 * diagonal, 1.0);
  }
  double farthest = 0.0;
  for (int corner = 0; corner < 8 && !bounds.empty(); ++corner)
  {
    const glm::dvec3 p((corner & 1) ? bounds.max.x : bounds.min.x, (corner & 2) ? bounds.max.y : bounds.min.y,
      (corner & 4) ? bounds.max.z : bounds.min.z);
    farthest = std::max(farthest, glm::length(p - light.position));
  }
  double nearestPlane = HUGE_VAL;
  for (const WeldedMesh& caster : casters)
  {
    for (const auto& corners : caster.triangles)
    {
      const glm::dvec3 a(caster.positions[corners[0]]);
      const glm::dvec3 b(caster.positions[corners[1]]);
      const glm::dvec3 c(caster.positions[corners[2]]);
      if (lightOrientation(a, b, c, light) == 0)
      {
        continue;
      }
      const glm::dvec3 normal = glm::normalize(glm::cross(b - a, c - a));
      nearestPlane = std::min(nearestPlane, std::abs(glm::dot(normal, light.position - a)));
    }
  }
  if (!(nearestPlane < HUGE_VAL))
  {
    return 2.0; // no volume at all
  }
  return std::max(2.0 * farthest / nearestPlane, 2.0);
}

void appendTriangle(
  ShadowVolumeGeometry& geometry, const glm::vec4& a, const glm::vec4& b, const glm::vec4& c, const glm::vec4& plane)
{
  geometry.vertices.insert(geometry.vertices.end(), { a, b, c });
  geometry.planes.push_back(plane);
}

} // namespace

ShadowVolumeGeometry buildShadowVolumes(const std::vector<WeldedMesh>& casters, const VolumeLight& light,
  VolumeExtrusion extrusion, const Bounds& sceneBounds)
{
  const double finiteScale =
    extrusion == VolumeExtrusion::Finite ? finiteExtrusionScale(casters, light, sceneBounds) : 0.0;
  const Extruder extruder(light, extrusion, finiteScale);
  const bool drawFarCaps = !(light.directional && extrusion == VolumeExtrusion::ToInfinity);

  ShadowVolumeGeometry geometry;
  ShadowVolumeStatistics& statistics = geometry.statistics;
  std::vector<int> orientation;
  for (const WeldedMesh& caster : casters)
  {
    ++statistics.casterObjects;
    statistics.casterTriangles += caster.triangles.size();
    statistics.collapsedTriangles += caster.collapsedTriangles;
    statistics.edges += caster.edges.size();
    statistics.boundaryEdges += caster.boundaryEdgeCount();
    statistics.nonManifoldEdges += caster.nonManifoldEdgeCount();
    statistics.inconsistentEdges += caster.inconsistentEdgeCount();

    // Rule 1 and 3: orientation toward the light; caps of every light-oriented triangle.
    orientation.assign(caster.triangles.size(), 0);
    for (std::size_t triangle = 0; triangle < caster.triangles.size(); ++triangle)
    {
      const auto& corners = caster.triangles[triangle];
      const glm::vec3& a = caster.positions[corners[0]];
      glm::vec3 b = caster.positions[corners[1]];
      glm::vec3 c = caster.positions[corners[2]];
      orientation[triangle] = lightOrientation(glm::dvec3(a), glm::dvec3(b), glm::dvec3(c), light);
      if (orientation[triangle] == 0)
      {
        ++statistics.edgeOnTriangles;
        continue;
      }
      if (orientation[triangle] < 0)
      {
        ++statistics.flippedTriangles;
        std::swap(b, c);
      }
      // Near cap: the light-oriented triangle, whose outward side (the volume's) faces the light.
      appendTriangle(geometry, glm::vec4(a, 1.0f), glm::vec4(b, 1.0f), glm::vec4(c, 1.0f),
        planeThrough(glm::dvec3(a), glm::dvec3(b), glm::dvec3(c)));
      ++statistics.nearCaps;
      if (drawFarCaps)
      {
        // Far cap: the same triangle away from the light, wound the other way (outward = away).
        appendTriangle(geometry, extruder.far(a), extruder.far(c), extruder.far(b), extruder.farCapPlane(a, c, b));
        ++statistics.farCaps;
      }
    }

    // Rule 2: per-edge multiplicity, |m| side quads.
    for (const WeldedEdge& edge : caster.edges)
    {
      int multiplicity = 0;
      for (std::uint32_t use = edge.firstUse; use < edge.firstUse + edge.useCount; ++use)
      {
        const EdgeUse& edgeUse = caster.edgeUses[use];
        multiplicity += orientation[edgeUse.triangle] * (edgeUse.forward ? 1 : -1);
      }
      if (multiplicity == 0)
      {
        continue;
      }
      // The light-oriented triangles run from -> to; the side quad (to, from, from', to') then has its
      // outward normal pointing away from those triangles' interiors.
      const glm::vec3& from = caster.positions[multiplicity > 0 ? edge.v0 : edge.v1];
      const glm::vec3& to = caster.positions[multiplicity > 0 ? edge.v1 : edge.v0];
      const int copies = std::abs(multiplicity);
      const glm::vec4 plane = extruder.sidePlane(from, to);
      for (int copy = 0; copy < copies; ++copy)
      {
        appendTriangle(geometry, glm::vec4(to, 1.0f), glm::vec4(from, 1.0f), extruder.far(from), plane);
        appendTriangle(geometry, glm::vec4(to, 1.0f), extruder.far(from), extruder.far(to), plane);
      }
      SilhouetteEdge silhouette;
      silhouette.objectIndex = caster.objectIndex;
      silhouette.from = from;
      silhouette.to = to;
      silhouette.multiplicity = copies;
      silhouette.incidentTriangles = edge.useCount;
      geometry.silhouettes.push_back(silhouette);
      ++statistics.silhouetteEdges;
      statistics.sideQuads += static_cast<std::size_t>(copies);
    }
  }
  SL_CHECK(geometry.vertices.size() == 3 * statistics.volumeTriangles());
  SL_CHECK(geometry.planes.size() == statistics.volumeTriangles());
  return geometry;
}

} // namespace sl
