#include "techniques/pcf/PcfTechnique.h"

#include "techniques/ApproximationRules.h"

#include "structures/shadowmap/ShadowMapStructure.h"

#include "techniques/ProbeSupport.h"
#include "techniques/ShadowMapParameters.h"
#include "techniques/pcf/vtkSLPcfPass.h"

#include <algorithm>
#include <cmath>
#include <random>

namespace sl
{

PcfSettings PcfSettings::from(const ParameterValues& values)
{
  PcfSettings settings;
  settings.bias = biasSettings(values);
  settings.kernelTexels = values.getInt("kernel_texels");
  settings.pattern = choiceOf<PcfPattern>(values, "pattern", { { "grid", PcfPattern::Grid }, { "poisson", PcfPattern::Poisson } });
  settings.poissonSamples = values.getInt("poisson_samples");
  settings.filter = choiceOf<PcfFilter>(values, "filter",
    { { "nearest", PcfFilter::Nearest }, { "hardware_bilinear", PcfFilter::HardwareBilinear } });
  return settings;
}

TechniqueDescriptor pcfTechnique()
{
  TechniqueDescriptor descriptor = describeShadowMapTechnique("pcf", "Percentage-closer filtering",
    "Reeves, Salesin & Cook 1987; survey (Scherzer et al. 2011) §6");
  descriptor.addParameters({
    { "kernel_texels", 3, 1, 64, "texels", "filter width: grid side, or Poisson disk diameter", {}, true },
    { "pattern", 0, 0, 1, "", "tap layout: grid (every texel of the kernel) or poisson (rotated Poisson disk)", { "grid", "poisson" }, true },
    { "poisson_samples", 16, 1, maxPoissonSamples, "taps", "taps of the Poisson disk (pattern = poisson)", {}, true },
    { "filter", 0, 0, 1, "", "nearest: one comparison per tap; hardware_bilinear: the hardware's 2x2 bilinear comparison per tap (survey Fig. 23)", { "nearest", "hardware_bilinear" }, true },
  });
  descriptor.addParameters(shadowMapWarpParameters());
  descriptor.addParameters(shadowMapCascadeParameters());
  descriptor.addParameters(shadowMapFvsmParameters());
  descriptor.addParameters(shadowMapCubeParameters());
  descriptor.buffers = {
    { "kernel_texels", "texels", "filter footprint width in shadow-map texels" },
    { "taps", "comparisons", "depth comparisons made for the pixel" },
    texelRatioBuffer(),
    depthBiasBuffer(),
  };
  descriptor.lightSpaceRequest = [](const ParameterValues& values) {
    return LightSpaceRequest{ "kernel_texels", static_cast<double>(PcfSettings::from(values).kernelTexels) };
  };
  descriptor.createPass = newTechniquePass<vtkSLPcfPass>;
  descriptor.probe = [](const ProbeContext& context, glm::ivec2 pixel, ProbeRecorder& recorder) {
    const std::vector<ShadowMapInputs> inputs = viewInputsOf(*context.frame, *context.scene, context.lightIndex);
    const ParameterValues& values = context.frame->parameters;
    const ReferenceSample sample = partitionedReference(*context.frame, inputs, pixel.x, pixel.y,
      [&](const ShadowMapInputs& view, int x, int y, ProbeRecorder* r) { return pcfReference(view, values, x, y, r); },
      &recorder);
    // GpuCpuTest's tolerances on unambiguous pixels: nearest taps are a sum of 0/1 divided by the count (1e-5);
    // the hardware's bilinear weights have the texture unit's sub-texel precision (8 bits on llvmpipe: 2^-7).
    const bool hardware = PcfSettings::from(values).filter == PcfFilter::HardwareBilinear;
    return probeOutcome(sample, hardware ? 1.0 / 128.0 : 1e-5, "pcfReference (pcf/PcfTechnique.h), double precision");
  };
  // Area lights are sampled from their centre (hard/README.md, "Common to hard and pcf"): held to the single ray to
  // the centre.
  // The filter averages the comparisons over its kernel (survey §6): where they differ the value is a blend, by
  // design, and a caster within twice the bias of the receiver is hidden by it (survey §5).
  descriptor.accuracy.reference = ReferenceModel::LightCentre;
  descriptor.accuracy.tolerance = 1e-3;
  descriptor.accuracy.approximations = { { "filter footprint",
    "the comparisons within kernel_texels / 2 + 1 texels of the receiver's differ after the pixel's depth_bias (a "
    "filtered edge), or a caster lies within twice the bias of the receiver" },
    { "depth layer gap",
      "depth_layer = midpoint or dual: a texel within kernel_texels / 2 + 1 of the receiver's holds its nearest caster "
      "in front of the receiver (after depth_bias) but a compared depth behind it: lit only by the gap to the second "
      "layer, where a light leak and removed acne look alike (survey §5)" } };
  descriptor.accuracy.markApproximations = [](const ApproximationContext& context, ImageF& codes) {
    const ImageF& kernel = context.frame->find("kernel_texels")->image;
    markDepthLayerGap(context, codes, 2.0f, &kernel);
    markShadowMapSampling(context, codes, 1.0f, &kernel);
  };
  return descriptor;
}

namespace
{

// GL's linear filtering of comparisons (GL 4.5 §8.14.2, §8.23.1): sample at uv*size - 0.5, weights from
// the fraction, each of the 2x2 texels (clamped to the edge) compared with ref <= D. `tapWeight` (1 / taps)
// scales the texels' recorded weights to their share of the pixel's visibility.
double bilinearCompare(const ShadowMapInputs& inputs, const glm::dvec2& uvTexels, double referenceWindowDepth,
  ReferenceSample& sample, ProbeRecorder* recorder, double tapWeight)
{
  const int size = inputs.shadowMapWindow.width;
  const glm::dvec2 shifted = uvTexels - 0.5;
  const glm::dvec2 base = glm::floor(shifted);
  // The filtered result is continuous in the weights, so no texel-edge ambiguity here (only depth).
  const glm::dvec2 weight = shifted - base;
  double result = 0.0;
  for (int dj = 0; dj <= 1; ++dj)
  {
    for (int di = 0; di <= 1; ++di)
    {
      const int i = std::clamp(static_cast<int>(base.x) + di, 0, size - 1);
      const int j = std::clamp(static_cast<int>(base.y) + dj, 0, size - 1);
      const double stored = inputs.shadowMapWindow.at(i, j);
      sample.noteDepthComparison(referenceWindowDepth, stored);
      const double texelWeight = (di ? weight.x : 1.0 - weight.x) * (dj ? weight.y : 1.0 - weight.y);
      const bool lit = referenceWindowDepth <= stored;
      result += texelWeight * (lit ? 1.0 : 0.0);
      if (recorder)
      {
        // Window depths: the hardware compares in the depth buffer's units.
        recorder->texel({ { i, j }, "bilinear tap (window depth)", stored, referenceWindowDepth, !lit, texelWeight * tapWeight });
      }
    }
  }
  return result;
}

} // namespace

ReferenceSample pcfReference(const ShadowMapInputs& inputs, const ParameterValues& values, int x, int y,
  ProbeRecorder* recorder)
{
  const PcfSettings settings = PcfSettings::from(values);
  ShadowLookup lookup = prepareShadowLookup(inputs, settings.bias, x, y, recorder);
  ReferenceSample& sample = lookup.sample;
  if (!sample.evaluated)
  {
    return sample;
  }
  const bool hardware = settings.filter == PcfFilter::HardwareBilinear;
  const bool grid = settings.pattern == PcfPattern::Grid;
  const int kernelTexels = settings.kernelTexels;
  const int tapCount = grid ? kernelTexels * kernelTexels : settings.poissonSamples;
  const double referenceWindowDepth = inputs.lightView.windowDepth(lookup.comparisonDepth);
  if (recorder)
  {
    // The footprint: grid taps one texel apart centred on the receiver (or a disk of that diameter), each
    // reading the texel that holds it (nearest) or the 2x2 texels around it (bilinear: one texel more).
    const double footprint = kernelTexels + (hardware ? 1.0 : 0.0);
    recorder->beginGroup("kernel");
    recorder->quantity("kernel_texels", footprint, "texels", "Reeves et al. 1987 §3 (filter region); survey §6, Fig. 23");
    const glm::dvec3 pWs(inputs.position.at(x, y, 0), inputs.position.at(x, y, 1), inputs.position.at(x, y, 2));
    recorder->quantity("kernel_world_size",
      footprint * receiverTexelWorldSize(inputs.lightView, pWs, lookup.sm.depthLin), "world units",
      "ShadowLab: kernel_texels x one texel at the receiver (the warped texel's footprint under a warp)");
    recorder->quantity("taps", static_cast<double>(hardware ? 4 * tapCount : tapCount), "count",
      "Reeves et al. 1987 §3 (one depth comparison per sample; bilinear: 2x2 per tap)");
    recorder->category("pattern", grid ? "grid" : "rotated poisson disk", "ShadowLab (pattern); survey §6");
    recorder->category("filter", hardware ? "hardware_bilinear" : "nearest", "survey Fig. 23 (GL_LINEAR comparison)");
    recorder->kernel({ grid ? "pcf grid" : "pcf poisson disk (bounding square)", lookup.sm.uvTexels - 0.5 * footprint,
      lookup.sm.uvTexels + 0.5 * footprint, "", "Reeves et al. 1987 §3" });
    recorder->beginGroup("filter taps");
  }
  const double tapWeight = 1.0 / tapCount;
  const auto tap = [&](const glm::dvec2& offset) {
    const glm::dvec2 uv = lookup.sm.uvTexels + offset;
    return hardware ? bilinearCompare(inputs, uv, referenceWindowDepth, sample, recorder, tapWeight)
                    : nearestTexelTest(inputs, uv, lookup.comparisonDepth, sample, recorder, "filter tap", tapWeight);
  };
  double litSum = 0.0;
  if (grid)
  {
    const double firstOffset = -0.5 * (kernelTexels - 1);
    for (int j = 0; j < kernelTexels; ++j)
    {
      for (int i = 0; i < kernelTexels; ++i)
      {
        litSum += tap({ firstOffset + i, firstOffset + j });
      }
    }
  }
  else
  {
    const glm::dmat2 rotation = pixelRotation(x, y);
    const double radiusTexels = 0.5 * kernelTexels;
    for (int k = 0; k < tapCount; ++k)
    {
      litSum += tap(radiusTexels * (rotation * poissonDisk()[static_cast<std::size_t>(k)]));
    }
  }
  sample.visibility = litSum / tapCount;
  if (recorder)
  {
    recorder->beginGroup("result");
    recorder->quantity("lit_taps", litSum, "count", "Reeves et al. 1987 §3 (comparisons passed; bilinear: weighted)");
    recorder->quantity("visibility", sample.visibility, "", "Reeves et al. 1987 §3: lit taps / taps");
  }
  return sample;
}

} // namespace sl
