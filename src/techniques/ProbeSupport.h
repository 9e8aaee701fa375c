// What the techniques' probe recorders (TechniqueDescriptor::probe, `shadowlab probe`) share: the twins' inputs
// rebuilt from a rendered frame, and the tests' ambiguity rule (tests/render/GpuCpuTest.cpp) as a sentence.
#pragma once

#include "frame/FrameResult.h"
#include "frame/ProbeRecord.h"
#include "frame/TechniqueDescriptor.h"
#include "techniques/ShadowMapReference.h"

#include <functional>
#include <string>
#include <vector>

namespace sl
{

// The read-back inputs a shadow-map twin needs (G-buffer, shadow map, light view) from a rendered frame; throws
// when the frame has no shadow map.
// `withWindowDepth` false leaves shadowMapWindow empty: one map-sized copy fewer for callers that only read the
// linear depths (the approximation rules run on every frame).
// With views that partition the pixels (FrameResult::partitions: cascades), `view` names the map: its light view and
// shadow_map_depth<suffix> (partitionViewSuffix: _c<k> for cascade k).
ShadowMapInputs shadowMapInputsOf(
  const FrameResult& frame, const Scene& scene, int lightIndex = 0, bool withWindowDepth = true, int view = -1);
// Every view's inputs (one element for a frame without partitions).
std::vector<ShadowMapInputs> viewInputsOf(
  const FrameResult& frame, const Scene& scene, int lightIndex = 0, bool withWindowDepth = true);
// A shadow-map twin evaluated as the multi-view loop does (survey §4.3): the pixel's selection (selectView, the CPU
// twin of the GPU's), `twin` on the primary view's inputs (with `recorder`) and, where the pixel blends, on the
// secondary's; visibility blended by the primary's weight, margins the smaller of the two. Without partitions, `twin`
// on the only inputs.
using ShadowMapTwin = std::function<ReferenceSample(const ShadowMapInputs&, int x, int y, ProbeRecorder*)>;
ReferenceSample partitionedReference(const FrameResult& frame, const std::vector<ShadowMapInputs>& inputs, int x,
  int y, const ShadowMapTwin& twin, ProbeRecorder* recorder = nullptr);

// The tests' float-rounding thresholds (GpuCpuTest.cpp): a depth comparison within 2e-6 (relative), a tap within
// 1e-4 texel of a texel edge, a light-reach cosine under 1e-5.
inline constexpr double probeDepthAmbiguity = 2e-6;
inline constexpr double probeTexelEdgeAmbiguity = 1e-4;
inline constexpr double probeReachAmbiguity = 1e-5;
// "" when no decision of `sample` is within those thresholds of its boundary, else which ones and how close.
std::string ambiguityOf(const ReferenceSample& sample);
// Appends "<what> <margin>" to `ambiguity` (comma-separated) when margin < threshold; for the techniques' own
// margins (kernel edges, HSM decisions, ...).
void noteAmbiguity(std::string& ambiguity, const char* what, double margin, double threshold);

// The outcome of a twin that returns a ReferenceSample: evaluated, visibility, ambiguity; `tolerance` and `twin`
// as given.
ProbeOutcome probeOutcome(const ReferenceSample& sample, double tolerance, std::string twin);

// The frame's value of a buffer at a pixel (component 0), throws when the frame has no buffer of that name.
double bufferValue(const FrameResult& frame, const std::string& buffer, glm::ivec2 pixel);
// Components 0..2 of a buffer at a pixel (the G-buffer's position and normal), same check.
glm::dvec3 bufferVector(const FrameResult& frame, const std::string& buffer, glm::ivec2 pixel);

// For recorders that read the G-buffer themselves: a pixel whose receives_shadows buffer says no is lit without a
// shadow test. Then sets outcome.visibility = 1, records the category in the current group and returns true;
// false for a shadow receiver.
bool litWithoutShadowTest(const FrameResult& frame, glm::ivec2 pixel, ProbeRecorder& recorder, ProbeOutcome& outcome);

// Throws InputError for sublights = S > 1: a frame keeps one light-space export, so a replay of S x S sub-light
// shadow maps has nothing to read.
void requireSingleSubLight(const FrameResult& frame);

} // namespace sl
