#include "techniques/dcs/DcsTechnique.h"

#include "techniques/ApproximationRules.h"

#include "lightspace/LightView.h"
#include "structures/lightsamples/LightSampleSetStructure.h"
#include "scene/WeldedMesh.h"
#include "techniques/ProbeSupport.h"
#include "objectspace/DcsGeometry.h"
#include "techniques/dcs/DcsReference.h"
#include "techniques/dcs/vtkSLDcsPass.h"
#include "techniques/VolumeCountStatus.h"
#include "objectspace/ShadowVolumeReference.h"
#include "objectspace/StsvDrawer.h"

#include <string>

namespace sl
{
namespace
{

const Category<DcsCounterStatus> dcsCounterCategories[] = {
  { DcsCounterStatus::Exact, "EXACT", "counters exact" },
  { DcsCounterStatus::RangeExceeded, "RANGE_EXCEEDED", "8-bit counter range exceeded: not exact", true },
};

} // namespace

std::uint32_t DcsCounterLayers::replicated(int value)
{
  std::uint32_t word = 0;
  for (int counter = 0; counter < kCountersPerLayer; ++counter)
  {
    word |= (static_cast<std::uint32_t>(value) & kCounterMask) << (kCounterBits * counter);
  }
  return word;
}

std::vector<ShaderConstant> dcsCounterLayerShaderConstants(int sampleCount)
{
  const DcsCounterLayers layers(sampleCount);
  return {
    { "DCS_SAMPLE_COUNTER_LAYERS", layers.sampleCounterLayers, "layers of packed sample counters (DcsCounterLayers)" },
    { "DCS_CHECKSUM_LAYER", layers.checksum(), "the layer of the sum of changes (DcsCounterLayers)" },
    { "DCS_WEIGHTED_CHECKSUM_LAYER", layers.weightedChecksum(), "the layer of the index-weighted sum (DcsCounterLayers)" },
    { "DCS_COVERING_LAYER", layers.covering(), "the layer of the wedges containing the point (DcsCounterLayers)" },
    { "DCS_COUNTER_LAYERS", layers.total(), "all layers of the counters (DcsCounterLayers)" },
  };
}

DcsSettings DcsSettings::from(const ParameterValues& values)
{
  DcsSettings settings;
  settings.receiverOffset = receiverOffsetOf(values);
  settings.lightSamples = lightSampleSetSettings(values);
  settings.exportSampleCounts = values.getInt("export_sample_counts") != 0;
  settings.stsvTest = stsvOcclusionTestOf(values);
  return settings;
}

TechniqueDescriptor dcsTechnique()
{
  TechniqueDescriptor descriptor = describeTechnique("dcs",
    "Depth complexity sampling (per-sample occluder counts from silhouette wedges)",
    "Forest, Barthe & Paulin 2008 (DCS); Forest et al. 2009 §3.2, §4.1");
  descriptor.parameters = {
    // 1e-4, ten times shadow-volume's: at 1e-5, segments to samples that graze a faceted surface re-enter it next to
    // the point, and every pattern's bunny penumbra RMSE against the reference (whose rays start 1e-4 of the scene's
    // radius along the normal) stopped at 0.064-0.066 at N = 256, 0.023-0.027 at 1e-4 (docs/bench/dcs).
    receiverOffsetParameter(1e-4, " before its samples are counted, as shadow-volume does"),
  };
  // The light-sample set's own parameters (light_samples, samples, sample_seed), declared as the structure does.
  const LightSpaceStructure& samples = lightSampleSetStructure();
  descriptor.addParameters(samples.parameters);
  ParameterSpec exportCounts{ "export_sample_counts", 0.0, 0.0, 1.0, "",
    "1: also publish sample_depth_complexity, every sample's count (N floats per pixel; for tests and probes)" };
  exportCounts.integer = true;
  descriptor.parameters.push_back(exportCounts);
  descriptor.parameters.push_back(stsvOppositeSideCheckParameter());
  descriptor.lightStructures = { &samples };
  descriptor.drawsSceneGeometry = true;
  descriptor.perforatedCastersByStsv = true;
  descriptor.buffers = {
    { "visibility_stderr", "", "sqrt(v (1 - v) / (N - 1)), the Bernoulli bound of N light samples, as the reference's" },
    { "depth_complexity_center", "surfaces",
      "caster triangles crossed by the segment from the point to the light's centre (the reference sample, from the shadow volumes)" },
    { "occluded_samples", "light samples", "samples whose count is > 0 (of N)" },
    { "dc_min", "surfaces", "the smallest sample count; < 0 flags a topology error (FBP08)" },
    { "dc_max", "surfaces", "the largest sample count" },
    { "wedges_covering", "wedges", "wedges whose region holds the point (the per-pixel cost of the wedge pass)" },
    categoricalBuffer("counter_status",
      "the range check of the packed 8-bit counters (vtkSLDcsPass.h): range exceeded marks a pixel whose counts are not exact",
      dcsCounterCategories),
    volumeCountStatusBuffer(),
  };
  BufferSpec mask{ "light_sample_mask", "bits",
    "which samples are hidden (blocked or below the tangent plane): bit i % 16 of component i / 16, N/16 components (Forest et al. 2009 §5.1's LS_buffer)" };
  mask.fromPass = true;
  mask.kind = BufferKind::BitMask;
  BufferSpec counts{ "sample_depth_complexity", "surfaces",
    "every sample's count, N components; only with export_sample_counts = 1" };
  counts.fromPass = true;
  descriptor.buffers.push_back(mask);
  descriptor.buffers.push_back(counts);
  descriptor.supportedLights = { LightType::Area, LightType::Point };
  descriptor.shaderConstants = wedgePassShaderConstants();
  descriptor.shaderConstants.insert(descriptor.shaderConstants.end(), {
    { "DCS_COUNTER_BIAS", kDcsCounterBias, "the 8-bit counters' bias (DcsTechnique.h)" },
    { "DCS_COUNTERS_PER_LAYER", DcsCounterLayers::kCountersPerLayer, "counters per 32-bit word (DcsCounterLayers)" },
    { "DCS_COUNTER_BITS", DcsCounterLayers::kCounterBits, "bits per counter (DcsCounterLayers)" },
    { "DCS_COUNTER_MASK", DcsCounterLayers::kCounterMask, "one counter's bits (DcsCounterLayers)" },
  });
  descriptor.createPass = newTechniquePass<vtkSLDcsPass>;
  descriptor.probe = [](const ProbeContext& context, glm::ivec2 pixel, ProbeRecorder& recorder) {
    return probeDcs(*context.frame, *context.scene, context.lightIndex, pixel, recorder);
  };
  // Exact per light sample (FBP08): the area integral up to the N samples' noise, which visibility_stderr publishes
  // (the differential test adds it to the tolerance).
  descriptor.accuracy.reference = ReferenceModel::AreaLight;
  descriptor.accuracy.tolerance = 0.05;
  descriptor.accuracy.lightSampleCount = [](const ParameterValues& values) { return DcsSettings::from(values).lightSamples.count; };
  return descriptor;
}

ProbeOutcome probeDcs(const FrameResult& frame, const Scene& scene, int lightIndex, glm::ivec2 pixel,
  ProbeRecorder& recorder)
{
  const Light& light = scene.lights.at(static_cast<std::size_t>(lightIndex));
  ProbeOutcome outcome;
  outcome.twin = "dcsPixelTwin (dcs/DcsReference.h): the centre's crossings in double plus every wedge's per-sample "
                 "change (DcsGeometry.h), on the frame's light samples";
  outcome.tolerance = 0.0;
  if (bufferValue(frame, "coverage", pixel) <= 0.5)
  {
    return outcome;
  }
  const glm::dvec3 pWs = bufferVector(frame, "position", pixel);
  const glm::dvec3 nWs = bufferVector(frame, "normal", pixel);
  const DcsSettings settings = DcsSettings::from(frame.parameters);
  const LightSampleSet samples(settings.lightSamples);
  const DcsEdgeSet wedges = potentialSilhouetteWedges(weldCasters(scene, true), light);
  recorder.beginGroup("receiver");
  recorder.quantity("position", pWs, "world units", "G-buffer (pWs)");
  recorder.quantity("normal", nWs, "", "G-buffer (nWs)");
  recorder.quantity("light_samples", samples.count(), "samples",
    "Forest et al. 2009 §4.1: " + lightSamplePatternName(samples.settings()) + ", toroidally shifted per pixel");
  const DcsPixelTwin twin = dcsPixelTwin(scene, light, wedges, samples, pixel, pWs, nWs,
    settings.receiverOffset, &recorder, settings.stsvTest);
  recorder.beginGroup("counts");
  recorder.quantity("counted_point", twin.countedPoint, "world units", "ShadowLab: pWs + receiver_offset (eye - pWs)");
  recorder.quantity("depth_complexity_center", twin.centreCount, "surfaces",
    "FBP08: the reference sample's count, from the centre's shadow volumes");
  recorder.quantity("wedges_covering", twin.wedgesCovering, "wedges", "DcsGeometry.h wedgeContains");
  recorder.quantity("occluded_samples", twin.occludedSamples, "light samples", "FBP08: samples with count > 0");
  recorder.quantity("dc_min", twin.dcMin, "surfaces", "FBP08: < 0 flags a topology error");
  recorder.quantity("dc_max", twin.dcMax, "surfaces", "FBP08");
  // A sample whose segment passes within float rounding of an edge may be counted either way on the GPU.
  outcome.ambiguity = "";
  recorder.beginGroup("result");
  if (litWithoutShadowTest(frame, pixel, recorder, outcome))
  {
    return outcome;
  }
  if (!lightCanReach(light, pWs, nWs))
  {
    recorder.category("light_reach", "faces away / outside the light's reach: unlit, no shadow test",
      "ShadowLab (lightCanReach, LightView.h)");
    return outcome;
  }
  outcome.evaluated = true;
  outcome.visibility = twin.visibility;
  // One sample decided within float rounding changes the visibility by 1/N: the tests' per-pixel bound.
  outcome.tolerance = 1.0 / samples.count();
  recorder.quantity("visibility", twin.visibility, "", "Forest et al. 2009 §3.2: the fraction of samples with count 0 (above the tangent plane)");
  return outcome;
}

} // namespace sl
