#include "techniques/PcssReference.h"

#include "techniques/ProbeSupport.h"
#include "techniques/SamplingPatterns.h"
#include "techniques/ShadowMapParameters.h"
#include "techniques/SoftShadowSupport.h"

#include <algorithm>
#include <cmath>

namespace sl
{
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

PcssSample pcssReference(const ShadowMapInputs& inputs, const ParameterValues& values, int x, int y,
  ProbeRecorder* recorder, bool recordFilter)
{
  PcssSample result;
  ShadowLookup lookup = prepareShadowLookup(inputs, biasSettings(values), x, y, recorder);
  result.sample = lookup.sample;
  if (!lookup.sample.evaluated)
  {
    return result;
  }
  const bool receiverPlane = values.choice("receiver_plane_bias") == "on";
  const SoftShadowGeometry geometry = softShadowGeometry(inputs, lookup, receiverPlane, x, y);
  const int size = inputs.shadowMapLinear.width;
  const auto clampedTexel = [&](const glm::dvec2& uv) {
    return glm::clamp(glm::ivec2(glm::floor(uv)), glm::ivec2(0), glm::ivec2(size - 1));
  };
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
  const bool gridSearch = values.choice("blocker_search") == "grid";
  // 1. Blocker search.
  const glm::dvec2 searchHalf = geometry.kernelHalfTexels(geometry.nearDepth);
  result.blockerKernelTexels = 2.0 * std::max(searchHalf.x, searchHalf.y);
  if (recorder)
  {
    recorder->category("receiver_plane_bias", receiverPlane ? "on: each tap compares against the receiver's tangent plane" : "off: one comparison depth per pixel",
      "Isidoro 2006 (receiver plane depth bias)");
    recorder->beginGroup("blocker search");
    recorder->quantity("light_size", geometry.lightSize, "world units", "Fernando 2005 (w_light; 0 for point and spot lights)");
    recorder->quantity("search_plane_depth", geometry.nearDepth, "linear depth",
      "Alg. 1 L7, VSSM (Yang et al. 2010): the map's near plane, at the nearest caster");
    recorder->quantity("blocker_kernel_texels", result.blockerKernelTexels, "texels",
      "Alg. 1 L7, VSSM (Yang et al. 2010): w_i = w_light (d - z_near) / z_near, in texels");
    recorder->quantity("blocker_kernel_world_size", geometry.lightSize * (d - geometry.nearDepth) / d, "world units",
      "Alg. 1 L7, VSSM (Yang et al. 2010): w_i on the search plane, w_light (d - z_near) / d");
    recorder->kernel({ "blocker search", uv - searchHalf, uv + searchHalf, gridSearch ? "grid" : "poisson",
      "Alg. 1 L7, VSSM (Yang et al. 2010); Fernando 2005 step 1" });
  }
  double blockerSum = 0.0;
  int blockers = 0;
  int searchTaps = 0;
  const auto visitBlocker = [&](const glm::dvec2& position) {
    const double z = stored(position);
    const double compared = tapComparison(position);
    result.sample.noteDepthComparison(compared, z);
    noteEdges(position, compared, true);
    ++searchTaps;
    if (z < compared)
    {
      blockerSum += z;
      ++blockers;
    }
    if (recorder)
    {
      recorder->texel({ clampedTexel(position), "blocker search", z, compared, z < compared, 1.0 });
    }
  };
  if (gridSearch)
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
  if (recorder)
  {
    recorder->quantity("blocker_samples", searchTaps, "count", "Fernando 2005 step 1 (depth samples read in w_i)");
    recorder->quantity("blockers_found", blockers, "count", "Fernando 2005 step 1 (samples with z < d - bias)");
  }
  if (blockers == 0)
  {
    result.sample.visibility = 1.0;
    if (recorder)
    {
      recorder->beginGroup("result");
      recorder->quantity("visibility", 1.0, "", "Fernando 2005 step 1: no blocker in w_i, fully lit");
    }
    return result;
  }
  result.foundBlockers = true;

  // 2. Penumbra estimate.
  result.averageBlockerDepth = blockerSum / blockers;
  result.penumbraWidth = geometry.lightSize * (d - result.averageBlockerDepth) / result.averageBlockerDepth;
  const glm::dvec2 filterHalf = geometry.kernelHalfTexels(result.averageBlockerDepth);
  result.penumbraKernelTexels = 2.0 * std::max(filterHalf.x, filterHalf.y);
  result.filterHalfTexels = filterHalf;
  if (recorder)
  {
    recorder->beginGroup("penumbra estimate");
    recorder->quantity("avg_blocker_depth", result.averageBlockerDepth, "linear depth",
      "Fernando 2005 step 1 (average of the blockers' depths, z_avg)");
    recorder->quantity("penumbra_width", result.penumbraWidth, "world units",
      "Fernando 2005 step 2 (penumbra estimate): w_penumbra = (d_receiver - d_blocker) w_light / d_blocker");
    recorder->quantity("penumbra_kernel_texels", result.penumbraKernelTexels, "texels",
      "Alg. 1 L16, VSSM (Yang et al. 2010): w_p = w_light (d - z_avg) / z_avg, in texels");
    recorder->quantity("penumbra_kernel_world_size", geometry.lightSize * (d - result.averageBlockerDepth) / d,
      "world units", "Alg. 1 L16, VSSM (Yang et al. 2010): w_p on the plane at z_avg, w_light (d - z_avg) / d");
    recorder->kernel({ "penumbra", uv - filterHalf, uv + filterHalf, "w_p",
      "Alg. 1 L16, VSSM (Yang et al. 2010); Fernando 2005 step 2" });
  }

  // 3. PCF.
  const bool gridFilter = !values.has("filter") || values.choice("filter") == "grid";
  const Kernel kernel = gridFilter ? kernelGrid(uv, filterHalf, maxTaps, result.kernelEdgeMargin) : Kernel{};
  const int filterTaps = gridFilter ? kernel.count.x * kernel.count.y : poissonSamples;
  ProbeRecorder* filterRecorder = recordFilter ? recorder : nullptr;
  if (filterRecorder)
  {
    filterRecorder->beginGroup("filter");
  }
  double litSum = 0.0;
  int taps = 0;
  const auto visitFilter = [&](const glm::dvec2& position) {
    const double z = stored(position);
    const double compared = tapComparison(position);
    result.sample.noteDepthComparison(compared, z);
    noteEdges(position, compared, false);
    litSum += compared <= z ? 1.0 : 0.0;
    ++taps;
    if (filterRecorder)
    {
      filterRecorder->texel({ clampedTexel(position), "filter tap", z, compared, !(compared <= z), 1.0 / filterTaps });
    }
  };
  if (gridFilter)
  {
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
  if (filterRecorder)
  {
    filterRecorder->quantity("pcf_samples", taps, "count", "Fernando 2005 step 3 (PCF comparisons over w_p)");
    filterRecorder->beginGroup("result");
    filterRecorder->quantity("visibility", result.sample.visibility, "", "Fernando 2005 step 3: lit taps / taps");
  }
  return result;
}

} // namespace sl
