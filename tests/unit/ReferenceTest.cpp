// The Embree ground truth (src/reference/) against closed forms: the visible fraction of a square or disk
// light behind a parallel square or disk occluder is one minus the overlap of the light with the
// occluder's projection through the receiver point, divided by the light's area. Receivers are synthetic
// G-buffer images of points on the plane y = 0 (normal +y); the scenes hold only the casters. CPU only.
#include "core/Error.h"
#include "reference/EmbreeScene.h"
#include "reference/LightSampler.h"
#include "reference/ReferenceRenderer.h"
#include "scene/AlphaTexture.h"
#include "scene/Primitives.h"

#include <gtest/gtest.h>

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace sl
{
namespace
{

using test::kPi;

// The standard set-up, y up: an area light of size kLightSize centred kLightHeight above the origin,
// facing down; an occluder parallel to it at kOccluderHeight, centred at kOccluderCenter (off-axis, so
// nothing is symmetric by accident); receivers on y = 0.
constexpr double kLightHeight = 4.0;
constexpr double kLightSize = 1.0;
constexpr double kOccluderHeight = 2.0;
constexpr double kOccluderSide = 0.8;   // square occluder; its shadow's umbra exists (0.8 * 2 > 1)
constexpr double kOccluderRadius = 0.4; // disk occluder
const glm::dvec3 kOccluderCenter{ 0.1, kOccluderHeight, -0.05 };
constexpr int kGrid = 24;

Light areaLight(LightShape shape)
{
  Light light;
  light.type = LightType::Area;
  light.shape = shape;
  light.center = { 0.0, kLightHeight, 0.0 };
  light.normal = { 0.0, -1.0, 0.0 };
  light.up = { 0.0, 0.0, 1.0 }; // right() = +x
  light.size = kLightSize;
  return light;
}

SceneObject caster(const std::string& name, TriangleMesh mesh)
{
  SceneObject object;
  object.name = name;
  object.mesh = std::move(mesh);
  return object;
}

// A finely tessellated disk (a fan of 2048 triangles: its area is within 2e-6 of the circle's), in the
// plane y = center.y.
TriangleMesh fineDisk(const glm::dvec3& center, double radius)
{
  constexpr int kSegments = 2048;
  TriangleMesh mesh;
  mesh.positions.emplace_back(center);
  mesh.normals.emplace_back(0.0f, -1.0f, 0.0f);
  for (int i = 0; i < kSegments; ++i)
  {
    const double angle = 2.0 * kPi * i / kSegments;
    mesh.positions.emplace_back(center + radius * glm::dvec3(std::cos(angle), 0.0, std::sin(angle)));
    mesh.normals.emplace_back(0.0f, -1.0f, 0.0f);
  }
  for (int i = 0; i < kSegments; ++i)
  {
    mesh.indices.insert(mesh.indices.end(),
      { 0u, static_cast<std::uint32_t>(1 + i), static_cast<std::uint32_t>(1 + (i + 1) % kSegments) });
  }
  return mesh;
}

Scene squareOccluderScene()
{
  Scene scene;
  scene.objects.push_back(caster("square occluder",
    makeQuad(kOccluderCenter, { kOccluderSide, kOccluderSide }, { 0.0, -1.0, 0.0 }, { 0.0, 0.0, 1.0 })));
  return scene;
}

Scene diskOccluderScene()
{
  Scene scene;
  scene.objects.push_back(caster("disk occluder", fineDisk(kOccluderCenter, kOccluderRadius)));
  return scene;
}

// Receivers at y = 0 (normal +y) on an n x n grid centred at (centerX, 0, centerZ), spacing 2 halfExtent / n.
ReferenceInputs planeReceivers(const Scene& scene, const Light& light, int n, double centerX, double centerZ,
  double halfExtent)
{
  ReferenceInputs inputs;
  inputs.scene = &scene;
  inputs.light = &light;
  inputs.position = ImageF(n, n, 3);
  inputs.normal = ImageF(n, n, 3);
  inputs.coverage = ImageF(n, n, 1, 1.0f);
  inputs.receives = ImageF(n, n, 1, 1.0f);
  for (int j = 0; j < n; ++j)
  {
    for (int i = 0; i < n; ++i)
    {
      inputs.position.at(i, j, 0) = static_cast<float>(centerX + halfExtent * (2.0 * (i + 0.5) / n - 1.0));
      inputs.position.at(i, j, 1) = 0.0f;
      inputs.position.at(i, j, 2) = static_cast<float>(centerZ + halfExtent * (2.0 * (j + 0.5) / n - 1.0));
      inputs.normal.at(i, j, 1) = 1.0f;
    }
  }
  return inputs;
}

// The standard grid: centred on the occluder's shadow (the occluder centre projected from the light's
// centre, here 2 x its offset), wide enough to hold umbra, penumbra and fully lit points.
ReferenceInputs standardGrid(const Scene& scene, const Light& light)
{
  const double scale = kLightHeight / (kLightHeight - kOccluderHeight);
  return planeReceivers(scene, light, kGrid, scale * kOccluderCenter.x, scale * kOccluderCenter.z, 1.6);
}

glm::dvec3 receiverAt(const ReferenceInputs& inputs, int i, int j)
{
  return { inputs.position.at(i, j, 0), inputs.position.at(i, j, 1), inputs.position.at(i, j, 2) };
}

// One receiver per pixel of a single row, at the given points and normals (RGBA images, as the G-buffer
// has them), all covered and receiving unless the caller changes it.
ReferenceInputs pointReceivers(const Scene& scene, const Light& light, const std::vector<glm::dvec3>& points,
  const std::vector<glm::dvec3>& normals)
{
  const int n = static_cast<int>(points.size());
  ReferenceInputs inputs;
  inputs.scene = &scene;
  inputs.light = &light;
  inputs.position = ImageF(n, 1, 4);
  inputs.normal = ImageF(n, 1, 4);
  inputs.coverage = ImageF(n, 1, 1, 1.0f);
  inputs.receives = ImageF(n, 1, 1, 1.0f);
  for (int i = 0; i < n; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      inputs.position.at(i, 0, c) = static_cast<float>(points[i][c]);
      inputs.normal.at(i, 0, c) = static_cast<float>(normals[i][c]);
    }
  }
  return inputs;
}

double overlap1D(double aMin, double aMax, double bMin, double bMax)
{
  return std::max(0.0, std::min(aMax, bMax) - std::max(aMin, bMin));
}

// How much the occluder's projection through p onto the light plane is scaled: similar triangles.
double projectionScale(const glm::dvec3& p)
{
  return (kLightHeight - p.y) / (kOccluderHeight - p.y);
}

glm::dvec2 projectedOccluderCenter(const glm::dvec3& p)
{
  const glm::dvec3 projected = p + (kOccluderCenter - p) * projectionScale(p);
  return { projected.x, projected.z };
}

// Exact visible fraction of the square light: 1 - |light square n projected occluder square| / L^2.
double exactSquareVisibility(const glm::dvec3& p)
{
  const double half = 0.5 * kOccluderSide * projectionScale(p);
  const glm::dvec2 c = projectedOccluderCenter(p);
  const double l = 0.5 * kLightSize;
  const double overlap = overlap1D(c.x - half, c.x + half, -l, l) * overlap1D(c.y - half, c.y + half, -l, l);
  return 1.0 - overlap / (kLightSize * kLightSize);
}

// Area of the intersection of two disks (radii r1, r2, centres d apart): the lens formula.
double circleIntersectionArea(double r1, double r2, double d)
{
  if (d >= r1 + r2)
  {
    return 0.0;
  }
  if (d <= std::abs(r1 - r2))
  {
    const double r = std::min(r1, r2);
    return kPi * r * r;
  }
  const double a1 = std::acos(std::clamp((d * d + r1 * r1 - r2 * r2) / (2.0 * d * r1), -1.0, 1.0));
  const double a2 = std::acos(std::clamp((d * d + r2 * r2 - r1 * r1) / (2.0 * d * r2), -1.0, 1.0));
  const double kite = 0.5 * std::sqrt(std::max(0.0, (-d + r1 + r2) * (d + r1 - r2) * (d - r1 + r2) * (d + r1 + r2)));
  return r1 * r1 * a1 + r2 * r2 * a2 - kite;
}

double exactDiskVisibility(const glm::dvec3& p)
{
  const double lightRadius = 0.5 * kLightSize;
  const double occluderRadius = kOccluderRadius * projectionScale(p);
  const double d = glm::length(projectedOccluderCenter(p));
  return 1.0 - circleIntersectionArea(lightRadius, occluderRadius, d) / (kPi * lightRadius * lightRadius);
}

template <typename Exact>
double rmse(const ReferenceInputs& inputs, const ReferenceResult& result, Exact exact)
{
  double sum = 0.0;
  for (int j = 0; j < inputs.position.height; ++j)
  {
    for (int i = 0; i < inputs.position.width; ++i)
    {
      const double error = result.visibility.at(i, j) - exact(receiverAt(inputs, i, j));
      sum += error * error;
    }
  }
  return std::sqrt(sum / static_cast<double>(inputs.position.pixelCount()));
}

struct RegionCounts
{
  int umbra = 0;
  int penumbra = 0;
  int lit = 0;
};

template <typename Exact>
RegionCounts countRegions(const ReferenceInputs& inputs, Exact exact)
{
  RegionCounts counts;
  for (int j = 0; j < inputs.position.height; ++j)
  {
    for (int i = 0; i < inputs.position.width; ++i)
    {
      const double v = exact(receiverAt(inputs, i, j));
      (v <= 0.0 ? counts.umbra : v >= 1.0 ? counts.lit : counts.penumbra)++;
    }
  }
  return counts;
}

ReferenceSettings settingsWith(int samples, LightSampling sampling = LightSampling::Stratified)
{
  ReferenceSettings settings;
  settings.samples = samples;
  settings.sampling = sampling;
  return settings;
}

// RMSE against `exact` at 64, 256 and 1024 samples; checks the grid spans all three regions.
template <typename Exact>
std::vector<double> convergence(const Scene& scene, const Light& light, LightSampling sampling, Exact exact)
{
  const ReferenceInputs inputs = standardGrid(scene, light);
  const RegionCounts regions = countRegions(inputs, exact);
  EXPECT_GT(regions.umbra, 10);
  EXPECT_GT(regions.penumbra, 100);
  EXPECT_GT(regions.lit, 10);
  std::vector<double> errors;
  for (int samples : { 64, 256, 1024 })
  {
    errors.push_back(rmse(inputs, renderReference(inputs, settingsWith(samples, sampling)), exact));
  }
  return errors;
}

TEST(ReferenceSquareLight, MatchesClosedFormOverlapAndConverges)
{
  const Scene scene = squareOccluderScene();
  const Light light = areaLight(LightShape::Square);
  const std::vector<double> errors = convergence(scene, light, LightSampling::Stratified, exactSquareVisibility);
  std::printf("[ reference ] square light, stratified: RMSE 64 %.5f, 256 %.5f, 1024 %.5f\n", errors[0], errors[1],
    errors[2]);
  EXPECT_LT(errors[2], 0.005) << "RMSE at 1024 samples";
  EXPECT_LT(errors[1], errors[0]) << "RMSE 256 " << errors[1] << " vs 64 " << errors[0];
  EXPECT_LT(errors[2], errors[1]) << "RMSE 1024 " << errors[2] << " vs 256 " << errors[1];
}

TEST(ReferenceSquareLight, StandardErrorBoundsTheActualError)
{
  const Scene scene = squareOccluderScene();
  const Light light = areaLight(LightShape::Square);
  const ReferenceInputs inputs = standardGrid(scene, light);
  const ReferenceResult result = renderReference(inputs, settingsWith(1024));
  int within = 0;
  int penumbraWithError = 0;
  for (int j = 0; j < kGrid; ++j)
  {
    for (int i = 0; i < kGrid; ++i)
    {
      const glm::dvec3 p = receiverAt(inputs, i, j);
      const double exact = exactSquareVisibility(p);
      const double v = result.visibility.at(i, j);
      const double se = result.standardError.at(i, j);
      EXPECT_NEAR(se, v > 0.0 && v < 1.0 ? std::sqrt(v * (1.0 - v) / 1023.0) : 0.0, 1e-6) << "pixel " << i << "," << j;
      if (std::abs(v - exact) <= 4.0 * se + 1e-3)
      {
        ++within;
      }
      else
      {
        std::printf("pixel %d,%d: reference %.5f exact %.5f stderr %.5f\n", i, j, v, exact, se);
      }
      penumbraWithError += (exact > 0.0 && exact < 1.0 && se > 0.0) ? 1 : 0;
    }
  }
  EXPECT_GE(within, static_cast<int>(std::ceil(0.99 * kGrid * kGrid))) << within << " of " << kGrid * kGrid;
  EXPECT_GT(penumbraWithError, 100) << "the standard error must be nonzero in the penumbra";
  std::printf("[ reference ] %llu rays in %.3f s, %.3g rays/s\n", static_cast<unsigned long long>(result.raysTraced),
    result.seconds, result.raysPerSecond);
  EXPECT_GT(result.raysTraced, 0u);
  EXPECT_LE(result.raysTraced, static_cast<std::uint64_t>(kGrid * kGrid * 1024));
  EXPECT_GT(result.raysPerSecond, 0.0);
}

TEST(ReferenceSquareLight, HaltonConverges)
{
  const Scene scene = squareOccluderScene();
  const Light light = areaLight(LightShape::Square);
  const std::vector<double> errors = convergence(scene, light, LightSampling::Halton, exactSquareVisibility);
  std::printf("[ reference ] square light, Halton: RMSE 64 %.5f, 256 %.5f, 1024 %.5f\n", errors[0], errors[1],
    errors[2]);
  EXPECT_LT(errors[2], 0.005) << "RMSE at 1024 samples";
  EXPECT_LT(errors[1], errors[0]) << "RMSE 256 " << errors[1] << " vs 64 " << errors[0];
  EXPECT_LT(errors[2], errors[1]) << "RMSE 1024 " << errors[2] << " vs 256 " << errors[1];
}

TEST(ReferenceDiskLight, MatchesLensAreaOfDiskOccluder)
{
  const Scene scene = diskOccluderScene();
  const Light light = areaLight(LightShape::Disk);
  for (LightSampling sampling : { LightSampling::Stratified, LightSampling::Halton })
  {
    const std::vector<double> errors = convergence(scene, light, sampling, exactDiskVisibility);
    std::printf("[ reference ] disk light, %s: RMSE 64 %.5f, 256 %.5f, 1024 %.5f\n",
      sampling == LightSampling::Halton ? "Halton" : "stratified", errors[0], errors[1], errors[2]);
    EXPECT_LT(errors[2], 0.005) << "RMSE at 1024 samples";
    EXPECT_LT(errors[2], errors[0]) << "RMSE 1024 " << errors[2] << " vs 64 " << errors[0];
  }
}

// A 2x2 checker on a 2 x 2 quad at y = 2, seen from a point light at (0, 4, 0): the ray from a receiver p
// on y = 0 crosses the quad at p.xz / 2. The quad's uv (makeQuad) is ((x + 1)/2, (z + 1)/2); texel
// (0,0) and (1,1) are opaque, (1,0) and (0,1) holes.
TEST(ReferencePerforation, PointLightPassesThroughCheckerHoles)
{
  Scene scene;
  SceneObject checker = caster("checker", makeQuad({ 0.0, 2.0, 0.0 }, { 2.0, 2.0 }, { 0.0, -1.0, 0.0 }, { 0.0, 0.0, 1.0 }));
  checker.hasAlphaTexture = true;
  checker.alphaTexture.source = "checker";
  checker.alphaTexture.alpha = ImageF(2, 2, 1);
  checker.alphaTexture.alpha.at(0, 0) = 1.0f;
  checker.alphaTexture.alpha.at(1, 0) = 0.2f;
  checker.alphaTexture.alpha.at(0, 1) = 0.49f;
  checker.alphaTexture.alpha.at(1, 1) = 0.5f; // exactly 0.5 is opaque: holes are alpha < 0.5
  scene.objects.push_back(checker);
  Light light;
  light.type = LightType::Point;
  light.center = { 0.0, 4.0, 0.0 };

  struct Case
  {
    glm::dvec3 p;
    float expected;
  };
  const std::vector<Case> cases = {
    { { -1.0, 0.0, -1.0 }, 0.0f }, // crosses at (-0.5, -0.5): texel (0,0), opaque
    { { 1.0, 0.0, -1.0 }, 1.0f },  // (0.5, -0.5): texel (1,0), a hole
    { { -1.0, 0.0, 1.0 }, 1.0f },  // (-0.5, 0.5): texel (0,1), a hole (alpha 0.49)
    { { 1.0, 0.0, 1.0 }, 0.0f },   // (0.5, 0.5): texel (1,1), alpha 0.5, opaque
    { { 1.7, 0.0, -0.3 }, 1.0f },  // (0.85, -0.15): hole
    { { -0.3, 0.0, -1.7 }, 0.0f }, // (-0.15, -0.85): opaque
    { { 2.5, 0.0, 2.5 }, 1.0f },   // (1.25, 1.25): misses the quad
  };
  std::vector<glm::dvec3> points;
  for (const Case& c : cases)
  {
    points.push_back(c.p);
  }
  const ReferenceInputs inputs =
    pointReceivers(scene, light, points, std::vector<glm::dvec3>(points.size(), glm::dvec3(0.0, 1.0, 0.0)));
  const ReferenceResult result = renderReference(inputs, settingsWith(1));
  for (std::size_t i = 0; i < cases.size(); ++i)
  {
    EXPECT_EQ(result.visibility.at(static_cast<int>(i), 0), cases[i].expected)
      << "receiver (" << cases[i].p.x << ", " << cases[i].p.z << ")";
    EXPECT_EQ(result.standardError.at(static_cast<int>(i), 0), 0.0f);
  }

  // Without the alpha texture, every ray through the quad is blocked.
  scene.objects[0].hasAlphaTexture = false;
  const ReferenceResult solid = renderReference(inputs, settingsWith(1));
  for (std::size_t i = 0; i + 1 < cases.size(); ++i)
  {
    EXPECT_EQ(solid.visibility.at(static_cast<int>(i), 0), 0.0f) << "case " << i;
  }
}

// The procedural fence and leaves textures, tiled 3 times with a negative offset (so repeat wrap matters),
// on the same quad: every receiver's answer is the texel at the crossing's uv, computed here independently.
// (The fence alone is symmetric under u and v flips; the leaves are not, so they catch a flipped axis.)
void expectTexelAtCrossing(const std::string& pattern, const ImageF& texture)
{
  constexpr double kTiling = 3.0;
  constexpr double kUvOffset = -0.37;
  Scene scene;
  SceneObject fence = caster(pattern, makeQuad({ 0.0, 2.0, 0.0 }, { 2.0, 2.0 }, { 0.0, -1.0, 0.0 }, { 0.0, 0.0, 1.0 }));
  for (glm::vec2& uv : fence.mesh.uvs)
  {
    uv = glm::vec2(kTiling * glm::dvec2(uv) + kUvOffset);
  }
  fence.hasAlphaTexture = true;
  fence.alphaTexture.source = pattern;
  fence.alphaTexture.alpha = texture;
  const ImageF& alpha = texture;
  scene.objects.push_back(fence);
  Light light;
  light.type = LightType::Point;
  light.center = { 0.0, 4.0, 0.0 };

  constexpr int kFenceGrid = 64;
  const ReferenceInputs inputs = planeReceivers(scene, light, kFenceGrid, 0.0, 0.0, 1.87);
  const ReferenceResult result = renderReference(inputs, settingsWith(1));
  int holes = 0;
  int opaque = 0;
  int checked = 0;
  for (int j = 0; j < kFenceGrid; ++j)
  {
    for (int i = 0; i < kFenceGrid; ++i)
    {
      const glm::dvec3 p = receiverAt(inputs, i, j);
      const glm::dvec2 crossing = 0.5 * glm::dvec2(p.x, p.z); // the ray meets y = 2 halfway to the light
      const glm::dvec2 uv = kTiling * (crossing + 1.0) / 2.0 + kUvOffset;
      const glm::dvec2 texelCoord = uv * glm::dvec2(alpha.width, alpha.height);
      const glm::dvec2 fraction = texelCoord - glm::floor(texelCoord);
      if (glm::any(glm::lessThan(fraction, glm::dvec2(0.02))) || glm::any(glm::greaterThan(fraction, glm::dvec2(0.98))))
      {
        continue; // too close to a texel edge for single-precision barycentrics to be sure
      }
      const auto wrap = [](double t, int size) { return ((static_cast<int>(std::floor(t)) % size) + size) % size; };
      const bool hole = alpha.at(wrap(texelCoord.x, alpha.width), wrap(texelCoord.y, alpha.height)) < 0.5f;
      (hole ? holes : opaque)++;
      ++checked;
      EXPECT_EQ(result.visibility.at(i, j), hole ? 1.0f : 0.0f)
        << pattern << ": receiver " << i << "," << j << " uv " << uv.x << "," << uv.y << (hole ? " (hole)" : " (opaque)");
    }
  }
  EXPECT_GT(checked, kFenceGrid * kFenceGrid * 8 / 10) << pattern;
  EXPECT_GT(holes, 200) << pattern;
  EXPECT_GT(opaque, 200) << pattern;
}

TEST(ReferencePerforation, FenceAndLeavesMatchTexelAtCrossing)
{
  expectTexelAtCrossing("fence", makeFenceAlpha());
  expectTexelAtCrossing("leaves", makeLeavesAlpha());
}

TEST(ReferenceDeterminism, SameSeedSameImageForAnyThreadCount)
{
  struct Setup
  {
    Scene scene;
    Light light;
    double (*exact)(const glm::dvec3&);
  };
  const std::vector<Setup> setups = {
    { squareOccluderScene(), areaLight(LightShape::Square), exactSquareVisibility },
    { diskOccluderScene(), areaLight(LightShape::Disk), exactDiskVisibility },
  };
  for (const Setup& setup : setups)
  {
    const ReferenceInputs inputs = standardGrid(setup.scene, setup.light);
    for (LightSampling sampling : { LightSampling::Stratified, LightSampling::Halton })
    {
      for (int samples : { 256, 10 })
      {
        const std::string label = format(setup.scene.objects[0].name, ", ",
          sampling == LightSampling::Halton ? "Halton" : "stratified", ", ", samples, " samples");
        ReferenceSettings settings = settingsWith(samples, sampling);
        settings.seed = 7;
        settings.threads = 1;
        const ReferenceResult one = renderReference(inputs, settings);
        settings.threads = 4;
        const ReferenceResult four = renderReference(inputs, settings);
        EXPECT_EQ(one.visibility.data, four.visibility.data) << label;
        EXPECT_EQ(one.standardError.data, four.standardError.data) << label;
        EXPECT_EQ(one.raysTraced, four.raysTraced) << label;

        settings.seed = 8;
        const ReferenceResult other = renderReference(inputs, settings);
        int differing = 0;
        for (int j = 0; j < kGrid; ++j)
        {
          for (int i = 0; i < kGrid; ++i)
          {
            if (one.visibility.at(i, j) != other.visibility.at(i, j))
            {
              ++differing;
              const double exact = setup.exact(receiverAt(inputs, i, j));
              EXPECT_TRUE(exact > 0.0 && exact < 1.0)
                << label << ": only penumbra pixels may change with the seed, pixel " << i << "," << j << " exact "
                << exact << " seed 7 " << one.visibility.at(i, j) << " seed 8 " << other.visibility.at(i, j);
            }
          }
        }
        EXPECT_GT(differing, 20) << label << ": seed 7 vs 8";
      }
    }
  }
}

// Point, spot and directional lights: one exact ray, visibility 0 or 1, standard error 0. A non-casting
// quad covering everything must be ignored.
TEST(ReferenceHardLights, PointSpotAndDirectionalAreExact)
{
  Scene scene = squareOccluderScene();
  SceneObject ghost = caster("non-caster", makeQuad({ 0.0, 3.0, 0.0 }, { 20.0, 20.0 }, { 0.0, -1.0, 0.0 }, { 0.0, 0.0, 1.0 }));
  ghost.castShadows = false;
  scene.objects.push_back(ghost);

  Light point;
  point.type = LightType::Point;
  point.center = { 0.3, 4.0, -0.2 };
  Light spot = point;
  spot.type = LightType::Spot;
  spot.normal = { 0.0, -1.0, 0.0 };
  spot.coneAngleDeg = 25.0;
  Light directional;
  directional.type = LightType::Directional;
  directional.direction = glm::normalize(glm::dvec3(0.4, -1.0, 0.25));

  for (const Light* light : { &point, &spot, &directional })
  {
    const ReferenceInputs inputs = planeReceivers(scene, *light, 32, 0.0, 0.0, 2.5);
    const ReferenceResult result = renderReference(inputs, settingsWith(1024));
    std::uint64_t reachable = 0;
    int shadowed = 0;
    int lit = 0;
    int outsideCone = 0;
    for (int j = 0; j < 32; ++j)
    {
      for (int i = 0; i < 32; ++i)
      {
        const glm::dvec3 p = receiverAt(inputs, i, j);
        const glm::dvec3 toLight = light == &directional ? -directional.direction : glm::normalize(light->center - p);
        const glm::dvec3 crossing = p + toLight * ((kOccluderHeight - p.y) / toLight.y);
        const glm::dvec2 offset(crossing.x - kOccluderCenter.x, crossing.z - kOccluderCenter.z);
        const double edgeDistance = 0.5 * kOccluderSide - std::max(std::abs(offset.x), std::abs(offset.y));
        double expected = edgeDistance > 0.0 ? 0.0 : 1.0;
        const double coneMargin = glm::dot(spot.normal, -toLight) - std::cos(glm::radians(spot.coneAngleDeg));
        if (light == &spot && std::abs(coneMargin) < 1e-6)
        {
          continue; // on the cone's boundary
        }
        if (light == &spot && coneMargin < 0.0)
        {
          expected = 0.0;
          ++outsideCone;
        }
        else
        {
          ++reachable;
          if (std::abs(edgeDistance) < 1e-3)
          {
            continue; // grazing the occluder's edge
          }
        }
        (expected == 0.0 ? shadowed : lit)++;
        EXPECT_EQ(result.visibility.at(i, j), expected) << "light type " << static_cast<int>(light->type)
                                                        << " receiver " << p.x << "," << p.z;
        EXPECT_EQ(result.standardError.at(i, j), 0.0f);
      }
    }
    EXPECT_EQ(result.raysTraced, reachable) << "one ray per reachable receiver";
    EXPECT_GT(shadowed, 20);
    EXPECT_GT(lit, 20);
    if (light == &spot)
    {
      EXPECT_GT(outsideCone, 20);
    }
  }
}

// Pixels decided without (or before) tracing, and the tangent-plane rule for area lights.
TEST(ReferenceSpecialPixels, CoverageReceivesReachAndHorizon)
{
  const Scene scene = squareOccluderScene();
  const Light light = areaLight(LightShape::Square);
  const glm::dvec3 umbra(2.0 * kOccluderCenter.x, 0.0, 2.0 * kOccluderCenter.z);
  struct Case
  {
    const char* what;
    glm::dvec3 p;
    glm::dvec3 n;
    float coverage;
    float receives;
    double expected;
  };
  const glm::dvec3 up(0.0, 1.0, 0.0);
  const std::vector<Case> cases = {
    { "umbra", umbra, up, 1.0f, 1.0f, 0.0 },
    { "uncovered, lit", { 3.0, 0.0, 3.0 }, up, 0.0f, 1.0f, 0.0 },
    { "not receiving, in the umbra", umbra, up, 1.0f, 0.0f, 1.0 },
    { "facing away", { 3.0, 0.0, 3.0 }, -up, 1.0f, 1.0f, 0.0 },
    { "behind the one-sided light", { 0.0, 5.0, 0.0 }, up, 1.0f, 1.0f, 0.0 },
    { "lit", { 3.0, 0.0, 3.0 }, up, 1.0f, 1.0f, 1.0 },
    // Tilted normal (1,1,0)/sqrt2 at x = 3.8: the tangent plane cuts the light at x = -0.2, so 70% of it is
    // above the horizon (no occluder in between).
    { "horizon cuts the light", { 3.8, 0.0, 0.0 }, glm::normalize(glm::dvec3(1.0, 1.0, 0.0)), 1.0f, 1.0f, 0.7 },
  };
  const int n = static_cast<int>(cases.size());
  std::vector<glm::dvec3> points;
  std::vector<glm::dvec3> normals;
  for (const Case& c : cases)
  {
    points.push_back(c.p);
    normals.push_back(c.n);
  }
  ReferenceInputs inputs = pointReceivers(scene, light, points, normals);
  for (int i = 0; i < n; ++i)
  {
    inputs.coverage.at(i, 0) = cases[i].coverage;
    inputs.receives.at(i, 0) = cases[i].receives;
  }
  const ReferenceResult result = renderReference(inputs, settingsWith(1024));
  for (int i = 0; i < n; ++i)
  {
    EXPECT_NEAR(result.visibility.at(i, 0), cases[i].expected, 0.01) << cases[i].what;
    if (cases[i].expected == 0.0 || cases[i].expected == 1.0)
    {
      EXPECT_EQ(result.visibility.at(i, 0), static_cast<float>(cases[i].expected)) << cases[i].what;
      EXPECT_EQ(result.standardError.at(i, 0), 0.0f) << cases[i].what;
    }
  }
  // Only the umbra, lit and horizon pixels trace: 1024 + 1024 + about 700 rays (below-horizon samples are free).
  EXPECT_GT(result.raysTraced, 2u * 1024u + 650u);
  EXPECT_LT(result.raysTraced, 2u * 1024u + 750u);
}

TEST(ReferenceSettingsCheck, BadSettingsThrowInputError)
{
  const Scene scene = squareOccluderScene();
  const Light light = areaLight(LightShape::Square);
  const ReferenceInputs inputs = planeReceivers(scene, light, 2, 0.0, 0.0, 1.0);
  const auto messageOf = [&](const ReferenceSettings& settings) -> std::string {
    try
    {
      renderReference(inputs, settings);
    }
    catch (const InputError& error)
    {
      return error.what();
    }
    return "(no InputError)";
  };
  EXPECT_EQ(messageOf(settingsWith(0)), "--samples 0: must be >= 1");
  EXPECT_EQ(messageOf(settingsWith(-3)), "--samples -3: must be >= 1");
  ReferenceSettings threads = settingsWith(4);
  threads.threads = -1;
  EXPECT_NE(messageOf(threads).find("--threads -1"), std::string::npos) << messageOf(threads);
  ReferenceSettings offset = settingsWith(4);
  offset.rayOffset = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(messageOf(offset).find("--ray-offset"), std::string::npos) << messageOf(offset);
}

TEST(ReferenceRayOffset, DefaultsToScaledBoundingRadius)
{
  const Scene scene = squareOccluderScene();
  ReferenceSettings settings;
  EXPECT_DOUBLE_EQ(referenceRayOffset(scene, settings), 1e-4 * scene.bounds().radius());
  settings.rayOffset = 0.25;
  EXPECT_EQ(referenceRayOffset(scene, settings), 0.25);
  settings.rayOffset = 0.0;
  EXPECT_EQ(referenceRayOffset(scene, settings), 0.0);
}

TEST(ReferenceProgress, ReportsOnCallingThreadAndCanCancel)
{
  const Scene scene = squareOccluderScene();
  const Light light = areaLight(LightShape::Square);
  const ReferenceInputs inputs = planeReceivers(scene, light, 100, 0.0, 0.0, 1.5);
  ReferenceSettings settings = settingsWith(16);
  settings.threads = 2;
  std::vector<double> reports;
  const std::thread::id caller = std::this_thread::get_id();
  bool otherThread = false;
  renderReference(inputs, settings, [&](double fraction) {
    otherThread = otherThread || std::this_thread::get_id() != caller;
    reports.push_back(fraction);
  });
  EXPECT_FALSE(otherThread);
  ASSERT_FALSE(reports.empty());
  EXPECT_LE(reports.size(), 34u);
  EXPECT_EQ(reports.back(), 1.0);
  EXPECT_TRUE(std::is_sorted(reports.begin(), reports.end()));

  int calls = 0;
  EXPECT_THROW(renderReference(inputs, settings,
                 [&](double) {
                   if (++calls == 1)
                   {
                     throw std::runtime_error("cancelled");
                   }
                 }),
    std::runtime_error);
}

TEST(ReferenceLightSampler, StratifiesAndStaysOnTheLight)
{
  const Light square = areaLight(LightShape::Square);
  // A perfect square: every stratum of the 4 x 4 grid holds exactly one sample, in every pixel.
  const LightSampler sixteen(square, 16, LightSampling::Stratified, 3);
  EXPECT_EQ(sixteen.columns(), 4);
  EXPECT_EQ(sixteen.rows(), 4);
  // N = 10: a 4 x 3 grid, 10 distinct strata, a different subset in different pixels.
  const LightSampler ten(square, 10, LightSampling::Stratified, 3);
  EXPECT_EQ(ten.columns(), 4);
  EXPECT_EQ(ten.rows(), 3);
  std::set<std::set<int>> subsets;
  glm::dvec2 mean(0.0);
  for (int pixel = 0; pixel < 50; ++pixel)
  {
    std::set<int> strata;
    for (int i = 0; i < 16; ++i)
    {
      const glm::dvec2 u = sixteen.unitSample(pixel, 2 * pixel, i);
      ASSERT_TRUE(u.x >= 0.0 && u.x < 1.0 && u.y >= 0.0 && u.y < 1.0);
      strata.insert(static_cast<int>(u.x * 4) + 4 * static_cast<int>(u.y * 4));
      const glm::dvec3 s = sixteen.point(pixel, 2 * pixel, i) - square.center;
      EXPECT_NEAR(glm::dot(s, square.normal), 0.0, 1e-12);
      EXPECT_LE(std::abs(glm::dot(s, square.right())), 0.5 * square.size);
      EXPECT_LE(std::abs(glm::dot(s, square.up)), 0.5 * square.size);
      mean += u / (50.0 * 16.0);
    }
    EXPECT_EQ(strata.size(), 16u) << "pixel " << pixel;
    std::set<int> tenStrata;
    for (int i = 0; i < 10; ++i)
    {
      const glm::dvec2 u = ten.unitSample(pixel, 0, i);
      tenStrata.insert(static_cast<int>(u.x * 4) + 4 * static_cast<int>(u.y * 3));
    }
    EXPECT_EQ(tenStrata.size(), 10u) << "pixel " << pixel;
    subsets.insert(tenStrata);
  }
  EXPECT_GT(subsets.size(), 10u) << "the strata left out must vary from pixel to pixel";
  EXPECT_NEAR(mean.x, 0.5, 0.02);
  EXPECT_NEAR(mean.y, 0.5, 0.02);

  // Halton with a Cranley-Patterson rotation: the first 4 points still fall one per quarter in x.
  const LightSampler halton(square, 4, LightSampling::Halton, 3);
  for (int pixel = 0; pixel < 10; ++pixel)
  {
    std::set<int> quarters;
    for (int i = 0; i < 4; ++i)
    {
      quarters.insert(static_cast<int>(halton.unitSample(pixel, 0, i).x * 4));
    }
    EXPECT_EQ(quarters.size(), 4u) << "pixel " << pixel;
  }

  // Disk: inside the radius, on the plane.
  const LightSampler disk(areaLight(LightShape::Disk), 64, LightSampling::Stratified, 3);
  for (int i = 0; i < 64; ++i)
  {
    const glm::dvec3 s = disk.point(5, 6, i) - square.center;
    EXPECT_LE(glm::length(s), 0.5 * square.size + 1e-12);
    EXPECT_NEAR(s.y, 0.0, 1e-12);
  }
}

TEST(ReferenceLightSampler, ConcentricMapAndRadicalInverse)
{
  const auto expectNear = [](const glm::dvec2& a, const glm::dvec2& b) {
    EXPECT_NEAR(a.x, b.x, 1e-12);
    EXPECT_NEAR(a.y, b.y, 1e-12);
  };
  expectNear(concentricDiskMap({ 0.5, 0.5 }), { 0.0, 0.0 });
  expectNear(concentricDiskMap({ 1.0, 0.5 }), { 1.0, 0.0 });
  expectNear(concentricDiskMap({ 0.5, 1.0 }), { 0.0, 1.0 });
  expectNear(concentricDiskMap({ 0.0, 0.5 }), { -1.0, 0.0 });
  expectNear(concentricDiskMap({ 1.0, 1.0 }), { std::sqrt(0.5), std::sqrt(0.5) });
  EXPECT_DOUBLE_EQ(radicalInverse(2, 1), 0.5);
  EXPECT_DOUBLE_EQ(radicalInverse(2, 3), 0.75);
  EXPECT_DOUBLE_EQ(radicalInverse(2, 6), 0.375);
  EXPECT_DOUBLE_EQ(radicalInverse(3, 1), 1.0 / 3.0);
  EXPECT_DOUBLE_EQ(radicalInverse(3, 5), 7.0 / 9.0);
  // permuteIndex is a bijection.
  for (std::uint32_t length : { 1u, 7u, 12u, 100u })
  {
    std::set<std::uint32_t> images;
    for (std::uint32_t i = 0; i < length; ++i)
    {
      images.insert(permuteIndex(i, length, 0x1234567u));
    }
    EXPECT_EQ(images.size(), length);
    EXPECT_LT(*images.rbegin(), length);
  }
}

TEST(ReferenceEmbreeScene, OnlyCastersAreBuilt)
{
  Scene scene = squareOccluderScene();
  SceneObject ghost = caster("non-caster", makeQuad({ 0.0, 3.0, 0.0 }, { 2.0, 2.0 }, { 0.0, 1.0, 0.0 }, { 0.0, 0.0, 1.0 }));
  ghost.castShadows = false;
  scene.objects.push_back(ghost);
  scene.objects.push_back(caster("empty", TriangleMesh{}));
  const EmbreeScene casters(scene);
  EXPECT_EQ(casters.geometryCount(), 1u);
  EXPECT_EQ(casters.triangleCount(), 2u);
  const glm::dvec3 below(kOccluderCenter.x, 0.0, kOccluderCenter.z);
  // Two-sided: blocked from below and from above; the segment's ends are respected.
  EXPECT_TRUE(casters.occluded(below, { 0.0, 1.0, 0.0 }, 0.0, 10.0));
  EXPECT_TRUE(casters.occluded(below + glm::dvec3(0.0, 4.0, 0.0), { 0.0, -1.0, 0.0 }, 0.0, 10.0));
  EXPECT_FALSE(casters.occluded(below, { 0.0, 1.0, 0.0 }, 0.0, 1.9));
  EXPECT_FALSE(casters.occluded(below, { 0.0, 1.0, 0.0 }, 2.1, std::numeric_limits<double>::infinity()));
  EXPECT_TRUE(casters.occluded(below, { 0.0, 1.0, 0.0 }, 0.0, std::numeric_limits<double>::infinity()));
  EXPECT_FALSE(casters.occluded(below + glm::dvec3(1.0, 0.0, 0.0), { 0.0, 1.0, 0.0 }, 0.0, 10.0));
}

} // namespace
} // namespace sl
