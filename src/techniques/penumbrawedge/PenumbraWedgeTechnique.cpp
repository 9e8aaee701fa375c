#include "techniques/penumbrawedge/PenumbraWedgeTechnique.h"

#include "techniques/ApproximationRules.h"

#include "lightspace/LightView.h"
#include "structures/lightsamples/LightSampleSetStructure.h"
#include "techniques/ProbeSupport.h"
#include "objectspace/DcsGeometry.h"
#include "techniques/penumbrawedge/PenumbraWedgeGeometry.h"
#include "techniques/penumbrawedge/vtkSLPenumbraWedgePass.h"
#include "techniques/VolumeCountStatus.h"
#include "objectspace/ShadowVolumeReference.h"
#include "objectspace/StsvDrawer.h"

#include <algorithm>

namespace sl
{

PenumbraWedgeSettings PenumbraWedgeSettings::from(const ParameterValues& values)
{
  PenumbraWedgeSettings settings;
  settings.receiverOffset = receiverOffsetOf(values);
  settings.lightSamples = lightSampleSetSettings(values);
  settings.stsvTest = stsvOcclusionTestOf(values);
  return settings;
}

TechniqueDescriptor penumbraWedgeTechnique()
{
  TechniqueDescriptor descriptor = describeTechnique("penumbra-wedge",
    "Penumbra wedges (hard shadow from the centre plus each centre silhouette's share of the light)",
    "Akenine-Moller & Assarsson 2002; Assarsson & Akenine-Moller 2003; Forest et al. 2009 §3.1");
  descriptor.parameters = {
    receiverOffsetParameter(1e-4, " before the centre's volumes, the wedges and the STSVs are evaluated, as dcs does"),
    stsvOppositeSideCheckParameter(),
  };
  // The light samples of the perforated casters' LS_buffer (Forest et al. 2009 §3.1): the shared set, 64 by default (the
  // paper's PWedge+STSV64).
  const LightSpaceStructure& samples = lightSampleSetStructure();
  for (ParameterSpec spec : samples.parameters)
  {
    if (spec.name == "samples")
    {
      spec.defaultValue = static_cast<double>(std::find(spec.choices.begin(), spec.choices.end(), "64") - spec.choices.begin());
    }
    descriptor.parameters.push_back(spec);
  }
  descriptor.lightStructures = { &samples };
  descriptor.drawsSceneGeometry = true;
  descriptor.perforatedCastersByStsv = true;
  descriptor.buffers = {
    { "pw_occlusion_raw", "fraction of light",
      "the centre's hard-shadow status plus every wedge's signed share, plus the STSVs' hidden samples / N, before clamping: > 1 or < 0 where overlapping silhouettes are counted twice (Forest et al. 2009 §3.1)",
      BufferKind::Signed },
    { "depth_complexity_center", "surfaces",
      "opaque caster triangles crossed by the segment from the point to the light's centre (the shadow volumes' count)" },
    { "wedges_covering", "wedges", "centre-silhouette wedges whose region holds the point (the per-pixel cost of the wedge pass)" },
    { "stsv_covering", "STSVs", "soft textured shadow volumes holding the point (Forest et al. 2009 §2.3)" },
    { "stsv_empty_hits", "STSVs", "STSVs holding the point that hide none of its samples: how conservative the extrusion is" },
    { "stsv_occluded_samples", "light samples", "samples hidden by perforated casters (the LS_buffer's popcount, of N)" },
    volumeCountStatusBuffer(),
  };
  BufferSpec mask{ "light_sample_mask", "bits",
    "which samples perforated casters hide (the STSVs' LS_buffer, Forest et al. 2009 §3.1): bit i % 16 of component i / 16, N/16 components" };
  mask.fromPass = true;
  mask.kind = BufferKind::BitMask;
  descriptor.buffers.push_back(mask);
  descriptor.supportedLights = { LightType::Area };
  descriptor.supportedAreaShapes = { LightShape::Square };
  descriptor.shaderConstants = wedgePassShaderConstants();
  descriptor.createPass = newTechniquePass<vtkSLPenumbraWedgePass>;
  descriptor.probe = [](const ProbeContext& context, glm::ivec2 pixel, ProbeRecorder& recorder) {
    return probePenumbraWedge(*context.frame, *context.scene, context.lightIndex, pixel, recorder);
  };
  // Exact for one convex occluder (AAM03); where silhouettes overlap their wedges' contributions are added twice and
  // silhouettes seen only from the rest of the light are missed, as in the paper. Perforated casters are sampled by
  // STSV's N shared light samples (Forest et al. 2009 Eq. 1-5).
  descriptor.accuracy.reference = ReferenceModel::AreaLight;
  descriptor.accuracy.tolerance = 0.05;
  descriptor.accuracy.approximations = {
    { "overlapping silhouettes",
      "the segment to the light's centre crosses two or more caster surfaces (depth_complexity_center >= 2), or "
      "two or more wedges hold the point (wedges_covering >= 2: their silhouettes' projections onto the light may "
      "overlap; the buffers do not say whether they belong to one convex caster, where the method is exact)" },
    { "sampled stsv", "a soft textured shadow volume holds the point (stsv_covering > 0): N light samples" } };
  descriptor.accuracy.markApproximations = [](const ApproximationContext& context, ImageF& codes) {
    markWhere(*context.frame, "depth_complexity_center", [](float count) { return count >= 2.0f; }, codes, 1.0f);
    markWhere(*context.frame, "wedges_covering", [](float count) { return count >= 2.0f; }, codes, 1.0f);
    markWhere(*context.frame, "stsv_covering", [](float count) { return count > 0.0f; }, codes, 2.0f);
  };
  return descriptor;
}

ProbeOutcome probePenumbraWedge(const FrameResult& frame, const Scene& scene, int lightIndex, glm::ivec2 pixel,
  ProbeRecorder& recorder)
{
  const Light& light = scene.lights.at(static_cast<std::size_t>(lightIndex));
  ProbeOutcome outcome;
  outcome.twin = "penumbraWedgePixel (penumbrawedge/PenumbraWedgeGeometry.h): the centre's crossings and every "
                 "centre-silhouette wedge's far region, in double";
  if (bufferValue(frame, "coverage", pixel) <= 0.5)
  {
    return outcome;
  }
  const glm::dvec3 pWs = bufferVector(frame, "position", pixel);
  const glm::dvec3 nWs = bufferVector(frame, "normal", pixel);
  recorder.beginGroup("receiver");
  recorder.quantity("position", pWs, "world units", "G-buffer (pWs)");
  recorder.quantity("normal", nWs, "", "G-buffer (nWs)");
  const PenumbraWedgeSettings settings = PenumbraWedgeSettings::from(frame.parameters);
  const LightSampleSet samples(settings.lightSamples);
  const PenumbraWedgePixel twin = penumbraWedgePixel(penumbraWedgeScene(scene, light), scene, light, pWs,
    settings.receiverOffset, dcsSamplePoints(light, samples, pixel), settings.stsvTest,
    &recorder);
  recorder.beginGroup("result");
  recorder.quantity("counted_point", twin.countedPoint, "world units", "ShadowLab: pWs + receiver_offset (eye - pWs)");
  recorder.quantity("depth_complexity_center", twin.centreCount, "surfaces", "AAM03: the hard shadow from the centre");
  recorder.quantity("wedges_covering", twin.wedgesCovering, "wedges", "DcsGeometry.h wedgeContains");
  recorder.quantity("stsv_covering", twin.stsvCovering, "STSVs", "Forest et al. 2009 §2.3: STSVs holding the point");
  recorder.quantity("stsv_occluded_samples", twin.stsvOccludedSamples, "light samples",
    "Forest et al. 2009 §3.1: the LS_buffer's popcount (perforated casters)");
  recorder.quantity("pw_occlusion_raw", twin.occlusionRaw, "fraction of light",
    "AAM03: [centre hidden] + sum of the wedges' signed shares (Forest et al. 2009 §3.1: > 1 where overlaps count twice), + the "
    "STSVs' popcount / N (§3.1)");
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
  // Float clipping of the far regions (magnified where an edge lies close to the point) and blending's summation
  // order: the GPU tests' per-pixel bound.
  outcome.tolerance = 1e-3;
  recorder.quantity("visibility", twin.visibility, "", "AAM03: 1 - clamp(pw_occlusion_raw, 0, 1)");
  return outcome;
}

} // namespace sl
