// CPU twin of technique `dcs` for one pixel (double precision): the centre's count by direct crossing (as the shadow
// volumes give it), every light sample's count by the wedges' update rule (DcsGeometry.h), and the resolve's
// visibility. Tests compare it with the GPU; `shadowlab probe` records it.
#pragma once

#include "frame/ProbeRecord.h"
#include "lightspace/LightSampleSet.h"
#include "scene/Scene.h"
#include "objectspace/DcsGeometry.h"
#include "objectspace/StsvGeometry.h"

#include <glm/glm.hpp>

#include <vector>

namespace sl
{

struct DcsPixelTwin
{
  glm::dvec3 countedPoint{ 0.0 };  // the visible point moved receiver_offset toward the camera
  int centreCount = 0;             // depth_complexity_center
  std::vector<int> sampleCounts;   // per light sample: centreCount + the wedges' changes
  std::vector<bool> hidden;        // count > 0, or on or below the receiver's tangent plane
  int wedgesCovering = 0;          // wedges whose region R_e holds the counted point
  int occludedSamples = 0;         // samples with count > 0
  int dcMin = 0;
  int dcMax = 0;
  double visibility = 0.0;         // fraction of samples not hidden
};

// One pixel whose visible point is `pWs` with normal `nWs`. `wedges` are the opaque casters' (weldCasters(scene,
// true)): perforated ones go through STSVs (Forest et al. 2009 §3.2, STSV_DCS), each STSV holding the point adding 1 to
// the count of every sample its triangle hides (objectspace/StsvGeometry.h, under `test`). `recorder` (optional): the
// counted point, the centre's crossings, each wedge containing the point with its multiplicity and the samples it
// changes, the STSVs, every sample.
DcsPixelTwin dcsPixelTwin(const Scene& scene, const Light& light, const DcsEdgeSet& wedges,
  const LightSampleSet& samples, glm::ivec2 pixel, const glm::dvec3& pWs, const glm::dvec3& nWs,
  double receiverOffset, ProbeRecorder* recorder = nullptr,
  StsvOcclusionTest test = StsvOcclusionTest::PaperAndOppositeSides);

} // namespace sl
