#include "techniques/pcf/PcfTechnique.h"

#include "lightspace/shadowmap/ShadowMapStructure.h"

#include "techniques/ShadowMapParameters.h"
#include "techniques/pcf/vtkSLPcfPass.h"

#include <algorithm>
#include <cmath>
#include <random>

namespace sl
{

TechniqueDescriptor pcfTechnique()
{
  TechniqueDescriptor descriptor;
  descriptor.name = "pcf";
  descriptor.title = "Percentage-closer filtering";
  descriptor.paper = "Reeves, Salesin & Cook 1987; survey (Scherzer et al. 2011) §6";
  descriptor.parameters = shadowMapParameters();
  descriptor.parameters.insert(descriptor.parameters.end(), {
    { "kernel_texels", 3, 1, 64, "texels", "filter width: grid side, or Poisson disk diameter", {}, true },
    { "pattern", 0, 0, 1, "", "tap layout: grid (every texel of the kernel) or poisson (rotated Poisson disk)", { "grid", "poisson" }, true },
    { "poisson_samples", 16, 1, maxPoissonSamples, "taps", "taps of the Poisson disk (pattern = poisson)", {}, true },
    { "filter", 0, 0, 1, "", "nearest: one comparison per tap; hardware_bilinear: the hardware's 2x2 bilinear comparison per tap (survey Fig. 23)", { "nearest", "hardware_bilinear" }, true },
  });
  descriptor.lightStructures = { &shadowMapStructure() };
  descriptor.buffers = {
    { "kernel_texels", "texels", "filter footprint width in shadow-map texels" },
    { "taps", "comparisons", "depth comparisons made for the pixel" },
    { "texel_ratio", "pixels/texel", "aliasing error m (survey Eq. 2): screen pixels spanned by one shadow-map texel along its most stretched direction; > 1 means undersampling" },
    { "depth_bias", "world units", "depth bias applied at the pixel (constant + slope-scaled)" },
  };
  descriptor.supportedLights = shadowMapLights();
  descriptor.createPass = [] { return vtkSmartPointer<vtkSLTechniquePass>(vtkSmartPointer<vtkSLPcfPass>::New()); };
  return descriptor;
}

namespace
{

// GL's linear filtering of comparisons (GL 4.5 §8.14.2, §8.23.1): sample at uv*size - 0.5, weights from
// the fraction, each of the 2x2 texels (clamped to the edge) compared with ref <= D.
double bilinearCompare(const ShadowMapInputs& inputs, const glm::dvec2& uvTexels, double referenceWindowDepth,
  ReferenceSample& sample)
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
      result += texelWeight * (referenceWindowDepth <= stored ? 1.0 : 0.0);
    }
  }
  return result;
}

} // namespace

ReferenceSample pcfReference(const ShadowMapInputs& inputs, const ParameterValues& values, int x, int y)
{
  ShadowLookup lookup = prepareShadowLookup(inputs, biasSettings(values), x, y);
  ReferenceSample& sample = lookup.sample;
  if (!sample.evaluated)
  {
    return sample;
  }
  const bool hardware = values.choice("filter") == "hardware_bilinear";
  const double referenceWindowDepth = inputs.lightView.windowDepth(lookup.comparisonDepth);
  const auto tap = [&](const glm::dvec2& offset) {
    const glm::dvec2 uv = lookup.sm.uvTexels + offset;
    return hardware ? bilinearCompare(inputs, uv, referenceWindowDepth, sample)
                    : nearestTexelTest(inputs, uv, lookup.comparisonDepth, sample);
  };
  const int kernelTexels = values.getInt("kernel_texels");
  double litSum = 0.0;
  int tapCount = 0;
  if (values.choice("pattern") == "grid")
  {
    const double firstOffset = -0.5 * (kernelTexels - 1);
    for (int j = 0; j < kernelTexels; ++j)
    {
      for (int i = 0; i < kernelTexels; ++i)
      {
        litSum += tap({ firstOffset + i, firstOffset + j });
      }
    }
    tapCount = kernelTexels * kernelTexels;
  }
  else
  {
    tapCount = values.getInt("poisson_samples");
    const glm::dmat2 rotation = pixelRotation(x, y);
    const double radiusTexels = 0.5 * kernelTexels;
    for (int k = 0; k < tapCount; ++k)
    {
      litSum += tap(radiusTexels * (rotation * poissonDisk()[static_cast<std::size_t>(k)]));
    }
  }
  sample.visibility = litSum / tapCount;
  return sample;
}

} // namespace sl
