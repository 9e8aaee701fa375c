// Shadow-map math against closed forms (pbrt style): the aliasing measure of survey Eq. 2 in
// configurations where it can be written down, the bias formula, and the focused light frustum.
#include "core/Error.h"
#include "lightspace/CameraView.h"
#include "lightspace/LightView.h"
#include "lightspace/ShadowMapMath.h"
#include "scene/Scene.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cmath>

namespace sl
{
namespace
{

using test::kPi;

Camera orthographicCameraLookingDown(double parallelScale)
{
  Camera camera;
  camera.projection = Projection::Orthographic;
  camera.position = { 0.0, 5.0, 0.0 };
  camera.focalPoint = { 0.0, 0.0, 0.0 };
  camera.viewUp = { 0.0, 0.0, -1.0 };
  camera.parallelScale = parallelScale;
  return camera;
}

Bounds unitBounds()
{
  Bounds bounds;
  bounds.extend({ -2.0, -0.5, -2.0 });
  bounds.extend({ 2.0, 0.5, 2.0 });
  return bounds;
}

// An orthographic light looking at the origin from `direction` (unit, toward the light), window
// [-1, 1]^2 in world units.
LightView orthographicLight(const glm::dvec3& towardLight, int resolution)
{
  LightView view;
  view.projection = LightProjection::Orthographic;
  view.eyeWs = 10.0 * towardLight;
  view.viewFromWorld = glm::lookAt(view.eyeWs, glm::dvec3(0.0), glm::dvec3(1.0, 0.0, 0.0));
  view.window = { -1.0, 1.0, -1.0, 1.0 };
  view.nearDepth = 1.0;
  view.farDepth = 20.0;
  view.resolution = resolution;
  view.clipFromView = glm::ortho(-1.0, 1.0, -1.0, 1.0, 1.0, 20.0);
  view.clipFromWorld = view.clipFromView * view.viewFromWorld;
  return view;
}

TEST(TexelRatio, OrthographicCameraAndLightStraightDown)
{
  // Camera: 4 world units tall over 100 pixels -> 0.04 per pixel. Light: 2 units over 100 texels -> 0.02
  // per texel. One texel spans half a pixel.
  const CameraView camera = makeCameraView(orthographicCameraLookingDown(2.0), unitBounds(), { 200, 100 });
  const LightView light = orthographicLight({ 0.0, 1.0, 0.0 }, 100);
  for (const glm::dvec2 pixel : { glm::dvec2(100.5, 50.5), glm::dvec2(10.5, 90.5) })
  {
    const glm::dvec3 pWs = unprojectPixel(camera, pixel.x, pixel.y, 0.0) * glm::dvec3(1.0, 0.0, 1.0);
    EXPECT_NEAR(texelRatio(camera, light, pixel.x, pixel.y, pWs, { 0.0, 1.0, 0.0 }), 0.5, 1e-9);
  }
}

TEST(CameraView, OffsetViewShowsEachPixelTheShiftedWindowPosition)
{
  // offsetCameraView (the reference's multisample mode): pixel (x, y) of the shifted view sees what window position
  // (x + 0.5 + o.x, y + 0.5 + o.y) of the original sees, for perspective and orthographic cameras.
  Camera perspective;
  perspective.position = { 2.0, 3.0, 4.0 };
  perspective.focalPoint = { 0.0, 0.0, 0.0 };
  perspective.viewAngleDeg = 40.0;
  for (const Camera& camera : { perspective, orthographicCameraLookingDown(2.0) })
  {
    const CameraView view = makeCameraView(camera, unitBounds(), { 160, 120 });
    for (const glm::dvec2 offset : { glm::dvec2(-0.125, -0.375), glm::dvec2(0.375, 0.125), glm::dvec2(0.3, -0.2) })
    {
      const CameraView shifted = offsetCameraView(view, offset);
      for (const glm::dvec2 pixel : { glm::dvec2(0.5, 0.5), glm::dvec2(80.5, 60.5), glm::dvec2(159.5, 3.5) })
      {
        for (const double ndcZ : { -1.0, 0.0, 1.0 })
        {
          const glm::dvec3 seen = unprojectPixel(shifted, pixel.x, pixel.y, ndcZ);
          const glm::dvec3 original = unprojectPixel(view, pixel.x + offset.x, pixel.y + offset.y, ndcZ);
          EXPECT_LT(glm::length(seen - original), 1e-9 * (1.0 + glm::length(original))) << pixel.x << "," << pixel.y;
          // The camera-ray terms follow the shift (CameraRay.glsl reconstructs rays from them).
          const glm::dvec3 nearPoint = shifted.nearOrigin + pixel.x * shifted.nearStepX + pixel.y * shifted.nearStepY;
          EXPECT_LT(glm::length(nearPoint - unprojectPixel(view, pixel.x + offset.x, pixel.y + offset.y, -1.0)), 1e-9);
        }
      }
    }
  }
}

TEST(TexelRatio, TiltedLightStretchesTexelsByOneOverCosine)
{
  // Projection aliasing (survey §3.2): a light at angle theta from the normal stretches a texel's
  // footprint on the ground by 1/cos(theta) along the tilt: m = 0.02 / cos(theta) / 0.04.
  const CameraView camera = makeCameraView(orthographicCameraLookingDown(2.0), unitBounds(), { 100, 100 });
  for (const double thetaDeg : { 30.0, 60.0, 75.0 })
  {
    const double theta = thetaDeg * kPi / 180.0;
    const LightView light = orthographicLight({ 0.0, std::cos(theta), std::sin(theta) }, 100);
    const double expected = 0.02 / std::cos(theta) / 0.04;
    EXPECT_NEAR(texelRatio(camera, light, 50.5, 50.5, { 0.0, 0.0, 0.0 }, { 0.0, 1.0, 0.0 }), expected, 1e-9)
      << "theta " << thetaDeg;
  }
}

TEST(TexelRatio, PerspectiveMatchesFiniteDifferencesAlsoPerAxis)
{
  // General case: perspective camera and perspective light over a tilted plane. The reference
  // differentiates "pixel -> ray/plane hit -> texel" numerically (central differences).
  Camera camera;
  camera.position = { 2.0, 3.0, 4.0 };
  camera.focalPoint = { 0.0, 0.0, 0.0 };
  camera.viewAngleDeg = 40.0;
  const CameraView cameraView = makeCameraView(camera, unitBounds(), { 160, 120 });
  LightView light;
  light.projection = LightProjection::Perspective;
  light.eyeWs = { -1.0, 4.0, 1.0 };
  light.viewFromWorld = glm::lookAt(light.eyeWs, glm::dvec3(0.0), glm::dvec3(0.0, 0.0, -1.0));
  light.window = { -0.6, 0.5, -0.4, 0.7 };
  light.nearDepth = 1.0;
  light.farDepth = 10.0;
  light.resolution = 512;
  light.clipFromView = glm::frustum(-0.6, 0.5, -0.4, 0.7, 1.0, 10.0);
  light.clipFromWorld = light.clipFromView * light.viewFromWorld;
  const glm::dvec3 normal = glm::normalize(glm::dvec3(0.2, 1.0, -0.3));

  const auto texelAt = [&](double x, double y) {
    const glm::dvec3 nearPoint = unprojectPixel(cameraView, x, y, -1.0);
    const glm::dvec3 ray = unprojectPixel(cameraView, x, y, 1.0) - nearPoint;
    const double s = -glm::dot(normal, nearPoint) / glm::dot(normal, ray); // plane through the origin
    return projectToShadowMap(light, nearPoint + s * ray).uvTexels;
  };
  for (const glm::dvec2 pixel : { glm::dvec2(80.5, 60.5), glm::dvec2(30.5, 20.5), glm::dvec2(140.5, 100.5) })
  {
    const double h = 1e-3;
    const glm::dvec2 du = (texelAt(pixel.x + h, pixel.y) - texelAt(pixel.x - h, pixel.y)) / (2.0 * h);
    const glm::dvec2 dv = (texelAt(pixel.x, pixel.y + h) - texelAt(pixel.x, pixel.y - h)) / (2.0 * h);
    const double frobenius2 = glm::dot(du, du) + glm::dot(dv, dv);
    const double determinant = du.x * dv.y - du.y * dv.x;
    const double sigmaMax = std::sqrt(0.5 * (frobenius2 + std::sqrt(frobenius2 * frobenius2 - 4.0 * determinant * determinant)));
    const double expected = sigmaMax / std::abs(determinant);

    const glm::dvec3 nearPoint = unprojectPixel(cameraView, pixel.x, pixel.y, -1.0);
    const glm::dvec3 ray = unprojectPixel(cameraView, pixel.x, pixel.y, 1.0) - nearPoint;
    const glm::dvec3 pWs = nearPoint + (-glm::dot(normal, nearPoint) / glm::dot(normal, ray)) * ray;
    EXPECT_NEAR(texelRatio(cameraView, light, pixel.x, pixel.y, pWs, normal), expected, 1e-6 * expected)
      << "pixel " << pixel.x << "," << pixel.y;

    // Per axis (samplingError): the inverse Jacobian's columns are one s and one t texel step, in pixels; Eq. 1's
    // projection factor is the surface's cosine to the eye over its cosine to the light's centre.
    const glm::dmat2 pixelFromTexel = glm::inverse(glm::dmat2(du, dv));
    const double expectedS = glm::length(pixelFromTexel[0]);
    const double expectedT = glm::length(pixelFromTexel[1]);
    const SamplingError error = samplingError(cameraView, light, pixel.x, pixel.y, pWs, normal);
    EXPECT_NEAR(error.texelRatioS, expectedS, 1e-6 * expectedS) << "pixel " << pixel.x << "," << pixel.y;
    EXPECT_NEAR(error.texelRatioT, expectedT, 1e-6 * expectedT) << "pixel " << pixel.x << "," << pixel.y;
    const double cosToEye = std::abs(glm::dot(normal, glm::normalize(camera.position - pWs)));
    const double cosToLight = std::abs(glm::dot(normal, glm::normalize(light.eyeWs - pWs)));
    EXPECT_NEAR(error.projectionFactor, cosToEye / cosToLight, 1e-9);
  }
}

// The depth buffer's value for a linear depth: the closed form f (d - n) / (d (f - n)) between the planes, and 0 for
// every depth before the near plane, the light's centre and behind it included (z / w alone wraps past 1 for d < 0,
// which made a bias larger than the receiver's depth shadow it in pcf's hardware comparison).
TEST(LightView, WindowDepthIsTheHyperbolaAndZeroBeforeTheNearPlane)
{
  LightView light;
  light.nearDepth = 0.001;
  light.farDepth = 1.8;
  light.clipFromView = glm::frustum(-1.0, 1.0, -1.0, 1.0, light.nearDepth, light.farDepth);
  const double n = light.nearDepth;
  const double f = light.farDepth;
  for (const double d : { 0.001, 0.01, 0.5, 1.0, 1.8 })
  {
    EXPECT_NEAR(light.windowDepth(d), f * (d - n) / (d * (f - n)), 1e-12) << "d " << d;
  }
  for (const double d : { 0.0005, 0.0, -1e-6, -0.45, -3.0 })
  {
    EXPECT_EQ(light.windowDepth(d), 0.0) << "d " << d;
  }
}

TEST(DepthBias, ConstantPlusSlopeInTexelFootprints)
{
  LightView light;
  light.projection = LightProjection::Perspective;
  light.window = { -0.5, 0.5, -0.25, 0.25 };
  light.resolution = 100;
  // Texel footprint at depth 2: max(1.0, 0.5) / 100 * 2 = 0.02.
  EXPECT_NEAR(light.texelWorldSize(2.0), 0.02, 1e-15);
  BiasSettings bias;
  bias.constantTexels = 0.5;
  bias.slopeTexels = 1.0;
  bias.maxSlope = 10.0;
  const double tan45 = tanAngleToLight({ 0.0, 1.0, 0.0 }, glm::normalize(glm::dvec3(1.0, 1.0, 0.0)));
  EXPECT_NEAR(tan45, 1.0, 1e-12);
  EXPECT_NEAR(depthBias(light, bias, tan45, 2.0), 0.02 * 1.5, 1e-15);
  // Grazing: the slope term is clamped.
  const double tanGrazing = tanAngleToLight({ 0.0, 1.0, 0.0 }, glm::normalize(glm::dvec3(100.0, 1.0, 0.0)));
  EXPECT_NEAR(tanGrazing, 100.0, 1e-9);
  EXPECT_NEAR(depthBias(light, bias, tanGrazing, 2.0), 0.02 * 10.5, 1e-12);
}

// A synthetic G-buffer: a grid of ground points (y = 0, normal +y) covering [-extent, extent]^2.
void groundGBuffer(double extent, int size, ImageF& position, ImageF& normal)
{
  position = ImageF(size, size, 4, 0.0f);
  normal = ImageF(size, size, 4, 0.0f);
  for (int y = 0; y < size; ++y)
  {
    for (int x = 0; x < size; ++x)
    {
      position.at(x, y, 0) = static_cast<float>(-extent + 2.0 * extent * (x + 0.5) / size);
      position.at(x, y, 2) = static_cast<float>(-extent + 2.0 * extent * (y + 0.5) / size);
      position.at(x, y, 3) = 1.0f;
      normal.at(x, y, 1) = 1.0f;
      normal.at(x, y, 3) = 1.0f;
    }
  }
}

TEST(FitLightView, CoversEveryReceiverWithTheMarginAndTightDepth)
{
  // Square area light 3 above the ground, an occluder quad at height 1 (depth 2 from the light).
  Scene scene;
  Light light;
  light.center = { 0.0, 3.0, 0.0 };
  light.normal = { 0.0, -1.0, 0.0 };
  light.up = { 0.0, 0.0, -1.0 };
  scene.lights.push_back(light);
  SceneObject occluder;
  occluder.mesh.positions = { { -0.5f, 1.0f, -0.5f }, { 0.5f, 1.0f, -0.5f }, { 0.5f, 1.0f, 0.5f } };
  occluder.mesh.normals.assign(3, glm::vec3(0.0f, 1.0f, 0.0f));
  occluder.mesh.indices = { 0, 1, 2 };
  scene.objects.push_back(occluder);
  // A caster far outside the receivers' frustum, nearer to the light: must not pull the near plane.
  SceneObject outside = occluder;
  for (glm::vec3& p : outside.mesh.positions)
  {
    p += glm::vec3(30.0f, 1.5f, 0.0f);
  }
  scene.objects.push_back(outside);

  ImageF position;
  ImageF normal;
  groundGBuffer(1.5, 32, position, normal);
  FocusSettings focus;
  focus.resolution = 256;
  focus.marginTexels = 3.0;
  const LightView view = fitLightView(light, scene, position, normal, focus);
  EXPECT_EQ(view.receiverSampleCount, 32 * 32);
  double minTexel = 1e300;
  double maxTexel = -1e300;
  for (std::size_t i = 0; i < position.pixelCount(); ++i)
  {
    const glm::dvec3 pWs(position.data[i * 4], position.data[i * 4 + 1], position.data[i * 4 + 2]);
    const ShadowMapSample sample = projectToShadowMap(view, pWs);
    minTexel = std::min({ minTexel, sample.uvTexels.x, sample.uvTexels.y });
    maxTexel = std::max({ maxTexel, sample.uvTexels.x, sample.uvTexels.y });
    EXPECT_LT(sample.depthLin, view.farDepth);
  }
  // Receivers fill the map up to the margin (the extreme receivers sit exactly 3 texels from the edge).
  EXPECT_NEAR(minTexel, 3.0, 1e-6);
  EXPECT_NEAR(maxTexel, 256.0 - 3.0, 1e-6);
  // Near plane: the occluder (depth 2), not the outside caster (depth 0.5), with 0.1% slack.
  EXPECT_GT(view.nearDepth, 2.0 * (1.0 - 2e-3));
  EXPECT_LE(view.nearDepth, 2.0);
  EXPECT_NEAR(view.farDepth, 3.0, 0.01);
}

TEST(FitLightView, PointLightSurroundedByReceiversIsAnInputError)
{
  // L09/L12: the 80-degree refusal names the scene file and lights[i] (here the second light).
  Scene scene;
  scene.file = "scenes/room.json";
  Light first;
  first.type = LightType::Point;
  first.center = { 0.0, 10.0, 0.0 };
  Light second = first;
  second.center = { 0.0, 0.0, 0.0 };
  scene.lights = { first, second };
  // Receivers on the six sides of a cube around the second light, facing it.
  ImageF position(6, 1, 4, 0.0f);
  ImageF normal(6, 1, 4, 0.0f);
  const glm::dvec3 directions[6] = { { 1, 0, 0 }, { -1, 0, 0 }, { 0, 1, 0 }, { 0, -1, 0 }, { 0, 0, 1 }, { 0, 0, -1 } };
  for (int i = 0; i < 6; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      position.at(i, 0, c) = static_cast<float>(2.0 * directions[i][c]);
      normal.at(i, 0, c) = static_cast<float>(-directions[i][c]);
    }
    position.at(i, 0, 3) = 1.0f;
    normal.at(i, 0, 3) = 1.0f;
  }
  try
  {
    fitLightView(scene.lights[1], scene, position, normal, FocusSettings());
    FAIL() << "expected an InputError";
  }
  catch (const InputError& error)
  {
    EXPECT_EQ(std::string(error.what()).rfind("scenes/room.json: lights[1]: point light at (0, 0, 0) sees", 0), 0u)
      << error.what();
  }
}

} // namespace
} // namespace sl

namespace sl
{
namespace
{

Bounds boxAround(const glm::dvec3& centre, double halfSide)
{
  Bounds bounds;
  bounds.extend(centre - glm::dvec3(halfSide));
  bounds.extend(centre + glm::dvec3(halfSide));
  return bounds;
}

// Probe case O09: one vast, distant object stretches the scene box so far that the near plane at
// kMinNearOverFar of it used to cut away the whole near scene (coverage 0, exit 0). The near plane now moves in
// to every object wholly in front of the camera, and an object beyond the depth buffer's reach is an InputError.
TEST(CameraDepthRange, NearPlaneKeepsSmallObjectsInFrontOfAVastDistantOne)
{
  Camera camera; // at (0, 0, 5) looking down -z
  const Bounds nearObject = boxAround({ 0.0, 0.0, 0.0 }, 0.5);     // depths 4.5 .. 5.5
  const Bounds farObject = boxAround({ 0.0, 0.0, -4e5 }, 1e5);    // depths 3e5 .. 5e5
  Bounds scene = nearObject;
  scene.extend(farObject.min);
  scene.extend(farObject.max);

  const CameraView before = makeCameraView(camera, scene, { 64, 64 });
  EXPECT_GT(before.nearDepth, 5.5) << "the case no longer reproduces: the scene box alone keeps the near object";
  const CameraView view = makeCameraView(camera, scene, { 64, 64 }, { nearObject, farObject });
  EXPECT_LT(view.nearDepth, 4.5) << "the near object is still clipped";
  EXPECT_GE(view.nearDepth, view.farDepth * kMinNearOverFarForObjects);
  EXPECT_GE(view.farDepth, 5e5);

  // Without a vast object nothing changes: the near plane is the scene's nearest depth.
  const CameraView alone = makeCameraView(camera, nearObject, { 64, 64 }, { nearObject });
  EXPECT_NEAR(alone.nearDepth, 4.5 * 0.99, 1e-9);

  // A tiny object 1e-3 in front of the camera against a scene 1e6 deep: beyond any float depth range.
  const Bounds tiny = boxAround({ 0.0, 0.0, 5.0 - 1e-3 }, 1e-5);
  const Bounds deep = boxAround({ 0.0, 0.0, -9e5 }, 1e5);
  Bounds both = tiny;
  both.extend(deep.min);
  both.extend(deep.max);
  try
  {
    makeCameraView(camera, both, { 64, 64 }, { deep, tiny });
    ADD_FAILURE() << "expected an InputError";
  }
  catch (const InputError& error)
  {
    EXPECT_NE(std::string(error.what()).find("objects[1]"), std::string::npos) << error.what();
  }
}

} // namespace
} // namespace sl
