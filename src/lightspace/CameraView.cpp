#include "lightspace/CameraView.h"

#include "core/Error.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace sl
{

namespace
{

// The smallest and largest depth along `forward` of a box's corners, seen from `eye`.
glm::dvec2 depthRange(const Bounds& bounds, const glm::dvec3& eye, const glm::dvec3& forward)
{
  glm::dvec2 range(1e300, -1e300);
  for (int corner = 0; corner < 8; ++corner)
  {
    const glm::dvec3 p((corner & 1) ? bounds.max.x : bounds.min.x, (corner & 2) ? bounds.max.y : bounds.min.y,
      (corner & 4) ? bounds.max.z : bounds.min.z);
    const double depth = glm::dot(p - eye, forward);
    range = { std::min(range.x, depth), std::max(range.y, depth) };
  }
  return range;
}

// The terms that follow from viewFromWorld and clipFromView: the combined matrices and the camera rays.
void finishCameraView(CameraView& view)
{
  view.clipFromWorld = view.clipFromView * view.viewFromWorld;
  view.worldFromClip = glm::inverse(view.clipFromWorld);
  view.nearOrigin = unprojectPixel(view, 0.0, 0.0, -1.0);
  view.nearStepX = unprojectPixel(view, 1.0, 0.0, -1.0) - view.nearOrigin;
  view.nearStepY = unprojectPixel(view, 0.0, 1.0, -1.0) - view.nearOrigin;
  view.rayOrigin = unprojectPixel(view, 0.0, 0.0, 1.0) - view.nearOrigin;
  view.rayStepX = unprojectPixel(view, 1.0, 0.0, 1.0) - view.nearOrigin - view.nearStepX - view.rayOrigin;
  view.rayStepY = unprojectPixel(view, 0.0, 1.0, 1.0) - view.nearOrigin - view.nearStepY - view.rayOrigin;
}

} // namespace

CameraView makeCameraView(const Camera& camera, const Bounds& sceneBounds, glm::ivec2 resolution,
  const std::vector<Bounds>& objectBounds)
{
  CameraView view;
  view.resolution = resolution;
  view.viewFromWorld = glm::lookAt(camera.position, camera.focalPoint, camera.viewUp);
  const glm::dvec3 forward = glm::normalize(camera.focalPoint - camera.position);

  // Depth range: the scene's bounding box corners along the view axis.
  const glm::dvec2 sceneDepths = depthRange(sceneBounds, camera.position, forward);
  const double nearest = sceneDepths.x;
  const double farthest = sceneDepths.y;
  const double aspect = static_cast<double>(resolution.x) / static_cast<double>(resolution.y);
  if (camera.projection == Projection::Perspective)
  {
    view.farDepth = std::max(farthest * 1.01, 1e-3);
    view.nearDepth = std::max(nearest * 0.99, view.farDepth * kMinNearOverFar);
    for (std::size_t i = 0; i < objectBounds.size(); ++i)
    {
      const glm::dvec2 objectDepths = depthRange(objectBounds[i], camera.position, forward);
      if (objectDepths.y > 0.0 && objectDepths.y < view.nearDepth)
      {
        view.nearDepth = std::max(objectDepths.x * 0.99, view.farDepth * kMinNearOverFarForObjects);
      }
    }
    for (std::size_t i = 0; i < objectBounds.size(); ++i)
    {
      const glm::dvec2 objectDepths = depthRange(objectBounds[i], camera.position, forward);
      if (objectDepths.y > 0.0 && objectDepths.y < view.nearDepth)
      {
        throw InputError(format("objects[", i, "]: lies within ", objectDepths.y, " of the camera while the scene reaches ",
          farthest, " away; one depth buffer resolves at most a ratio of ", 1.0 / kMinNearOverFarForObjects,
          " between them (move the camera or shrink the scene)"));
      }
    }
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
  finishCameraView(view);
  return view;
}

CameraView offsetCameraView(const CameraView& view, glm::dvec2 pixelOffset)
{
  CameraView offset = view;
  // Window x = (ndc x + 1) W / 2, so moving the scene by -2 offset / W in NDC brings window position x + 0.5 + offset
  // to the centre x + 0.5. A clip-space translation scales with w, as the perspective divide requires.
  glm::dmat4 shift(1.0);
  shift[3][0] = -2.0 * pixelOffset.x / view.resolution.x;
  shift[3][1] = -2.0 * pixelOffset.y / view.resolution.y;
  offset.clipFromView = shift * view.clipFromView;
  finishCameraView(offset);
  return offset;
}

glm::dvec3 unprojectPixel(const CameraView& view, double x, double y, double ndcZ)
{
  const glm::dvec4 ndc(2.0 * x / view.resolution.x - 1.0, 2.0 * y / view.resolution.y - 1.0, ndcZ, 1.0);
  const glm::dvec4 pWs = view.worldFromClip * ndc;
  return glm::dvec3(pWs) / pWs.w;
}

} // namespace sl
