// Technique `penumbra-wedge`: soft shadows by penumbra wedges (Akenine-Moller & Assarsson 2002, Assarsson &
// Akenine-Moller 2003 = AAM03), the opaque half of Forest et al. 2009's PWedge+STSV (§3.1). The hard
// shadow of the light's centre (shadow volumes), then one wedge per silhouette edge from the centre, whose pixels add
// the signed fraction of the light that the edge's projection moves across the centre's status
// (PenumbraWedgeGeometry.h). Exact for one convex occluder; overlapping silhouettes are counted twice and
// silhouettes from the rest of the light are missed, AAM03's known limitations, measured rather than fixed. Square
// area lights.
//
// Buffers: pw_occlusion_raw (the occlusion before clamping: > 1 or < 0 mark the overlap artifact),
// depth_complexity_center, wedges_covering. Statistics: the shadow volumes' and silhouette_edges_centre,
// potential_silhouette_edges, wedges, wedges_drawn, wedge_fragments, wedge_build_ms (CPU), volumes_gpu_ms,
// wedges_gpu_ms, resolve_gpu_ms. Object-space exports: silhouettes.vtp, wedges.vtp.
// Perforated casters (alpha textures) are left out of the volumes and wedges and go through soft textured shadow volumes
// (Forest et al. 2009 §2, §3.1): per STSV holding the point, the samples of the shared light-sample set its triangle
// hides (Eq. 1-5) are OR-ed into the pixel's mask, and their share is added to the occlusion. More buffers:
// stsv_covering, stsv_empty_hits, stsv_occluded_samples, light_sample_mask; export stsv.vtp.
#pragma once

#include "frame/FrameResult.h"
#include "frame/ProbeRecord.h"
#include "frame/TechniqueDescriptor.h"
#include "lightspace/LightSampleSet.h"
#include "objectspace/StsvGeometry.h"

namespace sl
{

TechniqueDescriptor penumbraWedgeTechnique();

// penumbra-wedge's parameters, typed (parsed once, by from()).
struct PenumbraWedgeSettings
{
  double receiverOffset{};             // of the eye distance
  LightSampleSetSettings lightSamples; // the perforated casters' LS_buffer samples (the light-sample set's own)
  StsvOcclusionTest stsvTest{};        // stsv_opposite_side_check

  static PenumbraWedgeSettings from(const ParameterValues& values);
};

// The technique's probe: the centre's crossings, each covering wedge's far region and share, and the resolve
// (PenumbraWedgeGeometry.h penumbraWedgePixel).
ProbeOutcome probePenumbraWedge(const FrameResult& frame, const Scene& scene, int lightIndex, glm::ivec2 pixel,
  ProbeRecorder& recorder);

} // namespace sl
