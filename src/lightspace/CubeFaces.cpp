#include "lightspace/CubeFaces.h"

#include "core/Error.h"
#include "lightspace/PartitionViews.h"

#include <algorithm>
#include <cmath>

namespace sl
{

glm::dvec3 cubeFaceAxis(int face)
{
  SL_CHECK(face >= 0 && face < kCubeFaceCount);
  glm::dvec3 axis(0.0);
  axis[face / 2] = face % 2 == 0 ? 1.0 : -1.0;
  return axis;
}

const char* cubeFaceName(int face)
{
  static const char* const names[kCubeFaceCount] = { "+x", "-x", "+y", "-y", "+z", "-z" };
  SL_CHECK(face >= 0 && face < kCubeFaceCount);
  return names[face];
}

const char* cubeFaceTag(int face)
{
  static const char* const tags[kCubeFaceCount] = { "px", "nx", "py", "ny", "pz", "nz" };
  SL_CHECK(face >= 0 && face < kCubeFaceCount);
  return tags[face];
}

int dominantCubeFace(const glm::dvec3& direction)
{
  const glm::dvec3 size = glm::abs(direction);
  if (size.x >= size.y && size.x >= size.z)
  {
    return direction.x >= 0.0 ? 0 : 1;
  }
  if (size.y >= size.z)
  {
    return direction.y >= 0.0 ? 2 : 3;
  }
  return direction.z >= 0.0 ? 4 : 5;
}

std::vector<glm::dvec4> cubeFaceOwnerPlanes(const glm::dvec3& centerWs, int face)
{
  const glm::dvec3 axis = cubeFaceAxis(face);
  std::vector<glm::dvec4> planes;
  for (int other = 0; other < 3; ++other)
  {
    if (other == face / 2)
    {
      continue;
    }
    for (const double sign : { 1.0, -1.0 })
    {
      // dot(axis, d) - sign d_other >= 0 with d = p - centre.
      glm::dvec3 normal = axis;
      normal[other] -= sign;
      planes.push_back(glm::dvec4(normal, -glm::dot(normal, centerWs)));
    }
  }
  return planes;
}

void requireCubeMapLight(CubeMapMode mode, LightType lightType)
{
  if (mode == CubeMapMode::On && lightType != LightType::Point)
  {
    throw InputError(format("--set cube_map=on: cube shadow maps are for point lights (a ", lightTypeName(lightType),
      " light's receivers lie on one side of it); use cube_map=auto or off"));
  }
}

namespace
{

int viewOfFace(const PartitionSet& faces, int face)
{
  const auto found = std::find(faces.viewFaces.begin(), faces.viewFaces.end(), face);
  return found == faces.viewFaces.end() ? -1 : static_cast<int>(found - faces.viewFaces.begin());
}

} // namespace

ViewSelection selectCubeFace(const PartitionSet& faces, const glm::dvec3& pWs)
{
  SL_CHECK(faces.kind == PartitionKind::CubeFaces);
  const int view = std::max(0, viewOfFace(faces, dominantCubeFace(pWs - faces.lightCenterWs)));
  return { view, view, 1.0 };
}

int cubeFaceOf(const PartitionSet& faces, const glm::dvec3& pWs)
{
  const int face = dominantCubeFace(pWs - faces.lightCenterWs);
  return viewOfFace(faces, face) >= 0 ? face : -1;
}

PartitionSet fitCubeFaces(
  const Light& light, const Scene& scene, ReceiverSource& receivers, const FocusSettings& focus)
{
  SL_CHECK_MSG(light.type == LightType::Point, "cube faces need a point light");
  PartitionSet faces;
  faces.kind = PartitionKind::CubeFaces;
  faces.marginTexels = focus.marginTexels;
  faces.lightCenterWs = light.center;
  LightView firstFace;
  for (int face = 0; face < kCubeFaceCount; ++face)
  {
    FocusSettings settings = focus;
    settings.ownerPlanes = cubeFaceOwnerPlanes(light.center, face);
    settings.perspectiveAxis = cubeFaceAxis(face);
    const LightView view = fitLightView(light, scene, receivers, settings);
    if (face == 0)
    {
      firstFace = view;
    }
    if (view.receiverSampleCount == 0)
    {
      continue; // nothing this face could shadow: no map
    }
    faces.views.push_back(view);
    faces.ownerPlanes.push_back(settings.ownerPlanes);
    faces.viewFaces.push_back(face);
  }
  if (faces.views.empty())
  {
    faces.views.push_back(firstFace);
    faces.ownerPlanes.push_back(cubeFaceOwnerPlanes(light.center, 0));
    faces.viewFaces.push_back(0);
  }
  return faces;
}

} // namespace sl
