// The Embree reference's crossing counts (EmbreeScene::crossings) and its shared light-sample sets
// (ReferenceSettings::lightSampleSet), the ground truth that technique `dcs` (depth complexity sampling, Forest et al. 2009
// §3.2) is checked against sample by sample. Counts are compared with closed forms (stacks of quads, closed boxes,
// holes) and with a brute-force double-precision Moller-Trumbore count over every triangle; a (segment, triangle)
// pair whose line passes within 1e-6 (relative to the scene) of an edge, a segment end or a texel boundary is
// ambiguous, and only such pairs may disagree. Scenes are built in code, receivers are synthetic G-buffers. CPU only.
#include "core/Error.h"
#include "lightspace/LightSampleSet.h"
#include "lightspace/LightView.h"
#include "reference/EmbreeScene.h"
#include "reference/ReferenceRenderer.h"
#include "scene/AlphaTexture.h"
#include "scene/Primitives.h"
#include "scene/RayTriangle.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace sl
{
namespace
{

// Relative margin within which a segment's crossing of a triangle is ambiguous in single precision.
constexpr double kAmbiguity = 1e-6;
// The reference's shortening at the light's end (ReferenceRenderer.h).
constexpr double kLightEnd = 1.0 - 1e-6;

SceneObject caster(const std::string& name, TriangleMesh mesh)
{
  SceneObject object;
  object.name = name;
  object.mesh = std::move(mesh);
  return object;
}

// An axis-aligned box of 8 shared vertices and 12 triangles (welded, unlike makeBox's 24 vertices).
TriangleMesh weldedBox(const glm::dvec3& center, const glm::dvec3& size)
{
  TriangleMesh mesh;
  for (int corner = 0; corner < 8; ++corner)
  {
    const glm::dvec3 sign((corner & 1) ? 0.5 : -0.5, (corner & 2) ? 0.5 : -0.5, (corner & 4) ? 0.5 : -0.5);
    mesh.positions.emplace_back(center + sign * size);
    mesh.normals.emplace_back(glm::normalize(sign));
  }
  // Two triangles per face, corners by bit (x = 1, y = 2, z = 4).
  mesh.indices = { 0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6,   // z = -, z = +
    0, 1, 5, 0, 5, 4, 2, 6, 7, 2, 7, 3,                  // y = -, y = +
    0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5 };                // x = -, x = +
  return mesh;
}

// A quad at height y (normal -y, up +z) perforated by a 2 x 2 checker: texels (1, 0) and (0, 1) are holes. Its uv
// is ((x - cx) / side + 1/2, (z - cz) / side + 1/2), so the holes are the (+x, -z) and (-x, +z) quarters.
SceneObject checkerQuad(const glm::dvec3& center, double side)
{
  SceneObject checker = caster("checker", makeQuad(center, { side, side }, { 0.0, -1.0, 0.0 }, { 0.0, 0.0, 1.0 }));
  checker.hasAlphaTexture = true;
  checker.alphaTexture.source = "checker";
  checker.alphaTexture.alpha = ImageF(2, 2, 1);
  checker.alphaTexture.alpha.at(0, 0) = 1.0f;
  checker.alphaTexture.alpha.at(1, 0) = 0.2f;
  checker.alphaTexture.alpha.at(0, 1) = 0.49f;
  checker.alphaTexture.alpha.at(1, 1) = 0.5f; // exactly 0.5 is opaque: holes are alpha < 0.5
  return checker;
}

// The brute-force count: every caster triangle, double precision, on the segment Embree sees (origin and direction
// rounded to float, as EmbreeScene hands them over), the same alpha rule.
class BruteForceCounter
{
public:
  struct Count
  {
    int crossings = 0;
    bool ambiguous = false; // some triangle is crossed or missed within the margin
    std::set<std::pair<std::size_t, unsigned>> crossed; // (object, triangle)
  };

  explicit BruteForceCounter(const Scene& scene)
  {
    const Bounds bounds = scene.bounds();
    margin_ = kAmbiguity * std::max(1.0, bounds.empty() ? 1.0 : bounds.radius());
    for (std::size_t objectIndex = 0; objectIndex < scene.objects.size(); ++objectIndex)
    {
      const SceneObject& object = scene.objects[objectIndex];
      if (!object.castShadows)
      {
        continue;
      }
      const TriangleMesh& mesh = object.mesh;
      for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
      {
        Triangle triangle;
        for (int k = 0; k < 3; ++k)
        {
          const std::uint32_t index = mesh.indices[3 * t + k];
          triangle.corners[k] = glm::dvec3(mesh.positions[index]);
          triangle.uvs[k] = mesh.uvs.empty() ? glm::dvec2(0.0) : glm::dvec2(mesh.uvs[index]);
        }
        triangle.alpha = object.hasAlphaTexture ? &object.alphaTexture.alpha : nullptr;
        triangle.object = objectIndex;
        triangle.index = static_cast<unsigned>(t);
        triangles_.push_back(triangle);
      }
    }
  }

  Count count(const glm::dvec3& originIn, const glm::dvec3& directionIn, double tNear, double tFar) const
  {
    const glm::dvec3 origin = glm::dvec3(glm::vec3(originIn));
    const glm::dvec3 direction = glm::dvec3(glm::vec3(directionIn));
    const double tMargin = margin_ / glm::length(direction);
    Count result;
    for (const Triangle& triangle : triangles_)
    {
      const glm::dvec3& a = triangle.corners[0];
      const glm::dvec3 edge1 = triangle.corners[1] - a;
      const glm::dvec3 edge2 = triangle.corners[2] - a;
      const std::optional<RayTriangleHit> hit = intersectRayTriangle(origin, direction, a, edge1, edge2);
      const bool crosses = hit && hit->t > tNear && hit->t < tFar &&
        !(triangle.alpha && alphaHoleAt(*triangle.alpha, uvAt(triangle, hit->u, hit->v)));
      if (crosses)
      {
        ++result.crossings;
        result.crossed.insert({ triangle.object, triangle.index });
      }
      result.ambiguous = result.ambiguous || isAmbiguous(triangle, origin, direction, tNear, tFar, tMargin);
    }
    return result;
  }

private:
  struct Triangle
  {
    glm::dvec3 corners[3];
    glm::dvec2 uvs[3];
    const ImageF* alpha = nullptr;
    std::size_t object = 0;
    unsigned index = 0;
  };

  static glm::dvec2 uvAt(const Triangle& triangle, double u, double v)
  {
    return (1.0 - u - v) * triangle.uvs[0] + u * triangle.uvs[1] + v * triangle.uvs[2];
  }

  // True where the segment's line meets the triangle's plane within the margin of an edge (inside or out), or
  // inside it within the margin of a segment end or of a texel boundary of its alpha texture.
  bool isAmbiguous(const Triangle& triangle, const glm::dvec3& origin, const glm::dvec3& direction, double tNear,
    double tFar, double tMargin) const
  {
    const glm::dvec3& a = triangle.corners[0];
    const glm::dvec3 edge1 = triangle.corners[1] - a;
    const glm::dvec3 edge2 = triangle.corners[2] - a;
    // Moller-Trumbore without its range tests: the line's barycentrics even where it misses.
    const glm::dvec3 p = glm::cross(direction, edge2);
    const double determinant = glm::dot(edge1, p);
    const glm::dvec3 normal = glm::cross(edge1, edge2);
    const double twiceArea = glm::length(normal);
    if (std::abs(determinant) <= 1e-9 * twiceArea * glm::length(direction))
    {
      return false; // parallel to the plane: neither side counts it (random segments never lie in it)
    }
    const glm::dvec3 s = origin - a;
    const double u = glm::dot(s, p) / determinant;
    const double v = glm::dot(direction, glm::cross(s, edge1)) / determinant;
    const double t = glm::dot(edge2, glm::cross(s, edge1)) / determinant;
    if (t < tNear - tMargin || t > tFar + tMargin)
    {
      return false;
    }
    // Signed distances (world units) from the crossing point to the three edges: barycentric * height.
    const glm::dvec3 corners[3] = { triangle.corners[0], triangle.corners[1], triangle.corners[2] };
    const double barycentric[3] = { 1.0 - u - v, u, v };
    double nearest = 1e300;
    bool inside = true;
    for (int k = 0; k < 3; ++k)
    {
      const double opposite = glm::length(corners[(k + 2) % 3] - corners[(k + 1) % 3]);
      const double distance = barycentric[k] * twiceArea / opposite;
      inside = inside && distance >= -margin_;
      nearest = std::min(nearest, std::abs(distance));
    }
    if (!inside)
    {
      return false;
    }
    if (nearest <= margin_ || std::abs(t - tNear) <= tMargin || std::abs(t - tFar) <= tMargin)
    {
      return true;
    }
    if (triangle.alpha)
    {
      const glm::dvec2 uv = uvAt(triangle, u, v);
      const glm::dvec2 texel = uv * glm::dvec2(triangle.alpha->width, triangle.alpha->height);
      const glm::dvec2 fromBoundary = glm::abs(texel - glm::round(texel));
      const int texels = std::max(triangle.alpha->width, triangle.alpha->height);
      return std::min(fromBoundary.x, fromBoundary.y) <= kAmbiguity * texels;
    }
    return false;
  }

  std::vector<Triangle> triangles_;
  double margin_ = kAmbiguity;
};

using test::uniform;

// A stack of k parallel quads, each a different size but all covering |x|, |z| < 1: a segment from below all of
// them to above all of them crosses k, one ending between quads i and i+1 crosses i + 1.
TEST(ReferenceCrossings, StackOfParallelQuadsCountsEachQuad)
{
  std::mt19937_64 random(11);
  for (int k = 1; k <= 6; ++k)
  {
    Scene scene;
    for (int i = 0; i < k; ++i)
    {
      const double side = 2.2 + 0.3 * i;
      scene.objects.push_back(caster(format("quad ", i),
        makeQuad({ 0.05 * i, 1.0 + i, -0.03 * i }, { side, side }, { 0.0, i % 2 ? 1.0 : -1.0, 0.0 },
          { 0.0, 0.0, 1.0 })));
    }
    const EmbreeScene embree(scene);
    std::vector<EmbreeScene::Crossing> crossed;
    for (int ray = 0; ray < 200; ++ray)
    {
      const glm::dvec3 below(uniform(random, -0.9, 0.9), uniform(random, -0.5, 0.9), uniform(random, -0.9, 0.9));
      const glm::dvec3 above(uniform(random, -0.9, 0.9), k + uniform(random, 0.1, 2.0), uniform(random, -0.9, 0.9));
      ASSERT_EQ(embree.crossings(below, above - below, 0.0, 1.0, &crossed), k)
        << k << " quads, segment from (" << below.x << ", " << below.y << ", " << below.z << ")";
      // Each quad once (one of its two triangles), at its own height.
      std::set<std::size_t> objects;
      for (const EmbreeScene::Crossing& crossing : crossed)
      {
        objects.insert(crossing.objectIndex);
        EXPECT_LT(crossing.triangle, 2u);
        const double yAtHit = below.y + double(crossing.t) * (above.y - below.y);
        EXPECT_NEAR(yAtHit, 1.0 + double(crossing.objectIndex), 1e-5) << k << " quads";
      }
      EXPECT_EQ(objects.size(), static_cast<std::size_t>(k));
      // The same line, ending between quads: only those below its end; the reverse direction counts the same.
      const int stopBelow = 1 + ray % k; // ends between quad stopBelow - 1 and quad stopBelow
      const double tStop = (stopBelow + 0.5 - below.y) / (above.y - below.y);
      EXPECT_EQ(embree.crossings(below, above - below, 0.0, tStop), stopBelow) << k << " quads";
      EXPECT_EQ(embree.crossings(above, below - above, 0.0, 1.0), k) << k << " quads, downwards";
      // Starting between quads (tNear past the first ones).
      EXPECT_EQ(embree.crossings(below, above - below, tStop, 1.0), k - stopBelow) << k << " quads";
    }
    // Nothing above or beside the stack.
    EXPECT_EQ(embree.crossings({ 0.0, k + 1.0, 0.0 }, { 0.0, 1.0, 0.0 }, 0.0, 10.0), 0);
    EXPECT_EQ(embree.crossings({ 3.0, 0.0, 0.0 }, { 0.0, 1.0, 0.0 }, 0.0, 100.0), 0);
  }
}

// Three closed boxes in a row along x (makeBox's unwelded faces, a welded box, makeBox again): a segment through
// n of them crosses 2 n triangles (in and out), one starting inside a box 2 n - 1. Crossing points keep 1e-3 away
// from the faces' diagonals and edges, where the count is ambiguous.
TEST(ReferenceCrossings, ClosedBoxCountsTwoPerBoxCrossed)
{
  Scene scene;
  const glm::dvec3 size(1.0, 1.2, 0.8);
  scene.objects.push_back(caster("box 0", makeBox({ 0.0, 0.0, 0.0 }, size)));
  scene.objects.push_back(caster("welded box 1", weldedBox({ 2.0, 0.0, 0.0 }, size)));
  scene.objects.push_back(caster("box 2", makeBox({ 4.0, 0.0, 0.0 }, size)));
  const EmbreeScene embree(scene);
  EXPECT_EQ(embree.triangleCount(), 36u);
  std::mt19937_64 random(5);
  // A point on a box's x face (normalized coordinates a, b in (-1, 1)) away from both diagonals and the edges.
  const auto faceCoordinate = [&]() {
    while (true)
    {
      const double a = uniform(random, -0.95, 0.95);
      const double b = uniform(random, -0.95, 0.95);
      if (std::abs(a - b) > 1e-3 && std::abs(a + b) > 1e-3)
      {
        return glm::dvec2(a, b);
      }
    }
  };
  std::vector<EmbreeScene::Crossing> crossed;
  for (int ray = 0; ray < 300; ++ray)
  {
    // Straight along x at a fixed (y, z): every x face is crossed at the same face coordinates.
    const glm::dvec2 ab = faceCoordinate();
    const double y = 0.5 * size.y * ab.x;
    const double z = 0.5 * size.z * ab.y;
    const int boxes = 1 + ray % 3;
    const glm::dvec3 start(-1.0, y, z);
    const glm::dvec3 end(2.0 * boxes - 1.0, y, z); // between box boxes - 1 and box boxes
    EXPECT_EQ(embree.crossings(start, end - start, 0.0, 1.0, &crossed), 2 * boxes) << "ray " << ray;
    for (const EmbreeScene::Crossing& crossing : crossed)
    {
      EXPECT_LT(crossing.objectIndex, static_cast<std::size_t>(boxes));
    }
    const glm::dvec3 inside(0.1, y, z); // inside box 0
    EXPECT_EQ(embree.crossings(inside, end - inside, 0.0, 1.0), 2 * boxes - 1) << "ray " << ray;
  }
  // Oblique segments through box 1 alone (its y faces, both triangles of each, welded vertices): 2.
  int checked = 0;
  for (int ray = 0; ray < 300; ++ray)
  {
    const auto faceX = [&]() { return 2.0 + 0.5 * size.x * uniform(random, -0.95, 0.95); };
    const auto faceZ = [&]() { return 0.5 * size.z * uniform(random, -0.95, 0.95); };
    const glm::dvec3 bottom(faceX(), -1.0, faceZ());
    const glm::dvec3 top(faceX(), 1.0, faceZ());
    const glm::dvec3 direction = top - bottom;
    // Where it crosses y = -0.6 and y = 0.6, in the faces' normalized coordinates: off the diagonals.
    bool offDiagonals = true;
    for (double faceY : { -0.5 * size.y, 0.5 * size.y })
    {
      const glm::dvec3 p = bottom + direction * ((faceY - bottom.y) / direction.y);
      const double a = (p.x - 2.0) / (0.5 * size.x);
      const double b = p.z / (0.5 * size.z);
      offDiagonals = offDiagonals && std::abs(a - b) > 1e-3 && std::abs(a + b) > 1e-3;
    }
    if (!offDiagonals)
    {
      continue;
    }
    ++checked;
    EXPECT_EQ(embree.crossings(bottom, direction, 0.0, 1.0, &crossed), 2) << "oblique ray " << ray;
    for (const EmbreeScene::Crossing& crossing : crossed)
    {
      EXPECT_EQ(crossing.objectIndex, 1u);
    }
  }
  EXPECT_GT(checked, 250);
}

// A perforated quad over an opaque one: through a hole (alpha 0.2, 0.49) the segment crosses only the opaque
// quad, through the opaque texels (alpha 1, exactly 0.5) both. Without the texture, always both.
TEST(ReferenceCrossings, HoleOfPerforatedQuadIsNoCrossing)
{
  Scene scene;
  scene.objects.push_back(checkerQuad({ 0.0, 2.0, 0.0 }, 2.0));
  scene.objects.push_back(
    caster("opaque", makeQuad({ 0.0, 1.0, 0.0 }, { 4.0, 4.0 }, { 0.0, -1.0, 0.0 }, { 0.0, 0.0, 1.0 })));
  struct Case
  {
    double x, z;
    int crossings;
  };
  // Quarters: (-x, -z) texel (0,0) opaque; (+x, -z) texel (1,0) hole; (-x, +z) texel (0,1) hole; (+x, +z) opaque.
  // Off both quads' diagonals (|x| = |z|), where a segment meets both triangles of a quad: ambiguous, not tested.
  const Case cases[] = { { -0.5, -0.3, 2 }, { 0.5, -0.3, 1 }, { -0.3, 0.5, 1 }, { 0.6, 0.4, 2 }, { -0.9, -0.1, 2 },
    { 0.1, -0.9, 1 }, { -0.1, 0.9, 1 }, { 0.9, 0.1, 2 } };
  {
    const EmbreeScene embree(scene);
    std::vector<EmbreeScene::Crossing> crossed;
    for (const Case& c : cases)
    {
      const glm::dvec3 origin(c.x, 0.0, c.z);
      EXPECT_EQ(embree.crossings(origin, { 0.0, 3.0, 0.0 }, 0.0, 1.0, &crossed), c.crossings)
        << "x " << c.x << " z " << c.z;
      EXPECT_EQ(embree.occluded(origin + glm::dvec3(0.0, 1.5, 0.0), { 0.0, 1.0, 0.0 }, 0.0, 1.0), c.crossings == 2)
        << "occlusion filter, x " << c.x << " z " << c.z;
      if (c.crossings == 1)
      {
        ASSERT_EQ(crossed.size(), 1u);
        EXPECT_EQ(crossed[0].objectIndex, 1u);
      }
    }
  }
  scene.objects[0].hasAlphaTexture = false;
  const EmbreeScene opaque(scene);
  for (const Case& c : cases)
  {
    EXPECT_EQ(opaque.crossings({ c.x, 0.0, c.z }, { 0.0, 3.0, 0.0 }, 0.0, 1.0), 2) << "x " << c.x << " z " << c.z;
  }
}

// A soup of large, overlapping random triangles (what makes a high-quality build split triangles into several
// leaves, so that Embree reports one triangle more than once: its non-robust build does so on this soup, its robust
// build, EmbreeScene's, was not seen to) and a fine sphere: on random segments Embree's count equals the
// brute-force count, except on ambiguous segments; each crossed triangle is reported once and is one the brute
// force crosses.
TEST(ReferenceCrossings, EachTriangleCountedOnceInAHighQualityBuild)
{
  std::mt19937_64 random(2024);
  Scene scene;
  TriangleMesh soup;
  for (int t = 0; t < 1500; ++t)
  {
    const glm::dvec3 center(uniform(random, -1.0, 1.0), uniform(random, -1.0, 1.0), uniform(random, -1.0, 1.0));
    for (int k = 0; k < 3; ++k)
    {
      soup.positions.emplace_back(center + glm::dvec3(uniform(random, -0.8, 0.8), uniform(random, -0.8, 0.8),
                                             uniform(random, -0.8, 0.8)));
      soup.normals.emplace_back(0.0f, 1.0f, 0.0f);
      soup.indices.push_back(static_cast<std::uint32_t>(3 * t + k));
    }
  }
  scene.objects.push_back(caster("soup", soup));
  scene.objects.push_back(caster("sphere", makeSphere({ 0.3, -0.2, 0.1 }, 0.6)));
  const EmbreeScene embree(scene);
  const BruteForceCounter brute(scene);

  constexpr int kSegments = 6000;
  int equal = 0;
  int ambiguous = 0;
  long long totalCrossings = 0;
  std::vector<EmbreeScene::Crossing> crossed;
  for (int segment = 0; segment < kSegments; ++segment)
  {
    const glm::dvec3 a(uniform(random, -2.0, 2.0), uniform(random, -2.0, 2.0), uniform(random, -2.0, 2.0));
    const glm::dvec3 b(uniform(random, -2.0, 2.0), uniform(random, -2.0, 2.0), uniform(random, -2.0, 2.0));
    const int counted = embree.crossings(a, b - a, 0.0, kLightEnd, &crossed);
    const BruteForceCounter::Count expected = brute.count(a, b - a, 0.0, kLightEnd);
    totalCrossings += expected.crossings;
    std::set<std::pair<std::size_t, unsigned>> reported;
    for (const EmbreeScene::Crossing& crossing : crossed)
    {
      EXPECT_TRUE(reported.insert({ crossing.objectIndex, crossing.triangle }).second)
        << "segment " << segment << " reports object " << crossing.objectIndex << " triangle " << crossing.triangle
        << " twice";
    }
    EXPECT_EQ(static_cast<int>(reported.size()), counted);
    if (counted == expected.crossings && reported == expected.crossed)
    {
      ++equal;
      ambiguous += expected.ambiguous;
      continue;
    }
    EXPECT_TRUE(expected.ambiguous) << "segment " << segment << ": Embree " << counted << ", brute force "
                                    << expected.crossings << ", not near any edge";
    ++ambiguous;
  }
  EXPECT_GE(equal, 0.999 * kSegments) << ambiguous << " ambiguous segments";
  EXPECT_GT(totalCrossings, 20 * kSegments) << "the segments should cross many triangles each";
}

// Receivers of several kinds, one per pixel of a kSide x kSide image, under a scene of every caster kind above: a
// stack of two quads, a welded box, a perforated checker. Points on y = 0 and normals tilted up to ~80 degrees (so
// the tangent plane cuts through the light), plus uncovered, non-receiving and unreachable (facing away) pixels.
constexpr int kSide = 20;

Scene samplesScene()
{
  Scene scene;
  const glm::dvec3 up(0.0, 0.0, 1.0);
  scene.objects.push_back(caster("quad low", makeQuad({ -0.6, 1.2, 0.2 }, { 1.0, 0.8 }, { 0.0, -1.0, 0.0 }, up)));
  scene.objects.push_back(caster("quad high", makeQuad({ -0.4, 2.0, 0.0 }, { 0.9, 1.2 }, { 0.0, 1.0, 0.0 }, up)));
  scene.objects.push_back(caster("welded box", weldedBox({ 0.7, 1.5, -0.3 }, { 0.5, 0.6, 0.7 })));
  scene.objects.push_back(checkerQuad({ 0.3, 2.6, 0.6 }, 0.8));
  return scene;
}

Light squareLight()
{
  Light light;
  light.type = LightType::Area;
  light.shape = LightShape::Square;
  light.center = { 0.1, 4.0, 0.05 };
  light.normal = { 0.0, -1.0, 0.0 };
  light.up = { 0.0, 0.0, 1.0 };
  light.size = 1.5;
  return light;
}

ReferenceInputs sampleReceivers(const Scene& scene, const Light& light)
{
  std::mt19937_64 random(99);
  ReferenceInputs inputs;
  inputs.scene = &scene;
  inputs.light = &light;
  inputs.position = ImageF(kSide, kSide, 4);
  inputs.normal = ImageF(kSide, kSide, 4);
  inputs.coverage = ImageF(kSide, kSide, 1, 1.0f);
  inputs.receives = ImageF(kSide, kSide, 1, 1.0f);
  for (int y = 0; y < kSide; ++y)
  {
    for (int x = 0; x < kSide; ++x)
    {
      const glm::dvec3 p(-1.5 + 3.0 * (x + 0.5) / kSide, 0.0, -1.5 + 3.0 * (y + 0.5) / kSide);
      // Tilted by up to 80 degrees in a random direction; every 7th pixel faces down (unreachable).
      const double tilt = glm::radians(uniform(random, 0.0, 80.0));
      const double azimuth = uniform(random, 0.0, 6.283185307179586);
      glm::dvec3 n(std::sin(tilt) * std::cos(azimuth), std::cos(tilt), std::sin(tilt) * std::sin(azimuth));
      if ((x + kSide * y) % 7 == 3)
      {
        n = -n;
      }
      for (int c = 0; c < 3; ++c)
      {
        inputs.position.at(x, y, c) = static_cast<float>(p[c]);
        inputs.normal.at(x, y, c) = static_cast<float>(n[c]);
      }
      inputs.coverage.at(x, y) = (x + y) % 11 == 5 ? 0.0f : 1.0f;
      inputs.receives.at(x, y) = (x * y) % 13 == 6 ? 0.0f : 1.0f;
    }
  }
  return inputs;
}

glm::dvec3 vec3At(const ImageF& image, int x, int y)
{
  return { image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2) };
}

bool maskBit(const ReferenceResult& result, int x, int y, int sample)
{
  const float component = result.lightSampleMask.at(x, y, sample / 16);
  const auto bits = static_cast<std::uint32_t>(component);
  EXPECT_EQ(static_cast<float>(bits), component) << "mask component not an exact integer at " << x << "," << y;
  EXPECT_LT(bits, 65536u);
  return (bits >> (sample % 16)) & 1u;
}

// With a light-sample set, per pixel and sample: the point is LightSampleSet::point, its crossing count is the
// brute-force count of the segment from the ray origin to it, its mask bit is (below the tangent plane or
// crossed), and the visibility is the fraction of samples not hidden, except where a pixel rule decides.
TEST(ReferenceLightSampleSet, CrossingsMaskAndVisibilityMatchBruteForceOnTheSameSamples)
{
  const Scene scene = samplesScene();
  const BruteForceCounter brute(scene);
  Light disk = squareLight();
  disk.shape = LightShape::Disk;
  const Light lights[] = { squareLight(), disk };
  const std::pair<const char*, int> sets[] = { { "poisson", 16 }, { "zero_two_4x4", 64 }, { "stratified", 256 } };
  for (const Light& light : lights)
  {
    const ReferenceInputs inputs = sampleReceivers(scene, light);
    for (const auto& [pattern, count] : sets)
    {
      const std::string label = format(light.shape == LightShape::Disk ? "disk" : "square", " light, ", pattern,
        " x ", count);
      ReferenceSettings settings;
      settings.lightSampleSet = lightSampleSetSettings(pattern, count, 17);
      const LightSampleSet set(*settings.lightSampleSet);
      const ReferenceResult result = renderReference(inputs, settings);
      ASSERT_EQ(result.sampleCrossings.components, count) << label;
      ASSERT_EQ(result.lightSampleMask.components, count / 16) << label;
      ASSERT_EQ(result.sampleCrossings.width, kSide);
      ASSERT_EQ(result.lightSampleMask.height, kSide);
      const double offset = referenceRayOffset(scene, settings);

      long long pairs = 0;
      long long equalPairs = 0;
      int crossedSamples = 0;
      int belowSamples = 0;
      int counts[4] = { 0, 0, 0, 0 }; // regular, uncovered, non-receiving, unreachable pixels
      int unambiguousPixels = 0;
      std::uint64_t expectedRays = 0;
      for (int y = 0; y < kSide; ++y)
      {
        for (int x = 0; x < kSide; ++x)
        {
          const std::string where = format(label, ", pixel ", x, ",", y);
          const double visibility = result.visibility.at(x, y);
          if (inputs.coverage.at(x, y) <= 0.5f)
          {
            ++counts[1];
            EXPECT_EQ(visibility, 0.0) << where;
            for (int i = 0; i < count; ++i)
            {
              EXPECT_EQ(result.sampleCrossings.at(x, y, i), 0.0f) << where;
            }
            for (int c = 0; c < count / 16; ++c)
            {
              EXPECT_EQ(result.lightSampleMask.at(x, y, c), 0.0f) << where;
            }
            continue;
          }
          const glm::dvec3 p = vec3At(inputs.position, x, y);
          const glm::dvec3 n = vec3At(inputs.normal, x, y);
          const glm::dvec3 origin = p + offset * n;
          int hidden = 0;      // by the reference's counts
          int bruteHidden = 0; // by the brute force's
          bool pixelAmbiguous = false;
          for (int i = 0; i < count; ++i)
          {
            const glm::dvec3 s = set.point(light, x, y, i);
            const BruteForceCounter::Count expected = brute.count(origin, s - origin, 0.0, kLightEnd);
            const int counted = static_cast<int>(result.sampleCrossings.at(x, y, i));
            EXPECT_EQ(static_cast<float>(counted), result.sampleCrossings.at(x, y, i)) << where;
            ++pairs;
            ++expectedRays;
            if (counted == expected.crossings)
            {
              ++equalPairs;
            }
            else
            {
              EXPECT_TRUE(expected.ambiguous) << where << " sample " << i << ": reference " << counted
                                              << " crossings, brute force " << expected.crossings;
            }
            pixelAmbiguous = pixelAmbiguous || expected.ambiguous;
            const bool below = glm::dot(n, s - p) <= 0.0;
            const bool isHidden = below || counted > 0;
            EXPECT_EQ(maskBit(result, x, y, i), isHidden) << where << " sample " << i;
            hidden += isHidden;
            bruteHidden += below || expected.crossings > 0;
            belowSamples += below;
            crossedSamples += counted > 0;
          }
          if (inputs.receives.at(x, y) <= 0.5f)
          {
            ++counts[2];
            EXPECT_EQ(visibility, 1.0) << where;
          }
          else if (!lightCanReach(light, p, n))
          {
            ++counts[3];
            EXPECT_EQ(visibility, 0.0) << where;
          }
          else
          {
            ++counts[0];
            // Exactly the fraction of samples not hidden, from the reference's own counts ...
            EXPECT_EQ(visibility, static_cast<float>(static_cast<double>(count - hidden) / count)) << where;
            const double v = static_cast<double>(count - hidden) / count;
            EXPECT_FLOAT_EQ(result.standardError.at(x, y), static_cast<float>(std::sqrt(v * (1.0 - v) / (count - 1))))
              << where;
            // ... and the brute force's wherever no sample is ambiguous.
            if (!pixelAmbiguous)
            {
              ++unambiguousPixels;
              EXPECT_EQ(visibility, static_cast<float>(static_cast<double>(count - bruteHidden) / count)) << where;
            }
          }
        }
      }
      EXPECT_GE(static_cast<double>(equalPairs), 0.999 * static_cast<double>(pairs)) << label;
      EXPECT_EQ(result.raysTraced, expectedRays) << label << ": one crossing ray per sample of each covered pixel";
      // The scene exercises every case.
      EXPECT_GT(counts[0], kSide * kSide / 2) << label;
      EXPECT_GE(unambiguousPixels, counts[0] * 9 / 10) << label;
      EXPECT_GT(counts[1], 0) << label;
      EXPECT_GT(counts[2], 0) << label;
      EXPECT_GT(counts[3], 0) << label;
      EXPECT_GT(crossedSamples, static_cast<int>(pairs / 20)) << label;
      EXPECT_GT(belowSamples, static_cast<int>(pairs / 50)) << label;
    }
  }
}

// Samples whose segment crosses two or more casters exist, and their count is the number crossed, not 1.
TEST(ReferenceLightSampleSet, CountsDepthComplexityNotJustOcclusion)
{
  Scene scene;
  for (int i = 0; i < 3; ++i)
  {
    scene.objects.push_back(caster(format("layer ", i),
      makeQuad({ 0.0, 1.0 + i, 0.0 }, { 8.0, 8.0 }, { 0.0, -1.0, 0.0 }, { 0.0, 0.0, 1.0 })));
  }
  const Light light = squareLight();
  const ReferenceInputs inputs = sampleReceivers(scene, light);
  ReferenceSettings settings;
  settings.lightSampleSet = lightSampleSetSettings("grid", 16, 1);
  const ReferenceResult result = renderReference(inputs, settings);
  for (int y = 0; y < kSide; ++y)
  {
    for (int x = 0; x < kSide; ++x)
    {
      for (int i = 0; i < 16; ++i)
      {
        // Every covered pixel's every sample (below the tangent plane or not) passes all three layers.
        EXPECT_EQ(result.sampleCrossings.at(x, y, i), inputs.coverage.at(x, y) > 0.5f ? 3.0f : 0.0f)
          << "pixel " << x << "," << y << " sample " << i;
      }
      if (inputs.coverage.at(x, y) > 0.5f)
      {
        EXPECT_EQ(result.lightSampleMask.at(x, y, 0), 65535.0f) << "pixel " << x << "," << y;
        EXPECT_EQ(result.visibility.at(x, y), inputs.receives.at(x, y) > 0.5f ? 0.0f : 1.0f);
      }
    }
  }
}

TEST(ReferenceLightSampleSet, SameImagesForAnyThreadCount)
{
  const Scene scene = samplesScene();
  const Light light = squareLight();
  const ReferenceInputs inputs = sampleReceivers(scene, light);
  ReferenceSettings settings;
  settings.lightSampleSet = lightSampleSetSettings("poisson_4x4", 64, 5);
  settings.threads = 1;
  const ReferenceResult one = renderReference(inputs, settings);
  for (int threads : { 2, 3, 7 })
  {
    settings.threads = threads;
    const ReferenceResult other = renderReference(inputs, settings);
    EXPECT_EQ(one.visibility.data, other.visibility.data) << threads << " threads";
    EXPECT_EQ(one.standardError.data, other.standardError.data) << threads << " threads";
    EXPECT_EQ(one.sampleCrossings.data, other.sampleCrossings.data) << threads << " threads";
    EXPECT_EQ(one.lightSampleMask.data, other.lightSampleMask.data) << threads << " threads";
    EXPECT_EQ(one.raysTraced, other.raysTraced) << threads << " threads";
  }
  // Another seed moves the samples: some crossing counts change.
  settings.lightSampleSet->seed = 6;
  const ReferenceResult reseeded = renderReference(inputs, settings);
  EXPECT_NE(one.sampleCrossings.data, reseeded.sampleCrossings.data);
}

TEST(ReferenceLightSampleSet, OnlyWithASetAndOnlyForAreaLights)
{
  const Scene scene = samplesScene();
  Light light = squareLight();
  const ReferenceInputs inputs = sampleReceivers(scene, light);
  ReferenceSettings settings;
  settings.samples = 16;
  const ReferenceResult plain = renderReference(inputs, settings);
  EXPECT_TRUE(plain.sampleCrossings.empty());
  EXPECT_TRUE(plain.lightSampleMask.empty());

  const auto messageOf = [&](const ReferenceSettings& tried) -> std::string {
    try
    {
      renderReference(inputs, tried);
    }
    catch (const InputError& error)
    {
      return error.what();
    }
    return "(no InputError)";
  };
  settings.lightSampleSet = lightSampleSetSettings("grid", 16, 1);
  for (LightType type : { LightType::Point, LightType::Spot, LightType::Directional })
  {
    light.type = type;
    const std::string message = messageOf(settings);
    EXPECT_EQ(message.rfind("--light-samples grid: ", 0), 0u) << message;
    EXPECT_NE(message.find("area light"), std::string::npos) << message;
  }
  light.type = LightType::Area;
  settings.lightSampleSet->count = 10; // not a set's count: the CLI's message, not an abort
  const std::string message = messageOf(settings);
  EXPECT_EQ(message.rfind("--samples 10", 0), 0u) << message;
}

} // namespace
} // namespace sl
