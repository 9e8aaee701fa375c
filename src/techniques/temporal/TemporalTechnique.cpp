#include "techniques/temporal/TemporalTechnique.h"

#include "core/Error.h"
#include "frame/FrameResult.h"
#include "structures/shadowmap/ShadowMapStructure.h"
#include "techniques/ApproximationRules.h"
#include "techniques/ProbeSupport.h"
#include "techniques/ShadowMapParameters.h"
#include "techniques/temporal/vtkSLTemporalPass.h"

#include <algorithm>
#include <cmath>

namespace sl
{

TemporalSettings TemporalSettings::from(const ParameterValues& values)
{
  TemporalSettings settings;
  settings.frames = values.getInt("temporal_frames");
  settings.confidenceExponent = values.get("confidence_exponent");
  settings.confidenceThreshold = values.get("confidence_threshold");
  settings.disocclusionThreshold = values.get("disocclusion_threshold");
  settings.exportFrames = values.getInt("export_frames") == 1;
  settings.resolveByThreshold = values.getInt("resolve") == 1;
  settings.cameraStep = values.get("camera_step");
  settings.bias = biasSettings(values);
  return settings;
}

namespace
{

// The radical inverse of `index` in `base` (Halton 1964): 0.b0 b1 b2 ... of its digits.
double radicalInverse(int index, int base)
{
  double inverse = 0.0;
  double scale = 1.0 / base;
  for (int rest = index; rest > 0; rest /= base)
  {
    inverse += (rest % base) * scale;
    scale /= base;
  }
  return inverse;
}

// Into [-1/2, 1/2): a shift by a whole texel moves the grid onto itself, so the wrapped points sample the texel as
// the Halton points sample the unit square.
double wrapToCentredTexel(double value)
{
  return value >= 0.5 ? value - 1.0 : value;
}

} // namespace

glm::dvec2 temporalJitterOffset(int frame)
{
  SL_CHECK(frame >= 0);
  return { wrapToCentredTexel(radicalInverse(frame, 2)), wrapToCentredTexel(radicalInverse(frame, 3)) };
}

LightView jitteredLightView(const LightView& base, const glm::dvec2& offsetTexels)
{
  // uv = N (ndc / 2 + 1/2): a shift of uv by o is one of ndc by 2 o / N, i.e. clip x, y += (2 o / N) clip w.
  glm::dmat4 shift(1.0);
  shift[3][0] = 2.0 * offsetTexels.x / base.resolution;
  shift[3][1] = 2.0 * offsetTexels.y / base.resolution;
  LightView jittered = base;
  jittered.clipFromWorld = shift * base.clipFromWorld;
  return jittered;
}

CameraView temporalFrameCamera(const Scene& scene, glm::ivec2 resolution, double step, int frame, int frames)
{
  Camera camera = scene.camera;
  const glm::dvec3 right = glm::normalize(glm::cross(camera.focalPoint - camera.position, camera.viewUp));
  const glm::dvec3 shift = (static_cast<double>(frame) - static_cast<double>(frames - 1)) * step * right;
  camera.position += shift;
  camera.focalPoint += shift;
  return makeCameraView(camera, scene.bounds(), resolution, scene.objectBounds());
}

double shadowTestConfidence(const glm::dvec2& uvTexels)
{
  const glm::dvec2 fromCentre = glm::abs(uvTexels - glm::floor(uvTexels) - 0.5);
  return std::clamp(1.0 - 2.0 * std::max(fromCentre.x, fromCentre.y), 0.0, 1.0);
}

TemporalHistory updateTemporalHistory(
  const TemporalHistory& history, const TemporalSample& sample, const TemporalSettings& settings, bool* rejected)
{
  TemporalHistory kept = history;
  const bool disoccluded = history.frames > 0.0 &&
    std::abs(history.depth - sample.reprojectedDepth) > settings.disocclusionThreshold * std::abs(sample.reprojectedDepth);
  if (disoccluded)
  {
    kept = TemporalHistory{};
  }
  if (rejected)
  {
    *rejected = disoccluded;
  }
  // pow(0, 0) = 1: with m = 0 every frame weighs 1 (a plain mean), the texel border's included.
  const double weight = std::pow(std::clamp(sample.confidence, 0.0, 1.0), settings.confidenceExponent);
  TemporalHistory updated;
  updated.weight = kept.weight + weight;
  updated.visibility =
    updated.weight > 0.0 ? (kept.weight * kept.visibility + weight * sample.visibility) / updated.weight : sample.visibility;
  updated.frames = kept.frames + 1.0;
  updated.confidence = std::max(kept.confidence, sample.confidence);
  updated.depth = sample.depth;
  return updated;
}

double resolvedVisibility(const TemporalHistory& history, const TemporalSettings& settings)
{
  if (!settings.resolveByThreshold)
  {
    return history.visibility;
  }
  return history.visibility >= 0.5 ? 1.0 : 0.0;
}

TemporalFrameSample temporalFrameReference(
  const ShadowMapInputs& inputs, const BiasSettings& bias, int x, int y, ProbeRecorder* recorder)
{
  ShadowLookup lookup = prepareShadowLookup(inputs, bias, x, y, recorder);
  TemporalFrameSample result;
  if (lookup.sample.evaluated)
  {
    if (recorder)
    {
      recorder->beginGroup("last frame's shadow test");
      recorder->kernel({ "nearest texel", glm::floor(lookup.sm.uvTexels), glm::floor(lookup.sm.uvTexels) + 1.0, "",
        "Williams 1978: one depth comparison in the jittered map" });
    }
    lookup.sample.visibility = nearestTexelTest(
      inputs, lookup.sm.uvTexels, lookup.comparisonDepth, lookup.sample, recorder, "nearest texel");
    result.confidence = shadowTestConfidence(lookup.sm.uvTexels);
    if (recorder)
    {
      recorder->quantity("sample_visibility", lookup.sample.visibility, "", "Williams 1978: d - bias <= stored depth");
      recorder->quantity("sample_confidence", result.confidence, "",
        "survey §4.6: 1 - 2 max(|x - centre_x|, |y - centre_y|)");
    }
  }
  result.sample = lookup.sample;
  return result;
}

namespace
{

// A buffer the pass reads back itself (vtkSLTemporalPass::CollectPassBuffers).
BufferSpec passBuffer(std::string name, std::string unit, std::string doc)
{
  BufferSpec spec{ std::move(name), std::move(unit), std::move(doc) };
  spec.fromPass = true;
  return spec;
}

ProbeOutcome probeTemporal(const ProbeContext& context, glm::ivec2 pixel, ProbeRecorder& recorder)
{
  const FrameResult& frame = *context.frame;
  const TemporalSettings settings = TemporalSettings::from(frame.parameters);
  const NamedImage* visibilities = frame.find("sample_visibility_frames");
  const NamedImage* confidences = frame.find("sample_confidence_frames");
  if (settings.cameraStep != 0.0)
  {
    throw InputError(format("temporal: camera_step=", settings.cameraStep,
      ": the probe replays a static camera's history only; render with camera_step=0"));
  }
  if (!visibilities || !confidences)
  {
    throw InputError("temporal: the probe replays the history from every frame's samples; render with --set "
                     "export_frames=on");
  }
  const ShadowMapInputs inputs = shadowMapInputsOf(frame, *context.scene, context.lightIndex);
  const TemporalFrameSample last = temporalFrameReference(inputs, settings.bias, pixel.x, pixel.y, &recorder);
  if (!last.sample.evaluated)
  {
    return probeOutcome(last.sample, 0.0, "temporalFrameReference (temporal/TemporalTechnique.h), double precision");
  }
  const glm::dvec3 pWs(inputs.position.at(pixel.x, pixel.y, 0), inputs.position.at(pixel.x, pixel.y, 1),
    inputs.position.at(pixel.x, pixel.y, 2));
  const double depth = -(inputs.camera.viewFromWorld * glm::dvec4(pWs, 1.0)).z;
  // Frames 0 .. K-2 from the GPU's own samples (their maps are not exported), the last one from the CPU's test.
  TemporalHistory history;
  int rejections = 0;
  for (int k = 0; k + 1 < settings.frames; ++k)
  {
    const TemporalSample sample{ visibilities->image.at(pixel.x, pixel.y, k), confidences->image.at(pixel.x, pixel.y, k),
      depth, depth };
    bool rejected = false;
    history = updateTemporalHistory(history, sample, settings, &rejected);
    rejections += rejected ? 1 : 0;
  }
  bool rejected = false;
  history = updateTemporalHistory(
    history, TemporalSample{ last.sample.visibility, last.confidence, depth, depth }, settings, &rejected);
  rejections += rejected ? 1 : 0;
  recorder.beginGroup("history");
  recorder.quantity("history_frames", history.frames, "frames", "frames held since the history was last dropped");
  recorder.quantity("history_weight", history.weight, "", "SJW07: sum of conf^m over the frames held");
  recorder.quantity("confidence", history.confidence, "", "survey §4.6: the highest confidence among the frames held");
  recorder.quantity("disocclusions", static_cast<double>(rejections), "", "histories dropped (static camera: none)");
  recorder.quantity("history_visibility", history.visibility, "", "confidence-weighted mean of the frames' shadow tests");
  ReferenceSample replayed = last.sample;
  replayed.visibility = resolvedVisibility(history, settings);
  recorder.quantity("visibility", replayed.visibility, "", settings.resolveByThreshold ? "resolve = threshold: the mean rounded at 1/2" : "resolve = mean");
  // The weighted mean is accumulated in float on the GPU.
  return probeOutcome(replayed, 1e-4,
    "updateTemporalHistory over the GPU's frames 0..K-2 and temporalFrameReference's last frame "
    "(temporal/TemporalTechnique.h), double precision");
}

} // namespace

TechniqueDescriptor temporalTechnique()
{
  TechniqueDescriptor descriptor = describeShadowMapTechnique("temporal",
    "Temporal reprojection with shadow-test confidence", "Scherzer, Jeschke & Wimmer 2007; survey (Scherzer et al. 2011) §4.6", 1024);
  descriptor.addParameters({
    { "temporal_frames", 16, 1, 256, "frames",
      "K: frames of the static scene, each with the shadow map's viewport jittered by a sub-texel Halton (2, 3) offset (survey §4.6)",
      {}, true },
    { "confidence_exponent", 1, 0, 64, "",
      "m: a frame's weight in the history is conf^m; 1 = the survey's confidence as printed (§4.6), 0 = plain mean, large = the most central sample wins" },
    { "confidence_threshold", 0.5, 0, 1, "",
      "a pixel whose best confidence stays below this after K frames is flagged (buffer unconverged)" },
    { "disocclusion_threshold", 0.01, 0, 1, "",
      "the history is dropped where its depth and the reprojected depth differ by more than this x the depth (survey §4.6)" },
    { "resolve", 0, 0, 1, "",
      "mean: visibility is the history's confidence-weighted mean; threshold: that mean rounded to 0 or 1 at 1/2 (a hard shadow)",
      { "mean", "threshold" }, true },
    { "camera_step", 0, 0, 1, "world units",
      "moves the camera sideways by this much per frame, the last frame at the scene's camera: exercises the reprojection and the disocclusion test (0: static)" },
    { "export_frames", 0, 0, 1, "",
      "on: also publish every frame's sample (sample_visibility_frames, sample_confidence_frames), for the probe",
      { "off", "on" }, true },
  });
  BufferSpec unconverged = passBuffer("unconverged", "",
    "1 where the confidence stays below confidence_threshold after K frames (no frame sampled the map near a texel centre)");
  unconverged.flagAtOrAbove = 1.0;
  unconverged.flagWarning = "no frame sampled the shadow map near a texel centre there: raise temporal_frames";
  // The history lives in two RGBA32F targets of the pass (at most 8 draw buffers on llvmpipe), read back by the
  // pass: every buffer but depth_bias is the pass's.
  descriptor.buffers = {
    depthBiasBuffer(),
    passBuffer("history_visibility", "", "the history's confidence-weighted mean of the frames' shadow tests (visibility with resolve = mean)"),
    passBuffer("confidence", "", "the highest shadow-test confidence (survey §4.6) among the frames the history holds: 1 = a texel centre"),
    passBuffer("history_frames", "frames", "frames accumulated in the pixel's history since it was last dropped (disocclusion)"),
    passBuffer("history_weight", "", "sum of the held frames' weights conf^m"),
    passBuffer("history_depth", "world units", "view depth of the surface the history belongs to (the next frame's disocclusion test reads it)"),
    passBuffer("sample_visibility", "", "the last frame's single depth comparison (1 lit, 0 shadowed)"),
    passBuffer("sample_confidence", "", "the last frame's shadow-test confidence"),
    unconverged,
    passBuffer("sample_visibility_frames", "", "each frame's depth comparison, one component per frame (export_frames=on only)"),
    passBuffer("sample_confidence_frames", "", "each frame's confidence, one component per frame (export_frames=on only)"),
  };
  // The pass's two targets follow the pipeline's (visibility, depth_bias).
  const int pipelineTargets = static_cast<int>(descriptor.outputNames().size());
  descriptor.shaderConstants = {
    { "TEMPORAL_HISTORY_LOCATION", pipelineTargets, "RGBA: history_visibility, history_weight, history_frames, confidence" },
    { "TEMPORAL_SAMPLE_LOCATION", pipelineTargets + 1, "RGBA: history_depth, sample_visibility, sample_confidence" },
  };
  descriptor.createPass = newTechniquePass<vtkSLTemporalPass>;
  descriptor.probe = probeTemporal;
  // K shadow maps per frame: the registry-wide sweeps keep K small, and export the frames for the probe.
  descriptor.sweepTestSettings = { "temporal_frames=4", "export_frames=on" };
  descriptor.accuracy.reference = ReferenceModel::LightCentre;
  descriptor.accuracy.tolerance = 1e-3;
  descriptor.accuracy.approximations = {
    { "shadow-map sampling",
      "the texels within two of the receiver's in the last frame's map hold occluding and non-occluding depths after "
      "the pixel's depth_bias (the frames' jittered lookups span two texels), or a caster lies within twice the bias "
      "of the receiver" },
    { "unconverged history", "the confidence stays below confidence_threshold after K frames (buffer unconverged)" },
  };
  descriptor.accuracy.markApproximations = [](const ApproximationContext& context, ImageF& codes) {
    const ImageF jitteredFootprint(codes.width, codes.height, 1, 2.0f); // kernel_texels 2: radius 2 texels
    markShadowMapSampling(ShadowMapFootprint(context), *context.frame, codes, 1.0f, &jitteredFootprint);
    markWhere(*context.frame, "unconverged", [](float value) { return value >= 0.5f; }, codes, 2.0f);
  };
  return descriptor;
}

} // namespace sl
