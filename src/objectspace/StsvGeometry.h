// The CPU core of soft textured shadow volumes (Forest, Barthe, Guennebaud & Paulin 2009 = Forest et al. 2009, "STSV"), in
// double precision and written as the twin the GLSL will follow line by line: per perforated triangle ("S-triangle",
// Forest et al. 2009 §2) the matrices of Eq. 1-5 and the per-sample transmittance test (§2.4, Appendix A
// Appendix A), and the volume (§2.2, §4.2, Fig. 6) with its point-in-volume test (§2.3).
// tests/unit/StsvTest.cpp checks all of it against ray/triangle intersection, closed forms and brute force.
//
// Eq. 1-5 as reconstructed (the equations are hard to read in the text) and as decided by the tests:
//   Eq. 2, per triangle:  M = [ v1 - v0 | v2 - v0 | -n ]^-1   (3 x 3, columns; n the unit normal (v1-v0)x(v2-v0))
//   Eq. 3, per point p:   (a, b, e) = M (v0 - p);   W = [ 1 0 -a/e ]
//                                                       [ 0 1 -b/e ]
//                                                       [ 0 0  1/e ]
//   Eq. 1:                s*_h = J (s - p),  J = W M    (the input is the sample RELATIVE TO p, world units)
//   occluded by t iff     s*_h.x >= 0, s*_h.y >= 0, s*_h.z >= s*_h.x + s*_h.y         (the paper's test, §2.4)
//                     and s*_h.z > 1                                (ShadowLab's added check, see "The gap" below)
//                     and the texel at s is opaque:
//   Eq. 4, per triangle:  S = [ t1.x-t0.x  t2.x-t0.x  t0.x ]
//                             [ t1.y-t0.y  t2.y-t0.y  t0.y ]
//                             [ 0          0          1    ],   s_h = S s*_h
//   Eq. 5:                s = s_h.xy / s_h.z,   hole iff alphaHoleAt(alpha, s) (nearest texel, repeat, alpha < 0.5)
// Why: write d = s - p and (d_u, d_v, d_h) = M d, i.e. d = d_u e1 + d_v e2 - d_h n. The line p + lambda d meets the
// plane at lambda = e / d_h (e = n.(p - v0) is the SIGNED distance of p, which is exactly M(v0 - p).z), where its
// barycentrics are u = -a + lambda d_u, v = -b + lambda d_v (u weights v1, v weights v2, as in RayTriangle.h).
// Multiplied by d_h / e: (d_u - (a/e) d_h, d_v - (b/e) d_h, d_h / e) = W M d, so u = x/z, v = y/z and
// z = d_h / e = 1 / lambda. The last entry of W is therefore 1/e; the paper prints "1" (§2.4, Eq. 2), which equals 1/e
// only for e = 1. StsvEq1.HomogeneousBarycentricsEqualRayTriangleAndDecideW measures the readings over 10^5 cases
// against Moller-Trumbore: 1/e agrees to 7.1e-13 (lines at least 0.6 degrees off the plane; closer to grazing both
// methods lose ~1e-16/sin) with no wrong decision; "1" is off by up to 9.2e5 with 33 % of decisions wrong, an unsigned
// e ("orthogonal distance", §2.4) by 5.3e2 (18 % wrong, every p on the -n side), J applied to s itself instead of
// s - p by 2.2e5 (35 % wrong). The sign and length of n do not matter: flipping or scaling n scales d_h and e alike.
// Appendix A's DP3-only code (no translation term) also says the input is s - p.
//
// The gap in the paper's test (§2.4). z >= x + y >= 0 gives lambda > 0 but not lambda < 1: a sample on
// p's side of the plane whose line from p, continued past s, meets t passes as occluded. s and p lie on opposite
// sides iff lambda < 1 iff z > 1 (for either sign of e), the added check. Where it matters (proved, and measured in
// StsvTest): for p strictly inside an STSV's outer planes, no sample of that STSV's light piece can lie between p and
// t (each outer plane has the piece on its negative side and t on its non-negative side, so every point of [p, q], q
// on t, is positive when p is), so inside the volume the paper's test alone is already right for the STSV's own
// samples (0 false occlusions over 10^6 points). Receivers between the fence and the light are NOT affected: a
// sample there is farther from the plane than p, the line meets the plane behind p (z < 0) and the paper's test
// rejects it (a plate 0.02 above the `fence` dataset: 0). The check matters for a point farther from t's plane than
// a sample of its own side whose line meets t beyond the sample: beyond the light, or beside a fence that reaches
// above the light; there Eq. 1 without the check, evaluated without the volume test, hides samples falsely, and so
// does an STSV of the other side that evaluates all N samples when the light straddles t's plane (a fence cutting
// the light's square: 33 174 false of 384 000 pairs). stsvOcclusion evaluates only the STSV's own side's samples and
// keeps the check.
//
// The volume (§2.2). For each side of t's plane that holds part of the light (the whole light's outline, or both
// pieces of it when the plane cuts it, Forest et al. 2009 §6), with c the light's centre (of that piece when cut):
//  1. front cap t': the vertex of t closest to c stays, the other two move towards c to the same distance (AAM03's
//     robust construction, §2.2);
//  2. one outer plane per edge of t': the plane through the edge tangent to the light piece "on the outside" (§2.2-
//     209), i.e. with every corner of the piece on its negative side and t' on its positive side. In the section
//     across the edge it is the tangent through the corner whose direction is closest to t' (largest cosine);
//  3. the edge between two adjacent outer planes: direction m_prev x m_next (§2.2), oriented away from the
//     cone's apex (the sign of det(m_prev, m_next, m_opposite), the same for all three);
//  4. back cap: the three cap vertices moved along those directions to the level of the scene box along the front
//     cap's normal (§2.2, "clamp the extrusion at the level of the scene bounding box", §4.2), so the back
//     cap lies beyond every scene point; an extrusion that would need to go further than kStsvMaxExtrusion box
//     diagonals is cut there and the STSV says so (closedVolumeTruncated), as it does when two outer planes
//     coincide (t cuts through the light itself: the region is unbounded along t's plane).
//     closedVolumeTruncated means: the four planes are still right, the 8-triangle closed mesh may miss part of the
//     scene box, so a pass must not rely on rasterising it alone for such a volume (a full-screen or box pass can).
// Why t' lies towards c: with f any outer plane, f(c) <= 0 and f(v') >= 0 for a moved vertex v' = c + (v - c)/r,
// r >= 1, so f(v) = (1 - r) f(c) + r f(v') >= 0: t lies inside every outer plane, and by convexity so does every
// point p = s + lambda (q - s), lambda >= 1, of t's shadow from any light point s (the conservativeness the tests
// check over 10^6 points). The same argument makes the front cap plane conservative only when the light piece lies
// on c's side of t' 's plane; a large light close to a large triangle can cross it (then t' cuts off part of the
// shadow: 66 blocked (point, sample) pairs of 2 million in StsvVolume.ConservativeOverAMillionRandomPoints lie on the
// light's side of such a t'). ShadowLab then uses t itself as the front cap (frontCapIsTriangle): t's plane always has
// the piece on its near side. The paper does not discuss this case.
//
// Point in STSV (C4, Forest et al. 2009 §2.3 "on the same side of the four STSV planes"): the three outer planes and the front
// cap plane. Those four bound the volume the GPU rasterises; the back cap is left out because it lies beyond the
// scene box (no receiver is behind it). The triangle's own plane would be tighter (the slab between t' and t holds
// no point this side's samples can be blocked for), and trianglePlane is given for that: over the 10^6 random points,
// 40 % of the (point, STSV) inclusions block no sample with the front cap, 23 % with t's plane.
//
// Fig. 6's strip. Vertices 0, 1, 2 are the front cap, 3, 4, 5 the back cap (3 extruded from 0, ...); the strip
// 3 4 5 2 3 0 4 1 2 0 (§4.2) draws the back cap, the three outer quads and the front cap (8 triangles) with
// a coherent winding: frontCap is stored in the order that makes every strip triangle face outwards
// (counter-clockwise seen from outside, GL's strip rule: odd triangles swap their first two vertices).
#pragma once

#include "core/Image.h"
#include "scene/Scene.h"

#include <glm/glm.hpp>

#include <array>
#include <cstddef>
#include <vector>

namespace sl
{

// One perforated triangle with its per-triangle matrices (constant per S-triangle, Forest et al. 2009 §2.4, §4.2).
struct StsvTriangle
{
  std::size_t objectIndex = 0;   // Scene::objects index
  std::size_t triangleIndex = 0; // within the object's mesh
  std::array<glm::dvec3, 3> vertices{};  // v0, v1, v2, world
  std::array<glm::dvec2, 3> texCoords{}; // t0, t1, t2
  glm::dvec3 normal{ 0.0 };              // unit, (v1 - v0) x (v2 - v0) normalised
  glm::dmat3 triangleFromWorld{ 1.0 };   // M of Eq. 2 (acts on differences of world points)
  glm::dmat3 textureFromBarycentric{ 1.0 }; // S of Eq. 4
};

// The triangle (v0, v1, v2) with texture coordinates (t0, t1, t2). SL_CHECKs a finite, non-degenerate triangle
// (the scene loader drops degenerate ones).
StsvTriangle makeStsvTriangle(const glm::dvec3& v0, const glm::dvec3& v1, const glm::dvec3& v2, const glm::dvec2& t0,
  const glm::dvec2& t1, const glm::dvec2& t2);

// Every perforated triangle of `scene`: the triangles of objects that cast shadows and have an alpha texture
// (C1, Alg. 2 L5-6), positions (float in the scene) and texture coordinates as double.
std::vector<StsvTriangle> perforatedTriangles(const Scene& scene);

// The per-point part of Eq. 1 (Eq. 3): computed once per visible point p, whatever the number of samples.
struct StsvPointTransform
{
  glm::dvec3 planeOffset{ 0.0 };          // (a, b, e) = M (v0 - p); e = n . (p - v0), signed
  glm::dmat3 projection{ 1.0 };           // W
  glm::dmat3 barycentricFromSample{ 1.0 }; // J = W M, applied to s - p
  bool onPlane = false;                   // |e| <= the skip distance: t is not tested for p (never divides by e)
};

// The relative skip distance: p within kStsvOnPlaneRelative x (longest edge of t) of t's plane is taken to lie on
// t and is not shadowed by it (a fence pixel and its own triangle: a G-buffer position is float, ~6e-8 relative
// off the plane, and the line from p would meet the plane at p's own, opaque, texel).
constexpr double kStsvOnPlaneRelative = 1e-6;
// kStsvOnPlaneRelative times t's longest edge, world units.
double stsvOnPlaneDistance(const StsvTriangle& triangle);

// W and J for p. `onPlaneDistance` (world units, >= 0): see kStsvOnPlaneRelative; with onPlane set, W and J are
// left the identity.
StsvPointTransform stsvPointTransform(const StsvTriangle& triangle, const glm::dvec3& p, double onPlaneDistance);

// Which occlusion test a sample goes through.
enum class StsvOcclusionTest
{
  Paper,                  // x >= 0, y >= 0, z >= x + y only (Forest et al. 2009 §2.4, Appendix A): has the gap
  PaperAndOppositeSides,  // and z > 1: the sample and p on opposite sides of t's plane (ShadowLab's default)
};

// Everything Eq. 1-5 compute for one sample, for tests and probes.
struct StsvSampleEvaluation
{
  glm::dvec3 homogeneousBarycentric{ 0.0 }; // s*_h = J (s - p)
  bool insideTriangle = false;   // the paper's test
  bool oppositeSides = false;    // z > 1
  glm::dvec2 texCoord{ 0.0 };    // Eq. 5 (only when the tests passed, else 0)
  bool hole = false;             // alphaHoleAt(texCoord)
  bool occluded = false;         // the decision under the chosen test
};

StsvSampleEvaluation evaluateStsvSample(const StsvTriangle& triangle, const StsvPointTransform& transform,
  const ImageF& alpha, const glm::dvec3& p, const glm::dvec3& sample, StsvOcclusionTest test);

// For p and N light samples (world points), which samples triangle t hides from p (its alpha texture decides per
// sample): bit i set when sample i is occluded. Eq. 1 for every sample, no volume test. All bits clear when p lies
// on t (stsvOnPlaneDistance).
std::vector<bool> perforatedTriangleOcclusion(const StsvTriangle& triangle, const ImageF& alpha, const glm::dvec3& p,
  const std::vector<glm::dvec3>& samples, StsvOcclusionTest test = StsvOcclusionTest::PaperAndOppositeSides);

// +1 when `point` lies on the n side of t's plane, -1 on the other, 0 on it (exactly).
int triangleSideOf(const StsvTriangle& triangle, const glm::dvec3& point);

// A plane as (unit normal, offset): signed distance of x = dot(normal, x) + offset, positive inside the volume.
struct StsvPlane
{
  glm::dvec3 normal{ 0.0 };
  double offset = 0.0;
  double distance(const glm::dvec3& x) const { return glm::dot(normal, x) + offset; }
};

// One soft textured shadow volume: of triangle t, for the part of the light on one side of t's plane.
struct Stsv
{
  int lightSide = 0;                       // +1: this light piece is on the n side of t's plane; -1: the other
  bool lightStraddlesPlane = false;        // t's plane cuts the light: this is one of two STSVs
  std::vector<glm::dvec3> lightPiece;      // the corners of the light's outline on that side (clipped when cut)
  glm::dvec3 lightPieceCentre{ 0.0 };      // c: the light's centre, or the piece's corner mean when cut
  bool frontCapIsTriangle = false;         // the paper's t' would not be conservative: t itself is the front cap
  std::array<int, 3> frontCapVertexOfTriangle{ 0, 1, 2 }; // which vertex of t each front cap vertex comes from
  std::array<glm::dvec3, 3> frontCap{};    // t' (Fig. 6 vertices 0, 1, 2), in outward strip order
  std::array<glm::dvec3, 3> extrusion{};   // unit extrusion direction of each front cap vertex
  std::array<double, 3> extrusionLength{}; // world units
  std::array<glm::dvec3, 3> backCap{};     // Fig. 6 vertices 3, 4, 5: frontCap[i] + length[i] extrusion[i]
  std::array<StsvPlane, 3> outerPlanes{};  // plane i through front cap edge (i, i + 1), inside positive
  std::array<int, 3> outerPlaneCorner{};   // the lightPiece corner each outer plane is tangent at
  StsvPlane frontCapPlane;                 // inside (away from the light) positive
  StsvPlane trianglePlane;                 // t's plane, positive away from this light piece
  StsvPlane backCapPlane;                  // inside (towards the light) positive
  bool closedVolumeTruncated = false;      // the closed mesh may miss part of the box inside the four planes (see 4.)
};

// An extrusion is cut at this many times (scene box diagonal + distance from its front cap vertex to the box's
// centre), keeping every vertex at float-friendly magnitudes (the reason for the paper's clamp, §4.2).
constexpr double kStsvMaxExtrusion = 64.0;

// The STSVs of `triangle` under `light`: none when the light lies in t's plane, one when it lies on one side, two
// when t's plane cuts it (the paper's fix of the single light sample artifact, Forest et al. 2009 §6). The light's
// outline is lightOutline (DcsGeometry.h): a square's corners, the octagon around a disk (conservative), a point
// light's centre. `sceneBounds` (the receivers' box) places the back caps.
std::vector<Stsv> buildStsvs(const StsvTriangle& triangle, const Light& light, const Bounds& sceneBounds);

// C4: p inside the three outer planes and the front cap plane (boundary included).
bool stsvContains(const Stsv& stsv, const glm::dvec3& p);
// The closed volume: the same and the back cap plane.
bool stsvClosedVolumeContains(const Stsv& stsv, const glm::dvec3& p);

// The samples triangle t hides from p through this STSV, as a pass over the volume's fragments would find them:
// none unless stsvContains(p); otherwise Eq. 1-5 for each sample that lies on the STSV's light side (a sample of the
// other side belongs to the other STSV, so a DCS counter is incremented once per (p, s)), or for every sample when
// `onlyThisSide` is false (to show what the check guards against when the light straddles t's plane).
std::vector<bool> stsvOcclusion(const Stsv& stsv, const StsvTriangle& triangle, const ImageF& alpha,
  const glm::dvec3& p, const std::vector<glm::dvec3>& samples,
  StsvOcclusionTest test = StsvOcclusionTest::PaperAndOppositeSides, bool onlyThisSide = true);

// The perforated casters of a scene under one light, for the CPU twins: every S-triangle with its STSVs.
struct StsvSet
{
  std::vector<StsvTriangle> triangles;
  std::vector<std::vector<Stsv>> volumes; // per triangle
};
StsvSet buildStsvSet(const Scene& scene, const Light& light);

// What a pass over every STSV of `set` finds at the point p: per sample, how many STSVs holding p hide it (the
// counters STSV_DCS increments; > 0 is the LS_buffer's bit), the STSVs holding p, and those that hide nothing.
struct StsvPointOcclusion
{
  std::vector<int> hiddenBy;
  int covering = 0;
  int emptyHits = 0;
};
StsvPointOcclusion stsvPointOcclusion(const StsvSet& set, const Scene& scene, const glm::dvec3& p,
  const std::vector<glm::dvec3>& samples, StsvOcclusionTest test = StsvOcclusionTest::PaperAndOppositeSides);

// Fig. 6's 10-vertex strip (§4.2): indices into {frontCap[0..2], backCap[0..2]} = vertices 0..5.
constexpr std::array<int, 10> kStsvStripOrder{ 3, 4, 5, 2, 3, 0, 4, 1, 2, 0 };
// The strip's 10 positions.
std::array<glm::dvec3, 10> stsvStrip(const Stsv& stsv);

} // namespace sl
