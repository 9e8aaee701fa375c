#include "techniques/referencesm/ReferenceSmTechnique.h"

#include "techniques/ShadowMapParameters.h"
#include "techniques/referencesm/vtkSLReferenceShadowMapPass.h"

namespace sl
{

TechniqueDescriptor referenceSmTechnique()
{
  TechniqueDescriptor descriptor;
  descriptor.name = "reference-sm";
  descriptor.title = "Accumulated hard shadow maps from K light samples (GPU reference)";
  descriptor.paper = "the papers' reference, e.g. VSSM (Yang et al. 2010) §7; survey §5 bias per map";
  descriptor.parameters = shadowMapParameters();
  for (ParameterSpec& spec : descriptor.parameters)
  {
    if (spec.name == "shadow_map_size")
    {
      spec.defaultValue = 1024; // K maps per frame
    }
  }
  descriptor.parameters.insert(descriptor.parameters.end(), {
    { "samples", 256, 1, 4096, "light samples", "K: shadow maps rendered from points spread over the area light (papers: 1024)", {}, true },
    { "seed", 1, 0, 2147483647, "", "rotation of the Hammersley light samples (Cranley-Patterson)", {}, true },
  });
  descriptor.lightStructures = {}; // it renders its own K maps
  descriptor.buffers = {
    { "visibility_stderr", "", "standard error of the visibility estimate over the K samples (Bernoulli bound)" },
    { "sample_count", "light samples", "light samples averaged in the pixel" },
  };
  descriptor.supportedLights = shadowMapLights();
  descriptor.createPass = [] {
    return vtkSmartPointer<vtkSLTechniquePass>(vtkSmartPointer<vtkSLReferenceShadowMapPass>::New());
  };
  return descriptor;
}

} // namespace sl
