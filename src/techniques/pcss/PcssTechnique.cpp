#include "techniques/pcss/PcssTechnique.h"

#include "lightspace/shadowmap/ShadowMapStructure.h"

#include "techniques/SamplingPatterns.h"
#include "techniques/ShadowMapParameters.h"
#include "techniques/SoftShadowSupport.h"
#include "techniques/pcss/vtkSLPcssPass.h"

#include <algorithm>
#include <cmath>

namespace sl
{

TechniqueDescriptor pcssTechnique()
{
  TechniqueDescriptor descriptor;
  descriptor.name = "pcss";
  descriptor.title = "Percentage-closer soft shadows";
  descriptor.paper = "Fernando 2005; as in VSSM (Yang et al. 2010) §1 and Alg. 1 L7/L16";
  descriptor.parameters = shadowMapParameters();
  const std::vector<ParameterSpec> soft = softShadowParameters();
  descriptor.parameters.insert(descriptor.parameters.end(), soft.begin(), soft.end());
  descriptor.parameters.push_back(
    { "filter", 0, 0, 1, "", "grid: every texel of the penumbra kernel w_p (brute force); poisson: rotated Poisson taps", { "grid", "poisson" }, true });
  descriptor.lightStructures = { &shadowMapStructure() };
  descriptor.buffers = {
    { "blocker_kernel_texels", "texels", "width of the blocker search kernel w_i (Alg. 1 L7)" },
    { "blocker_samples", "taps", "depth samples read in the blocker search" },
    { "avg_blocker_depth", "world units", "average depth of the blockers found (0: none, lit)" },
    { "penumbra_width", "world units", "estimated penumbra width at the receiver, w_light (d - z_avg) / z_avg" },
    { "penumbra_kernel_texels", "texels", "width of the PCF kernel w_p (Alg. 1 L16)" },
    { "pcf_samples", "taps", "depth comparisons in the PCF step" },
    { "depth_bias", "world units", "depth bias applied at the pixel (constant + slope-scaled)" },
  };
  descriptor.supportedLights = { LightType::Area, LightType::Point, LightType::Spot };
  descriptor.coversLightArea = true;
  descriptor.createPass = [] { return vtkSmartPointer<vtkSLTechniquePass>(vtkSmartPointer<vtkSLPcssPass>::New()); };
  return descriptor;
}

namespace
{

struct Kernel
{
  glm::dvec2 origin;
  glm::dvec2 step;
  glm::ivec2 count;
};

// Mirrors kernelGrid() of PcssVisibility.glsl; records how close the kernel's edges are to texel centres.
Kernel kernelGrid(const glm::dvec2& uv, const glm::dvec2& halfTexels, int maxTaps, double& edgeMargin)
{
  Kernel kernel;
  for (int axis = 0; axis < 2; ++axis)
  {
    const double low = uv[axis] - halfTexels[axis] - 0.5;
    const double high = uv[axis] + halfTexels[axis] - 0.5;
    edgeMargin = std::min({ edgeMargin, std::abs(low - std::round(low)), std::abs(high - std::round(high)) });
    double first = std::ceil(low);
    double last = std::floor(high);
    if (last < first)
    {
      first = std::floor(uv[axis]);
      last = first;
    }
    const int dense = static_cast<int>(last - first) + 1;
    if (dense <= maxTaps)
    {
      kernel.origin[axis] = first + 0.5;
      kernel.step[axis] = 1.0;
      kernel.count[axis] = dense;
    }
    else
    {
      kernel.count[axis] = maxTaps;
      kernel.step[axis] = 2.0 * halfTexels[axis] / maxTaps;
      kernel.origin[axis] = uv[axis] - halfTexels[axis] + 0.5 * kernel.step[axis];
    }
  }
  return kernel;
}

} // namespace

PcssSample pcssReference(const ShadowMapInputs& inputs, const ParameterValues& values, int x, int y)
{
  PcssSample result;
  ShadowLookup lookup = prepareShadowLookup(inputs, biasSettings(values), x, y);
  result.sample = lookup.sample;
  if (!lookup.sample.evaluated)
  {
    return result;
  }
  const SoftShadowGeometry geometry =
    softShadowGeometry(inputs, lookup, values.choice("receiver_plane_bias") == "on", x, y);
  const int size = inputs.shadowMapLinear.width;
  const auto texel = [&](int i, int j) {
    return static_cast<double>(inputs.shadowMapLinear.at(std::clamp(i, 0, size - 1), std::clamp(j, 0, size - 1)));
  };
  const auto stored = [&](const glm::dvec2& uv) { return texel(static_cast<int>(std::floor(uv.x)), static_cast<int>(std::floor(uv.y))); };
  const double d = lookup.sm.depthLin;
  const double bias = lookup.sample.bias;
  const auto tapComparison = [&](const glm::dvec2& tap) { return geometry.tapComparisonDepth(tap, bias); };
  const glm::dvec2 uv = lookup.sm.uvTexels;
  const int maxTaps = values.getInt("max_grid_taps");
  const int poissonSamples = values.getInt("poisson_samples");
  const glm::dmat2 rotation = pixelRotation(x, y);
  const auto rotated = [&](int k) { return rotation * poissonDisk()[static_cast<std::size_t>(k)]; };
  // A tap within float rounding of a texel edge may read the neighbour on the GPU. That matters when the
  // neighbour decides differently, or (blocker search) holds a different depth for the average.
  const auto noteEdges = [&](const glm::dvec2& position, double comparedDepth, bool averagesDepth) {
    const TexelWithEdges cell = texelWithEdges(position);
    const double z = texel(cell.texel.x, cell.texel.y);
    for (const TexelEdge& edge : cell.edges)
    {
      if (edge.distance >= 1e-4)
      {
        continue;
      }
      const double neighbour = texel(edge.neighbour.x, edge.neighbour.y);
      const bool differentDecision = (neighbour < comparedDepth) != (z < comparedDepth);
      const bool differentDepth = averagesDepth && z < comparedDepth && std::abs(neighbour - z) > 1e-6 * std::abs(z);
      if (differentDecision || differentDepth)
      {
        result.sample.texelEdgeMargin = std::min(result.sample.texelEdgeMargin, edge.distance);
      }
    }
  };
  // 1. Blocker search.
  const glm::dvec2 searchHalf = geometry.kernelHalfTexels(geometry.nearDepth);
  result.blockerKernelTexels = 2.0 * std::max(searchHalf.x, searchHalf.y);
  double blockerSum = 0.0;
  int blockers = 0;
  const auto visitBlocker = [&](const glm::dvec2& position) {
    const double z = stored(position);
    const double compared = tapComparison(position);
    result.sample.noteDepthComparison(compared, z);
    noteEdges(position, compared, true);
    if (z < compared)
    {
      blockerSum += z;
      ++blockers;
    }
  };
  if (values.choice("blocker_search") == "grid")
  {
    const Kernel search = kernelGrid(uv, searchHalf, maxTaps, result.kernelEdgeMargin);
    for (int j = 0; j < search.count.y; ++j)
    {
      for (int i = 0; i < search.count.x; ++i)
      {
        visitBlocker(search.origin + glm::dvec2(i, j) * search.step);
      }
    }
  }
  else
  {
    for (int k = 0; k < poissonSamples; ++k)
    {
      visitBlocker(uv + searchHalf * rotated(k));
    }
  }
  result.uvTexels = uv;
  if (blockers == 0)
  {
    result.sample.visibility = 1.0;
    return result;
  }
  result.foundBlockers = true;

  // 2. Penumbra estimate.
  result.averageBlockerDepth = blockerSum / blockers;
  result.penumbraWidth = geometry.lightSize * (d - result.averageBlockerDepth) / result.averageBlockerDepth;
  const glm::dvec2 filterHalf = geometry.kernelHalfTexels(result.averageBlockerDepth);
  result.penumbraKernelTexels = 2.0 * std::max(filterHalf.x, filterHalf.y);
  result.filterHalfTexels = filterHalf;

  // 3. PCF.
  double litSum = 0.0;
  int taps = 0;
  const auto visitFilter = [&](const glm::dvec2& position) {
    const double z = stored(position);
    const double compared = tapComparison(position);
    result.sample.noteDepthComparison(compared, z);
    noteEdges(position, compared, false);
    litSum += compared <= z ? 1.0 : 0.0;
    ++taps;
  };
  const bool gridFilter = !values.has("filter") || values.choice("filter") == "grid";
  if (gridFilter)
  {
    const Kernel kernel = kernelGrid(uv, filterHalf, maxTaps, result.kernelEdgeMargin);
    for (int j = 0; j < kernel.count.y; ++j)
    {
      for (int i = 0; i < kernel.count.x; ++i)
      {
        visitFilter(kernel.origin + glm::dvec2(i, j) * kernel.step);
      }
    }
  }
  else
  {
    for (int k = 0; k < poissonSamples; ++k)
    {
      visitFilter(uv + filterHalf * rotated(k));
    }
  }
  result.sample.visibility = litSum / taps;
  return result;
}

} // namespace sl
