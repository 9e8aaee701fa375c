#include "techniques/hard/HardTechnique.h"

#include <algorithm>

#include "techniques/ApproximationRules.h"

#include "structures/shadowmap/ShadowMapStructure.h"

#include "techniques/ProbeSupport.h"
#include "techniques/ShadowMapParameters.h"
#include "techniques/hard/vtkSLHardShadowPass.h"

namespace sl
{

HardSettings HardSettings::from(const ParameterValues& values)
{
  HardSettings settings;
  settings.bias = biasSettings(values);
  return settings;
}

TechniqueDescriptor hardTechnique()
{
  TechniqueDescriptor descriptor = describeShadowMapTechnique("hard", "Hard shadow mapping with depth biasing",
    "Williams 1978; survey (Scherzer et al. 2011) §5");
  descriptor.addParameters(shadowMapWarpParameters());
  descriptor.addParameters(shadowMapCascadeParameters());
  descriptor.addParameters(shadowMapFvsmParameters());
  descriptor.addParameters(shadowMapCubeParameters());

  descriptor.buffers = {
    { "kernel_texels", "texels", "filter footprint width in shadow-map texels (1: a single texel)" },
    texelRatioBuffer(),
    depthBiasBuffer(),
    onShadowTestedPixels({ "depth_margin", "world units", "receiver depth - bias - stored caster depth: > 0 shadowed, <= 0 lit; values near 0 are where acne or leaks start", BufferKind::Signed }),
  };
  descriptor.createPass = newTechniquePass<vtkSLHardShadowPass>;
  descriptor.probe = [](const ProbeContext& context, glm::ivec2 pixel, ProbeRecorder& recorder) {
    const std::vector<ShadowMapInputs> inputs = viewInputsOf(*context.frame, *context.scene, context.lightIndex);
    const BiasSettings bias = HardSettings::from(context.frame->parameters).bias;
    const ReferenceSample sample = partitionedReference(*context.frame, inputs, pixel.x, pixel.y,
      [&](const ShadowMapInputs& view, int x, int y, ProbeRecorder* r) { return hardReference(view, bias, x, y, r); },
      &recorder);
    // GpuCpuTest: identical on unambiguous pixels (0 or 1).
    return probeOutcome(sample, 0.0, "hardReference (hard/HardTechnique.h), double precision");
  };
  // Area lights are sampled from their centre (README.md here, "Common to hard and pcf"): held to the single ray to
  // the centre.
  // One depth comparison is exact there except where the texels around the receiver's disagree about it, or the
  // bias hides a caster touching the receiver (survey §5): the map's sampling decides those pixels, not the geometry.
  descriptor.accuracy.reference = ReferenceModel::LightCentre;
  descriptor.accuracy.tolerance = 1e-3;
  descriptor.accuracy.approximations = { { "shadow-map sampling",
    "the texels within one of the receiver's hold occluding and non-occluding depths after the pixel's depth_bias, "
    "or a caster lies within twice the bias of the receiver" },
    { "polygon id: several triangles per texel",
      "depth_layer = polygon_id: the 3 x 3 texels around the receiver's hold more than one triangle id (survey §5: "
      "the mechanism breaks down if more than one triangle is present per texel)" },
    { "depth layer gap",
      "depth_layer = midpoint or dual: a texel within one of the receiver's holds its nearest caster in front of the "
      "receiver (after depth_bias) but a compared depth behind it: lit only by the gap to the second layer, where a "
      "light leak and removed acne look alike (survey §5)" } };
  descriptor.accuracy.markApproximations = [](const ApproximationContext& context, ImageF& codes) {
    if (const NamedImage* ids = context.frame->find("polygon_id"))
    {
      // Receivers with id 0 cast no shadow and keep the depth test (and its approximation).
      markSeveralPolygonIds(context, codes, 2.0f);
      ImageF depthCodes(codes.width, codes.height, 1);
      markShadowMapSampling(context, depthCodes, 1.0f, nullptr);
      for (std::size_t i = 0; i < codes.data.size(); ++i)
      {
        codes.data[i] = ids->image.data[i] == 0.0f && codes.data[i] == 0.0f ? depthCodes.data[i] : codes.data[i];
      }
      return;
    }
    markDepthLayerGap(context, codes, 3.0f, nullptr);
    markShadowMapSampling(context, codes, 1.0f, nullptr);
  };
  return descriptor;
}

ReferenceSample hardReference(const ShadowMapInputs& inputs, const BiasSettings& bias, int x, int y,
  ProbeRecorder* recorder)
{
  ShadowLookup lookup = prepareShadowLookup(inputs, bias, x, y, recorder);
  if (lookup.sample.evaluated)
  {
    if (recorder)
    {
      recorder->beginGroup("shadow test");
      recorder->kernel({ "nearest texel", glm::floor(lookup.sm.uvTexels), glm::floor(lookup.sm.uvTexels) + 1.0, "",
        "Williams 1978: one depth comparison" });
    }
    lookup.sample.visibility = nearestTexelTest(
      inputs, lookup.sm.uvTexels, lookup.comparisonDepth, lookup.sample, recorder, "nearest texel");
    if (!inputs.shadowMapPolygonId.empty() && inputs.receiverPolygonId.at(x, y) != 0.0f)
    {
      // depth_layer = polygon_id (survey §5): the ids decide; the depth test above only fills the margins. A receiver
      // with id 0 casts no shadow (it is not in the map): the depth test decides it.
      lookup.sample.visibility = polygonIdTest(inputs, lookup.sm.uvTexels, x, y, recorder);
      lookup.sample.depthMargin = 1e300;
      lookup.sample.texelEdgeMargin = 1e300;
      for (const TexelEdge& edge : texelWithEdges(lookup.sm.uvTexels).edges)
      {
        // A GPU tap within float rounding of an edge may read the neighbour's id.
        if (edge.distance < 1e-3 &&
          polygonIdTest(inputs, glm::dvec2(edge.neighbour) + 0.5, x, y) != lookup.sample.visibility)
        {
          lookup.sample.texelEdgeMargin = std::min(lookup.sample.texelEdgeMargin, edge.distance);
        }
      }
    }
    if (recorder)
    {
      recorder->quantity("visibility", lookup.sample.visibility, "", "Williams 1978: d - bias <= stored depth");
    }
  }
  return lookup.sample;
}

} // namespace sl
