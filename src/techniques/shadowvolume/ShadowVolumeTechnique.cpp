#include "techniques/shadowvolume/ShadowVolumeTechnique.h"

#include "techniques/shadowvolume/vtkSLShadowVolumePass.h"

namespace sl
{

TechniqueDescriptor shadowVolumeTechnique()
{
  TechniqueDescriptor descriptor;
  descriptor.name = "shadow-volume";
  descriptor.title = "Z-fail stencil shadow volumes (exact hard shadows)";
  descriptor.paper = "Crow 1977; Everitt & Kilgard 2002 (z-fail, infinite volumes); Stich et al. 2007 (non-closed meshes)";
  descriptor.parameters = {
    { "receiver_offset", 1e-5, 0.0, 1e-2, "of the eye distance",
      "the visible point is taken this fraction of its distance to the eye toward the camera (orthographic: of the scene's radius): a volume face closer behind it than float rounding (its own caster's near cap) counts as behind" },
  };
  descriptor.lightStructures = {}; // object space: no shadow map
  descriptor.drawsSceneGeometry = true; // welded casters and the G-buffer's depth-stencil
  descriptor.buffers = {
    { "depth_complexity_center", "surfaces",
      "caster triangles crossed by the segment from the point to the light's centre (shadow volumes containing it)" },
    { "stencil_count", "", "the 8-bit stencil's z-fail count: depth_complexity_center modulo 256" },
  };
  descriptor.supportedLights = { LightType::Area, LightType::Point, LightType::Spot, LightType::Directional };
  descriptor.createPass = [] { return vtkSmartPointer<vtkSLTechniquePass>(vtkSmartPointer<vtkSLShadowVolumePass>::New()); };
  return descriptor;
}

} // namespace sl
