// Technique `shadow-volume` on the GPU (llvmpipe in CI) against independent CPU answers:
//  - visibility against the ray-traced reference (Embree) for the light's centre, on >= 99.9 % of the covered
//    pixels outside a 1-pixel band around shadow and silhouette edges;
//  - depth_complexity_center against a direct double-precision count of the caster triangles crossed by the
//    segment from the pixel's point to the light's centre (ShadowVolumeReference.h), on >= 99.9 % of the
//    covered pixels, and stencil_count equal to it modulo 256 on every covered pixel;
// on the datasets, with the camera inside a shadow volume, on an open quad and a non-manifold mesh, on a scene
// without any closed mesh, under an orthographic camera, and on generated random configurations.
#include "support/TestSupport.h"

#include "io/ImageIO.h"
#include "lightspace/LightView.h"
#include "reference/ReferenceRenderer.h"
#include "scene/Primitives.h"
#include "scene/WeldedMesh.h"
#include "objectspace/ShadowVolumeGeometry.h"
#include "objectspace/ShadowVolumeReference.h"
#include "techniques/shadowvolume/ShadowVolumeTechnique.h"
#include "techniques/VolumeCountStatus.h"
#include "techniques/Registry.h"

#include <gtest/gtest.h>

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkPolyData.h>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace sl
{
namespace
{

constexpr int kSize = 160;

// ---- scenes ---------------------------------------------------------------------------------------------

// Two tetrahedra sharing the edge from `base` to `base` + (0, 0.4, 0): that edge has four triangles.
SceneObject twoTetrahedra(const glm::dvec3& base)
{
  const glm::dvec3 bottom = base, top = base + glm::dvec3(0.0, 0.4, 0.0);
  const glm::dvec3 wings[2][2] = { { base + glm::dvec3(0.4, 0.2, 0.1), base + glm::dvec3(0.2, 0.2, 0.4) },
    { base + glm::dvec3(-0.4, 0.2, -0.1), base + glm::dvec3(-0.1, 0.2, -0.4) } };
  std::vector<glm::dvec3> corners;
  for (const auto& wing : wings)
  {
    test::appendTetrahedron(corners, { bottom, top, wing[0], wing[1] });
  }
  return test::flatObject("two tetrahedra", corners);
}

using test::sceneFromJson;


// ---- checks ---------------------------------------------------------------------------------------------

struct Agreement
{
  int covered = 0;
  int compared = 0;      // visibility: outside the edge band
  int visibilityAgree = 0;
  int shadowed = 0;      // reference, among compared
  int countAgree = 0;    // over all covered pixels
  int countNonZero = 0;
  int stencilAgree = 0;
  int negativeCounts = 0;
  int maxCount = 0;
  std::string firstMismatch;

  double visibilityShare() const { return compared ? static_cast<double>(visibilityAgree) / compared : 0.0; }
  double countShare() const { return covered ? static_cast<double>(countAgree) / covered : 0.0; }
};

// The point the z-fail count describes: a hair in front of the visible surface (a surface at the pixel's own
// depth counts as behind it), i.e. moved toward the camera.
// The parameter receiver_offset: a fraction of the distance to the eye, or of the scene's radius for an
// orthographic camera.
glm::dvec3 inFrontOfSurface(const Scene& scene, const FrameResult& frame, const glm::dvec3& pWs)
{
  return shadowVolumeReceiverPoint(scene, frame.parameters.get("receiver_offset"), pWs);
}

FrameResult renderShadowVolume(const Scene& scene, int width, int height, const std::vector<std::string>& settings = {})
{
  return test::renderDataset(scene, "shadow-volume", width, height, settings);
}

// Reference visibility of the light's centre (Embree, one ray per pixel; an area light becomes a point light
// at its centre, its one-sided reach kept), -1 where uncovered.
ImageF centreReference(const Scene& scene, const FrameResult& frame)
{
  Light centre = scene.lights[0];
  if (centre.type == LightType::Area)
  {
    centre.type = LightType::Point;
  }
  ReferenceInputs inputs = test::referenceInputs(frame, scene);
  inputs.light = &centre;
  ReferenceSettings settings;
  settings.samples = 1;
  ImageF reference = renderReference(inputs, settings).visibility;
  const ImageF& position = frame.find("position")->image;
  const ImageF& normal = frame.find("normal")->image;
  const ImageF& coverage = frame.find("coverage")->image;
  const ImageF& receives = frame.find("receives_shadows")->image;
  for (int y = 0; y < reference.height; ++y)
  {
    for (int x = 0; x < reference.width; ++x)
    {
      if (coverage.at(x, y) <= 0.5f)
      {
        reference.at(x, y) = -1.0f;
        continue;
      }
      const glm::dvec3 pWs(position.at(x, y, 0), position.at(x, y, 1), position.at(x, y, 2));
      const glm::dvec3 nWs(normal.at(x, y, 0), normal.at(x, y, 1), normal.at(x, y, 2));
      if (receives.at(x, y) > 0.5f && !lightCanReach(scene.lights[0], pWs, nWs))
      {
        reference.at(x, y) = 0.0f; // behind the area light's plane
      }
    }
  }
  return reference;
}

// Outside the 1-pixel band: every 8-neighbour has the same reference value (same coverage, same lit state).
bool outsideEdgeBand(const ImageF& reference, int x, int y)
{
  for (int dy = -1; dy <= 1; ++dy)
  {
    for (int dx = -1; dx <= 1; ++dx)
    {
      const int nx = x + dx, ny = y + dy;
      if (nx >= 0 && ny >= 0 && nx < reference.width && ny < reference.height && reference.at(nx, ny) != reference.at(x, y))
      {
        return false;
      }
    }
  }
  return true;
}

Agreement compare(const Scene& scene, const FrameResult& frame, bool withReference = true)
{
  Agreement result;
  const ImageF& visibility = frame.find("visibility")->image;
  const ImageF& count = frame.find("depth_complexity_center")->image;
  const ImageF& stencil = frame.find("stencil_count")->image;
  const ImageF& position = frame.find("position")->image;
  const ImageF& coverage = frame.find("coverage")->image;
  const ImageF reference = withReference ? centreReference(scene, frame) : ImageF();
  const VolumeLight light = VolumeLight::from(scene.lights[0]);
  for (int y = 0; y < count.height; ++y)
  {
    for (int x = 0; x < count.width; ++x)
    {
      if (coverage.at(x, y) <= 0.5f)
      {
        EXPECT_EQ(visibility.at(x, y), 0.0f) << "uncovered pixel " << x << "," << y;
        continue;
      }
      ++result.covered;
      const glm::dvec3 pWs(position.at(x, y, 0), position.at(x, y, 1), position.at(x, y, 2));
      const int expected = casterCrossings(scene, light, inFrontOfSurface(scene, frame, pWs));
      const float gpu = count.at(x, y);
      result.countAgree += std::abs(gpu - static_cast<float>(expected)) < 0.5f ? 1 : 0;
      if (std::abs(gpu - static_cast<float>(expected)) >= 0.5f && result.firstMismatch.empty())
      {
        std::ostringstream message;
        message << "pixel " << x << "," << y << " at " << pWs.x << " " << pWs.y << " " << pWs.z << ": gpu count "
                << gpu << ", cpu " << expected;
        result.firstMismatch = message.str();
      }
      result.countNonZero += expected > 0 ? 1 : 0;
      result.negativeCounts += gpu < -0.5f ? 1 : 0;
      result.maxCount = std::max(result.maxCount, static_cast<int>(std::lround(gpu)));
      const long wrapped = ((std::lround(gpu) % 256) + 256) % 256;
      result.stencilAgree += std::lround(stencil.at(x, y)) == wrapped ? 1 : 0;
      if (withReference && outsideEdgeBand(reference, x, y))
      {
        ++result.compared;
        result.shadowed += reference.at(x, y) < 0.5f ? 1 : 0;
        result.visibilityAgree += (visibility.at(x, y) > 0.5f) == (reference.at(x, y) > 0.5f) ? 1 : 0;
      }
    }
  }
  return result;
}

std::string describe(const Agreement& a)
{
  std::ostringstream text;
  text << "covered " << a.covered << ", visibility agrees on " << a.visibilityAgree << "/" << a.compared
       << " (reference shadowed " << a.shadowed << "), count agrees on " << a.countAgree << "/" << a.covered
       << " (non-zero " << a.countNonZero << ", max " << a.maxCount << "), stencil agrees on " << a.stencilAgree
       << "; " << a.firstMismatch;
  return text.str();
}

void expectExact(const std::string& label, const Agreement& a, bool withReference = true)
{
  std::cout << "[ measured ] " << label << ": " << describe(a) << "\n";
  EXPECT_GT(a.covered, kSize * kSize / 10) << label;
  EXPECT_GE(a.countShare(), 0.999) << label << ": " << describe(a);
  EXPECT_EQ(a.stencilAgree, a.covered) << label << ": the stencil and the exact count disagree modulo 256";
  EXPECT_EQ(a.negativeCounts, 0) << label;
  if (withReference)
  {
    EXPECT_GE(a.visibilityShare(), 0.999) << label << ": " << describe(a);
    EXPECT_GT(a.compared, a.covered / 2) << label;
  }
}

// ---- tests ----------------------------------------------------------------------------------------------

TEST(ShadowVolume, DatasetsAgreeWithTheRayTracedCentreAndTheCrossingCount)
{
  for (const std::string dataset : { "bunny", "stacked-occluders", "contact", "sphere-point" })
  {
    const Scene scene = test::loadDataset(dataset);
    const FrameResult frame = renderShadowVolume(scene, kSize, kSize);
    const Agreement agreement = compare(scene, frame);
    expectExact(dataset, agreement);
    EXPECT_GT(agreement.shadowed, agreement.compared / 50) << dataset << ": the view must show shadows";
    EXPECT_GT(agreement.countNonZero, agreement.covered / 50) << dataset;
  }
}

TEST(ShadowVolume, StatisticsAndSilhouettesMatchTheCpuGeometry)
{
  const Scene scene = test::loadDataset("bunny");
  const FrameResult frame = renderShadowVolume(scene, 96, 96);
  const ShadowVolumeGeometry geometry = buildShadowVolumes(
    weldCasters(scene), VolumeLight::from(scene.lights[0]), VolumeExtrusion::ToInfinity, scene.bounds());
  const auto statistic = [&frame](const std::string& name) {
    const auto found = frame.techniqueStatistics.find(name);
    EXPECT_NE(found, frame.techniqueStatistics.end()) << name;
    return found == frame.techniqueStatistics.end() ? -1.0 : found->second;
  };
  EXPECT_EQ(statistic("silhouette_edges"), static_cast<double>(geometry.statistics.silhouetteEdges));
  EXPECT_EQ(statistic("boundary_edges"), static_cast<double>(geometry.statistics.boundaryEdges));
  EXPECT_EQ(statistic("non_manifold_edges"), static_cast<double>(geometry.statistics.nonManifoldEdges));
  EXPECT_EQ(statistic("side_quads"), static_cast<double>(geometry.statistics.sideQuads));
  EXPECT_EQ(statistic("volume_triangles"), static_cast<double>(geometry.statistics.volumeTriangles()));
  EXPECT_GT(geometry.statistics.silhouetteEdges, 100u);
  EXPECT_GE(geometry.statistics.boundaryEdges, 4u) << "at least the ground quad's rim";
  std::cout << "[ measured ] bunny: " << geometry.statistics.silhouetteEdges << " silhouette edges, "
            << geometry.statistics.boundaryEdges << " boundary edges, " << geometry.statistics.volumeTriangles()
            << " volume triangles, CPU build " << statistic("volume_build_ms") << " ms\n";
}

TEST(ShadowVolume, CameraInsideAShadowVolume)
{
  // The camera sits under the upper occluder, inside its shadow volume (and the lower one's), looking
  // across the ground: z-pass would be off by the volumes around the eye; z-fail is not.
  const Scene scene = sceneFromJson(R"({ "position": [0.3, 0.35, 0.05], "focal_point": [2.0, 0.0, 1.5], "view_angle": 60 })",
    R"({ "type": "point", "center": [0.35, 3.0, 0.1] })",
    std::string(test::kGroundQuadJson) + R"(,
      { "primitive": "quad", "center": [0.35, 1.5, 0.1], "size": [1.6, 1.6], "normal": [0, 1, 0], "up": [0, 0, -1] },
      { "primitive": "box", "center": [0.3, 0.8, 0.05], "size": [0.5, 0.1, 0.5] },
      { "primitive": "sphere", "center": [1.4, 0.3, 1.0], "size": 0.3 })");
  const VolumeLight light = VolumeLight::from(scene.lights[0]);
  ASSERT_EQ(casterCrossings(scene, light, scene.camera.position), 3) << "the eye must be inside three volumes";
  const FrameResult frame = renderShadowVolume(scene, kSize, kSize);
  expectExact("camera in a volume", compare(scene, frame));
}

TEST(ShadowVolume, OpenQuadAndNonManifoldMeshCountWhatTheySpan)
{
  // A light level with the tetrahedra shines through both, past their shared edge, onto a wall facing it:
  // behind them the segment to the light crosses four faces, two of each.
  Scene scene = sceneFromJson(R"({ "position": [2.2, 2.4, -2.4], "focal_point": [-0.3, 0.8, -0.8], "view_angle": 50 })",
    R"({ "type": "point", "center": [2.92, 0.8, 2.4] })",
    std::string(test::kGroundQuadJson) + R"(,
      { "primitive": "quad", "center": [-0.56, 1.1, -1.06], "size": [3, 2.2], "normal": [1, 0, 1], "up": [0, 1, 0] },
      { "primitive": "quad", "center": [1.95, 1.08, 0.94], "size": [0.4, 0.3], "normal": [2.78, -0.8, 4.16], "up": [0, 1, 0] })");
  scene.objects.push_back(twoTetrahedra(glm::dvec3(0.7, 0.6, 0.2)));
  const std::vector<WeldedMesh> casters = weldCasters(scene);
  ASSERT_EQ(casters.size(), 4u);
  EXPECT_EQ(casters[2].boundaryEdgeCount(), 4u);
  EXPECT_EQ(casters[3].nonManifoldEdgeCount(), 1u);
  const VolumeLight light = VolumeLight::from(scene.lights[0]);
  ASSERT_EQ(casterCrossings(scene, light, { -0.55, 0.8, -1.05 }), 4); // in front of the wall
  ASSERT_EQ(casterCrossings(scene, light, { 0.15, 1.6, -1.75 }), 1);  // the open quad's shadow
  const FrameResult frame = renderShadowVolume(scene, kSize, kSize);
  const Agreement agreement = compare(scene, frame);
  expectExact("open quad + non-manifold", agreement);
  EXPECT_GE(agreement.maxCount, 4) << "behind both tetrahedra the segment crosses four faces";
  EXPECT_EQ(frame.techniqueStatistics.at("non_manifold_edges"), 1.0);
  EXPECT_EQ(frame.techniqueStatistics.at("boundary_edges"), 3 * 4.0); // the three quads' rims
}

TEST(ShadowVolume, SceneWithoutAnyClosedMeshRenders)
{
  // Only open surfaces (quads and a disk) under a directional and a spot light.
  for (const std::string light : { R"({ "type": "directional", "direction": [0.3, -1, 0.2] })",
         R"({ "type": "spot", "center": [0.4, 3.2, 0.3], "normal": [-0.1, -1, -0.05], "cone_angle_deg": 40 })" })
  {
    const Scene scene = sceneFromJson(R"({ "position": [0, 4.5, 3.5], "focal_point": [0, 0, 0], "view_angle": 35 })", light,
      std::string(test::kGroundQuadJson) + R"(,
        { "primitive": "quad", "center": [-0.35, 0.6, 0], "size": [0.8, 0.8], "normal": [0, 1, 0], "up": [0, 0, -1] },
        { "primitive": "disk", "center": [0.35, 1.5, 0.1], "size": 0.5, "normal": [0.2, -1, 0] })");
    for (const WeldedMesh& caster : weldCasters(scene))
    {
      EXPECT_GT(caster.boundaryEdgeCount(), 0u);
    }
    const FrameResult frame = renderShadowVolume(scene, kSize, kSize);
    const Agreement agreement = compare(scene, frame);
    expectExact(light, agreement);
    EXPECT_GT(agreement.shadowed, agreement.compared / 50) << light;
  }
}

TEST(ShadowVolume, OrthographicCameraCutsTheVolumesBeyondTheScene)
{
  // Orthographic views send every point at infinity to w = 0; the volumes are cut at a finite distance.
  // Looking straight down, the rays below a shadowed ground point stay inside the point light's volumes: only
  // the (cut) far caps close them.
  for (const std::string light : { R"({ "type": "directional", "direction": [0.31, -1, 0.17] })",
         R"({ "type": "point", "center": [0.1, 3.5, 0.2] })" })
  {
    const Scene scene = sceneFromJson(
      R"({ "projection": "orthographic", "position": [0.013, 5, 0.007], "focal_point": [0.013, 0, 0.007], "view_up": [0, 0, -1], "parallel_scale": 1.6 })",
      light, std::string(test::kGroundQuadJson) + R"(,
        { "primitive": "box", "center": [-0.4, 0.5, 0.2], "size": [0.5, 0.4, 0.6], "transform": { "rotate_deg": [0, 23, 0] } },
        { "primitive": "sphere", "center": [0.5, 0.8, -0.3], "size": 0.35 })");
    const FrameResult frame = renderShadowVolume(scene, kSize, kSize);
    expectExact(std::string("orthographic ") + light, compare(scene, frame));
  }
}

TEST(ShadowVolume, RandomOccluderStacksAndLights)
{
  std::mt19937 generator(1977u);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int configuration = 0; configuration < 4; ++configuration)
  {
    std::ostringstream objects;
    objects << test::kGroundQuadJson;
    const int occluders = 3 + configuration % 3;
    for (int occluder = 0; occluder < occluders; ++occluder)
    {
      const double x = 1.2 * (unit(generator) - 0.5), z = 1.2 * (unit(generator) - 0.5);
      const double y = 0.3 + 0.5 * occluder + 0.2 * unit(generator);
      switch ((occluder + configuration) % 3)
      {
      case 0:
        objects << R"(, { "primitive": "box", "center": [)" << x << ", " << y << ", " << z << R"(], "size": [)"
                << 0.3 + 0.4 * unit(generator) << ", " << 0.1 + 0.2 * unit(generator) << ", " << 0.3 + 0.4 * unit(generator)
                << R"(], "transform": { "rotate_deg": [0, )" << 90.0 * unit(generator) << ", 0] } }";
        break;
      case 1:
        objects << R"(, { "primitive": "sphere", "center": [)" << x << ", " << y << ", " << z << R"(], "size": )"
                << 0.15 + 0.2 * unit(generator) << " }";
        break;
      default:
        objects << R"(, { "primitive": "quad", "center": [)" << x << ", " << y << ", " << z << R"(], "size": [0.6, 0.5], "normal": [)"
                << unit(generator) - 0.5 << ", 1, " << unit(generator) - 0.5 << "] }";
      }
    }
    std::ostringstream light;
    if (configuration % 2 == 0)
    {
      light << R"({ "type": "point", "center": [)" << 1.5 * (unit(generator) - 0.5) << ", " << 3.0 + unit(generator) << ", "
            << 1.5 * (unit(generator) - 0.5) << "] }";
    }
    else
    {
      light << R"({ "type": "directional", "direction": [)" << unit(generator) - 0.5 << ", -1, " << unit(generator) - 0.5 << "] }";
    }
    const Scene scene = sceneFromJson(R"({ "position": [2.5, 4.0, 3.5], "focal_point": [0, 0.5, 0], "view_angle": 40 })",
      light.str(), objects.str());
    const FrameResult frame = renderShadowVolume(scene, 128, 128);
    const Agreement agreement = compare(scene, frame);
    expectExact("random configuration " + std::to_string(configuration) + " " + light.str(), agreement);
  }
}

TEST(ShadowVolume, WithoutTheReceiverOffsetCastersShadowThemselves)
{
  // The test has teeth: with receiver_offset = 0 a lit caster's own near cap lies at the visible point's
  // depth, and float rounding puts it in front on a large share of the pixels (acne).
  const Scene scene = test::loadDataset("contact");
  const Agreement agreement = compare(scene, renderShadowVolume(scene, kSize, kSize, { "receiver_offset=0" }));
  std::cout << "[ measured ] contact, receiver_offset=0: " << describe(agreement) << "\n";
  EXPECT_LT(agreement.visibilityShare(), 0.95);
  EXPECT_LT(agreement.countShare(), 0.95);
}

TEST(ShadowVolume, ProbeRecordsTheCrossedTrianglesAndTheGpuCount)
{
  // Every covered pixel: the probe's count is the GPU's depth_complexity_center, and its visibility the GPU's,
  // except where it reports a volume face within 1/512 pixel of the pixel centre (rasterisation decides those).
  std::vector<glm::ivec2> byCount(3, glm::ivec2(-1)); // stacked-occluders: a pixel with 0, 1 and >= 2 crossings
  for (const std::string dataset : { "stacked-occluders", "bunny" })
  {
    const Scene scene = test::loadDataset(dataset);
    const FrameResult frame = renderShadowVolume(scene, 128, 128);
    const ImageF& count = frame.find("depth_complexity_center")->image;
    const ImageF& visibility = frame.find("visibility")->image;
    const ImageF& coverage = frame.find("coverage")->image;
    int compared = 0;
    int ambiguous = 0;
    int mismatched = 0;
    std::string firstMismatch;
    for (int y = 0; y < 128; ++y)
    {
      for (int x = 0; x < 128; ++x)
      {
        if (coverage.at(x, y) <= 0.5f)
        {
          continue;
        }
        ProbeRecorder recorder;
        const ProbeOutcome outcome = probeShadowVolume(frame, scene, 0, { x, y }, recorder);
        // The record carries the GPU's own count and status at the pixel, whatever the twin finds.
        ASSERT_EQ(recorder.record().find("gpu_depth_complexity_center")->value.at(0), count.at(x, y));
        ASSERT_EQ(recorder.record().find("volume_count_status")->value.at(0),
          frame.find("volume_count_status")->image.at(x, y));
        if (!outcome.ambiguity.empty())
        {
          ++ambiguous;
          continue;
        }
        ++compared;
        const double probed = recorder.record().find("depth_complexity_center")->value.at(0);
        if (probed != count.at(x, y) || outcome.visibility != visibility.at(x, y))
        {
          if (mismatched++ == 0)
          {
            firstMismatch = format("pixel ", x, ",", y, ": probe count ", probed, " visibility ", outcome.visibility,
              ", GPU ", count.at(x, y), " ", visibility.at(x, y));
          }
        }
        const std::size_t slot = std::min<std::size_t>(2, static_cast<std::size_t>(probed));
        if (dataset == "stacked-occluders" && outcome.evaluated && byCount[slot].x < 0 && (x + y) % 7 == 0)
        {
          byCount[slot] = { x, y };
        }
      }
    }
    std::cout << "[ measured ] shadow-volume probe on " << dataset << ": " << compared << " pixels compared, "
              << ambiguous << " ambiguous (a volume face within 1/512 pixel), " << mismatched << " mismatched\n";
    EXPECT_EQ(mismatched, 0) << dataset << ": " << firstMismatch;
    EXPECT_LT(ambiguous, compared / 50) << dataset;
  }
  // Lit, one volume, two or more: the record through the registry's probe.
  const Scene scene = test::loadDataset("stacked-occluders");
  const FrameResult frame = renderShadowVolume(scene, 128, 128);
  for (const glm::ivec2 pixel : byCount)
  {
    ASSERT_GE(pixel.x, 0) << "no pixel with that many crossings";
    const std::string label = format("pixel ", pixel.x, ",", pixel.y);
    ProbeRecorder recorder;
    const ProbeOutcome outcome = findTechnique("shadow-volume").probe({ &frame, &scene, 0 }, pixel, recorder);
    const ProbeRecord& record = recorder.record();
    const int crossings = static_cast<int>(record.find("depth_complexity_center")->value.at(0));
    EXPECT_EQ(crossings, frame.find("depth_complexity_center")->image.at(pixel.x, pixel.y)) << label;
    EXPECT_EQ(record.find("stencil_count")->value.at(0), frame.find("stencil_count")->image.at(pixel.x, pixel.y)) << label;
    EXPECT_EQ(outcome.visibility, crossings == 0 ? 1.0 : 0.0) << label;
    ASSERT_EQ(record.lightSamples.size(), 1u) << label;
    EXPECT_EQ(record.lightSamples.front().depthComplexity, crossings) << label;
    EXPECT_EQ(record.lightSamples.front().blocked, crossings > 0) << label;
    // Each crossing recorded, on the segment from the counted point to the light's centre.
    const glm::dvec3 from(record.find("counted_point")->value[0], record.find("counted_point")->value[1],
      record.find("counted_point")->value[2]);
    const glm::dvec3 to = scene.lights[0].center;
    int points = 0;
    for (const ProbeQuantity& quantity : record.quantities)
    {
      if (quantity.name != "crossing_point")
      {
        continue;
      }
      ++points;
      const glm::dvec3 point(quantity.value[0], quantity.value[1], quantity.value[2]);
      const double along = glm::dot(point - from, to - from) / glm::dot(to - from, to - from);
      EXPECT_GT(along, 0.0) << label;
      EXPECT_LT(along, 1.0) << label;
      EXPECT_LT(glm::length(from + along * (to - from) - point), 1e-9) << label << ": off the segment";
    }
    EXPECT_EQ(points, crossings) << label;
  }
}

TEST(ShadowVolume, ExactCountBeyondTheEightBitStencil)
{
  // 256 stacked quads: below them the stencil wraps back to 0, the exact count says 256, and the point is
  // in shadow.
  std::ostringstream objects;
  objects << test::kGroundQuadJson;
  for (int layer = 0; layer < 256; ++layer)
  {
    objects << R"(, { "primitive": "quad", "center": [0, )" << 0.5 + 0.004 * layer << R"(, 0], "size": [0.8, 0.8], "normal": [0, 1, 0] })";
  }
  const Scene scene = sceneFromJson(R"({ "position": [0, 5, 3], "focal_point": [0, 0, 0], "view_angle": 40 })",
    R"({ "type": "point", "center": [0.05, 3.5, 0.03] })", objects.str());
  const FrameResult frame = renderShadowVolume(scene, 96, 96);
  const ImageF& count = frame.find("depth_complexity_center")->image;
  const ImageF& stencil = frame.find("stencil_count")->image;
  const ImageF& visibility = frame.find("visibility")->image;
  const ImageF& position = frame.find("position")->image;
  int wrapped = 0;
  for (int y = 0; y < count.height; ++y)
  {
    for (int x = 0; x < count.width; ++x)
    {
      if (std::abs(position.at(x, y, 1)) < 1e-4f && count.at(x, y) == 256.0f)
      {
        ++wrapped;
        EXPECT_EQ(stencil.at(x, y), 0.0f) << x << "," << y;
        EXPECT_EQ(visibility.at(x, y), 0.0f) << x << "," << y;
      }
    }
  }
  EXPECT_GT(wrapped, 20) << "ground pixels under all 256 layers";
  expectExact("256 layers", compare(scene, frame, false), false);
}


// ---- cracks (issue 27 item 2b): generated scenes, every miscounted pixel flagged or ambiguous -------------------

// A seeded random scene: the ground, a tilted meshed 16-hole plate, up to two boxes and spheres, a point light and a
// camera anywhere above.
Scene randomPlateScene(std::mt19937& generator, const std::string& mask)
{
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto signedUnit = [&] { return 2.0 * unit(generator) - 1.0; };
  std::ostringstream objects;
  objects << test::kGroundQuadJson;
  objects << R"(, { "primitive": "quad", "center": [)" << 0.5 * signedUnit() << ", " << 0.5 + unit(generator) << ", "
          << 0.5 * signedUnit() << R"(], "size": [)" << 1.0 + unit(generator) << ", " << 0.8 + unit(generator)
          << R"(], "normal": [)" << 0.4 * signedUnit() << ", 1, " << 0.4 * signedUnit() << R"(], "alpha_texture": ")" << mask
          << R"(", "mesh_alpha": true })";
  const int extra = static_cast<int>(3.0 * unit(generator));
  for (int k = 0; k < extra; ++k)
  {
    const double x = 1.6 * signedUnit(), y = 0.3 + 1.5 * unit(generator), z = 1.6 * signedUnit();
    if (k % 2 == 0)
    {
      objects << R"(, { "primitive": "box", "center": [)" << x << ", " << y << ", " << z << R"(], "size": [)"
              << 0.2 + 0.4 * unit(generator) << ", " << 0.2 + 0.4 * unit(generator) << ", " << 0.2 + 0.4 * unit(generator)
              << R"(], "transform": { "rotate_deg": [0, )" << 90.0 * unit(generator) << ", 0] } }";
    }
    else
    {
      objects << R"(, { "primitive": "sphere", "center": [)" << x << ", " << y << ", " << z << R"(], "size": )"
              << 0.15 + 0.2 * unit(generator) << " }";
    }
  }
  std::ostringstream light, camera;
  light << R"({ "type": "point", "center": [)" << 1.2 * signedUnit() << ", " << 2.6 + 2.0 * unit(generator) << ", "
        << 1.2 * signedUnit() << "] }";
  const double azimuth = 6.283185307 * unit(generator), elevation = 0.5 + 0.8 * unit(generator);
  const double distance = 4.0 + 2.0 * unit(generator);
  camera << R"({ "position": [)" << distance * std::cos(elevation) * std::cos(azimuth) << ", "
         << distance * std::sin(elevation) << ", " << distance * std::cos(elevation) * std::sin(azimuth)
         << R"(], "focal_point": [)" << 0.3 * signedUnit() << ", 0.3, " << 0.3 * signedUnit() << R"(], "view_angle": )"
         << 30.0 + 20.0 * unit(generator) << " }";
  return sceneFromJson(camera.str(), light.str(), objects.str());
}

using test::vec3At;

struct CrackCount
{
  int covered = 0;
  int mismatched = 0;      // GPU centre count != the CPU crossing count to the light's centre
  int negative = 0;        // GPU count < 0
  int flagged = 0;         // volume_count_status = inconsistent
  int flaggedMismatched = 0;
  int rasterAmbiguous = 0; // mismatched, a volume face within 1/512 pixel of the pixel centre (probeShadowVolume)
  int grazing = 0;         // mismatched, the counted point within 1e-6 radii of its own surface's plane
  int unexplained = 0;     // mismatched, unflagged and unambiguous
  double cutShortPixels = -1.0;
  std::string firstUnexplained;
};

CrackCount countCracks(const Scene& scene, const FrameResult& frame)
{
  CrackCount result;
  const ImageF& count = frame.find("depth_complexity_center")->image;
  const ImageF& status = frame.find("volume_count_status")->image;
  const ImageF& coverage = frame.find("coverage")->image;
  const VolumeLight light = VolumeLight::from(scene.lights[0]);
  const double tolerance = 1e-6 * scene.bounds().radius();
  for (int y = 0; y < count.height; ++y)
  {
    for (int x = 0; x < count.width; ++x)
    {
      if (coverage.at(x, y) <= 0.5f)
      {
        continue;
      }
      ++result.covered;
      const glm::dvec3 pWs = vec3At(frame.find("position")->image, x, y);
      const glm::dvec3 nWs = vec3At(frame.find("normal")->image, x, y);
      const glm::dvec3 counted = inFrontOfSurface(scene, frame, pWs);
      const int expected = casterCrossings(scene, light, counted);
      const bool flagged = std::lround(status.at(x, y)) == static_cast<long>(VolumeCountStatus::Inconsistent);
      result.flagged += flagged;
      result.negative += count.at(x, y) < -0.5f;
      if (std::lround(count.at(x, y)) == expected)
      {
        continue;
      }
      ++result.mismatched;
      if (flagged)
      {
        ++result.flaggedMismatched;
        continue;
      }
      ProbeRecorder recorder;
      if (!probeShadowVolume(frame, scene, 0, { x, y }, recorder).ambiguity.empty())
      {
        ++result.rasterAmbiguous;
        continue;
      }
      if (std::abs(glm::dot(nWs, counted - pWs)) <= tolerance)
      {
        ++result.grazing;
        continue;
      }
      if (result.unexplained++ == 0)
      {
        result.firstUnexplained = format("pixel ", x, ",", y, " at ", pWs.x, " ", pWs.y, " ", pWs.z, ": GPU ",
          count.at(x, y), ", crossings ", expected, ", n . (p' - p) ", glm::dot(nWs, counted - pWs));
      }
    }
  }
  const auto found = frame.techniqueStatistics.find("cut_short_pixels");
  result.cutShortPixels = found == frame.techniqueStatistics.end() ? -1.0 : found->second;
  return result;
}

void expectEveryCrackFlagged(const std::string& label, const CrackCount& c)
{
  std::cout << "[ measured ] shadow-volume cracks, " << label << ": " << c.covered << " covered, " << c.mismatched
            << " differ from the crossing count (" << c.flaggedMismatched << " flagged, " << c.rasterAmbiguous
            << " within 1/512 pixel of a volume face, " << c.grazing << " counted point within 1e-6 radii of its surface, "
            << c.unexplained << " unexplained), " << c.negative << " negative, " << c.flagged
            << " flagged in all, cut_short_pixels " << c.cutShortPixels << "\n";
  EXPECT_EQ(c.unexplained, 0) << label << ": first " << c.firstUnexplained;
  EXPECT_LE(c.negative, c.flagged) << label << ": a negative count must be flagged";
  EXPECT_EQ(c.cutShortPixels, static_cast<double>(c.flagged)) << label;
  EXPECT_LE(c.mismatched, c.covered / 1000 + 3) << label;
}

TEST(ShadowVolumeCracks, GroundRowOfTheRandomStackAt96)
{
  // The ground alone casting under a light at y = 4.789454: at 96^2 the camera rays of image row 32 run (to float
  // rounding) in the plane of the side quad over the ground's far edge. Before the fix all 96 pixels read -1.
  for (const std::string offset : { "receiver_offset=1e-5", "receiver_offset=1e-6" })
  {
    const Scene scene = loadScene(test::datasetPath("stacked-occluders"),
      { "/lights/0/center/1=4.789454", "/objects/1/cast_shadows=false", "/objects/2/cast_shadows=false" });
    const CrackCount c = countCracks(scene, renderShadowVolume(scene, 96, 96, { offset }));
    expectEveryCrackFlagged("ground row, " + offset, c);
    EXPECT_EQ(c.mismatched, 0) << offset;
    EXPECT_EQ(c.flagged, 0) << offset;
  }
}

// Eighteen seeded scenes with a tilted meshed 16-hole plate, boxes and spheres under a point light, rendered at 96^2,
// 112^2 and 128^2 in turn; two tests of nine each (5-11 s each on llvmpipe, 2 cores).
void expectPlateScenesFlagged(int first, int last)
{
  std::mt19937 generator(27);
  const std::string mask = test::sixteenHoleMaskPng("sixteen-holes.png");
  for (int k = 0; k <= last; ++k)
  {
    const Scene scene = randomPlateScene(generator, mask); // drawn for every k: scene k is the same in both tests
    if (k < first)
    {
      continue;
    }
    const int size = 96 + 16 * (k % 3);
    expectEveryCrackFlagged(format("perforated plate scene ", k, " at ", size, "^2"),
      countCracks(scene, renderShadowVolume(scene, size, size)));
  }
}

TEST(ShadowVolumeCracks, RandomStacksAndPerforatedPlates0To8)
{
  // Three random 3-stacks of rectangles (PenumbraWedgeGpu's generator), then plate scenes 0-8.
  std::mt19937 stacks(2002);
  for (int k = 0; k < 3; ++k)
  {
    const Scene scene = loadScene(test::datasetPath("stacked-occluders"), test::randomRectangleStack(stacks, 3));
    expectEveryCrackFlagged("random 3-stack " + std::to_string(k), countCracks(scene, renderShadowVolume(scene, 96, 96)));
  }
  expectPlateScenesFlagged(0, 8);
}

TEST(ShadowVolumeCracks, PerforatedPlates9To17)
{
  expectPlateScenesFlagged(9, 17);
}

} // namespace
} // namespace sl
