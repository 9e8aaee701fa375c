#include "lightspace/CameraView.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace sl
{

CameraView makeCameraView(const Camera& camera, const Bounds& sceneBounds, glm::ivec2 resolution)
{
  CameraView view;
  view.resolution = resolution;
  view.viewFromWorld = glm::lookAt(camera.position, camera.focalPoint, camera.viewUp);
  const glm::dvec3 forward = glm::normalize(camera.focalPoint - camera.position);

  // Depth range: the scene's bounding box corners along the view axis.
  double nearest = 1e300;
  double farthest = -1e300;
  for (int corner = 0; corner < 8; ++corner)
  {
    const glm::dvec3 p((corner & 1) ? sceneBounds.max.x : sceneBounds.min.x,
      (corner & 2) ? sceneBounds.max.y : sceneBounds.min.y, (corner & 4) ? sceneBounds.max.z : sceneBounds.min.z);
    const double depth = glm::dot(p - camera.position, forward);
    nearest = std::min(nearest, depth);
    farthest = std::max(farthest, depth);
  }
  const double aspect = static_cast<double>(resolution.x) / static_cast<double>(resolution.y);
  if (camera.projection == Projection::Perspective)
  {
    view.farDepth = std::max(farthest * 1.01, 1e-3);
    view.nearDepth = std::max(nearest * 0.99, view.farDepth * 1e-4);
    view.clipFromView = glm::perspective(glm::radians(camera.viewAngleDeg), aspect, view.nearDepth, view.farDepth);
  }
  else
  {
    const double margin = 0.01 * std::max(1e-3, farthest - nearest);
    view.nearDepth = nearest - margin;
    view.farDepth = farthest + margin;
    const double halfHeight = camera.parallelScale;
    view.clipFromView = glm::ortho(-halfHeight * aspect, halfHeight * aspect, -halfHeight, halfHeight,
      view.nearDepth, view.farDepth);
  }
  view.clipFromWorld = view.clipFromView * view.viewFromWorld;
  view.worldFromClip = glm::inverse(view.clipFromWorld);
  view.nearOrigin = unprojectPixel(view, 0.0, 0.0, -1.0);
  view.nearStepX = unprojectPixel(view, 1.0, 0.0, -1.0) - view.nearOrigin;
  view.nearStepY = unprojectPixel(view, 0.0, 1.0, -1.0) - view.nearOrigin;
  view.rayOrigin = unprojectPixel(view, 0.0, 0.0, 1.0) - view.nearOrigin;
  view.rayStepX = unprojectPixel(view, 1.0, 0.0, 1.0) - view.nearOrigin - view.nearStepX - view.rayOrigin;
  view.rayStepY = unprojectPixel(view, 0.0, 1.0, 1.0) - view.nearOrigin - view.nearStepY - view.rayOrigin;
  return view;
}

glm::dvec3 unprojectPixel(const CameraView& view, double x, double y, double ndcZ)
{
  const glm::dvec4 ndc(2.0 * x / view.resolution.x - 1.0, 2.0 * y / view.resolution.y - 1.0, ndcZ, 1.0);
  const glm::dvec4 pWs = view.worldFromClip * ndc;
  return glm::dvec3(pWs) / pWs.w;
}

} // namespace sl
