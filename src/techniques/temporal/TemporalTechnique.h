// Technique `temporal`: hard shadow mapping with temporal reprojection and shadow-test confidence (Scherzer, Jeschke
// & Wimmer 2007, as the survey describes it in §4.6). The same static scene and camera are rendered for
// temporal_frames frames, each with the shadow map's viewport shifted by a sub-texel offset (a Halton (2, 3)
// sequence); a per-pixel history accumulates each frame's single depth comparison weighted by the survey's
// confidence conf = 1 - 2 max(|x - centre_x|, |y - centre_y|) raised to confidence_exponent, and is dropped where
// the reprojected depth differs from the current one (disocclusion). Page: README.md here.
//
// Parameters (besides the shadow map's and the bias, ShadowMapParameters.h): temporal_frames (K), confidence_exponent
// (m), confidence_threshold, disocclusion_threshold (relative view depth), resolve (mean|threshold), camera_step
// (world units per frame; 0: the static camera), export_frames (off|on).
// Buffers: history_visibility, confidence, history_frames, history_weight, history_depth, sample_visibility, sample_confidence,
// unconverged (flagged), depth_bias; with export_frames=on also sample_visibility_frames and
// sample_confidence_frames (K components, one per frame).
#pragma once

#include "frame/TechniqueDescriptor.h"
#include "techniques/ShadowMapReference.h"

#include <glm/glm.hpp>

#include <vector>

namespace sl
{

TechniqueDescriptor temporalTechnique();

struct TemporalSettings
{
  int frames = 16;                     // temporal_frames, K
  double confidenceExponent = 1.0;     // confidence_exponent, m: a frame's weight is conf^m
  double confidenceThreshold = 0.5;    // confidence_threshold: below it after K frames a pixel is flagged
  double disocclusionThreshold = 0.01; // disocclusion_threshold: |history depth - reprojected depth| / depth
  bool exportFrames = false;           // export_frames
  bool resolveByThreshold = false;     // resolve = threshold: visibility is the history's mean rounded to 0 or 1
  double cameraStep = 0.0;             // camera_step: world units the camera moves sideways per frame
  BiasSettings bias;

  static TemporalSettings from(const ParameterValues& values);
};

// The shadow map's viewport offset of frame k, in texels, each component in [-1/2, 1/2): the Halton points of bases
// 2 and 3 (index k, so frame 0 is unshifted and K = 1 is `hard`), wrapped by a whole texel.
glm::dvec2 temporalJitterOffset(int frame);
// `base` with its window shifted so that every world point's shadow-map position moves by `offsetTexels` (a
// translation of clip x, y by 2 offset / N, applied after any warp).
LightView jitteredLightView(const LightView& base, const glm::dvec2& offsetTexels);

// The camera of frame k of `frames` when it moves `step` world units per frame along its right vector: frame K - 1 is
// `camera` itself (so the frame's buffers are the scene camera's), frame k lies (K - 1 - k) steps to its left.
CameraView temporalFrameCamera(const Scene& scene, glm::ivec2 resolution, double step, int frame, int frames);

// Survey §4.6: the confidence of a shadow-map lookup at `uvTexels` (texels, texel (i, j) spans [i, i+1) x [j, j+1)):
// 1 at the texel's centre, 0 on its border.
double shadowTestConfidence(const glm::dvec2& uvTexels);

// One pixel's history (the buffers of the same names).
struct TemporalHistory
{
  double visibility = 0.0; // confidence-weighted mean of the frames' shadow tests
  double weight = 0.0;     // history_weight: the sum of the frames' weights conf^m
  double frames = 0.0;     // history_frames
  double confidence = 0.0; // the highest confidence among the frames held
  double depth = 0.0;      // history_depth: view depth of the surface the history belongs to
};

// One frame's shadow test at the pixel.
struct TemporalSample
{
  double visibility = 0.0;
  double confidence = 0.0;
  double depth = 0.0;          // the pixel's view depth in this frame
  double reprojectedDepth = 0.0; // the surface's view depth in the history's camera (static camera: depth)
};

// The history update of frame `sample`: the history is dropped when it holds frames and its depth differs from the
// sample's reprojected depth by more than disocclusionThreshold x that depth (`rejected` then true); then
// W' = W + w, v' = (W v + w s) / W' with w = conf^m (v' = s when W' = 0), frames + 1, the highest confidence.
// GLSL twin: temporal/shaders/TemporalVisibility.glsl.
TemporalHistory updateTemporalHistory(
  const TemporalHistory& history, const TemporalSample& sample, const TemporalSettings& settings, bool* rejected = nullptr);
// The pixel's visibility from its history: the mean, or with resolve = threshold 1 where the mean is >= 1/2, else 0.
double resolvedVisibility(const TemporalHistory& history, const TemporalSettings& settings);

// CPU reference of the last frame at pixel (x, y): the single depth comparison of `hard` on the map and light view
// `inputs` hold (the last frame's, as the frame exports them), with the sample's confidence.
struct TemporalFrameSample
{
  ReferenceSample sample;
  double confidence = 0.0;
};
TemporalFrameSample temporalFrameReference(const ShadowMapInputs& inputs, const BiasSettings& bias, int x, int y,
  ProbeRecorder* recorder = nullptr);

} // namespace sl
