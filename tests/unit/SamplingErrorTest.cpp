// The shadow map's sampling error per axis and Eq. 1's two factors (ShadowMapMath.h samplingError) against closed
// forms: the survey's §3 configurations where each can be written down, and bounds that hold for any light matrix.
// The general case against finite differences is TexelRatio.PerspectiveMatchesFiniteDifferencesAlsoPerAxis.
#include "lightspace/CameraView.h"
#include "lightspace/LightView.h"
#include "lightspace/ShadowMapMath.h"
#include "scene/Scene.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace sl
{
namespace
{

using test::kPi;

Bounds groundBounds()
{
  Bounds bounds;
  bounds.extend({ -50.0, -0.5, -100.0 });
  bounds.extend({ 50.0, 5.0, 100.0 });
  return bounds;
}

// An orthographic light toward `towardLight` (unit) over the origin, window [-halfWidth, halfWidth]^2 in world units,
// its view's up vector `up` (the map's t axis follows it).
LightView orthographicLight(const glm::dvec3& towardLight, const glm::dvec3& up, double halfWidth, int resolution)
{
  LightView view;
  view.projection = LightProjection::Orthographic;
  view.eyeWs = 50.0 * towardLight;
  view.viewFromWorld = glm::lookAt(view.eyeWs, glm::dvec3(0.0), up);
  view.window = { -halfWidth, halfWidth, -halfWidth, halfWidth };
  view.nearDepth = 1.0;
  view.farDepth = 100.0;
  view.resolution = resolution;
  view.clipFromView = glm::ortho(-halfWidth, halfWidth, -halfWidth, halfWidth, 1.0, 100.0);
  view.clipFromWorld = view.clipFromView * view.viewFromWorld;
  return view;
}

// Where the camera ray through pixel (x, y) meets the plane through the origin with normal `normal`.
glm::dvec3 hitOnPlane(const CameraView& camera, double x, double y, const glm::dvec3& normal)
{
  const glm::dvec3 nearPoint = unprojectPixel(camera, x, y, -1.0);
  const glm::dvec3 ray = unprojectPixel(camera, x, y, 1.0) - nearPoint;
  return nearPoint + (-glm::dot(normal, nearPoint) / glm::dot(normal, ray)) * ray;
}

TEST(SamplingError, TiltedLightStretchesOnlyTheAxisInItsPlane)
{
  // Orthographic camera straight down (0.04 world units per pixel) and a light tilted by theta toward +z with its t
  // axis in the tilt's plane: a t-texel (0.02 across the light ray) lies 0.02 / cos(theta) long on the ground, the
  // s axis is untouched. Eq. 1: perspective 0.02 / 0.04, projection cos(0) / cos(theta), their product t's error.
  Camera camera;
  camera.projection = Projection::Orthographic;
  camera.position = { 0.0, 5.0, 0.0 };
  camera.focalPoint = { 0.0, 0.0, 0.0 };
  camera.viewUp = { 0.0, 0.0, -1.0 };
  camera.parallelScale = 2.0;
  const CameraView view = makeCameraView(camera, groundBounds(), { 100, 100 });
  for (const double thetaDeg : { 0.0, 30.0, 60.0, 75.0 })
  {
    const double theta = thetaDeg * kPi / 180.0;
    const glm::dvec3 towardLight(0.0, std::cos(theta), std::sin(theta));
    const LightView light = orthographicLight(towardLight, { 0.0, 0.0, -1.0 }, 1.0, 100);
    const SamplingError error = samplingError(view, light, 50.5, 50.5, { 0.0, 0.0, 0.0 }, { 0.0, 1.0, 0.0 });
    EXPECT_NEAR(error.texelRatioS, 0.5, 1e-9) << thetaDeg;
    EXPECT_NEAR(error.texelRatioT, 0.5 / std::cos(theta), 1e-9) << thetaDeg;
    EXPECT_NEAR(error.perspectiveFactor, 0.5, 1e-9) << thetaDeg;
    EXPECT_NEAR(error.projectionFactor, 1.0 / std::cos(theta), 1e-9) << thetaDeg;
    EXPECT_NEAR(error.texelRatio, std::max(error.texelRatioS, error.texelRatioT), 1e-9) << thetaDeg;
  }
}

TEST(SamplingError, SurveyFigure3ViewerOverAGroundUnderAnOverheadLight)
{
  // The survey's §3 analysis: an overhead directional light, a uniform map whose t axis runs along the view
  // direction, a perspective viewer at eye height looking down the ground. On the view axis dp/ds =
  // (1/z)(dz/ds)(cos alpha / cos beta) (Eq. 1): dz/ds the texel width 2 h / N, 1/z the pixel's angle
  // 2 tan(fov / 2) / H times the distance z, cos beta = 1 (overhead), cos alpha the ground's cosine to the eye.
  Camera camera;
  camera.position = { 0.0, 1.7, 0.0 };
  const double tilt = 10.0 * kPi / 180.0; // looking down 10 degrees
  camera.focalPoint = { 0.0, 1.7 - std::sin(tilt), -std::cos(tilt) };
  camera.viewAngleDeg = 40.0;
  const int width = 160;
  const int height = 120;
  const CameraView view = makeCameraView(camera, groundBounds(), { width, height });
  const double halfWidth = 40.0;
  const int resolution = 1024;
  const LightView light = orthographicLight({ 0.0, 1.0, 0.0 }, { 0.0, 0.0, -1.0 }, halfWidth, resolution);
  const glm::dvec3 up(0.0, 1.0, 0.0);
  const glm::dvec3 pWs = hitOnPlane(view, 0.5 * width, 0.5 * height, up);
  const double z = glm::length(pWs - camera.position);
  const double pixelAngle = 2.0 * std::tan(0.5 * camera.viewAngleDeg * kPi / 180.0) / height;
  const double texelWidth = 2.0 * halfWidth / resolution;
  const double cosAlpha = std::sin(tilt);

  const SamplingError error = samplingError(view, light, 0.5 * width, 0.5 * height, pWs, up);
  EXPECT_NEAR(error.perspectiveFactor, texelWidth / (z * pixelAngle), 1e-9 * error.perspectiveFactor);
  EXPECT_NEAR(error.projectionFactor, cosAlpha, 1e-12);
  EXPECT_NEAR(error.texelRatioT, error.perspectiveFactor * error.projectionFactor, 1e-9 * error.texelRatioT);
  // Across the view (the s axis) the ground is not foreshortened: no projection factor there.
  EXPECT_NEAR(error.texelRatioS, texelWidth / (z * pixelAngle), 1e-9 * error.texelRatioS);

  // Perspective aliasing (Fig. 5): nearer ground, larger error, about in proportion to 1/z along the central column
  // (off the axis the pixel's footprint across the ray shrinks by a power of the cosine: within 10 % here), and
  // with the steeper view the projection factor grows too.
  const glm::dvec3 nearer = hitOnPlane(view, 0.5 * width, 0.1 * height, up);
  const SamplingError nearError = samplingError(view, light, 0.5 * width, 0.1 * height, nearer, up);
  const double distanceRatio = z / glm::length(nearer - camera.position);
  EXPECT_NEAR(nearError.perspectiveFactor / error.perspectiveFactor, distanceRatio, 0.1 * distanceRatio);
  EXPECT_GT(nearError.projectionFactor, 2.0 * error.projectionFactor);
  EXPECT_GT(nearError.texelRatioT, 4.0 * error.texelRatioT);
}

TEST(SamplingError, TheMostStretchedDirectionBoundsBothAxesForRandomViews)
{
  // sigma_max(J^-1) is at least each column's length and at most their root sum of squares; turning the light's
  // view a quarter turn about its axis swaps s and t. Random perspective lights over random planes.
  std::mt19937 generator(29);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Camera camera;
  camera.position = { 3.0, 2.5, 5.0 };
  camera.focalPoint = { 0.0, 0.0, 0.0 };
  camera.viewAngleDeg = 35.0;
  const CameraView view = makeCameraView(camera, groundBounds(), { 128, 96 });
  int checked = 0;
  for (int trial = 0; trial < 200; ++trial)
  {
    const glm::dvec3 normal = glm::normalize(glm::dvec3(0.4 * unit(generator), 1.0, 0.4 * unit(generator)));
    const glm::dvec3 eye(3.0 * unit(generator), 4.0 + unit(generator), 3.0 * unit(generator));
    const glm::dvec3 up = glm::normalize(glm::dvec3(unit(generator), 0.1 * unit(generator), unit(generator)));
    if (glm::length(glm::cross(glm::normalize(-eye), up)) < 0.2)
    {
      continue;
    }
    const glm::dvec2 pixel(64.0 + 60.0 * unit(generator), 48.0 + 45.0 * unit(generator));
    const glm::dvec3 pWs = hitOnPlane(view, pixel.x, pixel.y, normal);
    LightView light;
    light.projection = LightProjection::Perspective;
    light.eyeWs = eye;
    light.viewFromWorld = glm::lookAt(eye, glm::dvec3(0.0), up);
    light.resolution = 256 << (trial % 3);
    light.clipFromView = glm::frustum(-0.5, 0.5, -0.5, 0.5, 1.0, 20.0);
    light.clipFromWorld = light.clipFromView * light.viewFromWorld;
    if (glm::dot(normal, glm::normalize(eye - pWs)) < 0.05 || glm::dot(normal, glm::normalize(camera.position - pWs)) < 0.05)
    {
      continue;
    }
    const SamplingError error = samplingError(view, light, pixel.x, pixel.y, pWs, normal);
    EXPECT_GE(error.texelRatio, std::max(error.texelRatioS, error.texelRatioT) * (1.0 - 1e-9)) << trial;
    EXPECT_LE(error.texelRatio, std::hypot(error.texelRatioS, error.texelRatioT) * (1.0 + 1e-9)) << trial;
    EXPECT_TRUE(std::isfinite(error.perspectiveFactor) && error.perspectiveFactor > 0.0) << trial;

    LightView turned = light;
    turned.viewFromWorld = glm::rotate(glm::dmat4(1.0), kPi / 2.0, glm::dvec3(0.0, 0.0, 1.0)) * light.viewFromWorld;
    turned.clipFromWorld = turned.clipFromView * turned.viewFromWorld;
    const SamplingError turnedError = samplingError(view, turned, pixel.x, pixel.y, pWs, normal);
    EXPECT_NEAR(turnedError.texelRatioS, error.texelRatioT, 1e-9 * error.texelRatioT) << trial;
    EXPECT_NEAR(turnedError.texelRatioT, error.texelRatioS, 1e-9 * error.texelRatioS) << trial;
    EXPECT_NEAR(turnedError.texelRatio, error.texelRatio, 1e-9 * error.texelRatio) << trial;
    ++checked;
  }
  EXPECT_GT(checked, 100);
}

TEST(SamplingError, GrazingViewOrLightGivesZerosNotInfinities)
{
  Camera camera;
  camera.position = { 0.0, 1.0, 5.0 };
  camera.focalPoint = { 0.0, 1.0, 0.0 }; // looking horizontally: its central row grazes the ground
  camera.viewAngleDeg = 40.0;
  const CameraView view = makeCameraView(camera, groundBounds(), { 64, 64 });
  const LightView overhead = orthographicLight({ 0.0, 1.0, 0.0 }, { 0.0, 0.0, -1.0 }, 10.0, 256);
  const SamplingError grazingEye = samplingError(view, overhead, 32.0, 32.0, { 0.0, 0.0, -5.0 }, { 0.0, 1.0, 0.0 });
  EXPECT_EQ(grazingEye.texelRatioT, 0.0);
  EXPECT_EQ(grazingEye.perspectiveFactor, 0.0);
  const LightView sideways = orthographicLight({ 1.0, 0.0, 0.0 }, { 0.0, 1.0, 0.0 }, 10.0, 256);
  const SamplingError grazingLight = samplingError(view, sideways, 32.0, 10.0, { 0.0, 0.0, -1.0 }, { 0.0, 1.0, 0.0 });
  EXPECT_EQ(grazingLight.projectionFactor, 0.0);
  EXPECT_EQ(grazingLight.texelRatioS, 0.0);
}

} // namespace
} // namespace sl
