// Technique dcs's core math on the CPU (src/objectspace/DcsGeometry.h), against direct counts: on random stacks of
// closed, open and non-manifold casters under random square and disk lights, the centre's count plus every wedge's
// per-sample change equals the number of caster triangles the segment from the point to the sample crosses (Moller-
// Trumbore in double over every triangle). Also: a wedge that changes a count contains the point (wedgeContains),
// and the point's pixel lies inside the wedge's screen polygon, so the rasterised wedges miss no change.
#include "lightspace/CameraView.h"
#include "lightspace/LightSamples.h"
#include "scene/Primitives.h"
#include "scene/RayTriangle.h"
#include "scene/WeldedMesh.h"
#include "objectspace/DcsGeometry.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace sl
{
namespace
{

TriangleMesh meshFrom(const std::vector<glm::dvec3>& points, const std::vector<std::uint32_t>& indices)
{
  TriangleMesh mesh;
  for (const glm::dvec3& point : points)
  {
    mesh.positions.emplace_back(point);
    mesh.normals.emplace_back(0.0f, 1.0f, 0.0f);
  }
  mesh.indices = indices;
  return mesh;
}

// A random configuration of casters: a box (split vertices, welded), a tetrahedron, an open quad at a random
// angle, two tetrahedra sharing an edge (a non-manifold edge of four triangles), and sometimes a sphere; each placed
// at random in a slab between the light and the ground.
std::vector<WeldedMesh> randomCasters(std::mt19937_64& random)
{
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto around = [&](double spread, double height) {
    return glm::dvec3((unit(random) - 0.5) * spread, height + unit(random), (unit(random) - 0.5) * spread);
  };
  const auto jitter = [&](double amount) {
    return glm::dvec3(unit(random) - 0.5, unit(random) - 0.5, unit(random) - 0.5) * amount;
  };
  std::vector<TriangleMesh> meshes;
  meshes.push_back(makeBox(around(3.0, 1.0), glm::dvec3(0.3 + unit(random), 0.2 + unit(random), 0.3 + unit(random))));
  {
    const glm::dvec3 c = around(3.0, 1.5);
    meshes.push_back(meshFrom({ c + jitter(1.5), c + jitter(1.5), c + jitter(1.5), c + jitter(1.5) },
      { 0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2 }));
  }
  {
    const glm::dvec3 normal = glm::normalize(glm::dvec3(unit(random) - 0.5, 1.0, unit(random) - 0.5));
    const glm::dvec3 up = orthogonalizedUp(glm::dvec3(0.0, 0.0, 1.0), normal);
    meshes.push_back(makeQuad(around(3.0, 2.0), glm::dvec2(0.5 + unit(random), 0.5 + unit(random)), normal, up));
  }
  {
    const glm::dvec3 c = around(3.0, 1.0);
    const glm::dvec3 a = c + jitter(1.0);
    const glm::dvec3 b = c + jitter(1.0);
    meshes.push_back(meshFrom({ a, b, c + jitter(1.5), c + jitter(1.5), c + jitter(1.5), c + jitter(1.5) },
      { 0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2, 0, 1, 4, 0, 5, 1, 0, 4, 5, 1, 5, 4 }));
  }
  if (unit(random) < 0.3)
  {
    meshes.push_back(makeSphere(around(3.0, 1.5), 0.2 + 0.5 * unit(random)));
  }
  std::vector<WeldedMesh> welded;
  for (std::size_t index = 0; index < meshes.size(); ++index)
  {
    welded.push_back(weldMesh(meshes[index], index));
  }
  return welded;
}

Light randomAreaLight(std::mt19937_64& random)
{
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Light light;
  light.type = LightType::Area;
  light.shape = unit(random) < 0.5 ? LightShape::Square : LightShape::Disk;
  light.center = glm::dvec3(unit(random) - 0.5, 4.5 + unit(random), unit(random) - 0.5);
  light.normal = glm::normalize(glm::dvec3(0.4 * (unit(random) - 0.5), -1.0, 0.4 * (unit(random) - 0.5)));
  light.up = orthogonalizedUp(glm::dvec3(0.0, 0.0, 1.0), light.normal);
  light.size = 0.2 + 3.0 * unit(random);
  return light;
}

// Caster triangles crossed by the open segment (p, s), directly.
int directCrossings(const std::vector<WeldedMesh>& casters, const glm::dvec3& p, const glm::dvec3& s)
{
  int count = 0;
  for (const WeldedMesh& mesh : casters)
  {
    for (const auto& triangle : mesh.triangles)
    {
      const glm::dvec3 a = mesh.positions[triangle[0]];
      const glm::dvec3 b = mesh.positions[triangle[1]];
      const glm::dvec3 c = mesh.positions[triangle[2]];
      const auto hit = intersectRayTriangle(p, s - p, a, b - a, c - a);
      count += hit && hit->t > 0.0 && hit->t < 1.0;
    }
  }
  return count;
}

bool insideConvexPolygon(const std::vector<glm::dvec2>& polygon, const glm::dvec2& point)
{
  for (std::size_t i = 0; i < polygon.size(); ++i)
  {
    const glm::dvec2 a = polygon[i];
    const glm::dvec2 b = polygon[(i + 1) % polygon.size()];
    if ((b.x - a.x) * (point.y - a.y) - (b.y - a.y) * (point.x - a.x) < 0.0)
    {
      return false;
    }
  }
  return polygon.size() >= 3;
}

TEST(DcsRule, CentreCountPlusWedgeChangesEqualsDirectCrossingsOnRandomCasters)
{
  std::mt19937_64 random(16);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Camera cameraSettings;
  cameraSettings.position = glm::dvec3(0.0, 3.0, 9.0);
  cameraSettings.focalPoint = glm::dvec3(0.0, 1.0, 0.0);
  Bounds sceneBounds;
  sceneBounds.extend(glm::dvec3(-4.0, -0.5, -4.0));
  sceneBounds.extend(glm::dvec3(4.0, 6.0, 4.0));
  const CameraView camera = makeCameraView(cameraSettings, sceneBounds, glm::ivec2(128, 128));
  std::size_t pairs = 0;
  std::size_t mismatches = 0;
  std::size_t nonZeroChanges = 0;
  std::size_t polygonChecks = 0;
  for (int configuration = 0; configuration < 60; ++configuration)
  {
    const std::vector<WeldedMesh> casters = randomCasters(random);
    const Light light = randomAreaLight(random);
    const DcsEdgeSet wedges = potentialSilhouetteWedges(casters, light);
    const std::vector<glm::dvec3> outline = lightOutline(light);
    std::vector<std::vector<glm::dvec2>> polygons;
    for (const DcsWedgeEdge& wedge : wedges.wedges)
    {
      polygons.push_back(wedgeScreenPolygon(wedge, light, outline, camera, true, sceneBounds));
    }
    for (int point = 0; point < 40; ++point)
    {
      const glm::dvec3 p((unit(random) - 0.5) * 6.0, -0.3 + 2.5 * unit(random), (unit(random) - 0.5) * 6.0);
      const int centre = directCrossings(casters, p, light.center);
      std::vector<glm::dvec3> samples;
      for (int k = 0; k < 24; ++k)
      {
        samples.push_back(pointOnAreaLight(light, glm::dvec2(unit(random), unit(random))));
      }
      std::vector<int> counts(samples.size(), centre);
      for (std::size_t w = 0; w < wedges.wedges.size(); ++w)
      {
        const DcsWedgeEdge& wedge = wedges.wedges[w];
        bool changesSome = false;
        for (std::size_t k = 0; k < samples.size(); ++k)
        {
          const int change = sampleCountChange(wedge, p, light.center, samples[k]);
          counts[k] += change;
          changesSome = changesSome || change != 0;
        }
        if (!changesSome)
        {
          continue;
        }
        ++nonZeroChanges;
        // A wedge that changes a count contains the point, and the point's pixel is inside its screen polygon.
        EXPECT_TRUE(wedgeContains(wedge, p, outline, light.normal)) << "configuration " << configuration;
        const glm::dvec4 clip = camera.clipFromWorld * glm::dvec4(p, 1.0);
        const glm::dvec2 ndc = glm::dvec2(clip) / clip.w;
        if (clip.w > 0.0 && std::abs(ndc.x) < 1.0 && std::abs(ndc.y) < 1.0)
        {
          ++polygonChecks;
          EXPECT_TRUE(insideConvexPolygon(polygons[w], ndc)) << "configuration " << configuration << " wedge " << w;
        }
      }
      for (std::size_t k = 0; k < samples.size(); ++k)
      {
        ++pairs;
        const int direct = directCrossings(casters, p, samples[k]);
        if (counts[k] != direct)
        {
          ++mismatches;
          ADD_FAILURE() << "configuration " << configuration << ": count " << counts[k] << ", direct " << direct;
        }
      }
    }
  }
  std::printf("[ dcs rule ] %zu (point, sample) pairs, %zu mismatches, %zu changing wedges (%zu polygon checks)\n",
    pairs, mismatches, nonZeroChanges, polygonChecks);
  EXPECT_GT(nonZeroChanges, 1000u); // the configurations do exercise the wedges
  EXPECT_GT(polygonChecks, 500u);
}

TEST(DcsRule, ClosedMeshesAreSilhouettesOnlyWhereTheirFacesDisagree)
{
  // A box far below a small square light: its potential silhouettes are its side edges seen from the light, never
  // a top-face diagonal (two coplanar faces facing the light alike everywhere).
  Light light;
  light.center = glm::dvec3(0.0, 10.0, 0.0);
  light.size = 0.5;
  const std::vector<WeldedMesh> casters = { weldMesh(makeBox(glm::dvec3(0.0, 1.0, 0.0), glm::dvec3(1.0)), 0) };
  const DcsEdgeSet wedges = potentialSilhouetteWedges(casters, light);
  EXPECT_EQ(wedges.statistics.edges, 18u);      // 12 box edges + 6 face diagonals
  EXPECT_EQ(wedges.statistics.boundaryEdges, 0u);
  EXPECT_EQ(wedges.statistics.potentialSilhouetteEdges, 4u); // the top face's rim, seen from above
  EXPECT_EQ(wedges.statistics.centreSilhouetteEdges, 4u);
  for (const DcsWedgeEdge& wedge : wedges.wedges)
  {
    EXPECT_EQ(wedge.oppositeCount, 2);
    EXPECT_NEAR(wedge.v0.y, 1.5, 1e-6);
    EXPECT_NEAR(wedge.v1.y, 1.5, 1e-6);
  }
  // Moved beside the box, the light sees two faces of some edges differently from its corners: more potential
  // silhouettes than silhouettes from the centre.
  light.center = glm::dvec3(0.52, 3.0, 0.0);
  light.size = 2.0;
  const DcsEdgeSet beside = potentialSilhouetteWedges(casters, light);
  EXPECT_GT(beside.statistics.potentialSilhouetteEdges, beside.statistics.centreSilhouetteEdges);
}

TEST(DcsRule, DiskOutlineIsTheOctagonAroundTheDisk)
{
  Light light;
  light.shape = LightShape::Disk;
  light.size = 2.0;
  const std::vector<glm::dvec3> outline = lightOutline(light);
  ASSERT_EQ(outline.size(), 8u);
  for (std::size_t i = 0; i < outline.size(); ++i)
  {
    // Each side's midpoint touches the disk (distance r from the centre), so the disk lies inside.
    const glm::dvec3 midpoint = 0.5 * (outline[i] + outline[(i + 1) % outline.size()]);
    EXPECT_NEAR(glm::length(midpoint - light.center), 1.0, 1e-12);
    EXPECT_NEAR(glm::dot(outline[i] - light.center, light.normal), 0.0, 1e-12);
  }
}

} // namespace
} // namespace sl
