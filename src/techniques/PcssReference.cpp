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

// The shadow map as PcssVisibility.glsl's taps read it, for one receiver: each tap's stored depth and comparison
// depth, and the sample's margins (depth comparisons and texel edges within float rounding of their decision).
class PcssTaps
{
public:
  PcssTaps(const ShadowMapInputs& inputs, const SoftShadowSettings& settings, const ShadowLookup& lookup,
    const SoftShadowGeometry& geometry, glm::ivec2 pixel, PcssSample& result)
    : map_(inputs.shadowMapLinear)
    , geometry_(geometry)
    , bias_(lookup.sample.bias)
    , uv_(lookup.sm.uvTexels)
    , maxTaps_(settings.maxGridTaps)
    , poissonSamples_(settings.poissonSamples)
    , rotation_(pixelRotation(pixel.x, pixel.y))
    , result_(result)
  {
  }

  const glm::dvec2& uv() const { return uv_; }
  int poissonSamples() const { return poissonSamples_; }
  glm::ivec2 clampedTexel(const glm::dvec2& position) const
  {
    return glm::clamp(glm::ivec2(glm::floor(position)), glm::ivec2(0), glm::ivec2(map_.width - 1));
  }
  double stored(const glm::dvec2& position) const
  {
    return texel(static_cast<int>(std::floor(position.x)), static_cast<int>(std::floor(position.y)));
  }
  double comparison(const glm::dvec2& position) const { return geometry_.tapComparisonDepth(position, bias_); }

  // Notes a tap's comparison for the sample's margins. A tap within float rounding of a texel edge may read the
  // neighbour on the GPU: that matters when the neighbour decides differently, or (blocker search) holds a
  // different depth for the average.
  void noteTap(const glm::dvec2& position, double comparedDepth, double storedDepth, bool averagesDepth) const
  {
    result_.sample.noteDepthComparison(comparedDepth, storedDepth);
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
        result_.sample.texelEdgeMargin = std::min(result_.sample.texelEdgeMargin, edge.distance);
      }
    }
  }

  // The kernel's taps, as the shader takes them: every texel centre of the rectangle (a MAX_GRID_TAPS sub-grid
  // beyond) for `grid`, else the rotated Poisson disk stretched over it.
  template <typename Visit>
  void forEachTap(bool grid, const glm::dvec2& halfTexels, Visit visit) const
  {
    if (grid)
    {
      const Kernel kernel = kernelGrid(uv_, halfTexels, maxTaps_, result_.kernelEdgeMargin);
      for (int j = 0; j < kernel.count.y; ++j)
      {
        for (int i = 0; i < kernel.count.x; ++i)
        {
          visit(kernel.origin + glm::dvec2(i, j) * kernel.step);
        }
      }
      return;
    }
    for (int k = 0; k < poissonSamples_; ++k)
    {
      visit(uv_ + halfTexels * (rotation_ * poissonDisk()[static_cast<std::size_t>(k)]));
    }
  }
  int tapCount(bool grid, const glm::dvec2& halfTexels) const
  {
    if (!grid)
    {
      return poissonSamples_;
    }
    double unused = 1e300;
    const Kernel kernel = kernelGrid(uv_, halfTexels, maxTaps_, unused);
    return kernel.count.x * kernel.count.y;
  }

private:
  double texel(int i, int j) const
  {
    return static_cast<double>(map_.at(std::clamp(i, 0, map_.width - 1), std::clamp(j, 0, map_.height - 1)));
  }

  const ImageF& map_;
  const SoftShadowGeometry& geometry_;
  double bias_;
  glm::dvec2 uv_;
  int maxTaps_;
  int poissonSamples_;
  glm::dmat2 rotation_;
  PcssSample& result_;
};

// Blockers found in a kernel: the taps read, those in front of their comparison depth, and their depth sum.
struct BlockerSearch
{
  int taps = 0;
  int blockers = 0;
  double depthSum = 0.0;
};

// Step 1, searchBlockers() of SoftShadowKernels.glsl: the depths z < d - bias in w_i at the map's near plane
// (VSSM Alg. 1 L7; Fernando 2005 step 1).
BlockerSearch searchBlockers(const PcssTaps& taps, const SoftShadowGeometry& geometry, double d, bool grid,
  PcssSample& result, ProbeRecorder* recorder)
{
  const glm::dvec2 searchHalf = geometry.kernelHalfTexels(geometry.nearDepth);
  result.blockerKernelTexels = 2.0 * std::max(searchHalf.x, searchHalf.y);
  if (recorder)
  {
    recorder->beginGroup("blocker search");
    recorder->quantity("light_size", geometry.lightSize, "world units", "Fernando 2005 (w_light; 0 for point and spot lights)");
    recorder->quantity("search_plane_depth", geometry.nearDepth, "linear depth",
      "Alg. 1 L7, VSSM (Yang et al. 2010): the map's near plane, at the nearest caster");
    recorder->quantity("blocker_kernel_texels", result.blockerKernelTexels, "texels",
      "Alg. 1 L7, VSSM (Yang et al. 2010): w_i = w_light (d - z_near) / z_near, in texels");
    recorder->quantity("blocker_kernel_world_size", geometry.lightSize * (d - geometry.nearDepth) / d, "world units",
      "Alg. 1 L7, VSSM (Yang et al. 2010): w_i on the search plane, w_light (d - z_near) / d");
    recorder->kernel({ "blocker search", taps.uv() - searchHalf, taps.uv() + searchHalf, grid ? "grid" : "poisson",
      "Alg. 1 L7, VSSM (Yang et al. 2010); Fernando 2005 step 1" });
  }
  BlockerSearch search;
  taps.forEachTap(grid, searchHalf, [&](const glm::dvec2& position) {
    const double z = taps.stored(position);
    const double compared = taps.comparison(position);
    taps.noteTap(position, compared, z, true);
    ++search.taps;
    if (z < compared)
    {
      search.depthSum += z;
      ++search.blockers;
    }
    if (recorder)
    {
      recorder->texel({ taps.clampedTexel(position), "blocker search", z, compared, z < compared, 1.0 });
    }
  });
  if (recorder)
  {
    recorder->quantity("blocker_samples", search.taps, "count", "Fernando 2005 step 1 (depth samples read in w_i)");
    recorder->quantity("blockers_found", search.blockers, "count", "Fernando 2005 step 1 (samples with z < d - bias)");
  }
  return search;
}

// Step 2, the penumbra estimate by similar triangles (Fernando 2005 step 2; VSSM Alg. 1 L16): z_avg, the penumbra
// width at the receiver and the kernel w_p at z_avg.
void estimatePenumbra(const PcssTaps& taps, const SoftShadowGeometry& geometry, double d, const BlockerSearch& search,
  PcssSample& result, ProbeRecorder* recorder)
{
  result.averageBlockerDepth = search.depthSum / search.blockers;
  result.penumbraWidth = geometry.lightSize * (d - result.averageBlockerDepth) / result.averageBlockerDepth;
  result.filterHalfTexels = geometry.kernelHalfTexels(result.averageBlockerDepth);
  result.penumbraKernelTexels = 2.0 * std::max(result.filterHalfTexels.x, result.filterHalfTexels.y);
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
    recorder->kernel({ "penumbra", taps.uv() - result.filterHalfTexels, taps.uv() + result.filterHalfTexels, "w_p",
      "Alg. 1 L16, VSSM (Yang et al. 2010); Fernando 2005 step 2" });
  }
}

// Step 3, PCF over w_p (Fernando 2005 step 3): the lit taps' share.
double filterPenumbra(const PcssTaps& taps, bool grid, const glm::dvec2& filterHalf, ProbeRecorder* recorder)
{
  // The weight each recorded tap shows (the probe only): the kernel counted once more, off the tests' pixel loops.
  const int filterTaps = recorder ? taps.tapCount(grid, filterHalf) : 0;
  if (recorder)
  {
    recorder->beginGroup("filter");
  }
  double litSum = 0.0;
  int tapsRead = 0;
  taps.forEachTap(grid, filterHalf, [&](const glm::dvec2& position) {
    const double z = taps.stored(position);
    const double compared = taps.comparison(position);
    taps.noteTap(position, compared, z, false);
    litSum += compared <= z ? 1.0 : 0.0;
    ++tapsRead;
    if (recorder)
    {
      recorder->texel({ taps.clampedTexel(position), "filter tap", z, compared, !(compared <= z), 1.0 / filterTaps });
    }
  });
  const double visibility = litSum / tapsRead;
  if (recorder)
  {
    recorder->quantity("pcf_samples", tapsRead, "count", "Fernando 2005 step 3 (PCF comparisons over w_p)");
    recorder->beginGroup("result");
    recorder->quantity("visibility", visibility, "", "Fernando 2005 step 3: lit taps / taps");
  }
  return visibility;
}

} // namespace

PcssSettings PcssSettings::from(const ParameterValues& values)
{
  PcssSettings settings;
  settings.bias = biasSettings(values);
  settings.soft = SoftShadowSettings::from(values);
  settings.filter = values.has("filter") ? tapPatternOf(values, "filter") : TapPattern::Grid;
  return settings;
}

PcssSample pcssReference(const ShadowMapInputs& inputs, const PcssSettings& settings, int x, int y,
  ProbeRecorder* recorder, bool recordFilter)
{
  PcssSample result;
  ShadowLookup lookup = prepareShadowLookup(inputs, settings.bias, x, y, recorder);
  result.sample = lookup.sample;
  if (!lookup.sample.evaluated)
  {
    return result;
  }
  const bool receiverPlane = settings.soft.receiverPlaneBias;
  const SoftShadowGeometry geometry = softShadowGeometry(inputs, lookup, receiverPlane, x, y);
  const PcssTaps taps(inputs, settings.soft, lookup, geometry, { x, y }, result);
  const double d = lookup.sm.depthLin;
  result.uvTexels = lookup.sm.uvTexels;
  if (recorder)
  {
    recorder->category("receiver_plane_bias", receiverPlane ? "on: each tap compares against the receiver's tangent plane" : "off: one comparison depth per pixel",
      "Isidoro 2006 (receiver plane depth bias)");
  }

  const BlockerSearch search =
    searchBlockers(taps, geometry, d, settings.soft.blockerSearch == TapPattern::Grid, result, recorder);
  if (search.blockers == 0)
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
  estimatePenumbra(taps, geometry, d, search, result, recorder);
  const bool gridFilter = settings.filter == TapPattern::Grid;
  result.sample.visibility = filterPenumbra(taps, gridFilter, result.filterHalfTexels, recordFilter ? recorder : nullptr);
  return result;
}

} // namespace sl
