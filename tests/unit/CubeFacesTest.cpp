// Cube-map shadows for point lights (survey §2, lightspace/CubeFaces.h) on the CPU: the faces' owner pyramids
// against the dominant-axis selection on random directions, the per-face fit on receivers all around a light
// (focused windows reaching past the 90-degree face only by the margin, empty faces dropped), oneMapCovers (the
// refusal's condition, cube_map=auto's switch), and which techniques list cube_map.
#include "core/Error.h"
#include "lightspace/CubeFaces.h"
#include "lightspace/PartitionViews.h"
#include "structures/shadowmap/ShadowMapStructure.h"
#include "techniques/Registry.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace sl
{
namespace
{

TEST(CubeFaces, TheDominantFaceIsTheOnlyPyramidHoldingThePointOffTheSeams)
{
  // For 20000 random directions from a light at (0.3, -1.2, 2.5): the dominant face's four planes hold the point, and
  // no other face's hold it unless the point lies on a seam (two components within 1e-9 in magnitude).
  const glm::dvec3 center(0.3, -1.2, 2.5);
  std::mt19937 generator(29);
  std::normal_distribution<double> normal(0.0, 1.0);
  int onSeams = 0;
  for (int i = 0; i < 20000; ++i)
  {
    const glm::dvec3 direction(normal(generator), normal(generator), normal(generator));
    const glm::dvec3 pWs = center + 3.7 * direction;
    const int face = dominantCubeFace(direction);
    ASSERT_TRUE(ownerRegionHolds(cubeFaceOwnerPlanes(center, face), pWs)) << "direction " << i << " face " << face;
    EXPECT_GT(glm::dot(cubeFaceAxis(face), direction), 0.0);
    const glm::dvec3 size = glm::abs(direction);
    const bool seam = std::abs(size.x - size.y) < 1e-9 || std::abs(size.y - size.z) < 1e-9 ||
      std::abs(size.x - size.z) < 1e-9;
    onSeams += seam ? 1 : 0;
    for (int other = 0; other < kCubeFaceCount; ++other)
    {
      if (other != face && !seam)
      {
        EXPECT_FALSE(ownerRegionHolds(cubeFaceOwnerPlanes(center, other), pWs)) << i << ": " << face << ", " << other;
      }
    }
  }
  EXPECT_LT(onSeams, 5);
  // On a seam both pyramids hold the point; the selection's tie goes to x before y before z, positive on zero.
  const glm::dvec3 seam(2.0, -2.0, 0.5);
  EXPECT_EQ(dominantCubeFace(seam), 0);
  EXPECT_TRUE(ownerRegionHolds(cubeFaceOwnerPlanes(glm::dvec3(0.0), 0), seam));
  EXPECT_TRUE(ownerRegionHolds(cubeFaceOwnerPlanes(glm::dvec3(0.0), 3), seam));
  EXPECT_EQ(dominantCubeFace(glm::dvec3(0.0, 1.0, -1.0)), 2);
  EXPECT_EQ(dominantCubeFace(glm::dvec3(0.0, 0.0, -1.0)), 5);
  EXPECT_EQ(std::string(cubeFaceName(3)), "-y");
  EXPECT_EQ(std::string(cubeFaceTag(4)), "pz");
}

// Receivers on a sphere of radius 2 around the light at the origin, facing it: `count` x `count` pixels, latitude
// from -90 to `maxLatitudeDeg`.
void sphereGBuffer(int count, double maxLatitudeDeg, ImageF& position, ImageF& normal)
{
  position = ImageF(count, count, 4, 0.0f);
  normal = ImageF(count, count, 4, 0.0f);
  for (int j = 0; j < count; ++j)
  {
    for (int i = 0; i < count; ++i)
    {
      const double latitude = glm::radians(-89.0 + (maxLatitudeDeg + 89.0) * (j + 0.5) / count);
      const double longitude = glm::radians(360.0 * (i + 0.5) / count);
      const glm::dvec3 direction(
        std::cos(latitude) * std::cos(longitude), std::sin(latitude), std::cos(latitude) * std::sin(longitude));
      for (int c = 0; c < 3; ++c)
      {
        position.at(i, j, c) = static_cast<float>(2.0 * direction[c]);
        normal.at(i, j, c) = static_cast<float>(-direction[c]);
      }
      position.at(i, j, 3) = 1.0f;
      normal.at(i, j, 3) = 1.0f;
    }
  }
}

TEST(CubeFaces, EachFaceIsFocusedOnTheReceiversItOwns)
{
  Scene scene;
  scene.file = "scenes/sphere.json";
  Light light;
  light.type = LightType::Point;
  light.center = glm::dvec3(0.0);
  scene.lights = { light };
  SceneObject caster; // a small triangle below the light: a near plane for the -y face
  caster.mesh.positions = { { -0.2f, -1.0f, -0.2f }, { 0.2f, -1.0f, -0.2f }, { 0.0f, -1.0f, 0.2f } };
  caster.mesh.normals.assign(3, glm::vec3(0.0f, 1.0f, 0.0f));
  caster.mesh.indices = { 0, 1, 2 };
  scene.objects.push_back(caster);
  FocusSettings focus;
  focus.resolution = 128;
  focus.marginTexels = 3.0;
  const double grow = 128.0 / (128.0 - 6.0);

  // Receivers all around: one map cannot cover them (the refusal), six faces can.
  ImageF position, normal;
  sphereGBuffer(48, 89.0, position, normal);
  ImageReceivers all(position, normal);
  EXPECT_FALSE(oneMapCovers(light, scene, all));
  EXPECT_THROW(fitLightView(light, scene, all, focus), InputError);
  const PartitionSet faces = fitCubeFaces(light, scene, all, focus);
  ASSERT_EQ(faces.kind, PartitionKind::CubeFaces);
  ASSERT_EQ(faces.viewCount(), 6);
  int total = 0;
  for (int k = 0; k < 6; ++k)
  {
    const LightView& view = faces.views[static_cast<std::size_t>(k)];
    EXPECT_EQ(faces.viewFaces[static_cast<std::size_t>(k)], k);
    EXPECT_EQ(view.projection, LightProjection::Perspective);
    // The face's axis, and a window inside its 90-degree pyramid grown by the margin only.
    const glm::dvec3 forward = -glm::dvec3(glm::transpose(glm::dmat3(view.viewFromWorld))[2]);
    EXPECT_NEAR(glm::dot(forward, cubeFaceAxis(k)), 1.0, 1e-12) << k;
    for (int side = 0; side < 4; ++side)
    {
      EXPECT_LE(std::abs(view.window[side]), grow + 1e-9) << "face " << k << " side " << side;
      EXPECT_GT(std::abs(view.window[side]), 0.8) << "face " << k << " side " << side; // the sphere fills the face
    }
    EXPECT_NEAR(view.farDepth, 2.0 * 1.001, 0.01) << k; // receivers at distance 2, depth 2 / sqrt(3) .. 2
    total += view.receiverSampleCount;
    // Every owned receiver projects inside the map with the margin to spare.
    for (std::size_t i = 0; i < position.pixelCount(); ++i)
    {
      const glm::dvec3 pWs(position.data[i * 4], position.data[i * 4 + 1], position.data[i * 4 + 2]);
      if (dominantCubeFace(pWs - light.center) != k)
      {
        continue;
      }
      double edge = 0.0;
      EXPECT_TRUE(mapHolds(view, 3.0 - 1e-6, pWs, edge)) << "face " << k << " receiver " << i;
      const ViewSelection selection = selectCubeFace(faces, pWs);
      EXPECT_EQ(selection.primary, k);
      EXPECT_EQ(selection.primaryWeight, 1.0);
    }
  }
  // Seams hold receivers of two faces (each fit owns the closed pyramid): at least every receiver once.
  EXPECT_GE(total, 48 * 48);
  const ViewSelection below = selectView(faces, CameraView(), glm::dvec3(0.1, -2.0, 0.3));
  EXPECT_EQ(faces.viewFaces[static_cast<std::size_t>(below.primary)], 3);
  EXPECT_EQ(partitionViewSuffix(faces, 3), "_ny");
  EXPECT_EQ(partitionViewLabel(faces, 3), "cube face -y");
  // The -y face's near plane: the caster at depth 1, not the light's centre.
  EXPECT_NEAR(faces.views[3].nearDepth, 1.0, 2e-3);

  // Receivers only below latitude -30 (at most 60 degrees off -y): one map covers them (cube_map=auto keeps it); the
  // faces fitted anyway (cube_map=on) drop +y, which holds none, and the side faces focus on their lower part.
  sphereGBuffer(48, -30.0, position, normal);
  ImageReceivers lower(position, normal);
  EXPECT_TRUE(oneMapCovers(light, scene, lower));
  const PartitionSet lowerFaces = fitCubeFaces(light, scene, lower, focus);
  ASSERT_EQ(lowerFaces.viewCount(), 5);
  for (int k = 0; k < lowerFaces.viewCount(); ++k)
  {
    const int face = lowerFaces.viewFaces[static_cast<std::size_t>(k)];
    EXPECT_NE(face, 2) << "the +y face owns no receiver";
    if (face != 3)
    {
      // Light view y is world y on a side face (up = +y): the window stops at tan(-30 deg) = -0.577, plus margin.
      const LightView& view = lowerFaces.views[static_cast<std::size_t>(k)];
      EXPECT_LT(view.window.w, -0.5) << "face " << cubeFaceName(face);
      EXPECT_GT(view.window.z, -grow - 1e-9) << "face " << cubeFaceName(face);
    }
  }
  EXPECT_EQ(cubeFaceOf(lowerFaces, glm::dvec3(0.0, 2.0, 0.1)), -1);
  EXPECT_EQ(cubeFaceOf(lowerFaces, glm::dvec3(0.0, -2.0, 0.1)), 3);
}

TEST(CubeFaces, OnlyHardAndPcfListCubeMap)
{
  int listing = 0;
  for (const TechniqueDescriptor& technique : techniqueRegistry())
  {
    const bool lists = technique.findParameter("cube_map") != nullptr;
    EXPECT_EQ(lists, technique.name == "hard" || technique.name == "pcf") << technique.name;
    listing += lists ? 1 : 0;
    if (technique.needs(shadowMapStructure()))
    {
      const ShadowMapSettings settings = shadowMapSettings(technique, technique.defaultParameters());
      EXPECT_EQ(settings.cubeMap.has_value(), lists) << technique.name;
      if (lists)
      {
        EXPECT_EQ(*settings.cubeMap, CubeMapMode::Auto) << technique.name;
      }
    }
  }
  EXPECT_EQ(listing, 2);
  ParameterValues values = findTechnique("pcf").defaultParameters();
  values.set("cube_map=on");
  EXPECT_EQ(*shadowMapSettings(findTechnique("pcf"), values).cubeMap, CubeMapMode::On);
  try
  {
    requireCubeMapLight(CubeMapMode::On, LightType::Spot);
    FAIL() << "a spot light's cube map was accepted";
  }
  catch (const InputError& error)
  {
    EXPECT_EQ(std::string(error.what()).rfind("--set cube_map=on: ", 0), 0u) << error.what();
  }
  EXPECT_NO_THROW(requireCubeMapLight(CubeMapMode::Auto, LightType::Directional));
  EXPECT_NO_THROW(requireCubeMapLight(CubeMapMode::On, LightType::Point));
}

} // namespace
} // namespace sl
