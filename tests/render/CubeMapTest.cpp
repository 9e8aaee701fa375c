// Cube-map shadows for point lights (survey §2, lightspace/CubeFaces.h) end to end on llvmpipe:
//   - the GPU's per-pixel face (buffer `cube_face`) against the CPU twin cubeFaceOf, pixel by pixel, on wall-ring (a
//     point light inside a ring of walls) and on random configurations; the sampling error of each pixel's face;
//   - hard and pcf visibility against their CPU twins run on each pixel's face map (partitionedReference), and hard
//     against the exact ray: misclassified pixels only along shadow edges;
//   - the face seams: a lit ground crossing them shows no acne, a shadow crossing them neither leaks nor jumps (the
//     pixels on both sides of a seam against the twin and the exact ray);
//   - cube_map=auto keeps one map where it covers the receivers (sphere-point unchanged), =on splits it anyway.
#include "support/RayCaster.h"
#include "support/TestSupport.h"
#include "core/Error.h"
#include "lightspace/CubeFaces.h"
#include "lightspace/PartitionViews.h"
#include "lightspace/ShadowMapMath.h"
#include "scene/RandomScenes.h"
#include "scene/Scene.h"
#include "techniques/ProbeSupport.h"
#include "techniques/hard/HardTechnique.h"
#include "techniques/pcf/PcfTechnique.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <random>
#include <vector>

namespace sl
{
namespace
{

// A float evaluation of the dominant axis may differ from the double twin's where the two largest |d| components
// are within 1e-5 (relative) of each other: on a seam.
bool onCubeSeam(const PartitionSet& faces, const glm::dvec3& pWs)
{
  glm::dvec3 size = glm::abs(pWs - faces.lightCenterWs);
  std::sort(&size[0], &size[0] + 3);
  return size[2] - size[1] < 1e-5 * std::max(size[2], 1.0);
}

struct FaceAgreement
{
  int covered = 0, seam = 0, mismatched = 0, notOwned = 0;
  std::vector<int> perFace = std::vector<int>(kCubeFaceCount, 0);
  std::string firstMismatch;
};

FaceAgreement compareFaces(const FrameResult& frame)
{
  const PartitionSet& faces = *frame.partitions;
  const ImageF& cubeFace = frame.find("cube_face")->image;
  const ImageF& position = frame.find("position")->image;
  const ImageF& coverage = frame.find("coverage")->image;
  FaceAgreement agreement;
  for (int y = 0; y < cubeFace.height; ++y)
  {
    for (int x = 0; x < cubeFace.width; ++x)
    {
      const int gpu = static_cast<int>(cubeFace.at(x, y));
      if (coverage.at(x, y) <= 0.5f)
      {
        EXPECT_EQ(gpu, -1) << "uncovered pixel " << x << "," << y;
        continue;
      }
      ++agreement.covered;
      const glm::dvec3 pWs = test::vec3At(position, x, y);
      const int cpu = cubeFaceOf(faces, pWs);
      if (gpu >= 0)
      {
        ++agreement.perFace.at(static_cast<std::size_t>(gpu));
      }
      // The view the twin selects owns the point (its map was fitted to it).
      const ViewSelection selection = selectView(faces, frame.camera, pWs);
      if (cpu >= 0 && !ownerRegionHolds(faces.ownerPlanes[static_cast<std::size_t>(selection.primary)], pWs))
      {
        ++agreement.notOwned;
      }
      if (onCubeSeam(faces, pWs))
      {
        ++agreement.seam;
        continue;
      }
      if (gpu != cpu && agreement.mismatched++ == 0)
      {
        agreement.firstMismatch = format("pixel ", x, ",", y, " gpu ", gpu, " cpu ", cpu);
      }
    }
  }
  return agreement;
}

TEST(CubeMapGpu, FaceSelectionMatchesTheCpuTwinPixelByPixel)
{
  const Scene scene = test::loadDataset("wall-ring");
  const FrameResult frame = test::renderDataset(scene, "hard", 96, 96, { "shadow_map_size=256" });
  ASSERT_TRUE(frame.partitions.has_value());
  ASSERT_EQ(frame.partitions->kind, PartitionKind::CubeFaces);
  EXPECT_EQ(frame.find("cascade"), nullptr);
  EXPECT_EQ(frame.find("cube_face")->kind, BufferKind::Categorical);
  EXPECT_EQ(frame.find("cube_face")->categoryLabels.size(), 6u);
  const FaceAgreement agreement = compareFaces(frame);
  std::string counts;
  for (int face = 0; face < kCubeFaceCount; ++face)
  {
    counts += format(" ", cubeFaceName(face), " ", agreement.perFace[static_cast<std::size_t>(face)]);
  }
  std::cout << "[ measured ] wall-ring 96x96: " << agreement.covered << " covered pixels, per face" << counts << "; "
            << agreement.seam << " on a seam, " << agreement.mismatched << " GPU != CPU; "
            << frame.partitions->viewCount() << " face maps\n";
  EXPECT_EQ(agreement.mismatched, 0) << agreement.firstMismatch;
  EXPECT_EQ(agreement.notOwned, 0);
  EXPECT_LT(agreement.seam, agreement.covered / 100 + 1);
  // The ground below the light (-y) and the walls and ground around it (+-x, +-z) are all read.
  for (const int face : { 0, 1, 3, 4, 5 })
  {
    EXPECT_GT(agreement.perFace[static_cast<std::size_t>(face)], 50) << cubeFaceName(face);
  }
  // The sampling-error buffers are each pixel's own face's (survey Eq. 2 with that face's matrix).
  const ImageF& ratioT = frame.find("texel_ratio_t")->image;
  const ImageF& ratioS = frame.find("texel_ratio_s")->image;
  int checked = 0;
  for (int y = 0; y < ratioT.height; ++y)
  {
    for (int x = 0; x < ratioT.width; ++x)
    {
      if (ratioT.at(x, y) <= 0.0f)
      {
        continue;
      }
      const glm::dvec3 pWs = test::vec3At(frame.find("position")->image, x, y);
      const LightView& view =
        frame.partitions->views[static_cast<std::size_t>(selectView(*frame.partitions, frame.camera, pWs).primary)];
      const SamplingError error = samplingError(
        frame.camera, view, x + 0.5, y + 0.5, pWs, test::vec3At(frame.find("normal")->image, x, y));
      EXPECT_NEAR(ratioT.at(x, y), error.texelRatioT, 1e-5 * error.texelRatioT) << x << "," << y;
      EXPECT_NEAR(ratioS.at(x, y), error.texelRatioS, 1e-5 * error.texelRatioS) << x << "," << y;
      ++checked;
    }
  }
  EXPECT_GT(checked, 5000);
  for (int k = 0; k < frame.partitions->viewCount(); ++k)
  {
    EXPECT_GT(frame.partitions->views[static_cast<std::size_t>(k)].receiverSampleCount, 0) << k;
    EXPECT_EQ(test::lightSpaceArray(frame, "shadow_map_depth" + partitionViewSuffix(*frame.partitions, k)).width, 256);
  }
  test::expectFiniteBuffersAndVisibilityInRange(frame, "wall-ring hard cube");
}

struct CubeVisibilityAgreement
{
  int evaluated = 0, ambiguous = 0, mismatched = 0;
  double maxDifference = 0.0;
  std::string firstMismatch;
};

// GPU visibility against the twin on each pixel's face map, at the pixels `include` accepts.
CubeVisibilityAgreement compareCubeVisibility(const FrameResult& frame, const Scene& scene,
  const std::string& technique, const std::function<bool(int, int)>& include = {})
{
  const std::vector<ShadowMapInputs> inputs = viewInputsOf(frame, scene);
  const ImageF& visibility = frame.find("visibility")->image;
  const BiasSettings bias = HardSettings::from(frame.parameters).bias;
  const ShadowMapTwin twin = [&](const ShadowMapInputs& in, int x, int y, ProbeRecorder*) {
    return technique == "hard" ? hardReference(in, bias, x, y) : pcfReference(in, frame.parameters, x, y);
  };
  const double tolerance = technique == "hard" ? 0.0 : 1e-5;
  CubeVisibilityAgreement agreement;
  for (int y = 0; y < visibility.height; ++y)
  {
    for (int x = 0; x < visibility.width; ++x)
    {
      if (include && !include(x, y))
      {
        continue;
      }
      const ReferenceSample cpu = partitionedReference(frame, inputs, x, y, twin);
      if (!cpu.evaluated)
      {
        continue;
      }
      ++agreement.evaluated;
      if (!ambiguityOf(cpu).empty() || onCubeSeam(*frame.partitions, test::vec3At(inputs.front().position, x, y)))
      {
        ++agreement.ambiguous;
        continue;
      }
      const double difference = std::abs(visibility.at(x, y) - cpu.visibility);
      agreement.maxDifference = std::max(agreement.maxDifference, difference);
      if (difference > tolerance && agreement.mismatched++ == 0)
      {
        agreement.firstMismatch = format("pixel ", x, ",", y, " gpu ", visibility.at(x, y), " cpu ", cpu.visibility);
      }
    }
  }
  return agreement;
}

// Whether every evaluated pixel within `radius` of (x, y) has the exact value `value`.
bool exactUniformAround(const ImageF& exact, int x, int y, int radius, float value)
{
  for (int dy = -radius; dy <= radius; ++dy)
  {
    for (int dx = -radius; dx <= radius; ++dx)
    {
      const int u = std::clamp(x + dx, 0, exact.width - 1), v = std::clamp(y + dy, 0, exact.height - 1);
      if (exact.at(u, v) >= 0.0f && exact.at(u, v) != value)
      {
        return false;
      }
    }
  }
  return true;
}

TEST(CubeMapGpu, HardAndPcfOnWallRingMatchTheTwinAndTheExactRay)
{
  const Scene scene = test::loadDataset("wall-ring");
  const test::RayCaster rays(scene);
  for (const std::string technique : { "hard", "pcf" })
  {
    const FrameResult frame = test::renderDataset(scene, technique, 96, 96, { "shadow_map_size=512" });
    ASSERT_TRUE(frame.partitions.has_value()) << technique;
    const CubeVisibilityAgreement twin = compareCubeVisibility(frame, scene, technique);
    const ImageF exact = test::exactPointVisibility(frame, scene, rays);
    const ImageF& visibility = frame.find("visibility")->image;
    int evaluated = 0, lit = 0, shadowed = 0, misclassified = 0, awayFromEdges = 0;
    for (int y = 0; y < exact.height; ++y)
    {
      for (int x = 0; x < exact.width; ++x)
      {
        const float value = exact.at(x, y);
        if (value < 0.0f)
        {
          continue;
        }
        ++evaluated;
        (value > 0.5f ? lit : shadowed) += 1;
        const bool wrong = std::abs(visibility.at(x, y) - value) > 0.5f;
        misclassified += wrong ? 1 : 0;
        // Two pixels from any exact shadow edge, the map's answer is the ray's.
        awayFromEdges += wrong && exactUniformAround(exact, x, y, 2, value) ? 1 : 0;
      }
    }
    std::cout << "[ measured ] wall-ring " << technique << " 96x96, 6 faces of 512^2: twin " << twin.evaluated
              << " evaluated, " << twin.ambiguous << " ambiguous, " << twin.mismatched
              << " mismatched (max |GPU - CPU| " << twin.maxDifference << "); exact ray: " << lit << " lit, " << shadowed << " shadowed, " << misclassified
              << " misclassified, " << awayFromEdges << " of them 2+ pixels from an edge\n";
    EXPECT_EQ(twin.mismatched, 0) << technique << ": " << twin.firstMismatch;
    EXPECT_LE(twin.ambiguous, twin.evaluated / 50) << technique;
    EXPECT_GT(lit, 1500) << technique;
    EXPECT_GT(shadowed, 1500) << technique;
    EXPECT_EQ(awayFromEdges, 0) << technique;
    EXPECT_LT(misclassified, evaluated / 30) << technique;
  }
}

TEST(CubeMapGpu, NoAcneLeakOrJumpAcrossFaceSeams)
{
  // A point light 2 above a 16 x 16 ground: the ground crosses the seams between -y and the side faces on the lines
  // |x| = 2 and |z| = 2. A bar at height 1 (x from -1 to 4, z from 0.2 to 1.6) casts a shadow from x = -2 to 8, z =
  // 0.4 to 3.2, across the seam x = 2 and the diagonal one between +x and +z; a box floating 0.4 above the ground
  // (no contact, whose PCF darkening is not a seam's) shadows z = -2 to -6, across the seam z = -2. Pixels next to a
  // seam (a 3 x 3 neighbourhood
  // with two faces) read two different maps on either side: there the GPU equals the twin, the lit ground is lit (no
  // acne), the shadow is dark (no leak): the exact ray's answer holds a filter's reach (2 pixels for hard, 4 for pcf's
  // 3-texel kernel) from its edges.
  const std::string text = R"({
    "camera": { "position": [0, 13, 7], "focal_point": [0, 0, 0], "view_angle": 60 },
    "lights": [ { "type": "point", "center": [0, 2, 0] } ],
    "objects": [
      { "primitive": "quad", "center": [0, 0, 0], "size": [16, 16], "normal": [0, 1, 0], "up": [0, 0, -1] },
      { "primitive": "box", "center": [1.5, 1, 0.9], "size": [5, 0.1, 1.4] },
      { "primitive": "box", "center": [-0.5, 0.8, -2], "size": [0.8, 0.8, 0.8] }
    ] })";
  const Scene scene = parseScene(text, "cube seams (cube map test)", test::sourceDir());
  const test::RayCaster rays(scene);
  for (const std::string technique : { "hard", "pcf" })
  {
    const FrameResult frame = test::renderDataset(scene, technique, 128, 96, { "shadow_map_size=256", "cube_map=on" });
    ASSERT_TRUE(frame.partitions.has_value()) << technique;
    const ImageF& cubeFace = frame.find("cube_face")->image;
    const auto nearSeam = [&](int x, int y) {
      const float face = cubeFace.at(x, y);
      for (int dy = -1; dy <= 1; ++dy)
      {
        for (int dx = -1; dx <= 1; ++dx)
        {
          const int u = std::clamp(x + dx, 0, cubeFace.width - 1), v = std::clamp(y + dy, 0, cubeFace.height - 1);
          if (face >= 0.0f && cubeFace.at(u, v) >= 0.0f && cubeFace.at(u, v) != face)
          {
            return true;
          }
        }
      }
      return false;
    };
    const CubeVisibilityAgreement twin = compareCubeVisibility(frame, scene, technique, nearSeam);
    const ImageF exact = test::exactPointVisibility(frame, scene, rays);
    const ImageF& visibility = frame.find("visibility")->image;
    int litSeam = 0, acne = 0, shadowSeam = 0, leaks = 0, misclassifiedSeam = 0;
    for (int y = 0; y < exact.height; ++y)
    {
      for (int x = 0; x < exact.width; ++x)
      {
        if (exact.at(x, y) < 0.0f || !nearSeam(x, y))
        {
          continue;
        }
        const float value = exact.at(x, y);
        misclassifiedSeam += std::abs(visibility.at(x, y) - value) > 0.5f ? 1 : 0;
        if (!exactUniformAround(exact, x, y, technique == "hard" ? 2 : 4, value))
        {
          continue;
        }
        if (value > 0.5f)
        {
          ++litSeam;
          acne += visibility.at(x, y) < 1.0f ? 1 : 0;
        }
        else
        {
          ++shadowSeam;
          leaks += visibility.at(x, y) > 0.0f ? 1 : 0;
        }
      }
    }
    std::cout << "[ measured ] cube seams " << technique << " 128x96, faces of 256^2: " << twin.evaluated
              << " pixels next to a seam, twin " << twin.mismatched << " mismatched (max |GPU - CPU| "
              << twin.maxDifference << ", " << twin.ambiguous << " ambiguous); a filter's reach from a shadow edge: "
              << litSeam
              << " lit (" << acne << " with acne), " << shadowSeam << " shadowed (" << leaks << " leaking); "
              << misclassifiedSeam << " misclassified next to a seam\n";
    EXPECT_EQ(twin.mismatched, 0) << technique << ": " << twin.firstMismatch;
    EXPECT_GT(twin.evaluated, 150) << technique;
    EXPECT_GT(litSeam, 100) << technique;
    EXPECT_GT(shadowSeam, 30) << technique;
    EXPECT_EQ(acne, 0) << technique;
    EXPECT_EQ(leaks, 0) << technique;
    EXPECT_LT(misclassifiedSeam, twin.evaluated / 15) << technique;
  }
}

TEST(CubeMapGpu, RandomConfigurationsMatchTheCpuTwin)
{
  // Differential seeds' scenes (ground, occluders, camera) under a point light drawn from the same seed, low over
  // the ground among the occluders (receivers on every side of it), with cube_map=on.
  for (const std::uint64_t seed : { 3u, 8u, 21u })
  {
    const RandomScene random = randomScene(seed, 80);
    Scene scene = parseScene(random.json, "cube seed " + std::to_string(seed), ".");
    std::mt19937 generator(static_cast<unsigned>(seed));
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const Bounds bounds = scene.bounds();
    Light& light = scene.lights.front();
    light.type = LightType::Point;
    const glm::dvec3 extent = bounds.max - bounds.min;
    light.center = glm::dvec3(bounds.min.x + extent.x * (0.3 + 0.4 * unit(generator)),
      bounds.min.y + std::max(0.05, extent.y) * (0.2 + 0.6 * unit(generator)),
      bounds.min.z + extent.z * (0.3 + 0.4 * unit(generator)));
    const std::vector<std::string> settings = { "shadow_map_size=" + std::to_string(128 << (seed % 2)), "cube_map=on",
      "kernel_texels=" + std::to_string(3 + 2 * static_cast<int>(seed % 3)) };
    for (const std::string technique : { "hard", "pcf" })
    {
      std::vector<std::string> used = settings;
      if (technique == "hard")
      {
        used.pop_back(); // kernel_texels is pcf's
      }
      const FrameResult frame = test::renderDataset(scene, technique, 80, 64, used);
      ASSERT_TRUE(frame.partitions.has_value());
      const FaceAgreement faces = compareFaces(frame);
      const CubeVisibilityAgreement twin = compareCubeVisibility(frame, scene, technique);
      int facesRead = 0;
      for (const int count : faces.perFace)
      {
        facesRead += count > 0 ? 1 : 0;
      }
      std::cout << "[ measured ] seed " << seed << " " << technique << " " << test::caseLabel("", used) << ", light "
                << light.center.x << "," << light.center.y << "," << light.center.z << ": " << facesRead
                << " faces read, " << faces.mismatched << " face mismatches; twin " << twin.evaluated
                << " evaluated, " << twin.ambiguous << " ambiguous, " << twin.mismatched
                << " mismatched (max |GPU - CPU| " << twin.maxDifference << ")\n";
      EXPECT_EQ(faces.mismatched, 0) << random.summary << ": " << faces.firstMismatch;
      EXPECT_GE(facesRead, 2) << random.summary;
      EXPECT_GT(twin.evaluated, 500) << random.summary;
      EXPECT_EQ(twin.mismatched, 0) << random.summary << ": " << twin.firstMismatch;
      EXPECT_LE(twin.ambiguous, twin.evaluated / 50) << random.summary;
    }
  }
}

TEST(CubeMapGpu, AutoKeepsOneMapWhereItCoversTheReceivers)
{
  // sphere-point's light sees its receivers within one map: cube_map=auto renders exactly as cube_map=off (no
  // partitions, the same visibility); cube_map=on splits the same frame into the faces that own receivers.
  const Scene scene = test::loadDataset("sphere-point");
  const FrameResult automatic = test::renderDataset(scene, "pcf", 64, 64, { "shadow_map_size=256" });
  const FrameResult off = test::renderDataset(scene, "pcf", 64, 64, { "shadow_map_size=256", "cube_map=off" });
  EXPECT_FALSE(automatic.partitions.has_value());
  EXPECT_EQ(automatic.find("cube_face"), nullptr);
  EXPECT_EQ(automatic.find("visibility")->image.data, off.find("visibility")->image.data);
  const FrameResult on = test::renderDataset(scene, "pcf", 64, 64, { "shadow_map_size=256", "cube_map=on" });
  ASSERT_TRUE(on.partitions.has_value());
  EXPECT_GE(on.partitions->viewCount(), 1);
  EXPECT_LT(on.partitions->viewCount(), 6) << "sphere-point has nothing above its light";
  EXPECT_EQ(compareFaces(on).mismatched, 0);
  // A spot light is refused in one line naming the setting, before any GL.
  const Scene spot = test::stackedOccludersUnder(
    R"({ "type": "spot", "center": [0, 4, 0], "normal": [0, -1, 0], "cone_angle_deg": 40 })");
  try
  {
    test::renderDataset(spot, "hard", 32, 32, { "cube_map=on" });
    FAIL() << "cube_map=on under a spot light was accepted";
  }
  catch (const InputError& error)
  {
    EXPECT_EQ(std::string(error.what()).rfind("--set cube_map=on: ", 0), 0u) << error.what();
  }
}

} // namespace
} // namespace sl
