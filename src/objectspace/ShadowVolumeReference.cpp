#include "objectspace/ShadowVolumeReference.h"

#include "scene/RayTriangle.h"

#include <glm/gtc/constants.hpp>

#include <cmath>
#include <optional>
#include <string>

namespace sl
{

double volumeWindingNumber(const ShadowVolumeGeometry& geometry, const glm::dvec3& point)
{
  const std::vector<glm::vec4>& vertices = geometry.vertices;
  // Direction from `point` to a homogeneous vertex (x, w), w >= 0: x - w point (x itself at infinity).
  const auto seen = [&point](const glm::vec4& vertex) {
    return glm::dvec3(vertex.x, vertex.y, vertex.z) - static_cast<double>(vertex.w) * point;
  };
  double solidAngle = 0.0;
  for (std::size_t first = 0; first + 2 < vertices.size(); first += 3)
  {
    const glm::dvec3 a = seen(vertices[first]);
    const glm::dvec3 b = seen(vertices[first + 1]);
    const glm::dvec3 c = seen(vertices[first + 2]);
    const double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
    // tan(Omega / 2) = a . (b x c) / (|a||b||c| + (a.b)|c| + (a.c)|b| + (b.c)|a|)
    const double numerator = glm::dot(a, glm::cross(b, c));
    const double denominator = la * lb * lc + glm::dot(a, b) * lc + glm::dot(a, c) * lb + glm::dot(b, c) * la;
    solidAngle += 2.0 * std::atan2(numerator, denominator);
  }
  return solidAngle / (4.0 * glm::pi<double>());
}

int casterCrossings(const Scene& scene, const VolumeLight& light, const glm::dvec3& point, ProbeRecorder* recorder,
  bool opaqueOnly)
{
  // Segment point + t direction, t in (0, tMax).
  const glm::dvec3 direction = light.directional ? -light.direction : light.position - point;
  const double tMax = light.directional ? HUGE_VAL : 1.0;
  int crossings = 0;
  for (std::size_t objectIndex = 0; objectIndex < scene.objects.size(); ++objectIndex)
  {
    const SceneObject& object = scene.objects[objectIndex];
    if (!object.castShadows || (opaqueOnly && object.hasAlphaTexture))
    {
      continue;
    }
    const TriangleMesh& mesh = object.mesh;
    for (std::size_t triangle = 0; triangle < mesh.triangleCount(); ++triangle)
    {
      const glm::dvec3 a(mesh.positions[mesh.indices[3 * triangle]]);
      const glm::dvec3 edge1 = glm::dvec3(mesh.positions[mesh.indices[3 * triangle + 1]]) - a;
      const glm::dvec3 edge2 = glm::dvec3(mesh.positions[mesh.indices[3 * triangle + 2]]) - a;
      // A segment parallel to the triangle's plane (determinant 0) crosses nothing.
      const std::optional<RayTriangleHit> hit = intersectRayTriangle(point, direction, a, edge1, edge2);
      if (hit && hit->t > 0.0 && hit->t < tMax)
      {
        ++crossings;
        if (recorder)
        {
          recorder->quantity("crossing_point", point + hit->t * direction, "world units",
            "Crow 1977: the segment to the light leaves this caster triangle's shadow volume (Moller-Trumbore)");
          recorder->category("crossed_triangle", "objects[" + std::to_string(objectIndex) + "] (" + object.name +
            ") triangle " + std::to_string(triangle), "Crow 1977 (one volume per caster triangle)");
        }
      }
    }
  }
  return crossings;
}

glm::dvec3 shadowVolumeReceiverPoint(const Scene& scene, double receiverOffset, const glm::dvec3& pWs)
{
  const Camera& camera = scene.camera;
  const glm::dvec3 towardCamera = camera.projection == Projection::Perspective
    ? camera.position - pWs
    : glm::normalize(camera.position - camera.focalPoint) * scene.bounds().radius();
  return pWs + receiverOffset * towardCamera;
}

double receiverOffsetOf(const ParameterValues& values)
{
  return values.get("receiver_offset");
}

ParameterSpec receiverOffsetParameter(double defaultValue, const std::string& why)
{
  return { "receiver_offset", defaultValue, 0.0, 1e-2, "of the eye distance",
    "the visible point is taken this fraction of its distance to the eye toward the camera (orthographic: of the "
    "scene's radius)" + why };
}

} // namespace sl
