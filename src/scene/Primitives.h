// Tessellation of the scene format's primitives (quad, box, sphere, disk) and object transforms.
//
// Every primitive is built in world units around its `center`, then the object's transform is applied
// (p_world = T * R * S * p, see Transform). Conventions shared by all primitives:
//  - Winding: counter-clockwise seen from the side the normal points to (outside for box and sphere).
//  - Texture coordinates lie in [0,1]^2:
//      quad:   u runs along right = cross(up, normal) (the same `right` as Light::right()), v along up;
//              (u,v) = (0,0) is the corner center - right*sx/2 - up*sy/2.
//      box:    each face is a quad with its own [0,1]^2 (face frames listed in Primitives.cpp).
//      sphere: longitude/latitude; u = azimuth / 2pi measured from +x toward -z (counter-clockwise seen
//              from +y), v = 0 at the south pole (-y) to 1 at the north pole (+y). The seam vertices
//              are duplicated so u goes from 0 to 1 without wrapping inside a triangle.
//      disk:   planar mapping (p_local + r) / (2r), with p_local = (p.right, p.up) relative to the center.
#pragma once

#include "scene/Scene.h"

#include <glm/glm.hpp>

namespace sl
{

constexpr int kSphereSegments = 64; // around the axis (longitude)
constexpr int kSphereRings = 32;    // pole to pole (latitude)
constexpr int kDiskSegments = 64;

// The `up` a planar thing (quad, disk, area light) gets when the scene gives none: world +y projected onto
// the plane, or +x projected onto it when +y is (nearly) parallel to the normal. Unit length.
glm::dvec3 defaultUp(const glm::dvec3& unitNormal);

// `up` with its component along `unitNormal` removed, normalised. Callers check first that `up` is not
// parallel to the normal (isParallel).
glm::dvec3 orthogonalizedUp(const glm::dvec3& up, const glm::dvec3& unitNormal);

// True when a and b (both non-zero) point along the same line, within a small angular tolerance.
bool isParallel(const glm::dvec3& a, const glm::dvec3& b);

// Quad of size.x along right = cross(up, normal) and size.y along up. 4 vertices, 2 triangles.
TriangleMesh makeQuad(const glm::dvec3& center, const glm::dvec2& size, const glm::dvec3& unitNormal,
  const glm::dvec3& unitUp);

// Axis-aligned box with full extents `size`. 24 vertices (flat per-face normals), 12 triangles.
TriangleMesh makeBox(const glm::dvec3& center, const glm::dvec3& size);

// UV sphere, kSphereSegments x kSphereRings, smooth normals. The pole rows are single triangles, so no
// triangle is degenerate.
TriangleMesh makeSphere(const glm::dvec3& center, double radius);

// Disk as a kDiskSegments-triangle fan around its center, flat normal.
TriangleMesh makeDisk(const glm::dvec3& center, double radius, const glm::dvec3& unitNormal,
  const glm::dvec3& unitUp);

// An object's `transform` block. Rotation is applied X, then Y, then Z (R = Rz * Ry * Rx), all about the
// world origin, after scaling and before translation.
struct Transform
{
  glm::dvec3 translate{ 0.0 };
  glm::dvec3 rotateDeg{ 0.0 };
  glm::dvec3 scale{ 1.0 };

  glm::dmat4 worldFromLocal() const; // T * R * S
};

// Applies `worldFromLocal` (affine, non-singular) to positions, and its inverse-transpose to normals
// (renormalised). Winding is kept: callers only pass positive scales, so orientation is preserved.
void transformMesh(TriangleMesh& mesh, const glm::dmat4& worldFromLocal);

} // namespace sl
