// The CPU side of technique `penumbra-wedge` (Akenine-Moller & Assarsson 2002, Assarsson & Akenine-Moller 2003 =
// AAM03, as Forest et al. 2009 §3.1 uses it), in double precision: what one penumbra wedge adds to a point's
// occlusion, and the twin of a whole pixel. penumbrawedge/shaders/PenumbraWedgeArea.glsl computes the same in float.
//
// The radial reading. The light's centre c has a hard-shadow status (the shadow volumes' count, technique
// `shadow-volume`). A light point s differs from c only if the segment c -> s on the light crosses the projection of
// some silhouette edge e from the point p, i.e. where e crosses the triangle (p, c, s): the rule of DcsGeometry.h,
// whose change there is sign(g(s)) M_e(p). The set of such s on the light is e's far region F_e(p): the light
// clipped by the plane of (v0, v1, p) on the side away from c, by the plane of (v0, v1, c) on p's side, and to the
// sector between the planes (p, c, v0) and (p, c, v1) -- four linear conditions on the light plane, so F_e(p) is a
// convex polygon (two, one per half of the double sector, of which one is empty) clipped from the light's square in
// closed form, with no projection to infinity of edge points level with p.
// AAM03's occlusion. Each wedge containing p moves the area of its far region from the centre's status to the other
// one:
//     occlusion_raw(p) = [count(c) > 0] + sum over centre-silhouette wedges of  sign(-sign(g(c)) M_e(p)) |F_e(p)| / |L|
//     visibility       = 1 - clamp(occlusion_raw, 0, 1)
// Exact for one convex occluder; where two occluders' projections overlap their areas are both counted (the
// over-shadowing of Forest et al. 2009 §3.1: occlusion_raw > 1, or a deficit in the overlap), and edges that are silhouettes
// from part of the light but not from its centre are ignored (the "single light sample" silhouette artifact). Samples
// below the receiver's tangent plane are not modelled (AAM03 has no receiver term), as the reference hides them.
// Square area lights only (the far region is clipped from the square's outline).
// Perforated casters (alpha textures) are not part of that: they go through soft textured shadow volumes (Forest et al. 2009 §3.1
// §3.1, objectspace/StsvGeometry.h). For every STSV holding p, the light samples its triangle hides (Eq. 1-5) are OR-ed
// into the pixel's light-sample mask (the LS_buffer), and its popcount's share of the N samples is added to the
// occlusion -- "we add this v_coef with the one computed during the penumbra-wedge pass" (§3.1), read as adding
// occlusions: occlusion_raw = AAM03's + popcount / N, so a perforated and an opaque occluder that overlap are both
// counted (Fig. 4 a).
#pragma once

#include "frame/ProbeRecord.h"
#include "scene/Scene.h"
#include "objectspace/DcsGeometry.h"
#include "objectspace/StsvGeometry.h"

#include <glm/glm.hpp>

#include <vector>

namespace sl
{

// One wedge at one point: its signed share of the light and the far region it moves.
struct PenumbraWedgeArea
{
  int multiplicity = 0;             // M_e(p) (DcsGeometry.h wedgeMultiplicity)
  int change = 0;                   // -sign(g(c)) M_e(p): the count change over the far region (0: none)
  double areaFraction = 0.0;        // |F_e(p)| / |L|, in [0, 1]
  double occlusionDelta = 0.0;      // sign(change) areaFraction: what AAM03 adds to the occlusion
  std::vector<glm::dvec2> farRegion; // light coordinates (right, up) from the centre; empty when none
};

// The far region F_e(p) of `wedge` at the point `p` under the square area light `light`, by the conditions above.
PenumbraWedgeArea penumbraWedgeArea(const DcsWedgeEdge& wedge, const glm::dvec3& p, const Light& light);

// The centre silhouettes of `wedges` (DcsWedgeEdge::silhouetteFromCentre): the wedges AAM03 draws.
std::vector<DcsWedgeEdge> centreSilhouetteWedges(const DcsEdgeSet& wedges);

// What the twin needs of a scene under one light, built once.
struct PenumbraWedgeScene
{
  std::vector<DcsWedgeEdge> wedges; // the opaque casters' centre silhouettes (perforated ones have STSVs instead)
  StsvSet stsvs;                    // the S-triangles (Forest et al. 2009 §2) and their STSVs
};
PenumbraWedgeScene penumbraWedgeScene(const Scene& scene, const Light& light);

struct PenumbraWedgePixel
{
  glm::dvec3 countedPoint{ 0.0 }; // the visible point moved receiver_offset toward the camera (as shadow-volume)
  int centreCount = 0;            // depth_complexity_center (opaque casters)
  int wedgesCovering = 0;         // centre-silhouette wedges whose region holds the point (wedgeContains)
  int stsvCovering = 0;           // STSVs holding the point (stsvContains)
  int stsvEmptyHits = 0;          // of those, the ones that hide none of its samples
  std::vector<bool> stsvHidden;   // per light sample: hidden by some S-triangle (the LS_buffer)
  int stsvOccludedSamples = 0;    // popcount of stsvHidden
  double occlusionRaw = 0.0;      // pw_occlusion_raw, before clamping: AAM03's plus popcount / N
  double visibility = 0.0;
};

// One pixel whose visible point is `pWs`; `samples` are its light samples (world points; may be empty without
// perforated casters). `recorder` (optional): the counted point, the centre's crossings, each covering wedge's far
// region (a light polygon) and share, each covering STSV and the samples it hides.
PenumbraWedgePixel penumbraWedgePixel(const PenumbraWedgeScene& prepared, const Scene& scene, const Light& light,
  const glm::dvec3& pWs, double receiverOffset, const std::vector<glm::dvec3>& samples,
  StsvOcclusionTest test = StsvOcclusionTest::PaperAndOppositeSides, ProbeRecorder* recorder = nullptr);

} // namespace sl
