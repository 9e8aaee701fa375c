#include "support/RayCaster.h"

#include "lightspace/LightView.h"
#include "scene/AlphaTexture.h"
#include "scene/RayTriangle.h"

#include <optional>

namespace sl::test
{

RayCaster::RayCaster(const Scene& scene)
{
  for (const SceneObject& object : scene.objects)
  {
    if (!object.castShadows)
    {
      continue;
    }
    const TriangleMesh& mesh = object.mesh;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
    {
      const auto index = [&](int k) { return mesh.indices[3 * t + k]; };
      Triangle triangle;
      const glm::dvec3 a(mesh.positions[index(0)]);
      triangle.a = a;
      triangle.edge1 = glm::dvec3(mesh.positions[index(1)]) - a;
      triangle.edge2 = glm::dvec3(mesh.positions[index(2)]) - a;
      if (!mesh.uvs.empty())
      {
        triangle.uvA = mesh.uvs[index(0)];
        triangle.uvB = mesh.uvs[index(1)];
        triangle.uvC = mesh.uvs[index(2)];
      }
      triangle.alpha = object.hasAlphaTexture ? &object.alphaTexture : nullptr;
      triangles_.push_back(triangle);
    }
  }
}

bool RayCaster::occluded(const glm::dvec3& origin, const glm::dvec3& direction, double tMin, double tMax) const
{
  for (const Triangle& triangle : triangles_)
  {
    const std::optional<RayTriangleHit> hit =
      intersectRayTriangle(origin, direction, triangle.a, triangle.edge1, triangle.edge2, 1e-15);
    if (!hit || hit->t <= tMin || hit->t >= tMax)
    {
      continue;
    }
    if (triangle.alpha)
    {
      const glm::dvec2 uv = (1.0 - hit->u - hit->v) * triangle.uvA + hit->u * triangle.uvB + hit->v * triangle.uvC;
      if (alphaHoleAt(triangle.alpha->alpha, uv))
      {
        continue; // a hole: the ray passes
      }
    }
    return true;
  }
  return false;
}

double RayCaster::pointVisibility(const Light& light, const glm::dvec3& pWs, const glm::dvec3& nWs, double offset) const
{
  if (!lightCanReach(light, pWs, nWs))
  {
    return 0.0;
  }
  const glm::dvec3 origin = pWs + offset * nWs;
  if (light.type == LightType::Directional)
  {
    return occluded(origin, -light.direction, 0.0, 1e30) ? 0.0 : 1.0;
  }
  const glm::dvec3 toLight = light.center - origin;
  const double distance = glm::length(toLight);
  return occluded(origin, toLight / distance, 0.0, distance) ? 0.0 : 1.0;
}

ImageF exactPointVisibility(const FrameResult& frame, const Scene& scene, const RayCaster& rays)
{
  const ImageF& position = frame.find("position")->image;
  const ImageF& normal = frame.find("normal")->image;
  const ImageF& coverage = frame.find("coverage")->image;
  const ImageF& receives = frame.find("receives_shadows")->image;
  const Light& light = scene.lights.front();
  ImageF exact(position.width, position.height, 1, -1.0f);
  for (int y = 0; y < position.height; ++y)
  {
    for (int x = 0; x < position.width; ++x)
    {
      const glm::dvec3 pWs(position.at(x, y, 0), position.at(x, y, 1), position.at(x, y, 2));
      const glm::dvec3 nWs(normal.at(x, y, 0), normal.at(x, y, 1), normal.at(x, y, 2));
      if (coverage.at(x, y) > 0.5f && receives.at(x, y) > 0.5f && lightCanReach(light, pWs, nWs))
      {
        exact.at(x, y) = static_cast<float>(rays.pointVisibility(light, pWs, nWs, 1e-4));
      }
    }
  }
  return exact;
}

} // namespace sl::test
