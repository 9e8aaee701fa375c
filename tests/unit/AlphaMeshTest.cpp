// The texel-exact mesh of a perforated quad (scene/AlphaMesh.h, scene key `mesh_alpha`, dataset `fence-meshed`): the
// "equivalent mesh" Forest et al. 2009 (Fig. 11) compares its two perforated triangles with. Checked
// against the mask itself, texel by texel, with code that does not share the generator's: the area is the opaque
// texel count times the texel area (exactly, on dyadic frames); every triangle's centre is opaque; every opaque
// texel is covered exactly once and no hole at all (2D point-in-triangle over a bucket grid of the plane); every
// edge inside the opaque region is shared by two triangles running along it in opposite directions, and the
// boundary edges are exactly the opaque/hole (or opaque/border) texel sides, counted from the mask; the project's
// welder (WeldedMesh.h) sees the same. Then the claim the mesh is for: with Embree and the shared light-sample set,
// `fence` (2 perforated triangles, alpha filter) and `fence-meshed` hide the same light samples on >= 99.9 % of
// (pixel, sample) pairs, and every pair that differs grazes a texel boundary. CPU only.
#include "core/Error.h"
#include "io/ImageIO.h"
#include "lightspace/LightSampleSet.h"
#include "reference/ReferenceRenderer.h"
#include "scene/AlphaMesh.h"
#include "scene/AlphaTexture.h"
#include "scene/Primitives.h"
#include "scene/Scene.h"
#include "scene/WeldedMesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <random>
#include <set>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace sl
{
namespace
{

namespace fs = std::filesystem;

const fs::path kDatasets = fs::path(SL_SOURCE_DIR) / "datasets";

// The mask's own rule, read directly (not through alphaHoleAt, which the generator uses): alpha < 0.5 is a hole,
// texels outside the mask are no surface.
bool opaqueAt(const ImageF& alpha, int x, int y)
{
  return x >= 0 && y >= 0 && x < alpha.width && y < alpha.height && alpha.at(x, y) >= 0.5f;
}

std::size_t countOpaque(const ImageF& alpha)
{
  std::size_t count = 0;
  for (int y = 0; y < alpha.height; ++y)
    for (int x = 0; x < alpha.width; ++x)
      count += opaqueAt(alpha, x, y) ? 1 : 0;
  return count;
}

// Texel sides between an opaque texel and a hole or the mask's border: the outline the mesh must leave open.
std::size_t countOutlineSides(const ImageF& alpha)
{
  std::size_t sides = 0;
  for (int y = 0; y < alpha.height; ++y)
    for (int x = 0; x < alpha.width; ++x)
      if (opaqueAt(alpha, x, y))
        sides += !opaqueAt(alpha, x - 1, y) + !opaqueAt(alpha, x + 1, y) + !opaqueAt(alpha, x, y - 1) +
          !opaqueAt(alpha, x, y + 1);
  return sides;
}

// uv of a point of the frame's plane: the least-squares solution of origin + u uAxis + v vAxis = p (normal
// equations of the 2x2 Gram matrix), so it does not lean on the mesh's own uvs.
glm::dvec2 uvOf(const QuadUvFrame& frame, const glm::dvec3& p)
{
  const glm::dvec3 d = p - frame.origin();
  const double uu = glm::dot(frame.uAxis(), frame.uAxis());
  const double uv = glm::dot(frame.uAxis(), frame.vAxis());
  const double vv = glm::dot(frame.vAxis(), frame.vAxis());
  const double du = glm::dot(d, frame.uAxis());
  const double dv = glm::dot(d, frame.vAxis());
  const double determinant = uu * vv - uv * uv;
  return { (du * vv - dv * uv) / determinant, (dv * uu - du * uv) / determinant };
}

glm::dvec3 corner(const TriangleMesh& mesh, std::size_t triangle, int k)
{
  return glm::dvec3(mesh.positions[mesh.indices[3 * triangle + static_cast<std::size_t>(k)]]);
}

// 2D coordinates in the plane along an orthonormal pair built from the normal alone (not the uv axes).
struct PlaneCoordinates
{
  explicit PlaneCoordinates(const glm::dvec3& normal)
  {
    const glm::dvec3 n = glm::normalize(normal);
    const glm::dvec3 helper = std::abs(n.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    e1 = glm::normalize(glm::cross(helper, n));
    e2 = glm::cross(n, e1);
  }
  glm::dvec2 of(const glm::dvec3& p) const { return { glm::dot(p, e1), glm::dot(p, e2) }; }
  glm::dvec3 e1, e2;
};

// Every triangle of a mesh in a uniform 2D bucket grid, for point-in-mesh queries.
class TriangleBuckets
{
public:
  TriangleBuckets(const TriangleMesh& mesh, const PlaneCoordinates& plane, double cellSize)
    : mesh_(mesh)
    , plane_(plane)
    , cellSize_(cellSize)
  {
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
    {
      glm::dvec2 low(1e300), high(-1e300);
      for (int k = 0; k < 3; ++k)
      {
        const glm::dvec2 q = plane.of(corner(mesh, t, k));
        low = glm::min(low, q);
        high = glm::max(high, q);
        projected_.push_back(q);
      }
      for (long long i = cell(low.x); i <= cell(high.x); ++i)
        for (long long j = cell(low.y); j <= cell(high.y); ++j)
          buckets_[key(i, j)].push_back(static_cast<std::uint32_t>(t));
    }
  }

  // Triangles containing `p`: strictly inside by more than `margin` (world units) when margin > 0, or within
  // -margin of it (inclusive) when margin < 0.
  int containing(const glm::dvec3& p, double margin) const
  {
    const glm::dvec2 q = plane_.of(p);
    const auto found = buckets_.find(key(cell(q.x), cell(q.y)));
    if (found == buckets_.end())
      return 0;
    int count = 0;
    for (const std::uint32_t t : found->second)
    {
      const glm::dvec2* c = &projected_[3 * static_cast<std::size_t>(t)];
      const double twiceArea = cross(c[1] - c[0], c[2] - c[0]);
      bool inside = true;
      for (int k = 0; k < 3; ++k)
      {
        const glm::dvec2 a = c[k];
        const glm::dvec2 b = c[(k + 1) % 3];
        // Signed distance from q to edge a-b, positive inside (for either orientation of the projection).
        const double distance = cross(b - a, q - a) / glm::length(b - a) * (twiceArea > 0 ? 1.0 : -1.0);
        inside = inside && distance > margin;
      }
      count += inside ? 1 : 0;
    }
    return count;
  }

private:
  static double cross(const glm::dvec2& a, const glm::dvec2& b) { return a.x * b.y - a.y * b.x; }
  long long cell(double coordinate) const { return static_cast<long long>(std::floor(coordinate / cellSize_)); }
  static std::uint64_t key(long long i, long long j)
  {
    return (static_cast<std::uint64_t>(i) << 32) ^ static_cast<std::uint64_t>(j & 0xFFFFFFFFll);
  }

  const TriangleMesh& mesh_;
  const PlaneCoordinates& plane_;
  double cellSize_;
  std::vector<glm::dvec2> projected_;
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> buckets_;
};

// Collects the first few failures of a many-element check into one message.
struct Failures
{
  std::size_t count = 0;
  std::string first;
  void add(const std::string& what)
  {
    if (count++ < 5)
      first += "\n  " + what;
  }
};

// All the structural checks of the file comment, for the mesh of `alpha` on `frame`. `areaTolerance` is relative
// (0 asks for exact equality).
void checkTexelMesh(const QuadUvFrame& frame, const ImageF& alpha, const TriangleMesh& mesh, double areaTolerance,
  const std::string& label)
{
  SCOPED_TRACE(label);
  const int width = alpha.width;
  const int height = alpha.height;
  const std::size_t opaque = countOpaque(alpha);
  ASSERT_EQ(mesh.triangleCount(), 2 * opaque);
  ASSERT_EQ(mesh.positions.size(), mesh.normals.size());
  ASSERT_EQ(mesh.positions.size(), mesh.uvs.size());

  // Shared grid: one vertex per texel corner used by an opaque texel, no more.
  std::set<std::pair<int, int>> usedCorners;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      if (opaqueAt(alpha, x, y))
        for (int c = 0; c < 4; ++c)
          usedCorners.insert({ x + (c & 1), y + (c >> 1) });
  EXPECT_EQ(mesh.positions.size(), usedCorners.size()) << "vertices are not one per used texel corner";

  // Vertices: on the frame at a texel corner, with that corner's uv and the quad's normal.
  const double texelArea = glm::length(glm::cross(frame.uAxis(), frame.vAxis())) / (double(width) * height);
  const double texelSide = std::max(glm::length(frame.uAxis()) / width, glm::length(frame.vAxis()) / height);
  const double scale =
    std::max({ 1.0, glm::length(frame.origin()), glm::length(frame.uAxis()), glm::length(frame.vAxis()) });
  Failures vertexFailures;
  for (std::size_t v = 0; v < mesh.positions.size(); ++v)
  {
    const glm::dvec3 p(mesh.positions[v]);
    const glm::dvec2 uv = uvOf(frame, p);
    const glm::dvec2 texelCorner(uv.x * width, uv.y * height);
    const glm::dvec2 nearest = glm::round(texelCorner);
    const double offPlane = std::abs(glm::dot(p - frame.origin(), frame.normal));
    if (glm::length(texelCorner - nearest) > 1e-4 || offPlane > 1e-6 * scale ||
      glm::length(glm::dvec2(mesh.uvs[v]) - nearest / glm::dvec2(width, height)) > 1e-6 ||
      glm::length(glm::dvec3(mesh.normals[v]) - frame.normal) > 1e-6)
      vertexFailures.add(format("vertex ", v, " at texel corner ", texelCorner.x, ",", texelCorner.y, " off plane ",
        offPlane, " uv ", mesh.uvs[v].x, ",", mesh.uvs[v].y));
  }
  EXPECT_EQ(vertexFailures.count, 0u) << vertexFailures.first;

  // Area, facing, and each triangle's centre opaque.
  double area = 0.0;
  Failures triangleFailures;
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
  {
    const glm::dvec3 a = corner(mesh, t, 0);
    const glm::dvec3 b = corner(mesh, t, 1);
    const glm::dvec3 c = corner(mesh, t, 2);
    const glm::dvec3 normal = glm::cross(b - a, c - a);
    const double triangleArea = 0.5 * glm::length(normal);
    area += triangleArea;
    const glm::dvec2 centreUv = uvOf(frame, (a + b + c) / 3.0);
    const bool facing = glm::dot(normal, frame.normal) > 0.0;
    const bool halfTexel = std::abs(triangleArea - 0.5 * texelArea) <= 1e-4 * texelArea;
    const bool centreOpaque = !alphaHoleAt(alpha, centreUv) &&
      opaqueAt(alpha, static_cast<int>(std::floor(centreUv.x * width)),
        static_cast<int>(std::floor(centreUv.y * height)));
    if (!facing || !halfTexel || !centreOpaque)
      triangleFailures.add(format("triangle ", t, (facing ? "" : " faces away"), (halfTexel ? "" : " area "),
        (halfTexel ? 0.0 : triangleArea / texelArea), (centreOpaque ? "" : " centre on a hole at uv "),
        centreUv.x, ",", centreUv.y));
  }
  EXPECT_EQ(triangleFailures.count, 0u) << triangleFailures.first;
  const double expectedArea = static_cast<double>(opaque) * texelArea;
  if (areaTolerance == 0.0)
    EXPECT_EQ(area, expectedArea) << "opaque texels " << opaque << ", difference " << area - expectedArea;
  else
    EXPECT_LE(std::abs(area - expectedArea), areaTolerance * expectedArea)
      << "area " << area << " expected " << expectedArea << " (" << opaque << " opaque texels)";

  // Coverage: each texel's centre (on its diagonal: inclusive test), and two points off the diagonal, a quarter
  // texel from every edge (strict test), covered exactly once on an opaque texel and never on a hole.
  const PlaneCoordinates plane(frame.normal);
  const TriangleBuckets buckets(mesh, plane, 2.0 * texelSide);
  const double margin = 1e-9 * texelSide;
  Failures coverageFailures;
  std::size_t coveredCentres = 0;
  for (int y = 0; y < height; ++y)
  {
    for (int x = 0; x < width; ++x)
    {
      const bool isOpaque = opaqueAt(alpha, x, y);
      const auto at = [&](double fx, double fy) {
        return frame.pointAt({ (x + fx) / width, (y + fy) / height });
      };
      const int centre = buckets.containing(at(0.5, 0.5), -margin);
      const int lowerRight = buckets.containing(at(0.75, 0.25), margin);
      const int upperLeft = buckets.containing(at(0.25, 0.75), margin);
      coveredCentres += centre > 0 ? 1 : 0;
      const int expected = isOpaque ? 1 : 0;
      if ((centre > 0) != isOpaque || lowerRight != expected || upperLeft != expected)
        coverageFailures.add(format("texel ", x, ",", y, isOpaque ? " (opaque)" : " (hole)", ": centre in ", centre,
          " triangles, quarter points in ", lowerRight, " and ", upperLeft));
    }
  }
  EXPECT_EQ(coverageFailures.count, 0u) << coverageFailures.first;
  EXPECT_EQ(coveredCentres, opaque);

  // Edges from the index lists.
  struct Use
  {
    std::size_t triangle;
    bool forward;
  };
  std::unordered_map<std::uint64_t, std::vector<Use>> edges;
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      const std::uint32_t from = mesh.indices[3 * t + static_cast<std::size_t>(k)];
      const std::uint32_t to = mesh.indices[3 * t + static_cast<std::size_t>((k + 1) % 3)];
      const std::uint64_t key = (std::uint64_t(std::min(from, to)) << 32) | std::max(from, to);
      edges[key].push_back({ t, from < to });
    }
  }
  std::size_t boundaryEdges = 0;
  Failures edgeFailures;
  for (const auto& [key, uses] : edges)
  {
    const glm::dvec3 p0(mesh.positions[key >> 32]);
    const glm::dvec3 p1(mesh.positions[key & 0xFFFFFFFFu]);
    const glm::dvec2 uv = uvOf(frame, 0.5 * (p0 + p1));
    const glm::dvec2 mid(uv.x * width, uv.y * height); // texel units
    if (uses.size() == 2)
    {
      if (uses[0].forward == uses[1].forward)
        edgeFailures.add(format("edge at texel coordinates ", mid.x, ",", mid.y, ": both triangles run the same way"));
      continue;
    }
    if (uses.size() != 1)
    {
      edgeFailures.add(format("edge at texel coordinates ", mid.x, ",", mid.y, " used by ", uses.size(), " triangles"));
      continue;
    }
    ++boundaryEdges;
    // A boundary edge is a texel side: one coordinate of its midpoint on a texel line, the other half-way along.
    const double nearX = std::abs(mid.x - std::round(mid.x));
    const double nearY = std::abs(mid.y - std::round(mid.y));
    bool border = false;
    if (nearX < 1e-4 && std::abs(nearY - 0.5) < 1e-4)
    {
      const int line = static_cast<int>(std::round(mid.x));
      const int row = static_cast<int>(std::floor(mid.y));
      border = opaqueAt(alpha, line - 1, row) != opaqueAt(alpha, line, row);
    }
    else if (nearY < 1e-4 && std::abs(nearX - 0.5) < 1e-4)
    {
      const int line = static_cast<int>(std::round(mid.y));
      const int column = static_cast<int>(std::floor(mid.x));
      border = opaqueAt(alpha, column, line - 1) != opaqueAt(alpha, column, line);
    }
    if (!border)
      edgeFailures.add(format("boundary edge at texel coordinates ", mid.x, ",", mid.y,
        " is not a side between an opaque texel and a hole or the border"));
  }
  EXPECT_EQ(edgeFailures.count, 0u) << edgeFailures.first;
  EXPECT_EQ(boundaryEdges, countOutlineSides(alpha));
  EXPECT_EQ(edges.size() - boundaryEdges, (3 * mesh.triangleCount() - boundaryEdges) / 2);

  // The welder the object-space techniques use finds the same connectivity: no two vertices at one point, the
  // same open edges, every other edge manifold and consistently wound.
  const WeldedMesh welded = weldMesh(mesh, 0);
  EXPECT_EQ(welded.positions.size(), mesh.positions.size());
  EXPECT_EQ(welded.collapsedTriangles, 0u);
  EXPECT_EQ(welded.boundaryEdgeCount(), countOutlineSides(alpha));
  EXPECT_EQ(welded.nonManifoldEdgeCount(), 0u);
  EXPECT_EQ(welded.inconsistentEdgeCount(), 0u);
}

// A frame whose every corner position, edge and area is exact in float and double: size 2 x 1.5 at height 1,
// like the fence's canopy (which is 2 x 1.4; 1.4 / 256 is not dyadic).
QuadUvFrame dyadicFrame()
{
  return quadUvFrame(makeQuad({ 0.0, 1.0, 0.0 }, { 2.0, 1.5 }, { 0.0, 1.0, 0.0 }, { 0.0, 0.0, -1.0 }));
}

ImageF maskFromRows(const std::vector<std::string>& rowsTopDown)
{
  // Rows as drawn, top row first; row 0 of the image is the bottom (v near 0). '#' = 1, '+' = exactly 0.5
  // (opaque), '-' = 0.49 (a hole), '.' = 0.
  const int height = static_cast<int>(rowsTopDown.size());
  const int width = static_cast<int>(rowsTopDown.front().size());
  ImageF alpha(width, height, 1);
  for (int row = 0; row < height; ++row)
  {
    for (int x = 0; x < width; ++x)
    {
      const char c = rowsTopDown[static_cast<std::size_t>(row)][static_cast<std::size_t>(x)];
      alpha.at(x, height - 1 - row) = c == '#' ? 1.0f : c == '+' ? 0.5f : c == '-' ? 0.49f : 0.0f;
    }
  }
  return alpha;
}

TEST(AlphaMesh, HandMadeMasksMeshExactlyAlongTexelBoundaries)
{
  const QuadUvFrame frame = dyadicFrame();
  // Diagonal contacts (a shared corner vertex, never a shared edge), threshold values, a hole enclosed by opaque
  // texels (an inner outline), texels on every border.
  const ImageF mixed = maskFromRows({
    "#.#.##",
    ".#.#.#",
    "##-+.#",
    "#+.###",
    "####.-",
  });
  // 6 and 5 texels do not divide 2 x 1.5 dyadically: corners are rounded to float, the area holds to 1e-6.
  checkTexelMesh(frame, mixed, meshOpaqueTexels(frame, mixed), 1e-6, "mixed 6 x 5");
  EXPECT_EQ(opaqueTexelCount(mixed), countOpaque(mixed));

  const ImageF full(4, 4, 1, 1.0f);
  const TriangleMesh fullMesh = meshOpaqueTexels(frame, full);
  checkTexelMesh(frame, full, fullMesh, 0.0, "opaque 4 x 4");
  EXPECT_EQ(fullMesh.positions.size(), 25u);

  const ImageF ring = maskFromRows({ "###", "#.#", "###" });
  const TriangleMesh ringMesh = meshOpaqueTexels(frame, ring);
  checkTexelMesh(frame, ring, ringMesh, 1e-6, "ring 3 x 3");
  EXPECT_EQ(weldMesh(ringMesh, 0).boundaryEdgeCount(), 16u); // 12 outer sides, 4 around the hole

  EXPECT_TRUE(meshOpaqueTexels(frame, ImageF(7, 3, 1, 0.2f)).indices.empty());

  // One opaque texel is the quad itself: its four corners bit for bit, its two triangles, its winding.
  const TriangleMesh quad = makeQuad({ 0.3, -0.7, 1.1 }, { 1.7, 0.9 }, glm::normalize(glm::dvec3(0.2, 1.0, -0.4)),
    glm::normalize(glm::dvec3(0.0, 0.4, 1.0)));
  const TriangleMesh single = meshOpaqueTexels(quadUvFrame(quad), ImageF(1, 1, 1, 1.0f));
  ASSERT_EQ(single.triangleCount(), 2u);
  for (std::size_t t = 0; t < 2; ++t)
    for (int k = 0; k < 3; ++k)
    {
      const std::uint32_t index = single.indices[3 * t + static_cast<std::size_t>(k)];
      const std::uint32_t quadIndex = quad.indices[3 * t + static_cast<std::size_t>(k)];
      EXPECT_EQ(single.positions[index], quad.positions[quadIndex]) << "triangle " << t << " corner " << k;
      EXPECT_EQ(single.uvs[index], quad.uvs[quadIndex]);
    }
}

// Random masks of every shape from 1 x 1 to 17 x 17 on random quads (tilted, off the origin, transformed with a
// non-uniform scale that shears the uv frame into a parallelogram).
TEST(AlphaMesh, RandomMasksOnRandomTransformedQuads)
{
  std::mt19937_64 random(2009);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto direction = [&]() {
    glm::dvec3 d;
    do
      d = glm::dvec3(unit(random), unit(random), unit(random)) * 2.0 - 1.0;
    while (glm::length(d) < 0.2 || glm::length(d) > 1.0);
    return glm::normalize(d);
  };
  for (int trial = 0; trial < 40; ++trial)
  {
    const int width = 1 + static_cast<int>(random() % 17);
    const int height = 1 + static_cast<int>(random() % 17);
    const double density = unit(random);
    ImageF alpha(width, height, 1);
    for (float& value : alpha.data)
      value = static_cast<float>(unit(random) < density ? 0.5 + 0.5 * unit(random) : 0.499 * unit(random));
    const glm::dvec3 normal = direction();
    glm::dvec3 up = direction();
    while (isParallel(up, normal))
      up = direction();
    TriangleMesh quad = makeQuad(glm::dvec3(unit(random), unit(random), unit(random)) * 4.0 - 2.0,
      { 0.2 + 3.0 * unit(random), 0.2 + 3.0 * unit(random) }, normal, orthogonalizedUp(up, normal));
    Transform transform;
    transform.rotateDeg = glm::dvec3(unit(random), unit(random), unit(random)) * 360.0;
    transform.scale = glm::dvec3(0.5 + unit(random), 0.5 + unit(random), 0.5 + unit(random));
    transform.translate = glm::dvec3(unit(random), unit(random), unit(random)) * 10.0 - 5.0;
    transformMesh(quad, transform.worldFromLocal());
    const QuadUvFrame frame = quadUvFrame(quad);
    checkTexelMesh(frame, alpha, meshOpaqueTexels(frame, alpha), 1e-5,
      format("trial ", trial, ": ", width, " x ", height, " density ", density));
  }
}

TEST(AlphaMesh, ProceduralPatternsAtFullSize)
{
  const QuadUvFrame frame = dyadicFrame();
  const ImageF fence = makeFenceAlpha();
  checkTexelMesh(frame, fence, meshOpaqueTexels(frame, fence), 0.0, "fence 256 x 256, dyadic frame");
  const ImageF leaves = makeLeavesAlpha();
  checkTexelMesh(frame, leaves, meshOpaqueTexels(frame, leaves), 0.0, "leaves 256 x 256, dyadic frame");
}

TEST(AlphaMesh, TooManyTrianglesIsAnInputErrorBeforeMeshing)
{
  // A fully opaque 2049 x 2048 mask is just past the limit (a 2048 x 2048 one is exactly at it).
  const ImageF large(2049, 2048, 1, 1.0f);
  try
  {
    meshOpaqueTexels(dyadicFrame(), large);
    FAIL() << "no error";
  }
  catch (const InputError& error)
  {
    EXPECT_NE(std::string(error.what()).find("4196352 opaque texels"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("more than the limit 8388608"), std::string::npos) << error.what();
  }
  EXPECT_EQ(2u * 2048u * 2048u, kMaxAlphaMeshTriangles);
}

// ---- the scene key and the dataset ------------------------------------------------------------------------

const char* const kSceneHead = R"({ "lights": [ { "type": "area", "center": [0, 3, 0], "size": 0.5 } ], "objects": [ )";

std::string sceneWith(const std::string& object)
{
  return std::string(kSceneHead) + object + " ] }";
}

std::string loadError(const std::string& text, const fs::path& baseDir = fs::temp_directory_path())
{
  try
  {
    parseScene(text, "inline", baseDir);
  }
  catch (const InputError& error)
  {
    return error.what();
  }
  return "(no error)";
}

TEST(AlphaMeshScene, FenceMeshedIsTheFenceQuadsOpaqueTexels)
{
  const auto start = std::chrono::steady_clock::now();
  const Scene meshed = loadScene(kDatasets / "fence-meshed" / "scene.json");
  const double loadSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const Scene fence = loadScene(kDatasets / "fence" / "scene.json");
  ASSERT_EQ(meshed.objects.size(), 2u);
  ASSERT_EQ(fence.objects.size(), 2u);
  const SceneObject& canopy = meshed.objects[1];
  EXPECT_FALSE(canopy.hasAlphaTexture);
  EXPECT_TRUE(canopy.alphaTexture.alpha.data.empty());
  EXPECT_EQ(canopy.name, "objects[1] (quad, alpha texture fence meshed)");
  EXPECT_TRUE(fence.objects[1].hasAlphaTexture);
  const ImageF& alpha = fence.objects[1].alphaTexture.alpha;
  EXPECT_EQ(canopy.mesh.triangleCount(), 2 * countOpaque(alpha));
  // The only difference between the two files is the key: same light, camera, ground and bounds.
  EXPECT_EQ(meshed.objects[0].mesh.positions, fence.objects[0].mesh.positions);
  EXPECT_EQ(meshed.bounds().min, fence.bounds().min);
  EXPECT_EQ(meshed.bounds().max, fence.bounds().max);
  // 1.4 / 256 is not dyadic, so corners are rounded to float: the area holds to float precision.
  checkTexelMesh(quadUvFrame(fence.objects[1].mesh), alpha, canopy.mesh, 1e-6, "fence-meshed");
  std::printf("[ fence-meshed ] %zu triangles, %zu vertices (%zu opaque texels of %d x %d); loadScene %.1f ms\n",
    canopy.mesh.triangleCount(), canopy.mesh.positions.size(), countOpaque(alpha), alpha.width, alpha.height,
    1e3 * loadSeconds);
}

// `mesh_alpha` after a transform meshes the transformed quad: every vertex is where the unmeshed, transformed quad
// has that uv; false leaves the perforated quad as it is.
TEST(AlphaMeshScene, MeshAlphaFollowsTheTransformAndFalseKeepsTheQuad)
{
  const std::string quad = R"({ "primitive": "quad", "center": [0.2, 1, -0.1], "size": [1.5, 0.75],
    "normal": [0, 1, 0.3], "up": [0, 0, -1], "alpha_texture": "leaves",
    "transform": { "rotate_deg": [10, 35, -20], "scale": [1.2, 0.7, 1.9], "translate": [0.1, 0.4, 0] })";
  const Scene plain = parseScene(sceneWith(quad + " }"), "inline", fs::temp_directory_path());
  const Scene kept = parseScene(sceneWith(quad + R"(, "mesh_alpha": false })"), "inline", fs::temp_directory_path());
  const Scene meshed = parseScene(sceneWith(quad + R"(, "mesh_alpha": true })"), "inline", fs::temp_directory_path());
  EXPECT_TRUE(kept.objects[0].hasAlphaTexture);
  EXPECT_EQ(kept.objects[0].mesh.positions, plain.objects[0].mesh.positions);
  const TriangleMesh& transformedQuad = plain.objects[0].mesh;
  const TriangleMesh& mesh = meshed.objects[0].mesh;
  ASSERT_FALSE(mesh.indices.empty());
  // The transformed quad's own interpolation: the vertex's uv solved for barycentrics in whichever of the quad's
  // two triangles holds it (by the triangles' uvs, as a renderer interpolates), then those barycentrics applied
  // to the triangle's corners.
  double worst = 0.0;
  for (std::size_t v = 0; v < mesh.positions.size(); ++v)
  {
    const glm::dvec2 uv(mesh.uvs[v]);
    bool found = false;
    for (std::size_t t = 0; t < 2 && !found; ++t)
    {
      glm::dvec2 uvs[3];
      glm::dvec3 corners[3];
      for (int k = 0; k < 3; ++k)
      {
        const std::uint32_t index = transformedQuad.indices[3 * t + static_cast<std::size_t>(k)];
        uvs[k] = glm::dvec2(transformedQuad.uvs[index]);
        corners[k] = glm::dvec3(transformedQuad.positions[index]);
      }
      const glm::dvec2 e1 = uvs[1] - uvs[0];
      const glm::dvec2 e2 = uvs[2] - uvs[0];
      const glm::dvec2 d = uv - uvs[0];
      const double determinant = e1.x * e2.y - e1.y * e2.x;
      const double b1 = (d.x * e2.y - d.y * e2.x) / determinant;
      const double b2 = (e1.x * d.y - e1.y * d.x) / determinant;
      if (b1 < -1e-12 || b2 < -1e-12 || b1 + b2 > 1.0 + 1e-12)
        continue;
      found = true;
      const glm::dvec3 expected = corners[0] + b1 * (corners[1] - corners[0]) + b2 * (corners[2] - corners[0]);
      worst = std::max(worst, glm::length(glm::dvec3(mesh.positions[v]) - expected));
    }
    EXPECT_TRUE(found) << "vertex " << v << " uv " << uv.x << "," << uv.y << " outside the quad";
  }
  EXPECT_LT(worst, 1e-6);
  checkTexelMesh(quadUvFrame(transformedQuad), plain.objects[0].alphaTexture.alpha, mesh, 1e-5, "transformed leaves");
}

TEST(AlphaMeshScene, BadMeshAlphaIsOneLineNamingTheKey)
{
  const std::string alphaQuad = R"({ "primitive": "quad", "alpha_texture": "fence", )";
  EXPECT_EQ(loadError(sceneWith(R"({ "primitive": "disk", "alpha_texture": "fence", "mesh_alpha": true })")),
    "inline: objects[0].mesh_alpha: applies only to a 'quad' primitive (with an 'alpha_texture')");
  EXPECT_EQ(loadError(sceneWith(R"({ "primitive": "box", "mesh_alpha": false })")),
    "inline: objects[0].mesh_alpha: applies only to a 'quad' primitive (with an 'alpha_texture')");
  EXPECT_EQ(loadError(sceneWith(R"({ "mesh": "x.obj", "alpha_texture": "fence", "mesh_alpha": true })")),
    "inline: objects[0].mesh_alpha: applies only to a 'quad' primitive (with an 'alpha_texture')");
  EXPECT_EQ(loadError(sceneWith(R"({ "primitive": "quad", "mesh_alpha": true })")),
    "inline: objects[0].mesh_alpha: needs an 'alpha_texture' on the quad (the mask whose opaque texels it meshes)");
  EXPECT_EQ(loadError(sceneWith(alphaQuad + R"("mesh_alpha": "yes" })")),
    "inline: objects[0].mesh_alpha: expected true or false, got string \"yes\"");
  EXPECT_EQ(loadError(sceneWith(alphaQuad + R"("mesh_alpha": 1 })")),
    "inline: objects[0].mesh_alpha: expected true or false, got 1");

  // A mask without an opaque texel (a black PNG: no alpha channel, luminance 0) would leave no triangle.
  const fs::path dir = fs::temp_directory_path() / format("sl-alphamesh-", ::getpid());
  fs::create_directories(dir);
  writePng(dir / "black.png", ImageU8(3, 2, 3, 0));
  EXPECT_EQ(loadError(sceneWith(R"({ "primitive": "quad", "alpha_texture": "black.png", "mesh_alpha": true })"), dir),
    "inline: objects[0].mesh_alpha: alpha texture 'black.png' has no opaque texel (alpha >= 0.5), so the mesh would "
    "be empty");
  std::error_code ignored;
  fs::remove_all(dir, ignored);
}

// ---- the claim: same hidden samples as the perforated quad --------------------------------------------------

// Synthetic receivers (no rendering): a side x side grid over the canopy's shadow at height `height`, normals
// tilted at random by up to `maxTiltDeg` (always facing up, so every sample is above the tangent plane).
ReferenceInputs gridReceivers(const Scene& scene, int side, double height, double maxTiltDeg, std::uint64_t seed)
{
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  ReferenceInputs inputs;
  inputs.scene = &scene;
  inputs.light = &scene.lights.front();
  inputs.position = ImageF(side, side, 3);
  inputs.normal = ImageF(side, side, 3);
  inputs.coverage = ImageF(side, side, 1, 1.0f);
  inputs.receives = ImageF(side, side, 1, 1.0f);
  // The light (centre (0.3, 3, 0.2), side 0.5) through the canopy (x in [-1, 1], z in [-0.7, 0.7], y = 1) reaches
  // y = 0 within x in [-1.8, 1.5], z in [-1.3, 1.1]; at greater heights the shadow is smaller.
  const double spread = (3.0 - height) / 2.0;
  const glm::dvec2 low(0.3 + spread * (-1.0 - 0.3) - 0.3, 0.2 + spread * (-0.7 - 0.2) - 0.3);
  const glm::dvec2 high(0.3 + spread * (1.0 - 0.3) + 0.3, 0.2 + spread * (0.7 - 0.2) + 0.3);
  for (int y = 0; y < side; ++y)
  {
    for (int x = 0; x < side; ++x)
    {
      const glm::dvec3 p(low.x + (high.x - low.x) * (x + 0.5) / side, height,
        low.y + (high.y - low.y) * (y + 0.5) / side);
      const double tilt = glm::radians(maxTiltDeg * unit(random));
      const double azimuth = 6.283185307179586 * unit(random);
      const glm::dvec3 n(std::sin(tilt) * std::cos(azimuth), std::cos(tilt), std::sin(tilt) * std::sin(azimuth));
      for (int c = 0; c < 3; ++c)
      {
        inputs.position.at(x, y, c) = static_cast<float>(p[c]);
        inputs.normal.at(x, y, c) = static_cast<float>(n[c]);
      }
    }
  }
  return inputs;
}

bool hiddenBit(const ReferenceResult& result, int x, int y, int sample)
{
  return (static_cast<std::uint32_t>(result.lightSampleMask.at(x, y, sample / 16)) >> (sample % 16)) & 1u;
}

// Embree with the shared light-sample set on `fence` (two perforated triangles, the alpha filter) and on
// `fence-meshed` (its opaque texels as triangles): the per-sample hidden bits agree on >= 99.9 % of (pixel, sample)
// pairs, and every pair that differs crosses the canopy within 1e-3 texel of a texel boundary, where the two
// representations decide in float whether the segment passes through the hole or the wire beside it.
TEST(AlphaMeshScene, FenceAndFenceMeshedHideTheSameLightSamples)
{
  const Scene fence = loadScene(kDatasets / "fence" / "scene.json");
  const Scene meshed = loadScene(kDatasets / "fence-meshed" / "scene.json");
  const QuadUvFrame canopy = quadUvFrame(fence.objects[1].mesh);
  const ImageF& alpha = fence.objects[1].alphaTexture.alpha;
  ReferenceSettings settings;
  settings.lightSampleSet = lightSampleSetSettings("poisson", 64, 3);
  const LightSampleSet samples(*settings.lightSampleSet);
  const double offset = referenceRayOffset(fence, settings);
  ASSERT_EQ(offset, referenceRayOffset(meshed, settings));

  constexpr int kSide = 64;
  long long pairs = 0;
  long long differing = 0;
  long long hidden = 0;
  double worstTexelDistance = 0.0;
  // The ground (wide penumbrae) and a plane just under the canopy with tilted normals (sharp texel-sized shadows).
  const std::pair<double, double> planes[] = { { 0.0, 0.0 }, { 0.8, 50.0 } };
  for (const auto& [height, tilt] : planes)
  {
    const ReferenceInputs fenceInputs = gridReceivers(fence, kSide, height, tilt, 7);
    ReferenceInputs meshedInputs = fenceInputs;
    meshedInputs.scene = &meshed;
    meshedInputs.light = &meshed.lights.front();
    const ReferenceResult perforated = renderReference(fenceInputs, settings);
    const ReferenceResult explicitMesh = renderReference(meshedInputs, settings);
    for (int y = 0; y < kSide; ++y)
    {
      for (int x = 0; x < kSide; ++x)
      {
        const glm::dvec3 p(fenceInputs.position.at(x, y, 0), fenceInputs.position.at(x, y, 1),
          fenceInputs.position.at(x, y, 2));
        const glm::dvec3 n(fenceInputs.normal.at(x, y, 0), fenceInputs.normal.at(x, y, 1),
          fenceInputs.normal.at(x, y, 2));
        const glm::dvec3 origin = p + offset * n;
        for (int i = 0; i < samples.count(); ++i)
        {
          ++pairs;
          const bool a = hiddenBit(perforated, x, y, i);
          const bool b = hiddenBit(explicitMesh, x, y, i);
          hidden += a ? 1 : 0;
          if (a == b)
            continue;
          ++differing;
          // Where the segment meets the canopy's plane, in texels: its distance to the nearest texel line.
          const glm::dvec3 s = samples.point(*fenceInputs.light, x, y, i);
          const double t = glm::dot(canopy.origin() - origin, canopy.normal) / glm::dot(s - origin, canopy.normal);
          const glm::dvec2 uv = uvOf(canopy, origin + t * (s - origin));
          const glm::dvec2 texel(uv.x * alpha.width, uv.y * alpha.height);
          const double distance =
            std::min(std::abs(texel.x - std::round(texel.x)), std::abs(texel.y - std::round(texel.y)));
          worstTexelDistance = std::max(worstTexelDistance, distance);
          EXPECT_LT(distance, 1e-3) << "height " << height << " pixel " << x << "," << y << " sample " << i
                                    << ": fence " << a << " fence-meshed " << b << " at texel " << texel.x << ","
                                    << texel.y;
        }
      }
    }
  }
  const double agreement = 1.0 - static_cast<double>(differing) / static_cast<double>(pairs);
  EXPECT_GE(agreement, 0.999) << differing << " of " << pairs << " pairs differ";
  // The comparison is not vacuous: a good share of the samples is hidden, and not all.
  EXPECT_GT(hidden, pairs / 10);
  EXPECT_LT(hidden, pairs - pairs / 10);
  std::printf("[ fence vs fence-meshed ] %lld of %lld (pixel, sample) pairs differ (agreement %.6f), %lld hidden; "
              "largest distance of a differing crossing from a texel line %.2e texel\n",
    differing, pairs, agreement, hidden, worstTexelDistance);
}

} // namespace
} // namespace sl
