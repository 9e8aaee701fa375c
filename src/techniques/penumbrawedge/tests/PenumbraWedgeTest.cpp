// The CPU side of technique `penumbra-wedge` (techniques/penumbrawedge/PenumbraWedgeGeometry.h, AAM03 as Forest et al. 2009
// §3.1 uses it) against closed forms: parallel squares under a square light, where each occluder's shadow is the
// light clipped by the occluder's projection, so AAM03's result is known exactly:
//     occlusion_raw = sum_i A_i + [k > 0] - k,   A_i = |L ∩ proj_i| / |L|,  k = occluders whose projection holds c
// (each convex occluder's wedges move its own area; the hard shadow of the centre counts once however many hold it).
// With one occluder that is the exact shadow; with overlapping ones it double-counts the overlap (Forest et al. 2009 §3.1).
// Then the GPU technique against this twin pixel by pixel, against the closed form, and against Embree and `dcs`.
#include "frame/FrameResult.h"
#include "lightspace/LightSampleSet.h"
#include "lightspace/LightView.h"
#include "structures/lightsamples/LightSampleSetStructure.h"
#include "metrics/ErrorMetrics.h"
#include "reference/ReferenceRenderer.h"
#include "scene/WeldedMesh.h"
#include "support/TestSupport.h"
#include "objectspace/DcsGeometry.h"
#include "techniques/penumbrawedge/PenumbraWedgeGeometry.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <functional>
#include <numeric>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace sl
{
namespace
{

using Polygon = std::vector<glm::dvec2>;

double signedArea(const Polygon& polygon)
{
  double twice = 0.0;
  for (std::size_t i = 0; i < polygon.size(); ++i)
  {
    twice += polygon[i].x * polygon[(i + 1) % polygon.size()].y - polygon[(i + 1) % polygon.size()].x * polygon[i].y;
  }
  return 0.5 * twice;
}

// The part of `subject` inside the convex polygon `clip` (Sutherland-Hodgman, either winding).
Polygon intersect(Polygon subject, const Polygon& clip)
{
  const double winding = signedArea(clip) >= 0.0 ? 1.0 : -1.0;
  for (std::size_t i = 0; i < clip.size() && subject.size() >= 3; ++i)
  {
    const glm::dvec2 a = clip[i];
    const glm::dvec2 b = clip[(i + 1) % clip.size()];
    const auto inside = [&](const glm::dvec2& x) {
      return winding * ((b.x - a.x) * (x.y - a.y) - (b.y - a.y) * (x.x - a.x));
    };
    Polygon next;
    for (std::size_t j = 0; j < subject.size(); ++j)
    {
      const glm::dvec2& u = subject[j];
      const glm::dvec2& v = subject[(j + 1) % subject.size()];
      const double fu = inside(u);
      const double fv = inside(v);
      if (fu >= 0.0)
      {
        next.push_back(u);
      }
      if ((fu >= 0.0) != (fv >= 0.0))
      {
        next.push_back(u + (fu / (fu - fv)) * (v - u));
      }
    }
    subject = next;
  }
  return subject.size() >= 3 ? subject : Polygon{};
}

bool contains(const Polygon& convex, const glm::dvec2& x)
{
  const double winding = signedArea(convex) >= 0.0 ? 1.0 : -1.0;
  for (std::size_t i = 0; i < convex.size(); ++i)
  {
    const glm::dvec2 a = convex[i];
    const glm::dvec2 b = convex[(i + 1) % convex.size()];
    if (winding * ((b.x - a.x) * (x.y - a.y) - (b.y - a.y) * (x.x - a.x)) <= 0.0)
    {
      return false;
    }
  }
  return true;
}

// An object's first triangle pair as a quad projected from p onto the light plane, in light coordinates.
Polygon projectedQuad(const SceneObject& object, const Light& light, const glm::dvec3& p)
{
  // The quad's corners: its distinct vertex positions, ordered around their centre.
  std::vector<glm::dvec3> corners;
  for (const glm::vec3& position : object.mesh.positions)
  {
    const glm::dvec3 corner(position);
    if (std::none_of(corners.begin(), corners.end(), [&](const glm::dvec3& c) { return glm::length(c - corner) < 1e-9; }))
    {
      corners.push_back(corner);
    }
  }
  EXPECT_EQ(corners.size(), 4u) << object.name;
  const double heightP = glm::dot(light.normal, p - light.center);
  Polygon projected;
  for (const glm::dvec3& q : corners)
  {
    const double heightQ = glm::dot(light.normal, q - light.center);
    const glm::dvec3 onPlane = p + (heightP / (heightP - heightQ)) * (q - p);
    projected.emplace_back(glm::dot(onPlane - light.center, light.right()), glm::dot(onPlane - light.center, light.up));
  }
  glm::dvec2 centre(0.0);
  for (const glm::dvec2& x : projected)
  {
    centre += x / static_cast<double>(projected.size());
  }
  std::sort(projected.begin(), projected.end(), [&](const glm::dvec2& a, const glm::dvec2& b) {
    return std::atan2(a.y - centre.y, a.x - centre.x) < std::atan2(b.y - centre.y, b.x - centre.x);
  });
  return projected;
}

struct Expected
{
  double aam03 = 0.0;    // sum A_i + [k > 0] - k
  double occluded = 0.0; // |L ∩ union proj_i| / |L|, the true shadow
  int centreCovered = 0; // k
};

// Occluders are every caster but the first (the ground); at most three (inclusion-exclusion).
Expected expectedAt(const Scene& scene, const glm::dvec3& p)
{
  const Light& light = scene.lights.front();
  const double half = 0.5 * light.size;
  const Polygon square = { { -half, -half }, { half, -half }, { half, half }, { -half, half } };
  const double lightArea = light.size * light.size;
  std::vector<Polygon> shadows;
  Expected expected;
  for (std::size_t i = 1; i < scene.objects.size(); ++i)
  {
    const Polygon projected = projectedQuad(scene.objects[i], light, p);
    shadows.push_back(intersect(square, projected));
    expected.aam03 += std::abs(signedArea(shadows.back())) / lightArea;
    expected.centreCovered += contains(projected, glm::dvec2(0.0)) ? 1 : 0;
  }
  expected.aam03 += (expected.centreCovered > 0 ? 1.0 : 0.0) - expected.centreCovered;
  // Union by inclusion-exclusion over the (convex) shadows.
  const int n = static_cast<int>(shadows.size());
  for (int subset = 1; subset < (1 << n); ++subset)
  {
    Polygon common = square;
    int members = 0;
    for (int i = 0; i < n && !common.empty(); ++i)
    {
      if (subset & (1 << i))
      {
        common = shadows[static_cast<std::size_t>(i)].empty() ? Polygon{} : intersect(common, shadows[static_cast<std::size_t>(i)]);
        ++members;
      }
    }
    expected.occluded += (members % 2 ? 1.0 : -1.0) * std::abs(signedArea(common)) / lightArea;
  }
  return expected;
}

struct Sweep
{
  int points = 0;
  int penumbra = 0;         // 0 < exact shadow < 1
  int overCounted = 0;      // occlusion_raw > true shadow + 1e-6
  int lighter = 0;          // visibility > true visibility + 1e-9
  int lighterDoubleCentre = 0; // ... of those, with the centre under two occluders
  double worstAam03 = 0.0;  // max |occlusion_raw - expected.aam03|
  double worstOverCount = 0.0;
};

Sweep sweepGround(const Scene& scene, double extent, int steps)
{
  const Light& light = scene.lights.front();
  const PenumbraWedgeScene prepared = penumbraWedgeScene(scene, light);
  Sweep sweep;
  for (int i = 0; i <= steps; ++i)
  {
    for (int j = 0; j <= steps; ++j)
    {
      // Just above the ground, so the ground's own triangles are not crossed on the way to the light.
      const glm::dvec3 p(-extent + 2.0 * extent * i / steps, 1e-9, -extent + 2.0 * extent * j / steps);
      const PenumbraWedgePixel twin = penumbraWedgePixel(prepared, scene, light, p, 0.0, {});
      const Expected expected = expectedAt(scene, p);
      ++sweep.points;
      sweep.penumbra += expected.occluded > 1e-9 && expected.occluded < 1.0 - 1e-9;
      sweep.worstAam03 = std::max(sweep.worstAam03, std::abs(twin.occlusionRaw - expected.aam03));
      EXPECT_EQ(twin.centreCount, expected.centreCovered) << p.x << ", " << p.z;
      if (twin.occlusionRaw > expected.occluded + 1e-6)
      {
        ++sweep.overCounted;
        sweep.worstOverCount = std::max(sweep.worstOverCount, twin.occlusionRaw - expected.occluded);
      }
      if (twin.visibility > 1.0 - expected.occluded + 1e-9)
      {
        ++sweep.lighter;
        sweep.lighterDoubleCentre += expected.centreCovered >= 2;
      }
    }
  }
  return sweep;
}

TEST(PenumbraWedge, OneConvexOccluderIsExact)
{
  // planar-occluder: a unit square at height 1 under the unit square light at 3 (the closed form of TestSupport).
  const Scene scene = test::loadDataset("planar-occluder");
  const Light& light = scene.lights.front();
  const PenumbraWedgeScene prepared = penumbraWedgeScene(scene, light);
  double worst = 0.0;
  int penumbra = 0;
  for (int i = 0; i <= 80; ++i)
  {
    for (int j = 0; j <= 80; ++j)
    {
      const double x = -2.0 + 4.0 * i / 80.0;
      const double z = -2.0 + 4.0 * j / 80.0;
      const PenumbraWedgePixel twin = penumbraWedgePixel(prepared, scene, light, { x, 1e-9, z }, 0.0, {});
      const double exact = test::parallelSquaresVisibility(1.0, 3.0, 1.0, 1.0, x, z);
      worst = std::max(worst, std::abs(twin.visibility - exact));
      penumbra += exact > 0.0 && exact < 1.0;
      EXPECT_GE(twin.occlusionRaw, -1e-9) << x << ", " << z;
      EXPECT_LE(twin.occlusionRaw, 1.0 + 1e-9) << x << ", " << z;
    }
  }
  std::cout << "[ measured ] penumbra-wedge twin, planar-occluder: max |V - closed form| " << worst << " over 6561 ground "
            << "points, " << penumbra << " in the penumbra\n";
  EXPECT_LT(worst, 1e-7);
  EXPECT_GT(penumbra, 1000);
}

TEST(PenumbraWedge, OverlappingOccludersCountTheirOverlapTwice)
{
  // stacked-occluders and seeded random stacks of 2 and 3 parallel squares (tests/support): AAM03's value is the
  // closed form above everywhere; where the centre is under at most one occluder it is never lighter than the true
  // shadow and over-counts exactly the overlap; under two, its single hard-shadow count makes it lighter.
  std::mt19937 generator(2003);
  std::vector<std::pair<std::string, Scene>> scenes;
  scenes.emplace_back("stacked-occluders", test::loadDataset("stacked-occluders"));
  for (const int count : { 2, 2, 3 })
  {
    scenes.emplace_back("random stack of " + std::to_string(count),
      loadScene(test::datasetPath("stacked-occluders"), test::randomRectangleStack(generator, count)));
  }
  int overCountedTotal = 0;
  for (const auto& [name, scene] : scenes)
  {
    const Sweep sweep = sweepGround(scene, 2.0, 60);
    std::cout << "[ measured ] penumbra-wedge twin, " << name << ": max |raw - closed form| " << sweep.worstAam03 << "; of "
              << sweep.points << " ground points (" << sweep.penumbra << " in the penumbra) " << sweep.overCounted
              << " over-counted (worst by " << sweep.worstOverCount << " of the light), " << sweep.lighter
              << " lighter than the true shadow, " << sweep.lighterDoubleCentre << " of them with the centre under two\n";
    EXPECT_LT(sweep.worstAam03, 1e-7) << name;
    EXPECT_EQ(sweep.lighter, sweep.lighterDoubleCentre) << name << ": lighter only where the centre is doubly covered";
    EXPECT_GT(sweep.penumbra, 200) << name;
    overCountedTotal += sweep.overCounted;
  }
  EXPECT_GT(overCountedTotal, 0) << "no overlap was exercised";
}

TEST(PenumbraWedge, WedgesOutsideTheLightChangeNothing)
{
  // A point whose wedges all miss the light (far from any shadow) and one inside the umbra get exactly 1 and 0.
  const Scene scene = test::loadDataset("planar-occluder");
  const Light& light = scene.lights.front();
  const PenumbraWedgeScene prepared = penumbraWedgeScene(scene, light);
  EXPECT_EQ(penumbraWedgePixel(prepared, scene, light, { 2.5, 1e-9, 2.5 }, 0.0, {}).visibility, 1.0);
  const PenumbraWedgePixel umbra = penumbraWedgePixel(prepared, scene, light, { 0.1, 1e-9, 0.05 }, 0.0, {});
  EXPECT_EQ(umbra.centreCount, 1);
  EXPECT_EQ(umbra.wedgesCovering, 0);
  EXPECT_EQ(umbra.visibility, 0.0);
}

// ---------------------------------------------------------------------------------------------------------------
// The GPU technique.

constexpr int kWedgeFrameSize = 96;
// The counted point is moved receiver_offset toward the camera; close to the receiver for the closed forms.
constexpr const char* kWedgeCloseReceiverOffset = "receiver_offset=1e-6";

using test::bufferOf;

glm::dvec3 pointAt(const FrameResult& frame, int x, int y)
{
  const ImageF& position = bufferOf(frame, "position");
  return { position.at(x, y, 0), position.at(x, y, 1), position.at(x, y, 2) };
}

struct GpuTwinCase
{
  std::string name;
  std::string dataset;
  std::vector<std::string> overrides;
};

class PenumbraWedgeGpu : public testing::TestWithParam<GpuTwinCase>
{
};

TEST_P(PenumbraWedgeGpu, MatchesTheTwinPixelByPixel)
{
  const GpuTwinCase& c = GetParam();
  const Scene scene = loadScene(test::datasetPath(c.dataset), c.overrides);
  const FrameResult frame = test::renderDataset(scene, "penumbra-wedge", kWedgeFrameSize, kWedgeFrameSize);
  const Light& light = scene.lights.front();
  const PenumbraWedgeScene prepared = penumbraWedgeScene(scene, light);
  const double receiverOffset = frame.parameters.get("receiver_offset");
  int compared = 0;
  int inPenumbra = 0;
  int centreMismatches = 0;
  int coveringMismatches = 0;
  int beyondOneTenThousandth = 0;
  double worstRaw = 0.0;
  double worstVisibility = 0.0;
  for (int y = 0; y < kWedgeFrameSize; ++y)
  {
    for (int x = 0; x < kWedgeFrameSize; ++x)
    {
      if (bufferOf(frame, "coverage").at(x, y) <= 0.5f || bufferOf(frame, "receives_shadows").at(x, y) <= 0.5f)
      {
        continue;
      }
      const glm::dvec3 normal(bufferOf(frame, "normal").at(x, y, 0), bufferOf(frame, "normal").at(x, y, 1),
        bufferOf(frame, "normal").at(x, y, 2));
      if (!lightCanReach(light, pointAt(frame, x, y), normal))
      {
        continue;
      }
      const PenumbraWedgePixel twin = penumbraWedgePixel(prepared, scene, light, pointAt(frame, x, y), receiverOffset, {});
      ++compared;
      inPenumbra += twin.wedgesCovering > 0;
      // The centre's count is the shadow volumes' (ShadowVolumeTest checks it); a pixel whose count differs (a
      // segment through an edge) is not this technique's to judge.
      if (static_cast<int>(bufferOf(frame, "depth_complexity_center").at(x, y)) != twin.centreCount)
      {
        ++centreMismatches;
        continue;
      }
      const double difference = std::abs(bufferOf(frame, "visibility").at(x, y) - twin.visibility);
      beyondOneTenThousandth += difference > 1e-4;
      coveringMismatches += static_cast<int>(bufferOf(frame, "wedges_covering").at(x, y)) != twin.wedgesCovering;
      worstRaw = std::max(worstRaw, std::abs(bufferOf(frame, "pw_occlusion_raw").at(x, y) - twin.occlusionRaw));
      worstVisibility = std::max(worstVisibility, std::abs(bufferOf(frame, "visibility").at(x, y) - twin.visibility));
    }
  }
  std::cout << "[ measured ] penumbra-wedge GPU against its twin, " << c.name << ": " << compared << " pixels (" << inPenumbra
            << " inside a wedge), max |raw| difference " << worstRaw << ", max |V| difference " << worstVisibility << " ("
            << beyondOneTenThousandth << " pixels beyond 1e-4); wedges_covering differing " << coveringMismatches
            << "; centre counts differing from the crossings " << centreMismatches << " (the shadow volumes')\n";
  EXPECT_GT(inPenumbra, 200) << c.name;
  // A point within float rounding of a wedge's region boundary contributes ~0 there either way.
  EXPECT_LE(coveringMismatches, compared / 100) << c.name;
  // Float far regions: where a silhouette edge lies close to the point (the bunny's contact with the ground) its
  // projection is magnified, and the float counted point and clipping move the area by up to a few 1e-4.
  EXPECT_LE(worstRaw, 1e-3) << c.name;
  EXPECT_LE(worstVisibility, 1e-3) << c.name;
  EXPECT_LE(beyondOneTenThousandth, std::max(1, inPenumbra / 20)) << c.name;
  // The hard shadow is shadow-volume's: its count is checked against the crossings in ShadowVolumeTest
  // (ShadowVolumeCracks). Here it is only reported. On random_stack_3 at 96^2 one whole image row of the ground read
  // -1 from the ground's own volume until the count shader took a side quad's crossing behind the eye as one at
  // infinity (issue 27 item 2b); a count still below 0 is flagged volume_count_status, counted in cut_short_pixels.
  std::cout << "[ measured ] penumbra-wedge " << c.name << ": cut_short_pixels "
            << frame.techniqueStatistics.at("cut_short_pixels") << "\n";
}

std::vector<GpuTwinCase> gpuTwinCases()
{
  std::mt19937 generator(2002);
  return { { "planar_occluder", "planar-occluder", {} }, { "stacked_occluders", "stacked-occluders", {} },
    { "bunny", "bunny", {} }, { "random_stack_3", "stacked-occluders", test::randomRectangleStack(generator, 3) } };
}

INSTANTIATE_TEST_SUITE_P(Scenes, PenumbraWedgeGpu, testing::ValuesIn(gpuTwinCases()),
  [](const testing::TestParamInfo<GpuTwinCase>& info) { return info.param.name; });

TEST(PenumbraWedgeGpuClosedForm, PlanarOccluderWithinOneTenThousandth)
{
  const Scene scene = test::loadDataset("planar-occluder");
  const FrameResult frame = test::renderDataset(scene, "penumbra-wedge", 128, 128, { kWedgeCloseReceiverOffset });
  const test::GroundError error = test::groundErrorAgainst(
    frame, [](double x, double z) { return test::parallelSquaresVisibility(1.0, 3.0, 1.0, 1.0, x, z); });
  std::cout << "[ measured ] penumbra-wedge, planar-occluder against the closed form: max " << error.maxError << ", RMSE "
            << error.rmse << " over " << error.ground << " ground pixels (" << error.penumbra << " in the penumbra)\n";
  EXPECT_GT(error.penumbra, 1000);
  EXPECT_LE(error.maxError, 1e-4);
}

TEST(PenumbraWedgeGpuClosedForm, StackedOccludersOverShadowWhereTheyOverlap)
{
  // Against Embree (2048 samples): lighter than the truth beyond the reference's noise only where the centre is
  // under two occluders (the single hard-shadow count); darker where the two shadows overlap in the penumbra, by the
  // double count; pw_occlusion_raw > 1 somewhere.
  const Scene scene = test::loadDataset("stacked-occluders");
  const FrameResult frame = test::renderDataset(scene, "penumbra-wedge", kWedgeFrameSize, kWedgeFrameSize, { kWedgeCloseReceiverOffset });
  ReferenceSettings settings;
  settings.samples = 2048;
  const ReferenceResult reference = renderReference(test::referenceInputs(frame, scene), settings);
  int lighter = 0;
  int lighterWithSingleCentre = 0;
  int darker = 0;
  int overOne = 0;
  double worstDarker = 0.0;
  for (int y = 0; y < kWedgeFrameSize; ++y)
  {
    for (int x = 0; x < kWedgeFrameSize; ++x)
    {
      if (bufferOf(frame, "coverage").at(x, y) <= 0.5f)
      {
        continue;
      }
      const double difference = bufferOf(frame, "visibility").at(x, y) - reference.visibility.at(x, y);
      const double noise = 4.0 * reference.standardError.at(x, y) + 1e-3;
      overOne += bufferOf(frame, "pw_occlusion_raw").at(x, y) > 1.0f + 1e-4f;
      if (difference > noise)
      {
        ++lighter;
        lighterWithSingleCentre += bufferOf(frame, "depth_complexity_center").at(x, y) < 1.5f;
      }
      if (difference < -noise)
      {
        ++darker;
        worstDarker = std::max(worstDarker, -difference);
      }
    }
  }
  std::cout << "[ measured ] penumbra-wedge, stacked-occluders against Embree: " << darker << " pixels darker (worst by "
            << worstDarker << "), " << lighter << " lighter (" << lighterWithSingleCentre << " of them with the centre "
            << "under fewer than two occluders), " << overOne << " with pw_occlusion_raw > 1\n";
  EXPECT_GT(darker, 50);
  EXPECT_EQ(lighterWithSingleCentre, 0);
  EXPECT_GT(overOne, 0);
}

TEST(PenumbraWedgeGpuClosedForm, BunnyErrorsAboveDcsWherePotentialSilhouettesOutnumberCentreOnes)
{
  // Forest et al. 2009 §3.1 against §3.2: on the bunny penumbra wedges miss the silhouettes seen from the rest of the light. The
  // pixels where dcs (potential silhouettes) finds more wedges than penumbra-wedge (centre silhouettes) hold its
  // excess error.
  const Scene scene = test::loadDataset("bunny");
  const FrameResult wedges = test::renderDataset(scene, "penumbra-wedge", kWedgeFrameSize, kWedgeFrameSize);
  const FrameResult dcs = test::renderDataset(scene, "dcs", kWedgeFrameSize, kWedgeFrameSize, { "samples=256" });
  ReferenceSettings settings;
  settings.samples = 2048;
  const ReferenceResult reference = renderReference(test::referenceInputs(wedges, scene), settings);
  const ImageF& coverage = bufferOf(wedges, "coverage");
  const ErrorMetrics wedgeError = computeErrorMetrics(bufferOf(wedges, "visibility"), reference.visibility, coverage, coverage);
  const ErrorMetrics dcsError = computeErrorMetrics(bufferOf(dcs, "visibility"), reference.visibility, coverage, coverage);
  double moreSquared = 0.0;
  double elsewhereSquared = 0.0;
  int more = 0;
  int elsewhere = 0;
  for (int y = 0; y < kWedgeFrameSize; ++y)
  {
    for (int x = 0; x < kWedgeFrameSize; ++x)
    {
      if (coverage.at(x, y) <= 0.5f)
      {
        continue;
      }
      const double error = bufferOf(wedges, "visibility").at(x, y) - reference.visibility.at(x, y);
      if (bufferOf(dcs, "wedges_covering").at(x, y) > bufferOf(wedges, "wedges_covering").at(x, y))
      {
        moreSquared += error * error;
        ++more;
      }
      else
      {
        elsewhereSquared += error * error;
        ++elsewhere;
      }
    }
  }
  const double moreRmse = std::sqrt(moreSquared / std::max(1, more));
  const double elsewhereRmse = std::sqrt(elsewhereSquared / std::max(1, elsewhere));
  std::cout << "[ measured ] bunny against Embree: RMSE penumbra-wedge " << wedgeError.covered.rmse << ", dcs (256 samples) "
            << dcsError.covered.rmse << "; penumbra-wedge RMSE " << moreRmse << " on the " << more << " pixels where potential "
            << "silhouettes outnumber centre ones, " << elsewhereRmse << " on the other " << elsewhere << " ("
            << 100.0 * moreSquared / (moreSquared + elsewhereSquared) << " % of its squared error)\n";
  EXPECT_GT(wedgeError.covered.rmse, 2.0 * dcsError.covered.rmse);
  EXPECT_GT(moreRmse, 2.0 * elsewhereRmse);
}

// ---------------------------------------------------------------------------------------------------------------
// Perforated casters: soft textured shadow volumes (Forest et al. 2009 §2, §3.1) on `fence`, against Embree on the same light
// samples, the twin, and dcs on the fence's equivalent mesh (Fig. 11's comparison).

// The counted point close to the receiver, so that it and Embree's ray origin (1e-4 of the scene's radius along the
// normal) see the same samples: at 1e-4 of the eye distance 0.24 % of the (pixel, sample) pairs differ, at 1e-5 0.08 %.
constexpr const char* kStsvReceiverOffset = "receiver_offset=1e-5";
const std::vector<std::string> kStsvSettings = { kStsvReceiverOffset, "light_samples=poisson", "samples=64" };

bool sampleHidden(const ImageF& mask, int x, int y, int index)
{
  return (static_cast<std::uint32_t>(mask.at(x, y, index / 16)) >> (index % 16)) & 1u;
}

// (pixel, sample) pairs of the ground (y = 0) whose hidden bits differ between two masks.
struct MaskAgreement
{
  long pairs = 0;
  long differing = 0;
  double fraction() const { return pairs > 0 ? 1.0 - static_cast<double>(differing) / static_cast<double>(pairs) : 0.0; }
};

MaskAgreement groundAgreement(const FrameResult& frame, const ImageF& a, const ImageF& b, int samples)
{
  MaskAgreement agreement;
  for (int y = 0; y < frame.resolution.y; ++y)
  {
    for (int x = 0; x < frame.resolution.x; ++x)
    {
      if (bufferOf(frame, "coverage").at(x, y) <= 0.5f || std::abs(pointAt(frame, x, y).y) > 1e-3)
      {
        continue;
      }
      for (int i = 0; i < samples; ++i)
      {
        ++agreement.pairs;
        agreement.differing += sampleHidden(a, x, y, i) != sampleHidden(b, x, y, i);
      }
    }
  }
  return agreement;
}

ImageF referenceMask(const FrameResult& frame, const Scene& scene)
{
  ReferenceSettings settings;
  settings.lightSampleSet = lightSampleSetSettings("poisson", 64, 1);
  return renderReference(test::referenceInputs(frame, scene), settings).lightSampleMask;
}

// `fence` with its light moved into the canopy's plane (y = 1), turned to face -x: the plane cuts the light, so
// every perforated triangle has two STSVs (Forest et al. 2009 §6).
std::vector<std::string> straddlingLight()
{
  return { "/lights/0/center=[1.6, 1.0, 0.2]", "/lights/0/normal=[-1, -0.05, 0]", "/lights/0/up=[0, 1, 0]" };
}

TEST(PenumbraWedgeStsv, FenceHidesTheRayTracersSamples)
{
  for (const bool straddling : { false, true })
  {
    const Scene scene = loadScene(test::datasetPath("fence"), straddling ? straddlingLight() : std::vector<std::string>{});
    const FrameResult frame = test::renderDataset(scene, "penumbra-wedge", 128, 128, kStsvSettings);
    const MaskAgreement agreement = groundAgreement(frame, bufferOf(frame, "light_sample_mask"), referenceMask(frame, scene), 64);
    const double stsvs = frame.techniqueStatistics.at("stsvs");
    std::cout << "[ measured ] penumbra-wedge STSVs on fence" << (straddling ? " (light straddling the canopy's plane)" : "")
              << ": " << stsvs << " STSVs; hidden bits equal Embree's on " << 100.0 * agreement.fraction() << " % of "
              << agreement.pairs << " ground (pixel, sample) pairs\n";
    EXPECT_EQ(stsvs, straddling ? 4.0 : 2.0);
    EXPECT_GE(agreement.fraction(), 0.999) << (straddling ? "straddling" : "fence");
    EXPECT_GT(agreement.pairs, 100000);
  }
}

TEST(PenumbraWedgeStsv, GpuBitsAreTheTwinsAndTheCheckChangesNothingInsideTheVolumes)
{
  // The twin (objectspace/StsvGeometry.h) sample for sample; a sample whose segment passes within float rounding of a texel
  // edge may go either way. With stsv_opposite_side_check off the GPU gives the same bits: inside an STSV the paper's
  // test alone is right for the STSV's own light piece (StsvGeometry.h, "The gap"), so the check only matters for
  // Eq. 1 evaluated outside the volumes (tests/unit/StsvTest.cpp).
  for (const bool straddling : { false, true })
  {
    const Scene scene = loadScene(test::datasetPath("fence"), straddling ? straddlingLight() : std::vector<std::string>{});
    const FrameResult frame = test::renderDataset(scene, "penumbra-wedge", 96, 96, kStsvSettings);
    std::vector<std::string> unchecked = kStsvSettings;
    unchecked.push_back("stsv_opposite_side_check=off");
    const FrameResult withoutCheck = test::renderDataset(scene, "penumbra-wedge", 96, 96, unchecked);
    const Light& light = scene.lights.front();
    const PenumbraWedgeScene prepared = penumbraWedgeScene(scene, light);
    const LightSampleSet samples(lightSampleSetSettings(frame.parameters));
    const ImageF& mask = bufferOf(frame, "light_sample_mask");
    long pairs = 0;
    long differing = 0;
    long hidden = 0;
    int coveringDiffers = 0;
    for (int y = 0; y < 96; ++y)
    {
      for (int x = 0; x < 96; ++x)
      {
        if (bufferOf(frame, "coverage").at(x, y) <= 0.5f)
        {
          continue;
        }
        const PenumbraWedgePixel twin = penumbraWedgePixel(prepared, scene, light, pointAt(frame, x, y),
          frame.parameters.get("receiver_offset"), dcsSamplePoints(light, samples, { x, y }));
        coveringDiffers += static_cast<int>(bufferOf(frame, "stsv_covering").at(x, y)) != twin.stsvCovering;
        for (int i = 0; i < samples.count(); ++i)
        {
          ++pairs;
          hidden += twin.stsvHidden[static_cast<std::size_t>(i)];
          differing += sampleHidden(mask, x, y, i) != twin.stsvHidden[static_cast<std::size_t>(i)];
        }
      }
    }
    const ImageF& maskWithoutCheck = bufferOf(withoutCheck, "light_sample_mask");
    const long changedByCheck = static_cast<long>(std::inner_product(mask.data.begin(), mask.data.end(),
      maskWithoutCheck.data.begin(), 0L, std::plus<>(), [](float a, float b) { return a != b ? 1L : 0L; }));
    std::cout << "[ measured ] penumbra-wedge STSVs against the twin" << (straddling ? " (straddling light)" : "") << ": "
              << differing << " of " << pairs << " (pixel, sample) pairs differ (" << hidden << " hidden), stsv_covering "
              << "differs on " << coveringDiffers << " pixels; mask components changed by turning the check off: "
              << changedByCheck << "\n";
    EXPECT_GT(hidden, 10000);
    EXPECT_LE(differing, pairs / 1000);
    EXPECT_LE(coveringDiffers, 96 * 96 / 1000);
    EXPECT_EQ(changedByCheck, 0);
  }
}

TEST(PenumbraWedgeStsv, DcsOnTheEquivalentMeshHidesTheSameSamples)
{
  // Fig. 11's comparison as bits: dcs on fence-meshed (63 488 triangles) and the STSVs of fence's two perforated
  // triangles, same light samples, same counted point.
  const Scene fence = test::loadDataset("fence");
  const Scene meshed = test::loadDataset("fence-meshed");
  const FrameResult stsv = test::renderDataset(fence, "penumbra-wedge", 128, 128, kStsvSettings);
  const FrameResult mesh = test::renderDataset(meshed, "dcs", 128, 128, kStsvSettings);
  const MaskAgreement agreement =
    groundAgreement(stsv, bufferOf(stsv, "light_sample_mask"), bufferOf(mesh, "light_sample_mask"), 64);
  std::cout << "[ measured ] fence: STSV bits (2 perforated triangles, " << stsv.techniqueStatistics.at("stsv_gpu_ms")
            << " ms) against dcs on fence-meshed (" << mesh.techniqueStatistics.at("wedges_drawn") << " wedges, "
            << mesh.techniqueStatistics.at("wedges_gpu_ms") << " ms): equal on " << 100.0 * agreement.fraction() << " % of "
            << agreement.pairs << " ground (pixel, sample) pairs\n";
  EXPECT_GE(agreement.fraction(), 0.999);
}

} // namespace
} // namespace sl
