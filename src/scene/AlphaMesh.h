// The opaque part of a perforated quad as an explicit mesh, cut exactly along texel boundaries: the "equivalent
// mesh" that Forest et al. 2009 sets its two perforated triangles against (Fig. 11, §6: a fence
// of 2 perforated triangles against its 233,358-triangle mesh, 27x; the 25-35x claim of §1). The scene key
// `mesh_alpha` (SceneLoader.cpp, docs/scene-format.md) replaces a quad with an alpha texture by this mesh.
//
// Layout. A quad's uv map (Primitives.h: u along right, v along up, (0,0) at the corner center - right sx/2 -
// up sy/2) runs over [0,1]^2, and texel (x, y) of a W x H mask covers u in [x, x+1)/W, v in [y, y+1)/H
// (AlphaTexture.h). Every texel that is not a hole (alphaHoleAt at its centre:
// alpha >= 0.5) becomes the two triangles
//     (x, y) (x+1, y) (x+1, y+1)   and   (x, y) (x+1, y+1) (x, y+1)
// over the grid of texel corners, the quad's own diagonal and winding (counter-clockwise around `normal`).
// Corners are one shared vertex grid: a corner used by several opaque texels is ONE vertex, so
//  - every edge inside the opaque region (a texel's diagonal, a side between two opaque texels) is used by exactly
//    two coplanar triangles running along it in opposite directions;
//  - the boundary edges (used once) are exactly the texel sides between an opaque texel and a hole or the quad's
//    border: the outline object-space techniques (`dcs`) must see as potential silhouettes, and nothing else.
// Opaque texels are never merged into larger rectangles: a merged rectangle's long side would meet its
// neighbours' corners in T-junctions, and those unshared edges inside the opaque region would count as
// silhouettes. Two opaque texels touching only at a corner share that vertex (a non-manifold vertex, but every
// edge stays manifold or boundary).
//
// Exactness. Corner (i, j) lies where the perforated quad itself puts uv (i/W, j/H): the renderers interpolate uv
// linearly over the quad's two float triangles (c0 c1 c2) and (c0 c2 c3) (corners c0..c3 at uv (0,0) (1,0) (1,1)
// (0,1)), so the texel boundaries they test against lie on that piecewise-affine map, not on one plane through
// three corners (the float corners are a parallelogram only to an ulp). QuadUvFrame::pointAt evaluates it in
// double, rounded once to float: the four outer corners are the quad's own bit for bit, and with power-of-two
// mask sizes and dyadic corners every vertex is exact. Texture coordinates (i/W, j/H) and the quad's normal are
// kept per vertex; the result has no alpha texture.
#pragma once

#include "core/Image.h"
#include "scene/Scene.h"

#include <glm/glm.hpp>

#include <array>
#include <cstddef>

namespace sl
{

// A quad's uv map over its two triangles, facing `normal` (unit; cross(uAxis(), vAxis()) points along it).
struct QuadUvFrame
{
  std::array<glm::dvec3, 4> corners{}; // at uv (0,0), (1,0), (1,1), (0,1)
  glm::dvec3 normal{ 0.0, 0.0, 1.0 };

  const glm::dvec3& origin() const { return corners[0]; }
  glm::dvec3 uAxis() const { return corners[1] - corners[0]; }
  glm::dvec3 vAxis() const { return corners[3] - corners[0]; }
  // The point of uv in [0,1]^2: barycentric interpolation on the quad's triangle that holds it, (c0 c1 c2) where
  // u >= v, else (c0 c2 c3). Both give c0 + u (c2 - c0) on the diagonal; uv (1,1) gives c2 exactly.
  glm::dvec3 pointAt(const glm::dvec2& uv) const
  {
    if (uv.x >= uv.y)
      return corners[0] + uv.x * (corners[1] - corners[0]) + uv.y * (corners[2] - corners[1]);
    return corners[0] + uv.x * (corners[2] - corners[3]) + uv.y * (corners[3] - corners[0]);
  }
};

// Largest mesh meshOpaqueTexels builds: a fully opaque 2048 x 2048 mask (2^23 triangles, about 0.4 GB of
// vertices and indices). A larger opaque area belongs in a mesh file, not in a mask meshed at load time.
constexpr std::size_t kMaxAlphaMeshTriangles = std::size_t(1) << 23;

// The uv frame of a quad as makeQuad builds it (4 vertices with uv (0,0), (1,0), (1,1), (0,1), 2 triangles),
// after any object transform: its corners found by their uv, normal the quad's vertex normal. A mesh of another
// layout, or one whose uv axes turn clockwise around its normal, is a bug (SL_CHECK).
QuadUvFrame quadUvFrame(const TriangleMesh& quad);

// Number of opaque texels (alphaHoleAt false at the texel centre) of a 1-component mask.
std::size_t opaqueTexelCount(const ImageF& alpha);

// The mesh of `alpha`'s opaque texels on `frame` (layout above). Empty when every texel is a hole. Throws
// InputError "the alpha texture has N opaque texels; meshing them would make 2N triangles, more than the limit
// kMaxAlphaMeshTriangles (...)" past the limit; callers prefix the key that asked for the mesh.
TriangleMesh meshOpaqueTexels(const QuadUvFrame& frame, const ImageF& alpha);

} // namespace sl
