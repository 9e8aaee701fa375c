#include "techniques/savsm/SavsmTechnique.h"

#include "lightspace/sat/SatStructure.h"
#include "lightspace/shadowmap/ShadowMapStructure.h"

#include "techniques/ShadowMapParameters.h"
#include "techniques/SoftShadowSupport.h"
#include "techniques/pcss/PcssTechnique.h"
#include "lightspace/sat/SummedAreaTable.h"
#include "techniques/savsm/vtkSLSavsmPass.h"

#include <algorithm>
#include <cmath>

namespace sl
{

TechniqueDescriptor savsmTechnique()
{
  TechniqueDescriptor descriptor;
  descriptor.name = "savsm";
  descriptor.title = "SAT-based variance soft shadow mapping";
  descriptor.paper = "Lauritzen 2007 (GPU Gems 3 ch. 8); VSSM (Yang et al. 2010) §2.3 baseline; survey §6.4";
  // The bias applies to the blocker search (the receiver must not find itself); Chebyshev compares the
  // receiver's own depth, where it is exact for two depths (see vsm).
  descriptor.parameters = shadowMapParameters();
  const std::vector<ParameterSpec> soft = softShadowParameters();
  descriptor.parameters.insert(descriptor.parameters.end(), soft.begin(), soft.end());
  descriptor.parameters.insert(descriptor.parameters.end(), {
    { "sat_precision", 1, 0, 1, "", "float_centred: float SAT of z - (near + far) / 2; int32: 16-bit fixed point, exact box sums (survey §6.4)", { "float_centred", "int32" }, true },
    { "light_bleeding_reduction", 0.0, 0, 0.99, "", "p_max below this amount becomes 0 and [amount, 1] maps to [0, 1] (Lauritzen 2007)", {}, false },
    { "min_variance", 1e-6, 0, 0.01, "d^2", "floor of the variance, relative to the squared receiver depth", {}, false },
  });
  descriptor.lightStructures = { &shadowMapStructure(), &summedAreaTableStructure() };
  descriptor.buffers = {
    { "p_max", "", "Chebyshev upper bound on the lit fraction over w_p, before light-bleeding reduction" },
    { "light_leak", "", "p_max minus the true PCF over the same rectangle of texels", BufferKind::Signed },
    { "blocker_kernel_texels", "texels", "width of the blocker search kernel w_i (Alg. 1 L7)" },
    { "blocker_samples", "taps", "depth samples read in the blocker search" },
    { "avg_blocker_depth", "world units", "average depth of the blockers found (0: none, lit)" },
    { "penumbra_kernel_texels", "texels", "width of the penumbra kernel w_p (Alg. 1 L16)" },
    { "depth_bias", "world units", "depth bias applied at the pixel" },
  };
  descriptor.supportedLights = { LightType::Area, LightType::Point, LightType::Spot };
  descriptor.coversLightArea = true;
  descriptor.createPass = [] { return vtkSmartPointer<vtkSLTechniquePass>(vtkSmartPointer<vtkSLSavsmPass>::New()); };
  return descriptor;
}

SavsmSample savsmReference(const ShadowMapInputs& inputs, const ParameterValues& values, int x, int y)
{
  const PcssSample pcss = pcssReference(inputs, values, x, y); // blocker search and w_p are PCSS's
  SavsmSample result;
  result.sample = pcss.sample;
  result.kernelEdgeMargin = pcss.kernelEdgeMargin;
  result.foundBlockers = pcss.foundBlockers;
  if (!pcss.sample.evaluated || !pcss.foundBlockers)
  {
    return result;
  }
  const TexelRectangle rectangle = kernelRectangle(pcss.uvTexels, pcss.filterHalfTexels, inputs.shadowMapLinear.width);
  result.lo = rectangle.lo;
  result.hi = rectangle.hi;
  const LightView& view = inputs.lightView;
  const bool integer = values.choice("sat_precision") == "int32";
  const BoxMoments moments =
    exactBoxMoments(inputs.shadowMapLinear, result.lo, result.hi, view.nearDepth, view.farDepth, integer);
  const ShadowLookup lookup = prepareShadowLookup(inputs, biasSettings(values), x, y);
  const double d = lookup.sm.depthLin;
  const double t = d;
  result.variance = std::max(moments.variance, values.get("min_variance") * d * d);
  result.pMax = t <= moments.mean ? 1.0 : result.variance / (result.variance + (t - moments.mean) * (t - moments.mean));
  const double amount = values.get("light_bleeding_reduction");
  result.sample.visibility = std::clamp((result.pMax - amount) / (1.0 - amount), 0.0, 1.0);
  return result;
}

} // namespace sl
