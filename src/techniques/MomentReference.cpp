#include "techniques/MomentReference.h"

#include "core/Error.h"
#include "techniques/ApproximationRules.h"
#include "techniques/ProbeSupport.h"
#include "techniques/SoftShadowSupport.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sl
{
namespace
{


} // namespace

FilteredMoments boxMoments(const ShadowMapInputs& inputs, const glm::dvec2& uvTexels, int width, double exponent,
  ProbeRecorder* recorder)
{
  FilteredMoments moments;
  const double nearDepth = inputs.lightView.nearDepth;
  const double farDepth = inputs.lightView.farDepth;
  const double weight = 1.0 / (static_cast<double>(width) * width);
  visitPrefilterBox(inputs, uvTexels, width, [&](double z, const glm::ivec2& texel) {
    moments.mean += z;
    moments.second += z * z;
    moments.exponential += std::exp(exponent * std::clamp((z - nearDepth) / (farDepth - nearDepth), 0.0, 1.0));
    if (recorder)
    {
      recorder->texel({ texel, "moment box", z, std::numeric_limits<double>::quiet_NaN(), false, weight });
    }
  });
  const double count = static_cast<double>(width) * width;
  moments.mean /= count;
  moments.second /= count;
  moments.exponential /= count;
  return moments;
}

double boxPcf(const ShadowMapInputs& inputs, const glm::dvec2& uvTexels, double comparisonDepth, int width,
  ProbeRecorder* recorder)
{
  double lit = 0.0;
  const double weight = 1.0 / (static_cast<double>(width) * width);
  visitPrefilterBox(inputs, uvTexels, width, [&](double z, const glm::ivec2& texel) {
    lit += comparisonDepth <= z ? 1.0 : 0.0;
    if (recorder)
    {
      recorder->texel({ texel, "light-leak pcf", z, comparisonDepth, !(comparisonDepth <= z), weight });
    }
  });
  return lit / (static_cast<double>(width) * width);
}

PcfRange boxPcfRange(const ShadowMapInputs& inputs, const glm::dvec2& uvTexels, double comparisonDepth, int width,
  double relative)
{
  PcfRange range;
  const double weight = 1.0 / (static_cast<double>(width) * width);
  visitPrefilterBox(inputs, uvTexels, width, [&](double z, const glm::ivec2&) {
    if (std::abs(comparisonDepth - z) < relative * std::max(1e-30, std::abs(z)))
    {
      ++range.ties;
      range.highest += weight;
    }
    else if (comparisonDepth <= z)
    {
      range.lowest += weight;
      range.highest += weight;
    }
  });
  return range;
}

void recordLightLeak(ProbeRecorder& recorder, double value, double pcf, const PcfRange& range, const std::string& source)
{
  recorder.quantity("box_pcf", pcf, "", "Reeves et al. 1987: the true PCF over the same texels");
  recorder.quantity("light_leak_tied_comparisons", range.ties, "count",
    "ShadowLab: comparisons within float rounding (2e-6) of the compared depth, which the GPU may decide either way");
  if (range.ties == 0)
  {
    recorder.quantity("light_leak", value - pcf, "", source);
  }
  else
  {
    recorder.quantity("light_leak_range", glm::dvec2(value - range.highest, value - range.lowest), "",
      source + "; the tied comparisons decided either way");
  }
}

MomentPrefilterSettings MomentPrefilterSettings::from(const ParameterValues& values)
{
  MomentPrefilterSettings settings;
  settings.prefilter =
    choiceOf<MomentPrefilter>(values, "prefilter", { { "blur", MomentPrefilter::Blur }, { "mipmap", MomentPrefilter::Mipmap } });
  settings.texels = values.getInt("prefilter_texels");
  return settings;
}

void requireBlurPrefilter(const MomentPrefilterSettings& settings)
{
  if (settings.prefilter == MomentPrefilter::Mipmap)
  {
    throw InputError("--set prefilter=mipmap: probe replays the box blur only (the trilinear mip-map lookup has no "
                     "CPU twin); use prefilter=blur");
  }
}

void recordMomentBox(ProbeRecorder& recorder, const ShadowMapInputs& inputs, const ShadowLookup& lookup, int width)
{
  const int size = inputs.shadowMapLinear.width;
  const glm::dvec2 center = glm::clamp(glm::floor(lookup.sm.uvTexels), glm::dvec2(0.0), glm::dvec2(size - 1));
  const glm::dvec2 lo = center + static_cast<double>(-(width - 1) / 2);
  recorder.beginGroup("moments");
  recorder.quantity("kernel_texels", width, "texels", "Donnelly & Lauritzen 2006 (filter region; prefilter_texels)");
  recorder.quantity("kernel_world_size", width * inputs.lightView.texelWorldSize(lookup.sm.depthLin), "world units",
    "ShadowLab: kernel_texels x one texel at the receiver's depth");
  recorder.kernel({ "moment box", lo, lo + static_cast<double>(width), "blur",
    "Donnelly & Lauritzen 2006 (prefiltered moments: box blur centred on the receiver's texel)" });
}

void noteMomentTexelEdge(std::string& ambiguity, const glm::dvec2& uvTexels)
{
  const TexelWithEdges cell = texelWithEdges(uvTexels);
  double nearest = 1e300;
  for (const TexelEdge& edge : cell.edges)
  {
    nearest = std::min(nearest, edge.distance);
  }
  noteAmbiguity(ambiguity, "receiver from a texel edge of the moment map (texels)", nearest, probeTexelEdgeAmbiguity);
}

AccuracyContract prefilteredCentreShadowAccuracy()
{
  AccuracyContract accuracy;
  accuracy.reference = ReferenceModel::LightCentre;
  accuracy.tolerance = 1e-3;
  accuracy.approximations = { { "filtered edge", "the value lies strictly between 0 and 1 (by 1e-3)" },
    { "light bleeding", "the value exceeds the PCF over the same texels by more than 1e-3 (light_leak)" } };
  accuracy.markApproximations = [](const ApproximationContext& context, ImageF& codes) {
    markPartialVisibility(*context.frame, codes, 1.0f);
    markWhere(*context.frame, "light_leak", [](float leak) { return std::abs(leak) > 1e-3f; }, codes, 2.0f);
  };
  return accuracy;
}

ParameterSpec momentBiasParameter()
{
  return { "moment_bias", 3e-5, 1e-6, 0.1, "",
    "alpha of MSM Alg. 3: b' = (1 - alpha) b + alpha (0.5, 0.5, 0.5, 0.5), keeps the Hankel matrix definite "
    "against rounding; larger leaks more light", {}, false };
}

double rectanglePcf(const ShadowMapInputs& inputs, const SoftShadowGeometry& geometry, int maxGridTaps, double bias,
  glm::ivec2 lo, glm::ivec2 hi, PcfRange* range, ProbeRecorder* recorder)
{
  const int size = inputs.shadowMapLinear.width;
  glm::dvec2 origin(0.0);
  glm::dvec2 step(1.0);
  glm::ivec2 count(0);
  for (int axis = 0; axis < 2; ++axis)
  {
    const int texels = hi[axis] - lo[axis] + 1;
    if (texels <= maxGridTaps)
    {
      origin[axis] = lo[axis] + 0.5;
      step[axis] = 1.0;
      count[axis] = texels;
    }
    else
    {
      count[axis] = maxGridTaps;
      step[axis] = static_cast<double>(texels) / maxGridTaps;
      origin[axis] = lo[axis] + 0.5 * step[axis];
    }
  }
  const double weight = 1.0 / (static_cast<double>(count.x) * count.y);
  double lit = 0.0;
  for (int j = 0; j < count.y; ++j)
  {
    for (int i = 0; i < count.x; ++i)
    {
      const glm::dvec2 tap = origin + glm::dvec2(i, j) * step;
      const glm::ivec2 texel = glm::clamp(glm::ivec2(glm::floor(tap)), glm::ivec2(0), glm::ivec2(size - 1));
      const double z = inputs.shadowMapLinear.at(texel.x, texel.y);
      const double compared = geometry.tapComparisonDepth(tap, bias);
      lit += compared <= z ? 1.0 : 0.0;
      if (range)
      {
        const bool tie = std::abs(compared - z) < probeDepthAmbiguity * std::max(1e-30, std::abs(z));
        range->ties += tie ? 1 : 0;
        range->lowest += !tie && compared <= z ? weight : 0.0;
        range->highest += tie || compared <= z ? weight : 0.0;
      }
      if (recorder)
      {
        recorder->texel({ texel, "light-leak pcf", z, compared, !(compared <= z), weight });
      }
    }
  }
  return lit * weight;
}

} // namespace sl
