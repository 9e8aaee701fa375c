#include "techniques/pcss/PcssTechnique.h"

#include "techniques/ApproximationRules.h"

#include "structures/shadowmap/ShadowMapStructure.h"

#include "techniques/PcssReference.h"
#include "techniques/ProbeSupport.h"
#include "techniques/ShadowMapParameters.h"
#include "techniques/SoftShadowSupport.h"
#include "techniques/pcss/vtkSLPcssPass.h"

namespace sl
{

TechniqueDescriptor pcssTechnique()
{
  TechniqueDescriptor descriptor = describeShadowMapTechnique("pcss", "Percentage-closer soft shadows",
    "Fernando 2005; as in VSSM (Yang et al. 2010) §1 and Alg. 1 L7/L16");
  const std::vector<ParameterSpec> soft = softShadowParameters();
  descriptor.addParameters(soft);
  descriptor.parameters.push_back(
    { "filter", 0, 0, 1, "", "grid: every texel of the penumbra kernel w_p (brute force); poisson: rotated Poisson taps", { "grid", "poisson" }, true });
  descriptor.buffers = {
    { "blocker_kernel_texels", "texels", "width of the blocker search kernel w_i (Alg. 1 L7)" },
    { "blocker_samples", "taps", "depth samples read in the blocker search" },
    { "avg_blocker_depth", "world units", "average depth of the blockers found (0: none, lit)" },
    { "penumbra_width", "world units", "estimated penumbra width at the receiver, w_light (d - z_avg) / z_avg" },
    { "penumbra_kernel_texels", "texels", "width of the PCF kernel w_p (Alg. 1 L16)" },
    { "pcf_samples", "taps", "depth comparisons in the PCF step" },
    depthBiasBuffer(),
  };
  descriptor.supportedLights = { LightType::Area, LightType::Point, LightType::Spot };
  descriptor.coversLightArea = true;
  descriptor.createPass = newTechniquePass<vtkSLPcssPass>;
  descriptor.probe = [](const ProbeContext& context, glm::ivec2 pixel, ProbeRecorder& recorder) {
    const ShadowMapInputs inputs = shadowMapInputsOf(*context.frame, *context.scene, context.lightIndex);
    const PcssSample sample = pcssReference(inputs, PcssSettings::from(context.frame->parameters), pixel.x, pixel.y, &recorder);
    // PcssTest: <= 1e-5 on unambiguous pixels (a sum of 0/1 taps divided by the count); a grid kernel's edge
    // within 1e-4 texel of a texel centre may gain or lose a row of taps in float.
    ProbeOutcome outcome =
      probeOutcome(sample.sample, 1e-5, "pcssReference (PcssReference.h), double precision");
    if (sample.sample.evaluated)
    {
      noteAmbiguity(outcome.ambiguity, "grid kernel edge from a texel centre (texels)", sample.kernelEdgeMargin,
        probeTexelEdgeAmbiguity);
    }
    return outcome;
  };
  // PCSS's penumbra estimate takes one average blocker depth (Fernando 2005): exact for blockers on one plane parallel
  // to the light, approximate wherever the casters that hide part of the light lie at different depths.
  descriptor.accuracy = oneLayerSoftShadowContract(BlockerDepthModel::Average, 0.1);
  return descriptor;
}

} // namespace sl
