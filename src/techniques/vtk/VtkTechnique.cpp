#include "techniques/vtk/VtkTechnique.h"

#include "techniques/ApproximationRules.h"

#include "lightspace/LightView.h"
#include "techniques/ProbeSupport.h"
#include "objectspace/ShadowVolumeGeometry.h"
#include "objectspace/ShadowVolumeReference.h"
#include "techniques/vtk/vtkSLVtkShadowMapPass.h"

#include <algorithm>
#include <cmath>

namespace sl
{

VtkSettings VtkSettings::from(const ParameterValues& values)
{
  VtkSettings settings;
  settings.shadowMapSize = values.getInt("shadow_map_size");
  return settings;
}

TechniqueDescriptor vtkTechnique()
{
  TechniqueDescriptor descriptor = describeTechnique("vtk", "VTK's vtkShadowMapPass (the in-ecosystem peer)",
    "VTK 9.1 vtkShadowMapBakerPass / vtkShadowMapPass");
  descriptor.parameters = {
    { "shadow_map_size", 1024, 16, 8192, "texels", "resolution of VTK's shadow map (vtkShadowMapBakerPass::SetResolution)", {}, true },
  };
  descriptor.lightStructures = {}; // VTK builds its own
  descriptor.buffers = {
    { "vtk_shadowed", "", "VTK's radiance with shadows (white diffuse material, light intensity 1)" },
    { "vtk_unshadowed", "", "VTK's radiance without shadows (same material and light)" },
  };
  descriptor.supportedLights = { LightType::Area, LightType::Point, LightType::Spot, LightType::Directional };
  descriptor.createPass = newTechniquePass<vtkSLVtkShadowMapPass>;
  descriptor.probe = [](const ProbeContext& context, glm::ivec2 pixel, ProbeRecorder& recorder) {
    return probeVtk(*context.frame, *context.scene, context.lightIndex, pixel, recorder);
  };
  // VTK's shadow-map pass samples the light from its centre and filters its comparisons (README.md here, "Known
  // limitations of the vtk technique"): held to the centre's ray where its value is 0 or 1.
  descriptor.accuracy.reference = ReferenceModel::LightCentre;
  descriptor.accuracy.tolerance = 1e-3;
  // VTK 9.1's documented per-frame limitations (README.md here, "Known limitations of the vtk technique"): its baker
  // loses the receivers when the light axis is parallel to its default view-up (y), and misplaces shadows in
  // non-square images. They hold for the whole frame, so every covered pixel of such a frame is flagged.
  descriptor.accuracy.approximations = { { "filtered edge", "the value lies strictly between 0 and 1 (by 1e-3)" },
    { "vtk frame limitation", "the light's axis is within 1e-6 of vertical, or the image is not square: VTK 9.1's "
      "baker loses or misplaces the shadow over the whole frame" } };
  descriptor.accuracy.markApproximations = [](const ApproximationContext& context, ImageF& codes) {
    markPartialVisibility(*context.frame, codes, 1.0f);
    const Light& light = context.scene->lights.at(static_cast<std::size_t>(context.lightIndex));
    const glm::dvec3 axis = light.type == LightType::Directional ? light.direction : light.normal;
    const bool vertical = glm::length(glm::cross(glm::normalize(axis), glm::dvec3(0.0, 1.0, 0.0))) < 1e-6;
    const bool nonSquare = codes.width != codes.height;
    if (vertical || nonSquare)
    {
      markWhere(*context.frame, "coverage", [](float covered) { return covered > 0.5f; }, codes, 2.0f);
    }
  };
  return descriptor;
}

ProbeOutcome probeVtk(const FrameResult& frame, const Scene& scene, int lightIndex, glm::ivec2 pixel,
  ProbeRecorder& recorder)
{
  const Light& light = scene.lights.at(static_cast<std::size_t>(lightIndex));
  ProbeOutcome outcome;
  outcome.twin = "the extraction of VtkVisibilityRatio.glsl replayed in double on the frame's vtk_shadowed and "
                 "vtk_unshadowed buffers (VTK's own shadow map has no twin; the hard ray to the light's centre is "
                 "context only)";
  // The shader divides the same two float values in float: the double quotient differs by float rounding.
  outcome.tolerance = 1e-6;
  if (bufferValue(frame, "coverage", pixel) <= 0.5)
  {
    return outcome;
  }
  const glm::dvec3 pWs = bufferVector(frame, "position", pixel);
  const glm::dvec3 nWs = bufferVector(frame, "normal", pixel);
  recorder.beginGroup("receiver");
  recorder.quantity("position", pWs, "world units", "G-buffer (pWs)");
  recorder.quantity("normal", nWs, "", "G-buffer (nWs)");

  recorder.beginGroup("vtk radiance");
  const double shadowed = bufferValue(frame, "vtk_shadowed", pixel);
  const double unshadowed = bufferValue(frame, "vtk_unshadowed", pixel);
  recorder.quantity("vtk_shadowed", shadowed, "", "VTK 9.1 vtkShadowMapPass: radiance of a white diffuse material with shadows (S)");
  recorder.quantity("vtk_unshadowed", unshadowed, "", "VTK 9.1: the same material and light without shadows (U)");

  // Context: what a hard shadow from the light's centre would say (VTK's map is a spot cone at that centre;
  // alpha textures are ignored there as VTK bakes opaque geometry). The ray leaves the surface by the ray-traced
  // reference's offset.
  recorder.beginGroup("context: hard ray to the light centre");
  const double rayOffset = 1e-4 * scene.bounds().radius();
  const int crossings = casterCrossings(scene, VolumeLight::from(light), pWs + rayOffset * nWs, &recorder);
  recorder.quantity("caster_crossings_to_light_centre", crossings, "count",
    "ShadowLab: caster triangles crossed by the segment from pWs + 1e-4 r n to the light's centre (context, not VTK's)");
  recorder.quantity("hard_ray_visibility", crossings == 0 ? 1.0 : 0.0, "", "Williams 1978 (exact, by a ray): lit when nothing crosses");

  recorder.beginGroup("result");
  if (litWithoutShadowTest(frame, pixel, recorder, outcome))
  {
    return outcome;
  }
  noteAmbiguity(outcome.ambiguity, "light-reach cosine", lightReachMargin(light, nWs, directionToLight(light, pWs)),
    probeReachAmbiguity);
  // Below 1e-3 of full irradiance the ratio is noise (VtkVisibilityRatio.glsl).
  constexpr double kMinUnshadowed = 1e-3;
  noteAmbiguity(outcome.ambiguity, "vtk_unshadowed from the 1e-3 cut (relative)",
    std::abs(unshadowed - kMinUnshadowed) / kMinUnshadowed, 1e-6);
  if (!lightCanReach(light, pWs, nWs) || unshadowed < kMinUnshadowed)
  {
    recorder.category("light_reach", "faces away, outside the light's reach, or vtk_unshadowed < 1e-3: unlit",
      "ShadowLab (VtkVisibilityRatio.glsl)");
    return outcome;
  }
  outcome.evaluated = true;
  outcome.visibility = std::clamp(shadowed / unshadowed, 0.0, 1.0);
  recorder.quantity("visibility", outcome.visibility, "",
    "ShadowLab (VtkVisibilityRatio.glsl): clamp(S / U, 0, 1), S = U x VTK's shadow factor where the light reaches");
  return outcome;
}

} // namespace sl
