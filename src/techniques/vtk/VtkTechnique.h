// Technique `vtk`: VTK's own shadow mapping (vtkShadowMapBakerPass + vtkShadowMapPass, VTK 9.1), run on
// the same scene and camera, so the in-ecosystem peer is measured with the same buffers and metrics.
//
// How visibility is obtained: see vtk/shaders/VtkVisibilityRatio.glsl (shadowed / unshadowed radiance
// of a white diffuse material, both rendered by VTK into float targets).
// What VTK does differently, by design of its passes (kept as is — this is the point of the comparison):
//  - the shadow map frustum is a spot cone at the light's position (area lights: their centre), fitted to
//    the scene's bounding box rather than focused on visible receivers;
//  - alpha textures are ignored (VTK bakes opaque geometry), so perforated casters shadow like solids;
//  - its filtering and bias are VTK's (exponential shadow-map style), not configurable here.
// Parameters: shadow_map_size (VTK's baker resolution). Buffers: vtk_shadowed, vtk_unshadowed.
#pragma once

#include "frame/FrameResult.h"
#include "frame/ProbeRecord.h"
#include "frame/TechniqueDescriptor.h"

namespace sl
{

TechniqueDescriptor vtkTechnique();

// vtk's parameters, typed (parsed once, by from()).
struct VtkSettings
{
  int shadowMapSize{}; // vtkShadowMapBakerPass::SetResolution

  static VtkSettings from(const ParameterValues& values);
};

// The technique's probe (TechniqueDescriptor::probe). VTK's passes keep their shadow map to themselves, so there
// is no twin of the map: the probe replays the extraction (visibility = vtk_shadowed / vtk_unshadowed under the
// project's reach rules, VtkVisibilityRatio.glsl) from the frame's buffers, and records, for context, the hard
// ray test from the point to the light's centre (caster crossings).
ProbeOutcome probeVtk(const FrameResult& frame, const Scene& scene, int lightIndex, glm::ivec2 pixel,
  ProbeRecorder& recorder);

} // namespace sl
