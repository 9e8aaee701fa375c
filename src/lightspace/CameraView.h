// The camera's matrices, with near/far fitted to the scene bounds so depth precision is not wasted.
#pragma once

#include "scene/Scene.h"

#include <glm/glm.hpp>

#include <vector>

namespace sl
{

struct CameraView
{
  glm::dmat4 viewFromWorld{ 1.0 };
  glm::dmat4 clipFromView{ 1.0 };
  glm::dmat4 clipFromWorld{ 1.0 };
  glm::dmat4 worldFromClip{ 1.0 };
  glm::ivec2 resolution{ 0 };
  double nearDepth = 0.1;
  double farDepth = 100.0;

  // The camera ray through pixel position (x, y) (pixel centres at +0.5) is N + s R with
  //   N = nearOrigin + x nearStepX + y nearStepY   (point on the near plane)
  //   R = rayOrigin + x rayStepX + y rayStepY      (near-plane point to far-plane point)
  // Both are affine in (x, y) for perspective and orthographic cameras. Precomputed in double so the
  // shaders never difference nearby unprojected points in float.
  glm::dvec3 nearOrigin{ 0.0 }, nearStepX{ 0.0 }, nearStepY{ 0.0 };
  glm::dvec3 rayOrigin{ 0.0 }, rayStepX{ 0.0 }, rayStepY{ 0.0 };
};

// `resolution` overrides the scene camera's (the CLI's --resolution); the aspect ratio follows it and
// view_angle stays the vertical field of view, so non-square images are never stretched.
// A perspective camera's near plane is the scene box's nearest depth, at least kMinNearOverFar of the far
// depth (the float depth buffer's working range). When that would cut away an object wholly in front of the
// camera (one vast, distant object stretches the scene box: probe case O09), the near plane moves in to that
// object, down to kMinNearOverFarForObjects; an object nearer still is an InputError naming objects[i], never
// a silently empty image. `objectBounds` holds each object's bounds, in the scene's order.
constexpr double kMinNearOverFar = 1e-4;
constexpr double kMinNearOverFarForObjects = 1e-7;
CameraView makeCameraView(const Camera& camera, const Bounds& sceneBounds, glm::ivec2 resolution,
  const std::vector<Bounds>& objectBounds = {});

// `view` with its projection shifted so that pixel (x, y) sees window position (x + 0.5 + pixelOffset.x,
// y + 0.5 + pixelOffset.y) (a translation in clip space; the camera-ray terms follow).
CameraView offsetCameraView(const CameraView& view, glm::dvec2 pixelOffset);

// World-space point on the near (ndcZ = -1) or far (ndcZ = 1) plane under pixel position (x, y) in
// pixels (pixel centres at +0.5).
glm::dvec3 unprojectPixel(const CameraView& view, double x, double y, double ndcZ);

} // namespace sl
