#include "scene/Scene.h"

#include <glm/gtc/constants.hpp>

namespace sl
{

namespace
{

void extendByObject(Bounds& bounds, const SceneObject& object)
{
  for (const glm::vec3& position : object.mesh.positions)
    bounds.extend(glm::dvec3(position));
}

Bounds boundsOf(const std::vector<SceneObject>& objects, bool castersOnly)
{
  Bounds bounds;
  for (const SceneObject& object : objects)
  {
    if (!castersOnly || object.castShadows)
      extendByObject(bounds, object);
  }
  return bounds;
}

} // namespace

double Light::area() const
{
  if (type != LightType::Area)
    return 0.0; // point, spot and directional lights are ideal: no extent
  if (shape == LightShape::Square)
    return size * size;
  const double radius = 0.5 * size; // `size` is the disk's diameter
  return glm::pi<double>() * radius * radius;
}

Bounds Scene::bounds() const
{
  return boundsOf(objects, false);
}

std::vector<Bounds> Scene::objectBounds() const
{
  std::vector<Bounds> bounds(objects.size());
  for (std::size_t i = 0; i < objects.size(); ++i)
    extendByObject(bounds[i], objects[i]);
  return bounds;
}

Bounds Scene::casterBounds() const
{
  return boundsOf(objects, true);
}

const char* lightTypeName(LightType type)
{
  switch (type)
  {
    case LightType::Area: return "area";
    case LightType::Point: return "point";
    case LightType::Directional: return "directional";
    case LightType::Spot: return "spot";
  }
  return "unknown";
}

const char* lightShapeName(LightShape shape)
{
  return shape == LightShape::Disk ? "disk" : "square";
}

} // namespace sl
