// The CPU side of technique `dcs` (depth complexity sampling, Forest, Barthe & Paulin 2008 = FBP08, as used by
// Forest et al. 2009 §3.2), in double precision: which edges draw a wedge, the per-sample
// update rule each wedge applies, and the screen polygon each wedge is rasterised as. The GLSL of
// techniques/dcs/shaders/DcsWedgeUpdate.glsl computes the same rule in float; techniques/dcs/tests/DcsRuleTest.cpp
// checks the rule against direct crossing counts, techniques/dcs/tests/DcsTest.cpp the GPU against Embree.
//
// What is counted. The depth complexity of (p, s) is the number of caster triangles the segment [p, s] crosses
// (two-sided, as Embree's reference counts surfaces). The reference sample is the light's centre c: its count
// comes from the centre's shadow volumes (technique `shadow-volume`, whose count is exactly this number). As a
// point x moves on the light along the straight segment from c to a sample s, the count of [p, x] changes only
// where [p, x] sweeps across a caster edge e = (v0, v1), i.e. where e crosses the triangle (p, c, s). There, each
// triangle T that uses e is entered or left: T is crossed by [p, x] near e exactly when x lies on the side of the
// plane Pi(p, e) where T's third corner w_T lies. So (FBP08's ±1 per edge, written orientation-free):
//   count(s) = count(c) + sum over edges e crossing triangle (p, c, s) of  sign(g(s)) * M_e(p),
//   g(x)   = orient(v0, v1, p, x)     (which side of Pi(p, e) a light point lies on),
//   M_e(p) = sum over triangles T of e of sign(orient(v0, v1, p, w_T)),
// with orient(a, b, c, d) = det(b - a, c - a, d - a). M_e is the signed multiplicity of the edge seen from p: 0 for
// an edge whose two faces lie on opposite sides of Pi (not a silhouette from anywhere on Pi), ±2 for a silhouette
// edge of a closed mesh, ±1 for a boundary edge, anything for a non-manifold one. No orientation of the mesh is
// used, so open, inconsistently wound and non-manifold casters are counted like closed ones (the multiplicity rule
// that Kim, Kim & Turk 2008 give for shadow volumes, per face instead of per light).
// "e crosses triangle (p, c, s)" is the segment-triangle test by orientations: orient(p, c, s, v0) and
// orient(p, c, s, v1) differ in sign, and orient(v0, v1, p, c), orient(v0, v1, c, s), orient(v0, v1, s, p) share
// it. Every orientation is linear in s, so per fragment it is four plane equations and per sample four 2-D dot
// products on the light plane (two of them, orient(v0, v1, c, s) and orient(p, c, s, v_i), vanish at s = c and
// have no constant term).
//
// Which edges draw a wedge (potential silhouettes). At a light point x on Pi(p, e), M_e(p) is, up to
// sign, sum_T sign(orient(v0, v1, x, w_T)): the facing of e's triangles seen from x. An edge whose triangles keep
// a facing over the whole light that sums to 0 can never change a count, and is skipped. The facing of one
// triangle is linear in x, so it is constant over the light when the light's outline corners (square) or its disk
// (centre ± radius times the in-plane part of the normal) lie strictly on one side of the triangle's plane. An edge
// is drawn in records of at most two triangles (a non-manifold edge's triangles are split over several records;
// the change is a sum over triangles, so splitting is exact).
//
// Where a wedge is drawn. A point p can only be changed by e when some segment from p to the light crosses e: p
// lies in R_e = {y + t (q - y) : y on the light, q on e, t >= 1}. R_e (up to where it leaves the scene's bounds)
// lies in the convex hull of e and of e's images from each outline corner L_i at the scale T = h_far / h_min, cut at
// the height h_far (h: height below the light plane; h_far: the deepest corner of the scene's box, h_min: the edge's
// shallowest end), since p = y + t (q - y) has height t h(q) <= h_far. The wedge is rasterised as that cut hull's
// screen projection (a convex polygon, cut at the camera's near plane, widened by 1.5 pixels, clipped to the
// viewport), so every pixel of R_e is covered exactly once; each fragment runs the exact per-sample rule above, so
// the hull only has to be conservative. A disk light's outline is the regular octagon around it.
#pragma once

#include "lightspace/CameraView.h"
#include "lightspace/LightSampleSet.h"
#include "scene/Scene.h"
#include "scene/WeldedMesh.h"

#include <glm/glm.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace sl
{

// One wedge: an edge of a welded caster with at most two of the triangles that use it.
struct DcsWedgeEdge
{
  std::size_t objectIndex = 0;         // Scene::objects index of its caster
  glm::dvec3 v0{ 0.0 };                // welded vertex positions (float values, held as double)
  glm::dvec3 v1{ 0.0 };
  int oppositeCount = 0;               // 1 or 2
  std::array<glm::dvec3, 2> opposite{}; // the third corner of each of its triangles
  std::uint32_t incidentTriangles = 0; // of the whole welded edge: 1 boundary, 2 manifold, > 2 non-manifold
  bool silhouetteFromCentre = false;   // its triangles' facings from the light's centre do not sum to 0
};

struct DcsEdgeStatistics
{
  std::size_t casterTriangles = 0;
  std::size_t edges = 0;                    // undirected welded edges
  std::size_t boundaryEdges = 0;
  std::size_t nonManifoldEdges = 0;
  std::size_t potentialSilhouetteEdges = 0; // welded edges with at least one wedge
  std::size_t centreSilhouetteEdges = 0;    // of those, silhouettes from the light's centre
  std::size_t wedges = 0;                   // records (a non-manifold edge may have several)
  std::size_t edgesAtLightPlane = 0;        // potential silhouettes that do not reach below the light plane: no wedge
};

struct DcsEdgeSet
{
  std::vector<DcsWedgeEdge> wedges;
  DcsEdgeStatistics statistics;
};

// Corners of a light's outline (lightOutline): the octagon around a disk.
constexpr int kDcsMaxOutlineCorners = 8;

// The light's outline: a square's 4 corners, or the 8 corners of the regular octagon around a disk, counter-clockwise
// seen from the scene. Any other light is a point: its centre alone.
std::vector<glm::dvec3> lightOutline(const Light& light);

// The wedges of every caster under `light` (an area light; other lights have no penumbra and get none).
DcsEdgeSet potentialSilhouetteWedges(const std::vector<WeldedMesh>& casters, const Light& light);

// The samples' positions of pixel `pixel` on `light` (world): the set's points on an area light, the centre for
// a point light.
std::vector<glm::dvec3> dcsSamplePoints(const Light& light, const LightSampleSet& samples, glm::ivec2 pixel);

// orient(a, b, c, d) = det(b - a, c - a, d - a): positive when d lies on the side of plane (a, b, c) that
// (b - a) x (c - a) points to.
double orient(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& d);

// M_e(p) of the rule above.
int wedgeMultiplicity(const DcsWedgeEdge& wedge, const glm::dvec3& p);

// The change wedge `wedge` makes to the count of sample `s` at the counting point p (centre c), by the rule above:
// sign(g(s)) M_e(p) when e crosses triangle (p, c, s), else 0.
int sampleCountChange(const DcsWedgeEdge& wedge, const glm::dvec3& p, const glm::dvec3& c, const glm::dvec3& s);

// Whether p lies in R_e for the light's outline polygon `outline` (the buffer wedges_covering counts these): the edge
// meets the pyramid with apex p over the outline (Cyrus-Beck clipping of e by the pyramid's side planes and the light
// plane, whose normal `lightNormal` points toward the scene).
bool wedgeContains(const DcsWedgeEdge& wedge, const glm::dvec3& p, const std::vector<glm::dvec3>& outline,
  const glm::dvec3& lightNormal);

// The wedge's screen polygon (normalised device coordinates, counter-clockwise, convex), see "Where a wedge is
// drawn"; empty when no part of it can hold a receiver in view.
std::vector<glm::dvec2> wedgeScreenPolygon(const DcsWedgeEdge& wedge, const Light& light,
  const std::vector<glm::dvec3>& outline, const CameraView& camera, bool perspective, const Bounds& sceneBounds);

// The screen polygon (normalised device coordinates, counter-clockwise, convex) of the convex hull of the clip-space
// points `clip` (clipFromWorld applied): with a perspective camera the hull's part in front of half the near plane's
// depth, widened by 1.5 pixels and clipped to just beyond the viewport; empty when nothing is left. Wedges and STSVs
// are rasterised as these.
std::vector<glm::dvec2> convexScreenPolygon(const std::vector<glm::dvec4>& clip, const CameraView& camera, bool perspective);

// The two outline corners whose planes through the edge support the light (the penumbra wedge's front and back planes,
// Akenine-Moller & Assarsson 2002), as indices into `outline`; {-1, -1} when the edge lies in the light's plane.
std::array<int, 2> wedgeSupportingCorners(const DcsWedgeEdge& wedge, const std::vector<glm::dvec3>& outline);

} // namespace sl
