#include "techniques/shadowvolume/ShadowVolumeTechnique.h"

#include "techniques/ApproximationRules.h"

#include "lightspace/LightView.h"
#include "techniques/ProbeSupport.h"
#include "techniques/VolumeCountStatus.h"
#include "objectspace/ShadowVolumeGeometry.h"
#include "objectspace/ShadowVolumeReference.h"
#include "techniques/vtkSLShadowVolumePass.h"

#include <cmath>
#include <string>

namespace sl
{
ShadowVolumeSettings ShadowVolumeSettings::from(const ParameterValues& values)
{
  ShadowVolumeSettings settings;
  settings.receiverOffset = receiverOffsetOf(values);
  return settings;
}

TechniqueDescriptor shadowVolumeTechnique()
{
  TechniqueDescriptor descriptor = describeTechnique("shadow-volume",
    "Z-fail stencil shadow volumes (exact hard shadows)",
    "Crow 1977; Everitt & Kilgard 2002 (z-fail, infinite volumes); Stich et al. 2007 (non-closed meshes)");
  descriptor.parameters = {
    receiverOffsetParameter(1e-5,
      ": a volume face closer behind it than float rounding (its own caster's near cap) counts as behind"),
  };
  descriptor.lightStructures = {}; // object space: no shadow map
  descriptor.drawsSceneGeometry = true; // welded casters and the G-buffer's depth-stencil
  descriptor.buffers = {
    { "depth_complexity_center", "surfaces",
      "caster triangles crossed by the segment from the point to the light's centre (shadow volumes containing it)" },
    { "stencil_count", "", "the 8-bit stencil's z-fail count: depth_complexity_center modulo 256" },
    volumeCountStatusBuffer(),
  };
  descriptor.supportedLights = { LightType::Area, LightType::Point, LightType::Spot, LightType::Directional };
  descriptor.createPass = newTechniquePass<vtkSLShadowVolumePass>;
  descriptor.probe = [](const ProbeContext& context, glm::ivec2 pixel, ProbeRecorder& recorder) {
    return probeShadowVolume(*context.frame, *context.scene, context.lightIndex, pixel, recorder);
  };
  // Exact hard shadows of the light's centre (Crow 1977); alpha textures are ignored by design, so a perforated
  // caster shadows as if solid.
  descriptor.accuracy.reference = ReferenceModel::LightCentre;
  descriptor.accuracy.tolerance = 1e-3;
  descriptor.accuracy.approximations = { { "perforated caster as solid",
    "the segment to the light's centre crosses a caster with an alpha texture" } };
  descriptor.accuracy.markApproximations = [](const ApproximationContext& context, ImageF& codes) {
    markCentreRayThroughPerforatedCaster(context, codes, 1.0f);
  };
  return descriptor;
}

namespace
{

// Where the camera ray through the pixel centre moved by `pixels` meets the receiver's tangent plane (the point
// `pWs`, normal `nWs`): the visible point of a pixel position that close, on the same surface.
glm::dvec3 shiftedOnSurface(
  const CameraView& camera, glm::ivec2 pixel, const glm::dvec3& pWs, const glm::dvec3& nWs, const glm::dvec2& pixels)
{
  const double x = pixel.x + 0.5 + pixels.x;
  const double y = pixel.y + 0.5 + pixels.y;
  const glm::dvec3 nearPoint = camera.nearOrigin + x * camera.nearStepX + y * camera.nearStepY;
  const glm::dvec3 ray = camera.rayOrigin + x * camera.rayStepX + y * camera.rayStepY;
  const double along = glm::dot(nWs, ray);
  if (std::abs(along) < 1e-12 * glm::length(ray))
  {
    return pWs; // the ray grazes the surface
  }
  return nearPoint + (glm::dot(nWs, pWs - nearPoint) / along) * ray;
}

} // namespace

ProbeOutcome probeShadowVolume(const FrameResult& frame, const Scene& scene, int lightIndex, glm::ivec2 pixel,
  ProbeRecorder& recorder)
{
  const Light& light = scene.lights.at(static_cast<std::size_t>(lightIndex));
  ProbeOutcome outcome;
  outcome.twin = "casterCrossings (objectspace/ShadowVolumeReference.h): caster triangles crossed by the segment "
                 "from the offset point to the light's centre, Moller-Trumbore in double";
  // The count is exact on the GPU (float blending of +-1, exact to 2^24), so visibility is too: ShadowVolumeTest
  // (ProbeRecordsTheCrossedTrianglesAndTheGpuCount) finds no pixel that differs outside the rasterisation margin
  // noted below.
  outcome.tolerance = 0.0;
  if (bufferValue(frame, "coverage", pixel) <= 0.5)
  {
    return outcome;
  }
  const glm::dvec3 pWs = bufferVector(frame, "position", pixel);
  const glm::dvec3 nWs = bufferVector(frame, "normal", pixel);
  const double receiverOffset = ShadowVolumeSettings::from(frame.parameters).receiverOffset;
  const glm::dvec3 point = shadowVolumeReceiverPoint(scene, receiverOffset, pWs);
  recorder.beginGroup("receiver");
  recorder.quantity("position", pWs, "world units", "G-buffer (pWs)");
  recorder.quantity("normal", nWs, "", "G-buffer (nWs)");
  recorder.quantity("receiver_offset", receiverOffset, "of the eye distance",
    "ShadowLab (receiver_offset): the point taken toward the camera so its own caster's near cap lies behind it");
  recorder.quantity("counted_point", point, "world units", "ShadowLab: pWs + receiver_offset (eye - pWs)");
  const VolumeLight volumeLight = VolumeLight::from(light);
  recorder.quantity(volumeLight.directional ? "light_direction" : "light_centre",
    volumeLight.directional ? volumeLight.direction : volumeLight.position, volumeLight.directional ? "" : "world units",
    "Crow 1977: the volumes are cast from the light's centre (an area light's centre)");

  recorder.beginGroup("crossings to the light centre");
  const int count = casterCrossings(scene, volumeLight, point, &recorder);
  recorder.quantity("depth_complexity_center", count, "count",
    "Crow 1977; Everitt & Kilgard 2002 (z-fail): shadow volumes containing the point = caster triangles crossed");
  recorder.quantity("stencil_count", count % 256, "count", "Everitt & Kilgard 2002: the 8-bit stencil holds the count modulo 256");
  recorder.lightSample({ glm::dvec2(0.0), count > 0, count });

  // What the GPU counted and whether its own check flagged the count (vtkSLShadowVolumePass.h): a flagged pixel is
  // the pass saying its value is not exact, so the probe says so too instead of reporting a disagreement.
  recorder.beginGroup("GPU count");
  const double gpuCount = bufferValue(frame, "depth_complexity_center", pixel);
  recorder.quantity("gpu_depth_complexity_center", gpuCount, "count", "the pass's z-fail count at the pixel");
  const auto status = static_cast<VolumeCountStatus>(std::lround(bufferValue(frame, "volume_count_status", pixel)));
  recorder.category("volume_count_status", static_cast<int>(status),
    volumeCountCategories[status == VolumeCountStatus::Inconsistent ? 1 : 0].label,
    "ShadowLab: count below 0, or the volume faces along the camera ray miss the eye's count");
  if (status == VolumeCountStatus::Inconsistent)
  {
    outcome.ambiguity = "the GPU flagged this pixel's count as inconsistent (volume_count_status), GPU count " +
      std::to_string(static_cast<long>(gpuCount)) + ", twin " + std::to_string(count);
  }

  // A volume face within rasterisation's sub-pixel precision of the pixel centre covers it or not on the GPU
  // (llvmpipe snaps vertices to 1/256 pixel, moving an edge by up to 1/512): the count at the visible points of
  // the pixel positions 1/512 pixel away on either axis, on the receiver's tangent plane. Measured at 128^2 on
  // stacked-occluders and the bunny (ShadowVolumeTest): no pixel outside this margin differs from the GPU.
  constexpr double kRasterMargin = 1.0 / 512.0;
  for (const glm::dvec2& shift : { glm::dvec2(kRasterMargin, 0.0), glm::dvec2(-kRasterMargin, 0.0),
         glm::dvec2(0.0, kRasterMargin), glm::dvec2(0.0, -kRasterMargin) })
  {
    const int shifted = casterCrossings(
      scene, volumeLight, shadowVolumeReceiverPoint(scene, receiverOffset, shiftedOnSurface(frame.camera, pixel, pWs, nWs, shift)));
    if (shifted != count)
    {
      outcome.ambiguity = "a shadow-volume face within 1/512 pixel of the pixel centre (count " + std::to_string(count) +
        ", " + std::to_string(shifted) + " beside it): rasterisation may cover it either way";
      break;
    }
  }

  recorder.beginGroup("result");
  if (litWithoutShadowTest(frame, pixel, recorder, outcome))
  {
    return outcome;
  }
  noteAmbiguity(outcome.ambiguity, "light-reach cosine", lightReachMargin(light, nWs, directionToLight(light, pWs)),
    probeReachAmbiguity);
  if (!lightCanReach(light, pWs, nWs))
  {
    recorder.category("light_reach", "faces away / outside the light's reach: unlit, no shadow test",
      "ShadowLab (lightCanReach, LightView.h)");
    return outcome;
  }
  outcome.evaluated = true;
  outcome.visibility = count == 0 ? 1.0 : 0.0;
  recorder.quantity("visibility", outcome.visibility, "", "Crow 1977: lit when no shadow volume contains the point");
  return outcome;
}

} // namespace sl
