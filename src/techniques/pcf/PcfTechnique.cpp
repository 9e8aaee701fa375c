#include "techniques/pcf/PcfTechnique.h"

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
  descriptor.lightStructures = { LightStructure::ShadowMap };
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

const std::vector<glm::dvec2>& poissonDisk()
{
  static const std::vector<glm::dvec2> disk = [] {
    // Mitchell's best-candidate sampling: each new point is the farthest of k candidates from the
    // points so far. std::mt19937's output sequence is fixed by the standard; the conversion to [0, 1)
    // is done here (not by a distribution, whose algorithm is implementation-defined).
    std::mt19937 generator(20091122u);
    const auto uniform = [&generator] { return static_cast<double>(generator() >> 8) * (1.0 / 16777216.0); };
    std::vector<glm::dvec2> points;
    while (static_cast<int>(points.size()) < maxPoissonSamples)
    {
      glm::dvec2 best(0.0);
      double bestDistance = -1.0;
      const int candidates = 10 * (static_cast<int>(points.size()) + 1);
      for (int c = 0; c < candidates; ++c)
      {
        const double radius = std::sqrt(uniform());
        const double angle = 6.283185307179586 * uniform();
        const glm::dvec2 candidate(radius * std::cos(angle), radius * std::sin(angle));
        double nearest = 1e300;
        for (const glm::dvec2& point : points)
        {
          nearest = std::min(nearest, glm::length(candidate - point));
        }
        if (nearest > bestDistance)
        {
          bestDistance = nearest;
          best = candidate;
        }
      }
      points.push_back(best);
    }
    return points;
  }();
  return disk;
}

std::uint32_t pixelHash(std::uint32_t x, std::uint32_t y)
{
  std::uint32_t v = x * 1664525u + y * 1013904223u;
  v ^= v >> 16;
  v *= 0x7feb352du;
  v ^= v >> 15;
  v *= 0x846ca68bu;
  v ^= v >> 16;
  return v;
}

double pixelHashAngle(std::uint32_t x, std::uint32_t y)
{
  return static_cast<double>(pixelHash(x, y)) * (6.283185307179586 / 4294967296.0);
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
      sample.depthMargin = std::min(sample.depthMargin, std::abs(referenceWindowDepth - stored) / std::max(1e-30, stored));
      const double texelWeight = (di ? weight.x : 1.0 - weight.x) * (dj ? weight.y : 1.0 - weight.y);
      result += texelWeight * (referenceWindowDepth <= stored ? 1.0 : 0.0);
    }
  }
  return result;
}

double windowDepth(const LightView& view, double depthLin)
{
  const glm::dvec4 clip = view.clipFromView * glm::dvec4(0.0, 0.0, -depthLin, 1.0);
  return 0.5 * clip.z / clip.w + 0.5;
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
  const double referenceWindowDepth = windowDepth(inputs.lightView, lookup.comparisonDepth);
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
    const double angle = pixelHashAngle(static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y));
    const double radiusTexels = 0.5 * kernelTexels;
    for (int k = 0; k < tapCount; ++k)
    {
      const glm::dvec2& point = poissonDisk()[static_cast<std::size_t>(k)];
      const glm::dvec2 rotated(std::cos(angle) * point.x - std::sin(angle) * point.y,
        std::sin(angle) * point.x + std::cos(angle) * point.y);
      litSum += tap(radiusTexels * rotated);
    }
  }
  sample.visibility = litSum / tapCount;
  return sample;
}

} // namespace sl
