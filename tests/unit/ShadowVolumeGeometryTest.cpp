// Technique `shadow-volume`, CPU side: welding (scene/WeldedMesh.h), silhouette extraction against a
// brute-force edge test, and the generated volumes against a direct count. The volumes' winding number at
// a point (solid angles of the very triangles the pass uploads) must equal the number of caster triangles
// the segment from the point to the light crosses, on closed, open, non-manifold and random meshes, for
// point and directional lights, extruded to infinity and cut at a finite distance.
#include "scene/Primitives.h"
#include "scene/WeldedMesh.h"
#include "objectspace/ShadowVolumeGeometry.h"
#include "objectspace/ShadowVolumeReference.h"
#include "objectspace/SilhouetteExport.h"

#include <gtest/gtest.h>

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkPolyData.h>

#include <cmath>
#include <map>
#include <random>
#include <string>
#include <tuple>
#include <vector>

namespace sl
{
namespace
{

// ---- meshes ---------------------------------------------------------------------------------------------

TriangleMesh meshFrom(const std::vector<glm::dvec3>& positions, const std::vector<std::uint32_t>& indices)
{
  TriangleMesh mesh;
  for (const glm::dvec3& position : positions)
  {
    mesh.positions.emplace_back(position);
    mesh.normals.emplace_back(0.0f, 0.0f, 1.0f);
  }
  mesh.indices = indices;
  return mesh;
}

// Two tetrahedra sharing the edge (0,0,0)-(0,0,1): that edge has four triangles, the others two.
TriangleMesh twoTetrahedraSharingAnEdge()
{
  const std::vector<glm::dvec3> positions = { { 0, 0, 0 }, { 0, 0, 1 }, { 1, 0, 0.5 }, { 0.5, 1, 0.5 },
    { -1, 0, 0.5 }, { -0.5, -1, 0.5 } };
  // Each tetrahedron (0, 1, a, b) wound outward.
  std::vector<std::uint32_t> indices;
  for (const auto& [a, b] : { std::pair<std::uint32_t, std::uint32_t>{ 2, 3 }, { 4, 5 } })
  {
    const glm::dvec3 centre = 0.25 * (positions[0] + positions[1] + positions[a] + positions[b]);
    const std::uint32_t faces[4][3] = { { 0, 1, a }, { 0, b, 1 }, { 0, a, b }, { 1, b, a } };
    for (const auto& face : faces)
    {
      const glm::dvec3 p0 = positions[face[0]], p1 = positions[face[1]], p2 = positions[face[2]];
      const bool outward = glm::dot(glm::cross(p1 - p0, p2 - p0), p0 - centre) > 0.0;
      indices.insert(indices.end(), { face[0], outward ? face[1] : face[2], outward ? face[2] : face[1] });
    }
  }
  return meshFrom(positions, indices);
}

// Triangles over a small pool of shared random points: shared, non-manifold, inconsistently wound and
// repeated edges, in any mix.
TriangleMesh randomSoup(std::mt19937& generator, int points, int triangles)
{
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  std::vector<glm::dvec3> positions;
  for (int point = 0; point < points; ++point)
  {
    positions.emplace_back(coordinate(generator), coordinate(generator), coordinate(generator));
  }
  std::uniform_int_distribution<std::uint32_t> pick(0, static_cast<std::uint32_t>(points - 1));
  std::vector<std::uint32_t> indices;
  while (indices.size() < 3u * static_cast<std::size_t>(triangles))
  {
    const std::uint32_t a = pick(generator), b = pick(generator), c = pick(generator);
    if (a != b && b != c && c != a)
    {
      indices.insert(indices.end(), { a, b, c });
    }
  }
  // Split every vertex per triangle, as primitives do: welding must find the sharing again.
  TriangleMesh split;
  for (const std::uint32_t index : indices)
  {
    split.indices.push_back(static_cast<std::uint32_t>(split.positions.size()));
    split.positions.emplace_back(positions[index]);
    split.normals.emplace_back(0.0f, 0.0f, 1.0f);
  }
  return split;
}

TriangleMesh openBox()
{
  TriangleMesh box = makeBox(glm::dvec3(0.2, 0.1, -0.1), glm::dvec3(1.0, 0.8, 1.2));
  box.indices.resize(box.indices.size() - 6); // without its last face (-z): four boundary edges
  return box;
}

Scene sceneOf(const std::vector<TriangleMesh>& meshes)
{
  Scene scene;
  for (const TriangleMesh& mesh : meshes)
  {
    SceneObject object;
    object.name = "test";
    object.mesh = mesh;
    scene.objects.push_back(object);
  }
  return scene;
}

VolumeLight pointLight(const glm::dvec3& position)
{
  VolumeLight light;
  light.position = position;
  return light;
}

VolumeLight directionalLight(const glm::dvec3& direction)
{
  VolumeLight light;
  light.directional = true;
  light.direction = glm::normalize(direction);
  return light;
}

// ---- welding --------------------------------------------------------------------------------------------

TEST(WeldedMesh, PrimitivesWeldIntoClosedManifoldsAndQuadsStayOpen)
{
  Transform transform;
  transform.translate = { 3.0, -2.0, 7.5 };
  transform.rotateDeg = { 31.0, -47.0, 12.5 };
  transform.scale = { 0.3, 2.0, 1.1 };
  TriangleMesh box = makeBox(glm::dvec3(0.1, 0.2, 0.3), glm::dvec3(1.0, 2.0, 0.5));
  transformMesh(box, transform.worldFromLocal());
  const WeldedMesh weldedBox = weldMesh(box, 4);
  EXPECT_EQ(weldedBox.objectIndex, 4u);
  EXPECT_EQ(weldedBox.positions.size(), 8u);
  EXPECT_EQ(weldedBox.triangles.size(), 12u);
  EXPECT_EQ(weldedBox.edges.size(), 18u);
  EXPECT_EQ(weldedBox.boundaryEdgeCount(), 0u);
  EXPECT_EQ(weldedBox.nonManifoldEdgeCount(), 0u);
  EXPECT_EQ(weldedBox.inconsistentEdgeCount(), 0u);

  TriangleMesh sphere = makeSphere(glm::dvec3(0.0, 1.0, 0.0), 0.5); // seam at z = 0: sin(2 pi) != 0
  transformMesh(sphere, transform.worldFromLocal());
  const WeldedMesh weldedSphere = weldMesh(sphere, 0);
  const std::size_t rings = kSphereRings - 1;
  EXPECT_EQ(weldedSphere.positions.size(), 2u + rings * kSphereSegments);
  EXPECT_EQ(weldedSphere.triangles.size(), sphere.triangleCount());
  // Euler: V - E + F = 2 for a closed sphere.
  EXPECT_EQ(weldedSphere.positions.size() + weldedSphere.triangles.size(), weldedSphere.edges.size() + 2u);
  EXPECT_EQ(weldedSphere.boundaryEdgeCount(), 0u);
  EXPECT_EQ(weldedSphere.nonManifoldEdgeCount(), 0u);
  EXPECT_EQ(weldedSphere.inconsistentEdgeCount(), 0u);

  const WeldedMesh quad = weldMesh(makeQuad(glm::dvec3(0.0), glm::dvec2(2.0, 1.0), { 0, 1, 0 }, { 0, 0, -1 }), 0);
  EXPECT_EQ(quad.positions.size(), 4u);
  EXPECT_EQ(quad.edges.size(), 5u);
  EXPECT_EQ(quad.boundaryEdgeCount(), 4u);

  const WeldedMesh tetrahedra = weldMesh(twoTetrahedraSharingAnEdge(), 0);
  EXPECT_EQ(tetrahedra.nonManifoldEdgeCount(), 1u);
  EXPECT_EQ(tetrahedra.boundaryEdgeCount(), 0u);
  EXPECT_EQ(tetrahedra.edges.size(), 11u);
  const WeldedMesh open = weldMesh(openBox(), 0);
  EXPECT_EQ(open.boundaryEdgeCount(), 4u);

  // One face of a box wound the other way: its four rim edges are used twice in the same direction.
  TriangleMesh flippedFace = makeBox(glm::dvec3(0.0), glm::dvec3(1.0));
  std::swap(flippedFace.indices[1], flippedFace.indices[2]);
  std::swap(flippedFace.indices[4], flippedFace.indices[5]);
  EXPECT_EQ(weldMesh(flippedFace, 0).inconsistentEdgeCount(), 4u);
}

TEST(WeldedMesh, ToleranceIsRelativeToTheObjectAndCollapsedTrianglesAreCounted)
{
  // A unit-size triangle pair; copies of a corner offset by half and by twice the tolerance.
  TriangleMesh mesh = meshFrom({ { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 1, 1, 0 } }, { 0, 1, 2 });
  const double tolerance = weldTolerance(mesh);
  EXPECT_NEAR(tolerance, 1e-6 * std::sqrt(2.0), 1e-12);
  mesh.positions.emplace_back(glm::dvec3(1.0 + 0.5 * tolerance, 0.0, 0.0)); // 4: welds to 1
  mesh.positions.emplace_back(glm::dvec3(0.0, 1.0 + 2.0 * tolerance, 0.0)); // 5: its own vertex
  mesh.normals.resize(mesh.positions.size());
  mesh.indices.insert(mesh.indices.end(), { 4, 3, 5 });
  mesh.indices.insert(mesh.indices.end(), { 1, 4, 3 }); // 1 and 4 weld: collapsed
  const WeldedMesh welded = weldMesh(mesh, 0);
  EXPECT_DOUBLE_EQ(welded.weldTolerance, weldTolerance(mesh)); // the bounds grew by 2 tolerances
  EXPECT_NEAR(welded.weldTolerance, tolerance, 1e-11);
  EXPECT_EQ(welded.positions.size(), 5u);
  ASSERT_EQ(welded.triangles.size(), 2u);
  EXPECT_EQ(welded.collapsedTriangles, 1u);
  EXPECT_EQ(welded.triangles[1][0], 1u);
  EXPECT_EQ(welded.sourceTriangles[1], 1u);
  // The welded vertex keeps its first vertex's position bit for bit.
  EXPECT_EQ(welded.positions[1], mesh.positions[1]);

  // Far from the origin the float spacing sets the tolerance: 4 float epsilons of the coordinate.
  const TriangleMesh far = meshFrom({ { 1e5, 0, 0 }, { 1e5 + 1e-2, 0, 0 }, { 1e5, 1e-2, 0 } }, { 0, 1, 2 });
  EXPECT_NEAR(weldTolerance(far), 4.0 * 1.1920929e-7 * 1e5, 1e-6);
}

// ---- silhouettes against a brute-force edge test ---------------------------------------------------------

using PositionKey = std::tuple<float, float, float>;
using EdgeKey = std::pair<PositionKey, PositionKey>;

PositionKey keyOf(const glm::vec3& p)
{
  return { p.x, p.y, p.z };
}

// Signed multiplicity per undirected edge, positive when the light-oriented triangles run from the
// lexicographically smaller end to the larger one.
std::map<EdgeKey, int> signedEdges(const std::vector<SilhouetteEdge>& silhouettes)
{
  std::map<EdgeKey, int> edges;
  for (const SilhouetteEdge& edge : silhouettes)
  {
    const PositionKey from = keyOf(edge.from), to = keyOf(edge.to);
    if (from < to)
      edges[{ from, to }] += edge.multiplicity;
    else
      edges[{ to, from }] -= edge.multiplicity;
  }
  return edges;
}

// Brute force on the welded mesh's own positions: every triangle's facing by a direct dot product, and
// the edges matched by comparing every directed edge with every other (no edge table).
std::map<EdgeKey, int> bruteForceSilhouettes(const WeldedMesh& mesh, const VolumeLight& light)
{
  struct DirectedEdge
  {
    glm::vec3 from, to;
  };
  std::vector<DirectedEdge> directed;
  for (const auto& corners : mesh.triangles)
  {
    glm::vec3 p[3] = { mesh.positions[corners[0]], mesh.positions[corners[1]], mesh.positions[corners[2]] };
    const glm::dvec3 a(p[0]), b(p[1]), c(p[2]);
    const glm::dvec3 normal = glm::cross(b - a, c - a);
    const glm::dvec3 toLight = light.directional ? -light.direction : light.position - a;
    const double sine = glm::dot(normal, toLight) / (glm::length(normal) * glm::length(toLight));
    if (std::abs(sine) < kEdgeOnSine)
    {
      continue;
    }
    if (sine < 0.0)
    {
      std::swap(p[1], p[2]);
    }
    for (int side = 0; side < 3; ++side)
    {
      directed.push_back({ p[side], p[(side + 1) % 3] });
    }
  }
  std::map<EdgeKey, int> edges;
  std::vector<bool> done(directed.size(), false);
  for (std::size_t i = 0; i < directed.size(); ++i)
  {
    if (done[i])
    {
      continue;
    }
    int multiplicity = 0;
    for (std::size_t j = i; j < directed.size(); ++j)
    {
      if (directed[j].from == directed[i].from && directed[j].to == directed[i].to)
      {
        ++multiplicity;
        done[j] = true;
      }
      else if (directed[j].from == directed[i].to && directed[j].to == directed[i].from)
      {
        --multiplicity;
        done[j] = true;
      }
    }
    if (multiplicity != 0)
    {
      const PositionKey from = keyOf(directed[i].from), to = keyOf(directed[i].to);
      if (from < to)
        edges[{ from, to }] = multiplicity;
      else
        edges[{ to, from }] = -multiplicity;
    }
  }
  return edges;
}

struct NamedMesh
{
  std::string name;
  TriangleMesh mesh;
};

std::vector<NamedMesh> testMeshes(std::mt19937& generator)
{
  std::vector<NamedMesh> meshes;
  meshes.push_back({ "box", makeBox(glm::dvec3(0.1, -0.2, 0.0), glm::dvec3(1.0, 0.7, 1.3)) });
  meshes.push_back({ "open box", openBox() });
  meshes.push_back({ "sphere", makeSphere(glm::dvec3(-0.1, 0.2, 0.05), 0.8) });
  meshes.push_back({ "quad", makeQuad(glm::dvec3(0.0, -0.3, 0.0), glm::dvec2(1.5, 1.2), glm::normalize(glm::dvec3(0.2, 1, 0.1)), { 0, 0, -1 }) });
  meshes.push_back({ "disk", makeDisk(glm::dvec3(0.3, 0.0, 0.0), 0.7, { 1, 0, 0 }, { 0, 1, 0 }) });
  meshes.push_back({ "two tetrahedra", twoTetrahedraSharingAnEdge() });
  for (int soup = 0; soup < 4; ++soup)
  {
    meshes.push_back({ "soup " + std::to_string(soup), randomSoup(generator, 8 + 4 * soup, 12 + 10 * soup) });
  }
  return meshes;
}

std::vector<VolumeLight> testLights(std::mt19937& generator)
{
  std::uniform_real_distribution<double> coordinate(-4.0, 4.0);
  std::vector<VolumeLight> lights = { pointLight({ 0.3, 3.0, 0.2 }), directionalLight({ 0.0, -1.0, 0.0 }),
    pointLight({ 0.0, 0.1, 0.0 }) }; // the last one inside the closed meshes
  for (int light = 0; light < 3; ++light)
  {
    lights.push_back(pointLight({ coordinate(generator), coordinate(generator), coordinate(generator) }));
    lights.push_back(directionalLight({ coordinate(generator), coordinate(generator), coordinate(generator) }));
  }
  return lights;
}

TEST(ShadowVolumeGeometry, SilhouettesEqualABruteForceEdgeTest)
{
  std::mt19937 generator(12u);
  const std::vector<NamedMesh> meshes = testMeshes(generator);
  const std::vector<VolumeLight> lights = testLights(generator);
  for (const NamedMesh& named : meshes)
  {
    const std::vector<WeldedMesh> casters = { weldMesh(named.mesh, 0) };
    for (std::size_t lightIndex = 0; lightIndex < lights.size(); ++lightIndex)
    {
      const VolumeLight& light = lights[lightIndex];
      const ShadowVolumeGeometry geometry =
        buildShadowVolumes(casters, light, VolumeExtrusion::ToInfinity, Bounds{});
      const std::map<EdgeKey, int> extracted = signedEdges(geometry.silhouettes);
      const std::map<EdgeKey, int> expected = bruteForceSilhouettes(casters[0], light);
      EXPECT_EQ(extracted.size(), geometry.silhouettes.size()) << named.name << ": an edge listed twice";
      EXPECT_EQ(extracted, expected) << named.name << ", light " << lightIndex << ": " << extracted.size()
                                     << " extracted, " << expected.size() << " brute force";
      // The silhouette is the boundary of the light-oriented triangles: it is closed (at every vertex as
      // many side quads arrive as leave), for every mesh.
      std::map<PositionKey, int> balance;
      for (const SilhouetteEdge& edge : geometry.silhouettes)
      {
        balance[keyOf(edge.from)] += edge.multiplicity;
        balance[keyOf(edge.to)] -= edge.multiplicity;
      }
      for (const auto& [vertex, net] : balance)
      {
        EXPECT_EQ(net, 0) << named.name << ", light " << lightIndex;
      }
      // Closed consistent meshes: every silhouette edge has multiplicity 2 (front and flipped back faces),
      // unless edge-on triangles (the box's sides under a vertical light) drop out.
      if ((named.name == "box" || named.name == "sphere") && geometry.statistics.edgeOnTriangles == 0)
      {
        for (const SilhouetteEdge& edge : geometry.silhouettes)
        {
          EXPECT_EQ(edge.multiplicity, 2) << named.name;
        }
      }
      if (named.name == "quad" || named.name == "disk")
      {
        // An open surface: its boundary, once, whatever the side the light is on (none when edge-on).
        EXPECT_EQ(geometry.statistics.silhouetteEdges, geometry.statistics.edgeOnTriangles > 0 ? 0u : casters[0].boundaryEdgeCount());
      }
    }
  }
}

TEST(ShadowVolumeGeometry, CountsOfABoxUnderAVerticalDirectionalLight)
{
  const std::vector<WeldedMesh> casters = { weldMesh(makeBox(glm::dvec3(0.0), glm::dvec3(1.0)), 2) };
  const ShadowVolumeGeometry geometry =
    buildShadowVolumes(casters, directionalLight({ 0, -1, 0 }), VolumeExtrusion::ToInfinity, Bounds{});
  const ShadowVolumeStatistics& statistics = geometry.statistics;
  EXPECT_EQ(statistics.casterObjects, 1u);
  EXPECT_EQ(statistics.casterTriangles, 12u);
  EXPECT_EQ(statistics.edgeOnTriangles, 8u); // the four sides contain the light's direction
  EXPECT_EQ(statistics.flippedTriangles, 2u); // the bottom
  EXPECT_EQ(statistics.nearCaps, 4u);
  EXPECT_EQ(statistics.farCaps, 0u); // a directional light's far cap is one point at infinity
  EXPECT_EQ(statistics.silhouetteEdges, 8u); // top and bottom rims, once each
  EXPECT_EQ(statistics.sideQuads, 8u);
  EXPECT_EQ(statistics.edges, 18u);
  EXPECT_EQ(statistics.boundaryEdges, 0u);
  EXPECT_EQ(geometry.vertices.size(), 3u * (2u * 8u + 4u));
  for (const SilhouetteEdge& edge : geometry.silhouettes)
  {
    EXPECT_EQ(edge.objectIndex, 2u);
    EXPECT_EQ(edge.multiplicity, 1);
    EXPECT_EQ(edge.incidentTriangles, 2u);
  }
  // Under the box the segment to the light crosses bottom and top: 2; beside it nothing.
  const Scene scene = sceneOf({ makeBox(glm::dvec3(0.0), glm::dvec3(1.0)) });
  EXPECT_EQ(casterCrossings(scene, directionalLight({ 0, -1, 0 }), { 0.1, -3.0, 0.2 }), 2);
  EXPECT_NEAR(volumeWindingNumber(geometry, { 0.1, -3.0, 0.2 }), 2.0, 1e-9);
  EXPECT_NEAR(volumeWindingNumber(geometry, { 0.7, -3.0, 0.2 }), 0.0, 1e-9);
  EXPECT_NEAR(volumeWindingNumber(geometry, { 0.1, 0.2, 0.2 }), 1.0, 1e-9); // inside: below the top only
}

// ---- volumes against the direct crossing count -----------------------------------------------------------

TEST(ShadowVolumeGeometry, VolumeCountAtAPointEqualsTheCrossingsOfItsSegmentToTheLight)
{
  std::mt19937 generator(2011u);
  const std::vector<NamedMesh> meshes = testMeshes(generator);
  const std::vector<VolumeLight> lights = testLights(generator);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int shadowedPoints = 0;
  int maximumCount = 0;
  for (const NamedMesh& named : meshes)
  {
    const Scene scene = sceneOf({ named.mesh });
    const std::vector<WeldedMesh> casters = weldCasters(scene);
    Bounds receivers = scene.bounds();
    receivers.extend(receivers.min - glm::dvec3(1.5));
    receivers.extend(receivers.max + glm::dvec3(1.5));
    for (std::size_t lightIndex = 0; lightIndex < lights.size(); ++lightIndex)
    {
      const VolumeLight& light = lights[lightIndex];
      for (const VolumeExtrusion extrusion : { VolumeExtrusion::ToInfinity, VolumeExtrusion::Finite })
      {
        const ShadowVolumeGeometry geometry = buildShadowVolumes(casters, light, extrusion, receivers);
        // Every triangle lies in its plane (a vertex at infinity: its direction runs in the plane); far caps at
        // infinity have none.
        ASSERT_EQ(geometry.planes.size() * 3, geometry.vertices.size());
        for (std::size_t triangle = 0; triangle < geometry.planes.size(); ++triangle)
        {
          const glm::dvec4 plane(geometry.planes[triangle]);
          const bool atInfinity = geometry.vertices[3 * triangle].w == 0.0f && geometry.vertices[3 * triangle + 1].w == 0.0f &&
            geometry.vertices[3 * triangle + 2].w == 0.0f;
          ASSERT_EQ(glm::dvec3(plane) == glm::dvec3(0.0), atInfinity) << named.name << " triangle " << triangle;
          for (int corner = 0; corner < 3 && !atInfinity; ++corner)
          {
            const glm::dvec4 vertex(geometry.vertices[3 * triangle + static_cast<std::size_t>(corner)]);
            const double scale = vertex.w == 0.0 ? glm::length(glm::dvec3(vertex)) : std::max(1.0, glm::length(glm::dvec3(vertex)));
            ASSERT_NEAR(glm::dot(glm::dvec3(plane), glm::dvec3(vertex)) - plane.w * vertex.w, 0.0, 1e-5 * scale)
              << named.name << " triangle " << triangle << " corner " << corner;
          }
        }
        for (int sample = 0; sample < 150; ++sample)
        {
          const glm::dvec3 point = receivers.min + (receivers.max - receivers.min) *
            glm::dvec3(unit(generator), unit(generator), unit(generator));
          const double winding = volumeWindingNumber(geometry, point);
          const int crossings = casterCrossings(scene, light, point);
          ASSERT_NEAR(winding, crossings, 1e-6)
            << named.name << ", light " << lightIndex << (extrusion == VolumeExtrusion::Finite ? " finite" : " infinite")
            << ", point " << point.x << " " << point.y << " " << point.z;
          shadowedPoints += crossings > 0 ? 1 : 0;
          maximumCount = std::max(maximumCount, crossings);
        }
      }
    }
  }
  // The samples must exercise shadows, and counts beyond 2 (soups and non-manifold edges).
  EXPECT_GT(shadowedPoints, 1000);
  EXPECT_GE(maximumCount, 4);
}

TEST(ShadowVolumeGeometry, SeveralCastersSumTheirCounts)
{
  // Stacked random occluders: boxes and spheres at random heights under a random point light.
  std::mt19937 generator(77u);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  for (int trial = 0; trial < 6; ++trial)
  {
    std::vector<TriangleMesh> meshes;
    for (int occluder = 0; occluder < 4; ++occluder)
    {
      const glm::dvec3 centre(0.5 * coordinate(generator), 0.6 * occluder, 0.5 * coordinate(generator));
      meshes.push_back(occluder % 2 == 0 ? makeBox(centre, glm::dvec3(0.6, 0.2, 0.5)) : makeSphere(centre, 0.25));
    }
    meshes.push_back(makeQuad(glm::dvec3(0.0, -0.5, 0.0), glm::dvec2(4.0, 4.0), { 0, 1, 0 }, { 0, 0, -1 }));
    const Scene scene = sceneOf(meshes);
    const std::vector<WeldedMesh> casters = weldCasters(scene);
    ASSERT_EQ(casters.size(), meshes.size());
    const VolumeLight light = pointLight({ 0.3 * coordinate(generator), 4.0, 0.3 * coordinate(generator) });
    const ShadowVolumeGeometry geometry = buildShadowVolumes(casters, light, VolumeExtrusion::ToInfinity, Bounds{});
    int deepest = 0;
    for (int sample = 0; sample < 200; ++sample)
    {
      // Points on and just above the ground, where the stack's shadows overlap.
      const glm::dvec3 point(0.8 * coordinate(generator), -0.5 + 0.01 * (coordinate(generator) + 1.0), 0.8 * coordinate(generator));
      const int crossings = casterCrossings(scene, light, point);
      ASSERT_NEAR(volumeWindingNumber(geometry, point), crossings, 1e-6) << "trial " << trial;
      deepest = std::max(deepest, crossings);
    }
    EXPECT_GE(deepest, 4) << "trial " << trial << ": the stack should overlap somewhere";
  }
}

// ---- the object-space export -----------------------------------------------------------------------------

TEST(ShadowVolumeGeometry, SilhouettePolyDataHoldsOneLinePerEdgeWithCasterAndMultiplicity)
{
  const std::vector<WeldedMesh> casters = { weldMesh(makeBox(glm::dvec3(0.0), glm::dvec3(1.0)), 3),
    weldMesh(twoTetrahedraSharingAnEdge(), 5) };
  const ShadowVolumeGeometry geometry =
    buildShadowVolumes(casters, pointLight({ 0.4, 5.0, 0.3 }), VolumeExtrusion::ToInfinity, Bounds{});
  const vtkSmartPointer<vtkPolyData> polyData = silhouettePolyData(geometry.silhouettes);
  ASSERT_EQ(polyData->GetNumberOfLines(), static_cast<vtkIdType>(geometry.silhouettes.size()));
  vtkDataArray* casterIds = polyData->GetCellData()->GetArray("caster_id");
  vtkDataArray* multiplicities = polyData->GetCellData()->GetArray("multiplicity");
  ASSERT_NE(casterIds, nullptr);
  ASSERT_NE(multiplicities, nullptr);
  ASSERT_NE(polyData->GetCellData()->GetArray("incident_triangles"), nullptr);
  std::map<int, int> perCaster;
  for (vtkIdType line = 0; line < polyData->GetNumberOfLines(); ++line)
  {
    const SilhouetteEdge& edge = geometry.silhouettes[static_cast<std::size_t>(line)];
    EXPECT_EQ(casterIds->GetTuple1(line), static_cast<double>(edge.objectIndex));
    EXPECT_EQ(multiplicities->GetTuple1(line), static_cast<double>(edge.multiplicity));
    double from[3];
    polyData->GetPoint(2 * line, from);
    EXPECT_EQ(static_cast<float>(from[0]), edge.from.x);
    ++perCaster[static_cast<int>(casterIds->GetTuple1(line))];
  }
  EXPECT_GT(perCaster[3], 0);
  EXPECT_GT(perCaster[5], 0);
  EXPECT_EQ(perCaster.size(), 2u);
}

} // namespace
} // namespace sl
