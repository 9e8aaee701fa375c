// The CPU side of technique `penumbra-wedge` (techniques/penumbrawedge/PenumbraWedgeGeometry.h, AAM03 as paper 003
// §3.1 uses it) against closed forms: parallel squares under a square light, where each occluder's shadow is the
// light clipped by the occluder's projection, so AAM03's result is known exactly:
//     occlusion_raw = sum_i A_i + [k > 0] - k,   A_i = |L ∩ proj_i| / |L|,  k = occluders whose projection holds c
// (each convex occluder's wedges move its own area; the hard shadow of the centre counts once however many hold it).
// With one occluder that is the exact shadow; with overlapping ones it double-counts the overlap (003 L384-387).
// Then the GPU technique against this twin pixel by pixel, against the closed form, and against Embree and `dcs`.
#include "frame/FrameResult.h"
#include "lightspace/LightView.h"
#include "metrics/ErrorMetrics.h"
#include "reference/ReferenceRenderer.h"
#include "scene/WeldedMesh.h"
#include "support/TestSupport.h"
#include "techniques/penumbrawedge/PenumbraWedgeGeometry.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
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
  const std::vector<DcsWedgeEdge> wedges = centreSilhouetteWedges(potentialSilhouetteWedges(weldCasters(scene), light));
  Sweep sweep;
  for (int i = 0; i <= steps; ++i)
  {
    for (int j = 0; j <= steps; ++j)
    {
      // Just above the ground, so the ground's own triangles are not crossed on the way to the light.
      const glm::dvec3 p(-extent + 2.0 * extent * i / steps, 1e-9, -extent + 2.0 * extent * j / steps);
      const PenumbraWedgePixel twin = penumbraWedgePixel(scene, light, wedges, p, 0.0);
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
  const std::vector<DcsWedgeEdge> wedges = centreSilhouetteWedges(potentialSilhouetteWedges(weldCasters(scene), light));
  double worst = 0.0;
  int penumbra = 0;
  for (int i = 0; i <= 80; ++i)
  {
    for (int j = 0; j <= 80; ++j)
    {
      const double x = -2.0 + 4.0 * i / 80.0;
      const double z = -2.0 + 4.0 * j / 80.0;
      const PenumbraWedgePixel twin = penumbraWedgePixel(scene, light, wedges, { x, 1e-9, z }, 0.0);
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
  const std::vector<DcsWedgeEdge> wedges = centreSilhouetteWedges(potentialSilhouetteWedges(weldCasters(scene), light));
  EXPECT_EQ(penumbraWedgePixel(scene, light, wedges, { 2.5, 1e-9, 2.5 }, 0.0).visibility, 1.0);
  const PenumbraWedgePixel umbra = penumbraWedgePixel(scene, light, wedges, { 0.1, 1e-9, 0.05 }, 0.0);
  EXPECT_EQ(umbra.centreCount, 1);
  EXPECT_EQ(umbra.wedgesCovering, 0);
  EXPECT_EQ(umbra.visibility, 0.0);
}

// ---------------------------------------------------------------------------------------------------------------
// The GPU technique.

constexpr int kFrameSize = 96;
// The counted point is moved receiver_offset toward the camera; close to the receiver for the closed forms.
constexpr const char* kCloseReceiverOffset = "receiver_offset=1e-6";

const ImageF& bufferOf(const FrameResult& frame, const std::string& name)
{
  const NamedImage* image = frame.find(name);
  if (image == nullptr)
  {
    throw std::runtime_error("frame has no buffer '" + name + "'");
  }
  return image->image;
}

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
  const FrameResult frame = test::renderDataset(scene, "penumbra-wedge", kFrameSize, kFrameSize);
  const Light& light = scene.lights.front();
  const std::vector<DcsWedgeEdge> wedges = centreSilhouetteWedges(potentialSilhouetteWedges(weldCasters(scene), light));
  const double receiverOffset = frame.parameters.get("receiver_offset");
  int compared = 0;
  int inPenumbra = 0;
  int centreMismatches = 0;
  int coveringMismatches = 0;
  int beyondOneTenThousandth = 0;
  double worstRaw = 0.0;
  double worstVisibility = 0.0;
  for (int y = 0; y < kFrameSize; ++y)
  {
    for (int x = 0; x < kFrameSize; ++x)
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
      const PenumbraWedgePixel twin = penumbraWedgePixel(scene, light, wedges, pointAt(frame, x, y), receiverOffset);
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
  // The hard shadow is shadow-volume's: its count is checked against the crossings in ShadowVolumeTest. Here it
  // is only reported (on random_stack_3 at 96^2 one whole image row of the ground gets -1 from the ground's own
  // volume, a shadow-volume defect seen at this size and light height only; the pixels are left out above).
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
  const FrameResult frame = test::renderDataset(scene, "penumbra-wedge", 128, 128, { kCloseReceiverOffset });
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
  const FrameResult frame = test::renderDataset(scene, "penumbra-wedge", kFrameSize, kFrameSize, { kCloseReceiverOffset });
  ReferenceSettings settings;
  settings.samples = 2048;
  const ReferenceResult reference = renderReference(test::referenceInputs(frame, scene), settings);
  int lighter = 0;
  int lighterWithSingleCentre = 0;
  int darker = 0;
  int overOne = 0;
  double worstDarker = 0.0;
  for (int y = 0; y < kFrameSize; ++y)
  {
    for (int x = 0; x < kFrameSize; ++x)
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
  // 003 §3.1 against §3.2: on the bunny penumbra wedges miss the silhouettes seen from the rest of the light. The
  // pixels where dcs (potential silhouettes) finds more wedges than penumbra-wedge (centre silhouettes) hold its
  // excess error.
  const Scene scene = test::loadDataset("bunny");
  const FrameResult wedges = test::renderDataset(scene, "penumbra-wedge", kFrameSize, kFrameSize);
  const FrameResult dcs = test::renderDataset(scene, "dcs", kFrameSize, kFrameSize, { "samples=256" });
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
  for (int y = 0; y < kFrameSize; ++y)
  {
    for (int x = 0; x < kFrameSize; ++x)
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

} // namespace
} // namespace sl
