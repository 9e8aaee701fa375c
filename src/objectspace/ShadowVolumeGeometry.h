// Shadow-volume geometry built on the CPU from the welded casters (technique `shadow-volume`): near caps,
// silhouette side quads and far caps, as one homogeneous triangle list ready to upload.
//
// The rule (Crow 1977's volumes; the multiplicity form for meshes that are not closed is Bergeron 1986 and
// Aldridge & Woods 2004, as used by Stich, Waechter & Keller, GPU Gems 3 ch. 11, 2007):
//  1. Every caster triangle is oriented toward the light: a triangle whose winding faces away from the
//     light is flipped. Its shadow volume is then the semi-infinite frustum behind it, bounded by the
//     triangle itself (near cap, facing the light), one side quad per edge, extruded away from the light,
//     and the triangle's image at infinity (far cap). Summed over all triangles, the count of volumes that
//     contain a point P is the number of caster triangles that the segment from P to the light crosses —
//     the buffer `depth_complexity_center` — and P is lit exactly when it is 0.
//  2. Side quads of one edge cancel in pairs when two light-oriented triangles run along it in opposite
//     directions. Per undirected welded edge (v0, v1), the multiplicity m = sum over its triangles of +1
//     when the light-oriented triangle runs v0 -> v1, -1 when it runs v1 -> v0. The edge contributes |m|
//     copies of its side quad, oriented as the triangles with the sign of m; silhouette edges are those
//     with m != 0. A closed, consistently oriented mesh gets |m| = 2 on its silhouette (the front faces'
//     volume and the flipped back faces' volume), a boundary edge |m| = 1, a non-manifold edge whatever the
//     sum is (0 to its number of triangles). No edge is special-cased: the rule is the same for all.
//  3. A triangle within kEdgeOnSine of containing the light (the light lies in its plane) has a volume of
//     no thickness; it contributes nothing (no caps, no sides) and is counted as edge-on.
// Orientation of the drawn triangles: counter-clockwise around the volume's outward normal, so a z-fail
// pass (Everitt & Kilgard 2002) increments on back faces and decrements on front faces that lie behind the
// receiver, and the stencil ends at the number of volumes containing it.
//
// Extrusion. Perspective cameras: vertices at infinity are homogeneous points (x - L, 0) (point light) or
// (d, 0) (directional light d), rasterised with depth clamping (Everitt & Kilgard's infinite volumes without
// the infinite projection matrix); a directional light's far cap is a single point at infinity and is not
// drawn. Orthographic cameras map every point at infinity to w_clip = 0, so a far cap would vanish: there the
// volumes are cut at a finite distance beyond every point of the scene's bounds (exact for every receiver),
// L + lambda (x - L) or x + K d, see buildShadowVolumes.
#pragma once

#include "scene/Scene.h"
#include "scene/WeldedMesh.h"

#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace sl
{

// Triangles whose plane passes within this angle (radians, as a sine) of the light are edge-on.
constexpr double kEdgeOnSine = 1e-6;

// The light as the volumes see it: a point (point and spot lights, the centre of an area light) or a
// direction (directional lights).
struct VolumeLight
{
  bool directional = false;
  glm::dvec3 position{ 0.0 };
  glm::dvec3 direction{ 0.0, -1.0, 0.0 }; // directional: unit, the direction the light travels

  static VolumeLight from(const Light& light);
};

enum class VolumeExtrusion
{
  ToInfinity, // w = 0 vertices, for perspective cameras
  Finite      // cut beyond the scene's bounds, for orthographic cameras
};

// One silhouette edge (m != 0), oriented as its side quads: the light-oriented triangles run from -> to.
struct SilhouetteEdge
{
  std::size_t objectIndex = 0; // Scene::objects index of its caster
  glm::vec3 from{ 0.0f };
  glm::vec3 to{ 0.0f };
  int multiplicity = 0;           // |m| >= 1: the number of side quads drawn for it
  std::uint32_t incidentTriangles = 0; // 1 boundary, 2 manifold, > 2 non-manifold (edge-on ones included)
};

struct ShadowVolumeStatistics
{
  std::size_t casterObjects = 0;
  std::size_t casterTriangles = 0;      // welded, after dropping collapsed ones
  std::size_t collapsedTriangles = 0;   // dropped by welding
  std::size_t flippedTriangles = 0;     // wound away from the light, flipped (rule 1)
  std::size_t edgeOnTriangles = 0;      // rule 3
  std::size_t edges = 0;                // undirected welded edges
  std::size_t boundaryEdges = 0;        // used by one triangle
  std::size_t nonManifoldEdges = 0;     // used by three or more
  std::size_t inconsistentEdges = 0;    // used by two triangles running the same way (winding flips there)
  std::size_t silhouetteEdges = 0;      // m != 0
  std::size_t sideQuads = 0;            // sum of |m|
  std::size_t nearCaps = 0;             // light-oriented triangles
  std::size_t farCaps = 0;              // nearCaps, or 0 for a directional light extruded to infinity
  std::size_t volumeTriangles() const { return 2 * sideQuads + nearCaps + farCaps; }
};

struct ShadowVolumeGeometry
{
  // Triangle list (3 vertices per triangle), world space, homogeneous: w = 1 on the casters, w = 0 at
  // infinity (VolumeExtrusion::ToInfinity).
  std::vector<glm::vec4> vertices;
  // One per triangle: its plane n . x = d as (n, d), n unit, computed in double from the caster's corners
  // and the light; (0, 0, 0, 0) for a far cap at infinity. The pass finds where the camera ray meets a
  // volume triangle from its plane rather than from rasterised depth (vtkSLShadowVolumePass.h says why).
  std::vector<glm::vec4> planes;
  std::vector<SilhouetteEdge> silhouettes;
  ShadowVolumeStatistics statistics;
};

// Builds the volumes of every welded caster for `light`. `sceneBounds` (every receiver lies inside) sets
// the finite extrusion's distance and is ignored for ToInfinity.
ShadowVolumeGeometry buildShadowVolumes(const std::vector<WeldedMesh>& casters, const VolumeLight& light,
  VolumeExtrusion extrusion, const Bounds& sceneBounds);

} // namespace sl
