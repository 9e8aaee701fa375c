#include "techniques/esm/EsmTechnique.h"

#include "lightspace/moments/MomentMapStructure.h"
#include "lightspace/shadowmap/ShadowMapStructure.h"

#include "techniques/MomentReference.h"
#include "techniques/MomentTechniquePass.h"
#include "techniques/ShadowMapParameters.h"

#include <algorithm>
#include <cmath>

namespace sl
{

TechniqueDescriptor esmTechnique()
{
  TechniqueDescriptor descriptor;
  descriptor.name = "esm";
  descriptor.title = "Exponential shadow maps";
  descriptor.paper = "Annen, Mertens, Seidel, Flerackers & Kautz 2008; survey §6";
  descriptor.parameters = shadowMapParameters();
  const std::vector<ParameterSpec>& prefilter = momentMapStructure().parameters;
  descriptor.parameters.insert(descriptor.parameters.end(), prefilter.begin(), prefilter.end());
  descriptor.parameters.insert(descriptor.parameters.end(), {
    { "esm_exponent", 40, 1, 80, "", "c in exp(c (z_n - t_n)), depths normalised to the light's range: sharper with larger c", {}, false },
  });
  descriptor.lightStructures = { &shadowMapStructure(), &momentMapStructure() };
  descriptor.buffers = {
    { "light_leak", "", "visibility minus the true PCF over the same box of texels", BufferKind::Signed },
    { "kernel_texels", "texels", "width of the prefilter box" },
    { "depth_bias", "world units", "depth bias applied at the pixel (constant + slope-scaled)" },
  };
  descriptor.supportedLights = shadowMapLights();
  descriptor.createPass = [] {
    auto pass = vtkSmartPointer<vtkSLMomentTechniquePass>::New();
    pass->SetFragmentShaderPath("esm/EsmVisibility.glsl");
    return vtkSmartPointer<vtkSLTechniquePass>(pass);
  };
  return descriptor;
}

ReferenceSample esmReference(const ShadowMapInputs& inputs, const ParameterValues& values, int x, int y)
{
  ShadowLookup lookup = prepareShadowLookup(inputs, biasSettings(values), x, y);
  if (!lookup.sample.evaluated)
  {
    return lookup.sample;
  }
  const double exponent = values.get("esm_exponent");
  const FilteredMoments moments = boxMoments(inputs, lookup.sm.uvTexels, values.getInt("prefilter_texels"), exponent);
  const LightView& view = inputs.lightView;
  const double t = (lookup.comparisonDepth - view.nearDepth) / (view.farDepth - view.nearDepth);
  lookup.sample.visibility = std::clamp(moments.exponential * std::exp(-exponent * t), 0.0, 1.0);
  return lookup.sample;
}

} // namespace sl
