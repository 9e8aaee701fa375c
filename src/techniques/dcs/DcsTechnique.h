// Technique `dcs`: depth complexity sampling (Forest, Barthe & Paulin 2008 = FBP08; the object-space half of paper
// Forest et al. 2009 §3.2) for opaque casters. For every visible point and every one of N light samples
// (the shared sets of lightspace/LightSampleSet.h, N = 16, 64 or 256), the number of caster surfaces the segment to
// the sample crosses; visibility is the fraction of samples with count 0 and above the receiver's tangent plane
// (Forest et al. 2009's v_coef, the reference's rule). Exact for its samples, so it is checked sample by sample against Embree.
//
// Per frame (vtkSLDcsPass.h): the reference sample's count from the centre's shadow volumes (the shadow-volume
// pass), then one wedge per potential silhouette edge updating the samples it separates from the centre (the rule of
// DcsGeometry.h), then a resolve. Square and disk area lights; a point light has all N samples at its centre, so it
// reduces to the shadow volume.
//
// Buffers: visibility_stderr, depth_complexity_center, occluded_samples, dc_min, dc_max (dc_min < 0 flags a topology
// error), wedges_covering, counter_status (range check, a cut-short mark), light_sample_mask (N/16 components of 16
// bits: bit i % 16 of component i / 16 set when sample i is hidden) and, with export_sample_counts = 1,
// sample_depth_complexity (N components). Statistics: the shadow volumes' and silhouette_edges_centre,
// potential_silhouette_edges, wedges, wedges_drawn, wedge_fragments, sample_buffer_bytes, paper_sample_buffer_bytes,
// volumes_gpu_ms, wedges_gpu_ms, resolve_gpu_ms, wedge_build_ms (CPU). Object-space exports: silhouettes.vtp and
// wedges.vtp. Light-space export: light_samples (the structure structures/lightsamples).
// Limits: alpha textures are not honoured (perforated casters are STSV's, a later issue).
#pragma once

#include "frame/FrameResult.h"
#include "frame/ProbeRecord.h"
#include "frame/TechniqueDescriptor.h"
#include "lightspace/LightSampleSet.h"
#include "objectspace/StsvGeometry.h"

#include <cstdint>
#include <vector>

namespace sl
{

// The bias of the 8-bit counters (shaders/dcs/DcsSampleCounters.glsl): a counter holds the change relative to the
// light's centre plus this.
constexpr int kDcsCounterBias = 128;

// The layers of the per-pixel light-sample counters (an R32UI 2-D array; shaders/dcs/DcsSampleCounters.glsl),
// declared once: the pass allocates, clears and reads them back with these, and its preamble defines them for the
// shaders (dcsCounterLayerShaderConstants: DCS_SAMPLE_COUNTER_LAYERS, DCS_CHECKSUM_LAYER, ..., DCS_COUNTER_LAYERS;
// DCS_COUNTERS_PER_LAYER, DCS_COUNTER_BITS and DCS_COUNTER_MASK are the descriptor's constants). Layers
// 0 .. sampleCounterLayers - 1 hold kCountersPerLayer counters of kCounterBits each (sample i in layer
// i / kCountersPerLayer, bits kCounterBits (i % kCountersPerLayer) ..); then the two checksums of the range check
// and the number of wedges that contain the pixel's point.
struct DcsCounterLayers
{
  static constexpr int kCountersPerLayer = 4;
  static constexpr int kCounterBits = 8;
  static constexpr int kCounterMask = (1 << kCounterBits) - 1;
  explicit DcsCounterLayers(int sampleCount)
    : sampleCounterLayers(sampleCount / kCountersPerLayer)
  {
  }
  int sampleCounterLayers;
  int checksum() const { return sampleCounterLayers; }
  int weightedChecksum() const { return sampleCounterLayers + 1; }
  int covering() const { return sampleCounterLayers + 2; }
  int total() const { return covering() + 1; }
  // A word whose every counter holds `value`.
  static std::uint32_t replicated(int value);
};
static_assert(DcsCounterLayers::kCountersPerLayer * DcsCounterLayers::kCounterBits == 32, "counters fill a 32-bit word");

// The layer indices of a frame with `sampleCount` light samples, for its shaders' preamble.
std::vector<ShaderConstant> dcsCounterLayerShaderConstants(int sampleCount);

// counter_status codes.
enum class DcsCounterStatus
{
  Exact = 0,
  RangeExceeded = 1
};

TechniqueDescriptor dcsTechnique();

// dcs's parameters, typed (parsed once, by from()).
struct DcsSettings
{
  double receiverOffset{};             // of the eye distance
  LightSampleSetSettings lightSamples; // light_samples, samples (N), sample_seed: the light-sample set's own
  bool exportSampleCounts{};           // publish sample_depth_complexity
  StsvOcclusionTest stsvTest{};        // stsv_opposite_side_check

  static DcsSettings from(const ParameterValues& values);
};

// The technique's probe: the centre's crossings, every wedge containing the pixel's point with its multiplicity and
// changes, each sample's count, and the resolve's visibility (DcsReference.h).
ProbeOutcome probeDcs(const FrameResult& frame, const Scene& scene, int lightIndex, glm::ivec2 pixel,
  ProbeRecorder& recorder);

} // namespace sl
