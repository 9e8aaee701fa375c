// depth_layer = midpoint and dual (survey §5, "depth biasing"): the peeled layers and the combined map against their
// CPU twin (layerComparisonDepth, double) on read-back buffers, hard's visibility against its twin on the combined
// map, and acne and light leaks against the exact single ray to the light's centre (test::exactPointVisibility).
#include "core/Error.h"
#include "scene/RandomScenes.h"
#include "scene/Scene.h"
#include "support/RayCaster.h"
#include "support/TestSupport.h"
#include "techniques/ShadowMapParameters.h"
#include "techniques/ShadowMapReference.h"
#include "techniques/hard/HardTechnique.h"
#include "techniques/pcf/PcfTechnique.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>

namespace sl
{
namespace
{

// Per texel, the combined map the GPU stored against layerComparisonDepth of the two layers it stored; and the second
// layer strictly behind the first wherever the first holds a caster. Returns the texels with a caster.
int expectCombinedMapMatchesTwin(const FrameResult& frame, ShadowMapDepthLayer layer, double dualMaxOffsetTexels,
  const std::string& label)
{
  const ImageF& first = test::lightSpaceArray(frame, "shadow_map_first_depth");
  const ImageF& second = test::lightSpaceArray(frame, "shadow_map_second_depth");
  const ImageF& combined = test::lightSpaceArray(frame, "shadow_map_depth");
  const LightView& view = *frame.lightView;
  const ImageF twin = layerComparisonMap(layer, first, second, view, dualMaxOffsetTexels);
  const double empty = 2.0 * view.farDepth;
  int casterTexels = 0;
  int mismatches = 0;
  int notBehind = 0;
  double worst = 0.0;
  for (int y = 0; y < first.height; ++y)
  {
    for (int x = 0; x < first.width; ++x)
    {
      const double difference = std::abs(static_cast<double>(combined.at(x, y)) - twin.at(x, y));
      worst = std::max(worst, difference);
      const bool mismatch = difference > 1e-6 * std::max(1.0, std::abs(static_cast<double>(twin.at(x, y))));
      if (mismatch && mismatches < 3)
      {
        std::cout << "  texel " << x << "," << y << ": first " << first.at(x, y) << " second " << second.at(x, y)
                  << " stored " << combined.at(x, y) << " twin " << twin.at(x, y) << "\n";
      }
      mismatches += mismatch ? 1 : 0;
      if (first.at(x, y) < 0.999 * empty)
      {
        ++casterTexels;
        notBehind += second.at(x, y) > first.at(x, y) ? 0 : 1;
      }
    }
  }
  std::cout << "[ measured ] " << label << ": " << casterTexels << " caster texels, combined map vs twin worst "
            << worst << ", mismatches " << mismatches << ", second layer not behind the first " << notBehind << "\n";
  EXPECT_EQ(mismatches, 0) << label;
  EXPECT_EQ(notBehind, 0) << label;
  return casterTexels;
}

// hard's GPU visibility against hardReference (double) on the frame's read-back buffers, the combined map included;
// pixels within float rounding of a decision (relative depth margin < 1e-5, a tap within 1e-3 texel of an edge) are
// left out. Returns the pixels compared.
int expectHardMatchesTwin(const FrameResult& frame, const Scene& scene, const std::string& label)
{
  const ShadowMapInputs inputs = test::shadowMapInputs(frame, scene);
  const BiasSettings bias = biasSettings(frame.parameters);
  const ImageF& visibility = frame.find("visibility")->image;
  int compared = 0;
  int disagreements = 0;
  for (int y = 0; y < visibility.height; ++y)
  {
    for (int x = 0; x < visibility.width; ++x)
    {
      const ReferenceSample sample = hardReference(inputs, bias, x, y);
      if (sample.evaluated && (sample.depthMargin < 1e-5 || sample.texelEdgeMargin < 1e-3))
      {
        continue;
      }
      ++compared;
      disagreements += std::abs(sample.visibility - visibility.at(x, y)) > 1e-3 ? 1 : 0;
    }
  }
  std::cout << "[ measured ] " << label << ": hard GPU vs twin, " << disagreements << " of " << compared
            << " pixels differ\n";
  EXPECT_EQ(disagreements, 0) << label;
  return compared;
}

struct RayErrors
{
  int acne = 0;  // shadowed on the GPU, lit by the exact ray
  int leaks = 0; // lit on the GPU, shadowed by the exact ray
  int rayLit = 0;
  int rayShadowed = 0;
};

// Acne and leaks against the exact ray away from its shadow boundaries (every pixel within `radius` has the same ray
// answer), where a map's discretisation cannot explain a difference; pixels whose normal is within `terminatorCosine`
// of perpendicular to the light are left out (the smooth normal and the flat facets disagree there).
RayErrors rayErrors(const FrameResult& frame, const Scene& scene, int radius, double terminatorCosine = 0.0)
{
  const test::RayCaster rays(scene);
  const ImageF exact = test::exactPointVisibility(frame, scene, rays);
  const ImageF& visibility = frame.find("visibility")->image;
  const ImageF& position = frame.find("position")->image;
  const ImageF& normal = frame.find("normal")->image;
  RayErrors errors;
  for (int y = 0; y < exact.height; ++y)
  {
    for (int x = 0; x < exact.width; ++x)
    {
      const float ray = exact.at(x, y);
      if (ray < 0.0f)
      {
        continue;
      }
      bool uniform = true;
      for (int dy = -radius; dy <= radius && uniform; ++dy)
      {
        for (int dx = -radius; dx <= radius; ++dx)
        {
          const int nx = x + dx;
          const int ny = y + dy;
          if (nx >= 0 && ny >= 0 && nx < exact.width && ny < exact.height && exact.at(nx, ny) >= 0.0f &&
            exact.at(nx, ny) != ray)
          {
            uniform = false;
            break;
          }
        }
      }
      const glm::dvec3 pWs = test::vec3At(position, x, y);
      const glm::dvec3 nWs = test::vec3At(normal, x, y);
      if (!uniform || std::abs(glm::dot(nWs, directionToLight(scene.lights[0], pWs))) < terminatorCosine)
      {
        continue;
      }
      errors.rayLit += ray == 1.0f ? 1 : 0;
      errors.rayShadowed += ray == 0.0f ? 1 : 0;
      errors.acne += (ray == 1.0f && visibility.at(x, y) < 0.5f) ? 1 : 0;
      errors.leaks += (ray == 0.0f && visibility.at(x, y) > 0.5f) ? 1 : 0;
    }
  }
  return errors;
}

const std::vector<std::string> kNoBias = { "bias_constant_texels=0", "bias_slope_texels=0" };

std::vector<std::string> withSettings(std::vector<std::string> settings, const std::vector<std::string>& more)
{
  settings.insert(settings.end(), more.begin(), more.end());
  return settings;
}

} // namespace

TEST(DepthLayers, CombinedMapAndHardMatchTheirTwins)
{
  for (const std::string dataset : { "contact", "grazing", "stacked-occluders", "bunny" })
  {
    const Scene scene = test::loadDataset(dataset);
    for (const auto& [layer, name] : { std::pair{ ShadowMapDepthLayer::Midpoint, "midpoint" }, std::pair{ ShadowMapDepthLayer::Dual, "dual" } })
    {
      const std::vector<std::string> settings =
        withSettings({ "shadow_map_size=256", std::string("depth_layer=") + name, "dual_max_offset_texels=3" }, kNoBias);
      const FrameResult frame = test::renderDataset(scene, "hard", 96, 80, settings);
      const std::string label = dataset + " " + name;
      EXPECT_GT(expectCombinedMapMatchesTwin(frame, layer, 3.0, label), 100) << label;
      EXPECT_GT(expectHardMatchesTwin(frame, scene, label), 96 * 80 / 4) << label;
      test::expectFiniteBuffersAndVisibilityInRange(frame, label);
    }
  }
}

// Random generated scenes (scene/RandomScenes.h: quads, boxes, perforated quads, area lights sampled from their
// centre) with random depth_layer (midpoint, dual, polygon_id), offset and map size: the same twins (hard's id test for
// polygon_id).
TEST(DepthLayers, RandomScenesMatchTheTwins)
{
  std::mt19937_64 random(20261204);
  for (std::uint64_t seed = 1; seed <= 9; ++seed)
  {
    const RandomScene generated = randomScene(seed, 80);
    const Scene scene = parseScene(generated.json, "random scene", test::sourceDir());
    const double draw = test::uniform(random, 0.0, 1.0);
    const bool dual = draw < 0.4;
    const bool ids = draw >= 0.8; // polygon_id: the id twin instead of the combined map
    const double offset = std::round(test::uniform(random, 0.0, 16.0) * 4.0) / 4.0;
    const int mapSize = 64 << static_cast<int>(test::uniform(random, 0.0, 3.0));
    const std::vector<std::string> settings = { "shadow_map_size=" + std::to_string(mapSize),
      std::string("depth_layer=") + (ids ? "polygon_id" : dual ? "dual" : "midpoint"),
      "dual_max_offset_texels=" + std::to_string(offset),
      "bias_constant_texels=" + std::to_string(test::uniform(random, 0.0, 1.0)), "bias_slope_texels=0" };
    const FrameResult frame =
      test::renderDataset(scene, "hard", scene.camera.resolution.x, scene.camera.resolution.y, settings);
    const std::string label = "seed " + std::to_string(seed) + " (" + generated.summary + ") " + settings[1] +
      " offset " + std::to_string(offset) + " map " + std::to_string(mapSize);
    if (!ids)
    {
      expectCombinedMapMatchesTwin(frame, dual ? ShadowMapDepthLayer::Dual : ShadowMapDepthLayer::Midpoint, offset, label);
    }
    expectHardMatchesTwin(frame, scene, label);
    test::expectFiniteBuffersAndVisibilityInRange(frame, label);
  }
}

// The peeled second layer of a box on the ground (closed, convex) is its bottom face, the back face a second-depth map
// (caster_faces = back, Wang & Molnar 1994) stores at the same texel: two different passes, one depth.
TEST(DepthLayers, PeeledSecondLayerOfAClosedConvexCasterIsItsBackFace)
{
  const Scene scene = test::loadDataset("contact");
  const std::vector<std::string> common = { "shadow_map_size=256", "bias_constant_texels=0", "bias_slope_texels=0" };
  const FrameResult layered = test::renderDataset(scene, "hard", 96, 80, withSettings(common, { "depth_layer=midpoint" }));
  const FrameResult backFaces = test::renderDataset(scene, "hard", 96, 80, withSettings(common, { "caster_faces=back" }));
  ASSERT_EQ(layered.lightView->clipFromWorld, backFaces.lightView->clipFromWorld);
  const ImageF& first = test::lightSpaceArray(layered, "shadow_map_first_depth");
  const ImageF& second = test::lightSpaceArray(layered, "shadow_map_second_depth");
  const ImageF& back = test::lightSpaceArray(backFaces, "shadow_map_depth");
  const double empty = 2.0 * layered.lightView->farDepth;
  int compared = 0;
  int differ = 0;
  for (int y = 0; y < first.height; ++y)
  {
    for (int x = 0; x < first.width; ++x)
    {
      // A texel whose first layer is the box's top (in front of its back face) and whose back face exists.
      if (back.at(x, y) < 0.999 * empty && first.at(x, y) < back.at(x, y) - 1e-4)
      {
        ++compared;
        differ += std::abs(second.at(x, y) - back.at(x, y)) > 1e-5 * back.at(x, y) ? 1 : 0;
      }
    }
  }
  std::cout << "[ measured ] contact: peeled second layer vs back-face map, " << differ << " of " << compared
            << " box texels differ\n";
  EXPECT_GT(compared, 50);
  EXPECT_LE(differ, compared / 50); // the box's silhouette texels, where the two rasterizations may pick other faces
}

// Woo 1992's claim (survey §5: "to remove depth biasing"): with no bias at all, the midpoint map has (next to) no acne
// on planar and convex receivers, where the nearest-depth map without a bias is covered in it.
TEST(DepthLayers, MidpointRemovesAcneWithoutABias)
{
  for (const std::string dataset : { "grazing", "contact", "planar-occluder", "sphere-point" })
  {
    const Scene scene = test::loadDataset(dataset);
    const std::vector<std::string> map = { "shadow_map_size=512" };
    const RayErrors nearest =
      rayErrors(test::renderDataset(scene, "hard", 128, 112, withSettings(map, kNoBias)), scene, 2, 0.1);
    const RayErrors midpoint = rayErrors(
      test::renderDataset(scene, "hard", 128, 112, withSettings(map, withSettings(kNoBias, { "depth_layer=midpoint" }))),
      scene, 2, 0.1);
    const RayErrors biased = rayErrors(test::renderDataset(scene, "hard", 128, 112, map), scene, 2, 0.1);
    std::cout << "[ measured ] " << dataset << " (map 512, 128 x 112, away from boundaries): acne pixels nearest "
              << "no bias " << nearest.acne << ", midpoint no bias " << midpoint.acne << ", nearest default bias "
              << biased.acne << " (of " << nearest.rayLit << " lit); leaks " << nearest.leaks << " / " << midpoint.leaks
              << " / " << biased.leaks << " (of " << nearest.rayShadowed << " shadowed)\n";
    EXPECT_LE(midpoint.acne, nearest.rayLit / 200) << dataset;
    EXPECT_LE(midpoint.leaks, biased.leaks + nearest.rayShadowed / 200) << dataset;
    if (dataset == "grazing")
    {
      EXPECT_GT(nearest.acne, nearest.rayLit / 20) << "the unbiased nearest-depth map should show acne";
    }
  }
}

// A thick gap between the layers (survey §5: "huge shadow caster thickness"): an open roof far above the ground with a
// small box under it, in its shadow. Where a texel's centre misses the box, the second layer is the ground, the
// midpoint lies halfway down and the box's rim in front of it is lit: light leaks. Dual maps cap the offset past the
// roof (dual_max_offset_texels), so the box stays shadowed.
TEST(DepthLayers, DualLimitsLeaksUnderAThickGap)
{
  const Scene scene = test::sceneFromJson(
    R"({ "projection": "perspective", "position": [0.8, 1.6, 4.5], "focal_point": [0, 1.6, 0], "view_up": [0, 1, 0],
         "view_angle": 40, "resolution": [128, 112] })",
    R"({ "type": "directional", "direction": [-0.35, -1, -0.25], "intensity": 1 })",
    R"({ "primitive": "quad", "center": [0, 0, 0], "size": [8, 8], "normal": [0, 1, 0], "up": [0, 0, -1] },
       { "primitive": "quad", "center": [0.6, 4, 0.4], "size": [3.2, 3.2], "normal": [0, 1, 0], "up": [0, 0, -1] },
       { "primitive": "box", "center": [0, 3.2, 0], "size": [0.6, 0.6, 0.6] })");
  std::vector<std::string> counts;
  RayErrors errors[3];
  const char* layers[3] = { "first", "midpoint", "dual" };
  for (int k = 0; k < 3; ++k)
  {
    const FrameResult frame = test::renderDataset(scene, "hard", 128, 112,
      withSettings({ "shadow_map_size=48", std::string("depth_layer=") + layers[k], "dual_max_offset_texels=2" }, kNoBias));
    errors[k] = rayErrors(frame, scene, 1);
    std::cout << "[ measured ] thick gap, map 48, no bias, depth_layer=" << layers[k] << ": leaks " << errors[k].leaks
              << " of " << errors[k].rayShadowed << " shadowed, acne " << errors[k].acne << " of " << errors[k].rayLit
              << " lit\n";
  }
  EXPECT_GT(errors[1].leaks, 10) << "the midpoint map should leak under the thick gap";
  EXPECT_LE(errors[2].leaks, errors[1].leaks / 4) << "dual should limit the leaks";
}

// pcf over a midpoint map (both of its depth textures hold the combined depth): its grid kernel and the hardware 2x2
// comparison match pcfReference on the read-back map, and a 7-texel kernel on grazing ground without any bias keeps
// (next to) no acne, where over the nearest-depth map it shadows the lit ground.
TEST(DepthLayers, PcfKernelOverTheMidpointMap)
{
  const Scene scene = test::loadDataset("grazing");
  for (const char* filter : { "nearest", "hardware_bilinear" })
  {
    const std::vector<std::string> common =
      withSettings({ "shadow_map_size=512", "kernel_texels=7", std::string("filter=") + filter }, kNoBias);
    const FrameResult nearestFrame = test::renderDataset(scene, "pcf", 128, 112, common);
    const FrameResult midpointFrame =
      test::renderDataset(scene, "pcf", 128, 112, withSettings(common, { "depth_layer=midpoint" }));
    const ShadowMapInputs inputs = test::shadowMapInputs(midpointFrame, scene);
    const ImageF& visibility = midpointFrame.find("visibility")->image;
    const double tolerance = std::string(filter) == "nearest" ? 1e-5 : 1.0 / 128.0;
    int compared = 0;
    int differ = 0;
    for (int y = 0; y < visibility.height; ++y)
    {
      for (int x = 0; x < visibility.width; ++x)
      {
        const ReferenceSample sample = pcfReference(inputs, midpointFrame.parameters, x, y);
        if (sample.evaluated && (sample.depthMargin < 1e-5 || sample.texelEdgeMargin < 1e-3))
        {
          continue;
        }
        ++compared;
        differ += std::abs(sample.visibility - visibility.at(x, y)) > tolerance ? 1 : 0;
      }
    }
    // Acne here: lit by the exact ray, away from its boundaries, and darker than 0.5 after the kernel.
    const RayErrors nearest = rayErrors(nearestFrame, scene, 5, 0.1);
    const RayErrors midpoint = rayErrors(midpointFrame, scene, 5, 0.1);
    std::cout << "[ measured ] grazing pcf kernel 7 " << filter << ", map 512, no bias: twin differs on " << differ
              << " of " << compared << " pixels; acne nearest " << nearest.acne << ", midpoint " << midpoint.acne
              << " (of " << nearest.rayLit << " lit); leaks " << nearest.leaks << " / " << midpoint.leaks << " (of "
              << nearest.rayShadowed << " shadowed)\n";
    EXPECT_EQ(differ, 0) << filter;
    EXPECT_GT(compared, 128 * 112 / 2) << filter;
    EXPECT_GT(nearest.acne, nearest.rayLit / 20) << filter;
    EXPECT_LE(midpoint.acne, nearest.rayLit / 200) << filter;
    EXPECT_LE(midpoint.leaks, nearest.leaks + 2) << filter;
  }
}

// Polygon-id shadow maps (survey §5, Hourcade & Nicolas 1985) with hard: GPU = hardReference's id test on the read-back
// ids, and right or flagged against the exact ray: every acne or leak pixel away from the ray's shadow boundaries is one
// the `approximation` buffer marks "polygon id: several triangles per texel" (code 2). `maxUnflagged` allows for the
// pixels whose own triangle is narrower than a texel in every direction, which no neighbourhood shows.
struct PolygonIdOutcome
{
  int acne = 0;
  int leaks = 0;
  int flagged = 0;
  int unflaggedWrong = 0;
  int tested = 0;
};

PolygonIdOutcome polygonIdOutcome(const Scene& scene, const std::string& label, int mapSize)
{
  const FrameResult frame =
    test::renderDataset(scene, "hard", 128, 112, { "shadow_map_size=" + std::to_string(mapSize), "depth_layer=polygon_id" });
  test::expectFiniteBuffersAndVisibilityInRange(frame, label);
  EXPECT_GT(expectHardMatchesTwin(frame, scene, label), 128 * 112 / 4) << label;
  const test::RayCaster rays(scene);
  const ImageF exact = test::exactPointVisibility(frame, scene, rays);
  const ImageF& visibility = frame.find("visibility")->image;
  const ImageF& codes = frame.find("approximation")->image;
  PolygonIdOutcome outcome;
  for (int y = 0; y < exact.height; ++y)
  {
    for (int x = 0; x < exact.width; ++x)
    {
      const float ray = exact.at(x, y);
      if (ray < 0.0f)
      {
        continue;
      }
      ++outcome.tested;
      const bool flagged = codes.at(x, y) == 2.0f;
      outcome.flagged += flagged ? 1 : 0;
      bool uniform = true;
      for (int dy = -1; dy <= 1; ++dy)
      {
        for (int dx = -1; dx <= 1; ++dx)
        {
          const int nx = std::clamp(x + dx, 0, exact.width - 1);
          const int ny = std::clamp(y + dy, 0, exact.height - 1);
          uniform = uniform && (exact.at(nx, ny) < 0.0f || exact.at(nx, ny) == ray);
        }
      }
      const bool acne = ray == 1.0f && visibility.at(x, y) < 0.5f;
      const bool leak = ray == 0.0f && visibility.at(x, y) > 0.5f;
      outcome.acne += acne ? 1 : 0;
      outcome.leaks += leak ? 1 : 0;
      outcome.unflaggedWrong += uniform && !flagged && (acne || leak) ? 1 : 0;
    }
  }
  std::cout << "[ measured ] " << label << " polygon_id, map " << mapSize << ", 128 x 112: " << outcome.tested
            << " tested, acne " << outcome.acne << ", leaks " << outcome.leaks << ", flagged " << outcome.flagged
            << ", wrong and unflagged away from the ray's boundaries " << outcome.unflaggedWrong << "\n";
  return outcome;
}

TEST(DepthLayers, PolygonIdHasNoAcneOnConvexMeshes)
{
  for (const std::string dataset : { "contact", "sphere-point", "planar-occluder", "grazing" })
  {
    const PolygonIdOutcome outcome = polygonIdOutcome(test::loadDataset(dataset), dataset, 512);
    EXPECT_EQ(outcome.unflaggedWrong, 0) << dataset;
    EXPECT_LE(outcome.acne, outcome.flagged) << dataset;
  }
  // A random scene whose ground casts no shadow (scene/RandomScenes.h): the ground is not in the map, so its pixels
  // (id 0) keep the depth test, and right or flagged still holds.
  const RandomScene generated = randomScene(3, 80);
  const Scene openGround = parseScene(generated.json, "random scene 3", test::sourceDir());
  ASSERT_FALSE(openGround.objects.front().castShadows);
  const PolygonIdOutcome outcome = polygonIdOutcome(openGround, "random seed 3 (ground casts no shadow)", 512);
  EXPECT_EQ(outcome.unflaggedWrong, 0);
  EXPECT_LE(outcome.acne + outcome.leaks, outcome.tested / 50);
}

// The survey's failure mode: "the mechanism breaks down if more than one triangle is present per texel". The bunny's
// triangles are far smaller than a texel of a 64-texel map: most of its pixels are flagged, and wrong ones unflagged
// are the few whose whole neighbourhood is one other triangle.
TEST(DepthLayers, PolygonIdFlagsManyTrianglesPerTexelOnTheBunny)
{
  const Scene scene = test::loadDataset("bunny");
  const PolygonIdOutcome coarse = polygonIdOutcome(scene, "bunny", 64);
  const PolygonIdOutcome fine = polygonIdOutcome(scene, "bunny", 1024);
  EXPECT_GT(coarse.flagged, coarse.tested / 20);
  EXPECT_GT(coarse.acne, 0) << "the coarse map should break down on the bunny";
  EXPECT_LE(coarse.unflaggedWrong, coarse.acne / 10);
  EXPECT_LT(fine.acne, coarse.acne);
}

// caster_faces = back with a layered depth, and polygon ids with a technique that compares depths, are refused.
TEST(DepthLayers, UnsupportedCombinationsAreRefused)
{
  const Scene scene = test::loadDataset("contact");
  try
  {
    test::renderDataset(scene, "hard", 32, 32, { "caster_faces=back", "depth_layer=dual" });
    FAIL() << "expected an InputError";
  }
  catch (const std::exception& error)
  {
    EXPECT_NE(std::string(error.what()).find("depth_layer=dual"), std::string::npos) << error.what();
  }
  // pcf's shader compares depths: polygon ids are refused, naming the setting.
  try
  {
    test::renderDataset(scene, "pcf", 32, 32, { "depth_layer=polygon_id" });
    FAIL() << "expected an InputError";
  }
  catch (const InputError& error)
  {
    EXPECT_EQ(std::string(error.what()).rfind("--set depth_layer=polygon_id:", 0), 0u) << error.what();
  }
}

} // namespace sl
