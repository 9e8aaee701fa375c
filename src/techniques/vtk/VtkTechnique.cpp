#include "techniques/vtk/VtkTechnique.h"

#include "techniques/vtk/vtkSLVtkShadowMapPass.h"

namespace sl
{

TechniqueDescriptor vtkTechnique()
{
  TechniqueDescriptor descriptor;
  descriptor.name = "vtk";
  descriptor.title = "VTK's vtkShadowMapPass (the in-ecosystem peer)";
  descriptor.paper = "VTK 9.1 vtkShadowMapBakerPass / vtkShadowMapPass";
  descriptor.parameters = {
    { "shadow_map_size", 1024, 16, 8192, "texels", "resolution of VTK's shadow map (vtkShadowMapBakerPass::SetResolution)", {}, true },
  };
  descriptor.lightStructures = {}; // VTK builds its own
  descriptor.buffers = {
    { "vtk_shadowed", "", "VTK's radiance with shadows (white diffuse material, light intensity 1)" },
    { "vtk_unshadowed", "", "VTK's radiance without shadows (same material and light)" },
  };
  descriptor.supportedLights = { LightType::Area, LightType::Point, LightType::Spot, LightType::Directional };
  descriptor.createPass = [] { return vtkSmartPointer<vtkSLTechniquePass>(vtkSmartPointer<vtkSLVtkShadowMapPass>::New()); };
  return descriptor;
}

} // namespace sl
