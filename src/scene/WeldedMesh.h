// Casters with welded connectivity, for techniques that draw the scene's geometry themselves (the
// object-space seam of issue 12). Shadow volumes need, for every undirected edge, every triangle that uses
// it and the direction in which that triangle runs along it; a TriangleMesh cannot say which corners are
// the same point, because primitives (box faces, the sphere's seam and poles) have split vertices.
//
// Welding rule. Two vertices of one object are the same vertex when every coordinate differs by at most
//   tolerance = max(1e-6 * |bounding-box diagonal|, 4 * FLT_EPSILON * max |coordinate|)
// of that object. Copies of a corner are computed by different double expressions (a box corner by each of
// its three faces, the sphere's seam with sin(2 pi) = -2.4e-16 instead of 0) and then rounded to float32,
// so they differ by at most a few float ulps of the coordinate; the first term covers coordinates near 0,
// where an ulp is tiny but the double residue (1e-16 of the radius) is not. 1e-6 of an object's size is
// below anything a float32 mesh resolves. Vertices are visited in order; each joins the first earlier
// welded vertex within the tolerance (a 27-cell hash grid of cell size `tolerance` finds it), otherwise it
// starts a new one, so the result does not depend on hashing. A welded vertex keeps the float position of
// its first vertex bit for bit, so welded geometry rasterises where the G-buffer drew it.
// A triangle whose corners weld together has no area at this tolerance; it is dropped and counted.
//
// Connectivity. OpenMesh's half-edge structure refuses a face that would make an edge non-manifold (its
// add_face reports a "complex edge" and returns an invalid handle), and the shadow-volume rule needs every
// face of such an edge; so the connectivity is our own edge -> incident-triangles table over the welded
// face list, which keeps every triangle. An edge used once is a boundary (open) edge, twice a manifold edge
// (consistently oriented when the two triangles run along it in opposite directions), three or more times a
// non-manifold edge.
#pragma once

#include "scene/Scene.h"

#include <glm/glm.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace sl
{

// One triangle's use of an edge.
struct EdgeUse
{
  std::uint32_t triangle = 0; // index into WeldedMesh::triangles
  bool forward = false;       // the triangle's winding runs from the edge's v0 to its v1
};

struct WeldedEdge
{
  std::uint32_t v0 = 0; // welded vertex indices, v0 < v1
  std::uint32_t v1 = 0;
  std::uint32_t firstUse = 0; // this edge's uses are edgeUses[firstUse, firstUse + useCount)
  std::uint32_t useCount = 0; // 1 boundary, 2 manifold, > 2 non-manifold
};

struct WeldedMesh
{
  std::size_t objectIndex = 0; // the caster's index in Scene::objects
  double weldTolerance = 0.0;  // world units, see the rule above
  std::vector<glm::vec3> positions; // world space, one per welded vertex (its first vertex's, bit for bit)
  std::vector<std::array<std::uint32_t, 3>> triangles; // welded corners, the object's winding
  std::vector<std::uint32_t> sourceTriangles;          // each triangle's index in the object's TriangleMesh
  // Edge indices of each triangle's sides (c0 c1), (c1 c2), (c2 c0).
  std::vector<std::array<std::uint32_t, 3>> triangleEdges;
  std::vector<WeldedEdge> edges;
  std::vector<EdgeUse> edgeUses;
  std::size_t collapsedTriangles = 0; // dropped: two or three corners welded into one vertex

  std::size_t boundaryEdgeCount() const;
  std::size_t nonManifoldEdgeCount() const;
  // Manifold edges whose two triangles run along it in the same direction (inconsistent winding).
  std::size_t inconsistentEdgeCount() const;
};

// The welding tolerance of the rule above for `mesh` (world units, > 0).
double weldTolerance(const TriangleMesh& mesh);

// Welds one object's mesh (its world-space positions) and builds the edge table.
WeldedMesh weldMesh(const TriangleMesh& mesh, std::size_t objectIndex);

// Every object that casts shadows (castShadows), in scene order. A welded caster is its whole triangle set: alpha
// textures are not looked at, unless `opaqueOnly` leaves perforated objects (hasAlphaTexture) out altogether (the
// techniques whose STSVs shadow them, Forest et al. 2009 §2).
std::vector<WeldedMesh> weldCasters(const Scene& scene, bool opaqueOnly = false);

} // namespace sl
