#include "techniques/hard/HardTechnique.h"

#include "lightspace/shadowmap/ShadowMapStructure.h"

#include "techniques/ShadowMapParameters.h"
#include "techniques/hard/vtkSLHardShadowPass.h"

namespace sl
{

TechniqueDescriptor hardTechnique()
{
  TechniqueDescriptor descriptor;
  descriptor.name = "hard";
  descriptor.title = "Hard shadow mapping with depth biasing";
  descriptor.paper = "Williams 1978; survey (Scherzer et al. 2011) §5";
  descriptor.parameters = shadowMapParameters();
  descriptor.lightStructures = { &shadowMapStructure() };
  descriptor.buffers = {
    { "kernel_texels", "texels", "filter footprint width in shadow-map texels (1: a single texel)" },
    { "texel_ratio", "pixels/texel", "aliasing error m (survey Eq. 2): screen pixels spanned by one shadow-map texel along its most stretched direction; > 1 means undersampling" },
    { "depth_bias", "world units", "depth bias applied at the pixel (constant + slope-scaled)" },
    { "depth_margin", "world units", "receiver depth - bias - stored caster depth: > 0 shadowed, <= 0 lit; values near 0 are where acne or leaks start", BufferKind::Signed },
  };
  descriptor.supportedLights = shadowMapLights();
  descriptor.createPass = [] { return vtkSmartPointer<vtkSLTechniquePass>(vtkSmartPointer<vtkSLHardShadowPass>::New()); };
  return descriptor;
}

ReferenceSample hardReference(const ShadowMapInputs& inputs, const BiasSettings& bias, int x, int y)
{
  ShadowLookup lookup = prepareShadowLookup(inputs, bias, x, y);
  if (lookup.sample.evaluated)
  {
    lookup.sample.visibility = nearestTexelTest(inputs, lookup.sm.uvTexels, lookup.comparisonDepth, lookup.sample);
  }
  return lookup.sample;
}

} // namespace sl
