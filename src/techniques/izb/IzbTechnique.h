// Technique `izb`: exact hard shadows by an irregular z-buffer (Johnson, Mark & Burns 2004; Johnson, Lee, Burns &
// Mark 2005; Aila & Laine 2004, alias-free shadow maps; Sintorn, Eisemann & Assarsson 2008; survey §4.5). The
// G-buffer's visible samples are listed per light-space texel, then every caster triangle is tested against the
// samples of every texel it overlaps: no shadow-map resolution, so no aliasing and no bias. README.md here.
//
// Parameters: grid_size (texels per side of a light-space face), node_budget (list nodes), list_budget (samples one
// texel's list may hold), normal_offset (of the scene's bounding radius: the receiver point leaves its surface along
// its normal, as the ray tracer's origin does).
// Buffers: izb_list_length (samples in the pixel's light texel), izb_triangle_tests (triangles tested against the
// pixel's sample), izb_ambiguous (1: the decision lies within float rounding of a triangle edge or plane, or the
// sample's texel placement does), izb_status (no test / tested / cut short by a budget, a cut-short mark).
// Statistics (stats.json technique_statistics): izb_ambiguous_pixels, izb_cut_short_pixels, izb_shared_edge_pixels
// (decided by two triangles sharing the edge the sample lies within rounding of), izb_samples,
// izb_nodes, izb_pairs, izb_triangles, izb_occupied_texels, izb_max_list_length, izb_cover_ms.
// Lights: point, spot, directional, and an area light from its centre (as hard and pcf take it; the single ray to the
// centre is the reference, ReferenceModel::LightCentre).
#pragma once

#include "frame/FrameResult.h"
#include "frame/ProbeRecord.h"
#include "frame/TechniqueDescriptor.h"

namespace sl
{

TechniqueDescriptor izbTechnique();

// izb's parameters, typed (parsed once, by from()).
struct IzbSettings
{
  int gridSize = 256;
  int nodeBudget = 0;
  int listBudget = 0;
  double normalOffset = 0.0; // of the scene's bounding radius

  static IzbSettings from(const ParameterValues& values);
  // normal_offset in world units for `scene`.
  double offsetWorld(const Scene& scene) const { return normalOffset * scene.bounds().radius(); }
};

// The bits of a pixel's state (IzbCommon.glsl's izbPixels[].x), shared with the shaders as IZB_FLAG_*.
enum IzbFlag : unsigned
{
  IzbFlagTested = 1u,          // listed for testing (covered, receives shadows, reachable)
  IzbFlagShadow = 2u,          // some triangle covers it between it and the light (float decision)
  IzbFlagDefinite = 4u,        // ... beyond rounding
  IzbFlagUncertain = 8u,       // some triangle's decision within rounding
  IzbFlagCutShort = 16u,       // not listed: list or node budget exceeded
  IzbFlagAmbiguousPlacement = 32u, // the texel placement within rounding (IzbGrid::placementErrorTexels)
};

// izb_status codes.
enum class IzbStatus
{
  NoTest = 0,
  Tested = 1,
  CutShort = 2
};

// The technique's probe: the twin's test of the pixel's sample against every caster triangle whose cover holds its
// texel, each covering triangle recorded.
ProbeOutcome probeIzb(const FrameResult& frame, const Scene& scene, int lightIndex, glm::ivec2 pixel,
  ProbeRecorder& recorder);

} // namespace sl
