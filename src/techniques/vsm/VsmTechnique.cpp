#include "techniques/vsm/VsmTechnique.h"

#include "lightspace/moments/MomentMapStructure.h"
#include "lightspace/shadowmap/ShadowMapStructure.h"

#include "techniques/esm/EsmTechnique.h"

#include "techniques/MomentReference.h"
#include "techniques/MomentTechniquePass.h"
#include "techniques/ShadowMapParameters.h"

#include <algorithm>

namespace sl
{

TechniqueDescriptor vsmTechnique()
{
  TechniqueDescriptor descriptor;
  descriptor.name = "vsm";
  descriptor.title = "Variance shadow maps";
  descriptor.paper = "Donnelly & Lauritzen 2006; Lauritzen 2007 (light bleeding); survey §6; VSSM §4.1";
  descriptor.parameters = shadowMapParameters();
  for (ParameterSpec& spec : descriptor.parameters)
  {
    // VSM compares the receiver's own depth: the variance (and its floor) absorbs the depth slope within the
    // filter region, and a bias would inflate p_max (Chebyshev is exact at t = the receiver's depth).
    if (spec.name == "bias_constant_texels" || spec.name == "bias_slope_texels")
    {
      spec.defaultValue = 0.0;
    }
  }
  const std::vector<ParameterSpec>& prefilter = momentMapStructure().parameters;
  descriptor.parameters.insert(descriptor.parameters.end(), prefilter.begin(), prefilter.end());
  descriptor.parameters.insert(descriptor.parameters.end(), {
    { "light_bleeding_reduction", 0.2, 0, 0.99, "", "p_max below this amount becomes 0 and [amount, 1] maps to [0, 1] (Lauritzen 2007)", {}, false },
    { "min_variance", 1e-6, 0, 0.01, "d^2", "floor of the variance, relative to the squared receiver depth (float cancellation in E[z^2] - E[z]^2)", {}, false },
  });
  descriptor.lightStructures = { &shadowMapStructure(), &momentMapStructure() };
  descriptor.buffers = {
    { "p_max", "", "Chebyshev upper bound on the lit fraction, before light-bleeding reduction" },
    { "light_leak", "", "p_max minus the true PCF over the same box of texels: > 0 where VSM bleeds light", BufferKind::Signed },
    { "kernel_texels", "texels", "width of the prefilter box" },
    { "depth_bias", "world units", "depth bias applied at the pixel (constant + slope-scaled)" },
  };
  descriptor.supportedLights = shadowMapLights();
  descriptor.createPass = [] {
    auto pass = vtkSmartPointer<vtkSLMomentTechniquePass>::New();
    pass->SetFragmentShaderPath("vsm/VsmVisibility.glsl");
    return vtkSmartPointer<vtkSLTechniquePass>(pass);
  };
  return descriptor;
}

VsmSample vsmReference(const ShadowMapInputs& inputs, const ParameterValues& values, int x, int y)
{
  VsmSample result;
  const ShadowLookup lookup = prepareShadowLookup(inputs, biasSettings(values), x, y);
  result.sample = lookup.sample;
  if (!lookup.sample.evaluated)
  {
    return result;
  }
  const int width = values.getInt("prefilter_texels");
  const FilteredMoments moments = boxMoments(inputs, lookup.sm.uvTexels, width, 0.0);
  const double d = lookup.sm.depthLin;
  result.variance = std::max(moments.second - moments.mean * moments.mean, values.get("min_variance") * d * d);
  const double t = lookup.comparisonDepth;
  result.pMax = t <= moments.mean ? 1.0 : result.variance / (result.variance + (t - moments.mean) * (t - moments.mean));
  const double amount = values.get("light_bleeding_reduction");
  result.sample.visibility = std::clamp((result.pMax - amount) / (1.0 - amount), 0.0, 1.0);
  result.lightLeak = result.pMax - boxPcf(inputs, lookup.sm.uvTexels, t, width);
  return result;
}

} // namespace sl
