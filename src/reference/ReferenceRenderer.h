// The ray-traced ground truth: per pixel, the fraction of the light visible from the surface point, with
// Embree (reference/EmbreeScene.h). Its conventions are the GPU pipeline's, so the two agree pixel for
// pixel wherever the techniques are exact:
//
//  - Inputs are per-pixel images of the camera's G-buffer (same size, row 0 = bottom): position (world,
//    components 0..2), normal (world, unit, components 0..2; RGBA G-buffer images can be passed as they
//    are), coverage (component 0, > 0.5 where a surface covers the pixel) and receives (component 0,
//    > 0.5 where that surface receives shadows).
//  - Uncovered pixel: visibility 0. Covered pixel whose surface does not receive shadows: visibility 1.
//    Otherwise, where !lightCanReach(light, p, n) (lightspace/LightView.h: the surface faces away from
//    the light's centre, lies behind a one-sided area light's plane, or outside a spot cone): 0. The
//    standard error is 0 in all these cases.
//  - Area light: the fraction of the light's AREA visible from p, unweighted (not cosine weighted):
//        visibility = (1/N) sum_s V(p, s)
//    over N points s on the light (reference/LightSampler.h: stratified or Halton, square or disk), where
//    V(p, s) = 0 if s is on or below p's tangent plane (dot(n, s - p) <= 0: the surface itself hides it)
//    or if a caster blocks the segment from the ray origin o to s, shortened by a relative 1e-6 at the
//    light's end (t in (0, 1 - 1e-6) along s - o, so the light's own plane never occludes); else 1.
//  - Shared light-sample set (ReferenceSettings::lightSampleSet, area lights only): the N points s_i of pixel
//    (x, y) are exactly LightSampleSet::point(light, x, y, i), i < N (lightspace/LightSampleSet.h), the points the
//    technique `dcs` takes, so the two can be compared sample by sample; `samples`, `sampling` and `seed` are
//    then unused (the set has its own seed).
//    V(p, s_i) is decided as above, but by counting rather than by an occlusion ray: for every covered pixel
//    and every sample, hidden or not,
//        crossings_i = EmbreeScene::crossings(o, s_i - o, 0, 1 - 1e-6)
//    (caster triangles crossed, holes excluded: the depth complexity that depth complexity sampling counts,
//    Forest et al. 2009 §3.2), and sample i is hidden when dot(n, s_i - p) <= 0 or crossings_i > 0. The result then
//    also holds sampleCrossings (crossings_i in component i) and lightSampleMask (see ReferenceResult).
//    visibility = (1/N) #(samples not hidden); standard error as below. The pixel rules above still decide
//    the visibility of uncovered, non-receiving and unreachable pixels; the two per-sample arrays are facts
//    about the samples, computed at every covered pixel whatever its visibility (0 at uncovered pixels,
//    where there is no point).
//  - Point and spot lights: one ray from o to the light's centre (same shortening); directional: one ray
//    from o along -direction, to infinity. Visibility is exactly 0 or 1 and the standard error 0.
//  - Ray origin: o = p + rayOffset * n, with rayOffset = 1e-4 * scene.bounds().radius() (the bounding
//    sphere of all objects) unless ReferenceSettings::rayOffset >= 0 sets it. The offset only lifts the
//    origin off the receiver's own triangles; the tangent-plane test above uses p itself.
//  - Standard error of an area-light estimate v from N samples: sqrt(v (1 - v) / (N - 1)), the i.i.d.
//    Bernoulli estimate. Stratification (and the Halton pattern) make the true error smaller, so it is a
//    conservative bound: penumbra errors shrink roughly like N^-3/4 rather than N^-1/2. With N = 1 nothing
//    can be estimated, and 0.5 (the largest standard deviation of a 0/1 variable) is reported.
//  - Casters: every object with castShadows, two-sided, perforated ones with holes where alpha < 0.5
//    (shaders/common/AlphaMask.glsl's rule). Receivers need not be in the scene at all.
//  - Determinism: a pixel's samples depend only on (seed, x, y, sample index), so the images are identical
//    for any thread count and any scheduling.
//
// Rows are shared among std::thread workers (threads = 0: std::thread::hardware_concurrency()). The
// progress callback is called on the calling thread, at most about 33 times, with the fraction of rows
// done; it may throw to cancel (the workers are stopped and joined, then the exception propagates).
#pragma once

#include "core/Image.h"
#include "lightspace/LightSampleSet.h"
#include "reference/LightSampler.h"
#include "scene/Scene.h"

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

namespace sl
{

struct ReferenceSettings
{
  int samples = 1024;                                // light samples per pixel (area lights), >= 1
  LightSampling sampling = LightSampling::Stratified;
  std::uint64_t seed = 1;
  int threads = 0;                                   // 0 = all cores
  double rayOffset = -1.0;                           // < 0: 1e-4 * scene bounding-sphere radius
  // The shared per-pixel sample set instead of `samples`/`sampling`/`seed` (area lights only; see above).
  std::optional<LightSampleSetSettings> lightSampleSet;
  // Only rows [rowBegin, rowEnd) are traced (rowEnd < 0: to the last row); the others stay 0. A pixel's samples
  // depend on (seed, x, y, index) only (LightSampler.h), so a reference traced in row tiles and merged
  // (reference --tile / --merge-tiles) equals the single-process one bit for bit.
  int rowBegin = 0;
  int rowEnd = -1;
};

struct ReferenceInputs
{
  const Scene* scene = nullptr;
  const Light* light = nullptr;
  ImageF position; // >= 3 components: pWs
  ImageF normal;   // >= 3 components: nWs
  ImageF coverage; // >= 1 component
  ImageF receives; // >= 1 component
};

struct FrameResult; // frame/FrameResult.h

// The receivers of a rendered frame (its G-buffer: position, normal, coverage, receives_shadows) under the scene's
// light `lightIndex` (checked: throws InputError naming --light when the scene has no such light).
ReferenceInputs referenceInputsOf(const FrameResult& frame, const Scene& scene, int lightIndex);

struct ReferenceResult
{
  ImageF visibility;     // 1 component, in [0, 1]
  ImageF standardError;  // 1 component
  // Only with a light-sample set (else empty), N = its count:
  ImageF sampleCrossings; // N components: caster triangles crossed on the way to sample i (0 where uncovered)
  // N / 16 components: bit i % 16 of component i / 16 set when sample i is hidden (below the tangent plane or
  // crossed), the 16-bit integer held exactly as a float (0 .. 65535); 0 where uncovered. Where no pixel rule
  // decides, visibility = 1 - popcount / N.
  ImageF lightSampleMask;
  std::uint64_t raysTraced = 0; // rays actually cast: occlusion rays (samples below the horizon cost none), or
                                // with a light-sample set one crossing-count ray per sample of a covered pixel
  double seconds = 0.0;         // wall time of the whole call: BVH build + tracing
  double raysPerSecond = 0.0;   // raysTraced / wall time of the tracing alone (BVH build excluded)
};

// Throws InputError for bad settings ("--samples 0: must be >= 1", "--threads -2: must be >= 0",
// non-finite rayOffset, a light-sample set with a light that is not an area light) and GraphicsError for
// Embree failures. Inputs of mismatched size are a bug
// (SL_CHECK).
ReferenceResult renderReference(const ReferenceInputs& inputs, const ReferenceSettings& settings,
  const std::function<void(double fractionDone)>& progress = {});

// Multisample mode (the like-for-like reference of multisampled frames, Schwarz and Stamminger 2008 §7): one set of
// inputs per sample, the G-buffer seen through that sample's position (ShadowRenderer::renderSampleGBuffers), each
// traced as renderReference does; then per pixel
//     visibility = the mean over the samples whose surface is covered, where sample 0's is; else 0
// (the multisampled frame's rule: its coverage is sample 0's), standard error sqrt(sum of the covered samples'
// squared errors) / their count, raysTraced summed, seconds the whole call. Light-sample sets are per-sample facts
// and cannot be averaged: an InputError names --light-samples.
ReferenceResult renderMultisampleReference(const std::vector<ReferenceInputs>& perSample,
  const ReferenceSettings& settings, const std::function<void(double fractionDone)>& progress = {});

// The ray offset renderReference uses for `scene` under `settings` (see above).
double referenceRayOffset(const Scene& scene, const ReferenceSettings& settings);

} // namespace sl
