#include "techniques/lvsm/LvsmTechnique.h"

#include "lightspace/LayeredMoments.h"
#include "structures/layeredmoments/LayeredMomentsStructure.h"
#include "structures/moments/MomentMapStructure.h"
#include "structures/shadowmap/ShadowMapStructure.h"

#include "techniques/MomentReference.h"
#include "techniques/ProbeSupport.h"
#include "techniques/ShadowMapParameters.h"
#include "techniques/lvsm/vtkSLLvsmPass.h"

#include "core/Error.h"
#include "frame/FrameResult.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sl
{

LvsmSettings LvsmSettings::from(const ParameterValues& values)
{
  LvsmSettings settings;
  settings.bias = biasSettings(values);
  settings.layers = values.getInt("layers");
  settings.layerBound =
    choiceOf<LvsmLayerBound>(values, "layer_bound", { { "own", LvsmLayerBound::Own }, { "tightest", LvsmLayerBound::Tightest } });
  settings.layerPlacement = LayeredMomentsSettings::from(values).placement;
  settings.prefilterTexels = values.getInt("prefilter_texels");
  settings.lightBleedingReduction = values.get("light_bleeding_reduction");
  settings.minVariance = values.get("min_variance");
  return settings;
}

LvsmSettings lvsmSettingsOf(const FrameResult& frame)
{
  LvsmSettings settings = LvsmSettings::from(frame.parameters);
  settings.layerEnds = layeredEndsOf(frame.techniqueStatistics);
  return settings;
}

std::vector<double> lvsmLayerEnds(const ShadowMapInputs& inputs, const LvsmSettings& settings)
{
  if (settings.layerEnds.empty())
  {
    SL_CHECK_MSG(settings.layerPlacement == LayerPlacement::Uniform,
      "layer_placement=gaps: the twin needs the frame's layer ends (lvsmSettingsOf)");
    return layeredUniformEnds(settings.layers, inputs.lightView.nearDepth, inputs.lightView.farDepth);
  }
  SL_CHECK_MSG(static_cast<int>(settings.layerEnds.size()) == settings.layers + 1, "lvsm: ", settings.layerEnds.size(),
    " layer ends for ", settings.layers, " layers");
  return settings.layerEnds;
}

TechniqueDescriptor lvsmTechnique()
{
  TechniqueDescriptor descriptor = describeShadowMapTechnique("lvsm", "Layered variance shadow maps",
    "Lauritzen & McCool 2008 (GI 2008); survey §6");
  for (ParameterSpec& spec : descriptor.parameters)
  {
    // As vsm: Chebyshev's bound compares the receiver's own depth (a bias would inflate p_max).
    if (spec.name == "bias_constant_texels" || spec.name == "bias_slope_texels")
    {
      spec.defaultValue = 0.0;
    }
  }
  descriptor.addParameters(layeredMomentsStructure().parameters);
  // The box the layers are blurred over and where: the moment map's prefilter_texels and prefilter_region
  // (LayeredMomentsSettings).
  for (const ParameterSpec& spec : momentMapStructure().parameters)
  {
    if (spec.name == "prefilter_texels" || spec.name == "prefilter_region")
    {
      descriptor.addParameters({ spec });
    }
  }
  descriptor.addParameters({
    { "layer_bound", 1, 0, 1, "", "which Chebyshev bound a receiver takes: own, its own layer's (Lauritzen & McCool 2008); tightest (ShadowLab's extension), the least of every layer's bound at its warped depth and vsm's bound on the unwarped depths of the same box, still an upper bound of the lit fraction (README.md)", { "own", "tightest" }, true },
    { "light_bleeding_reduction", 0.2, 0, 0.99, "", "p_max below this amount becomes 0 and [amount, 1] maps to [0, 1] (Lauritzen 2007), as vsm", {}, false },
    { "min_variance", 1e-6, 0, 0.01, "d^2", "floor of the variance, relative to the squared receiver depth in linear depth; rescaled by 1 / (q_i - p_i)^2 into the layer's warped units", {}, false },
  });
  descriptor.lightStructures = { &shadowMapStructure(), &layeredMomentsStructure() };
  descriptor.buffers = {
    { "p_max", "", "Chebyshev upper bound on the warped depths of the receiver's layer, before light-bleeding reduction" },
    onShadowTestedPixels({ "light_leak", "", "p_max minus pcf over the same box of texels (pcf's default bias): > 0 where LVSM bleeds light", BufferKind::Signed }),
    { "layer", "", "the depth layer the receiver read (0 nearest the light; -1 no shadow test)" },
    { "warped_depth", "", "the receiver's depth warped into its layer, phi_i(t) in [0, 1]" },
    { "clamped_above_vsm", "", "1 where the box holds depths in front of the receiver's layer (clamped onto its near end) and the layered bound exceeds vsm's by more than 0.05" },
    categoricalBuffer("vsm_comparison",
      "where vsm leaks more than 0.05 against the same PCF: whether lvsm leaks less, and if not why (README.md)",
      lvsmVsmComparisonCategories),
    depthBiasBuffer(),
  };
  for (BufferSpec& buffer : descriptor.buffers)
  {
    if (buffer.name == "clamped_above_vsm")
    {
      buffer.flagAtOrAbove = 1.0;
      buffer.flagWarning = "the layered bound exceeds vsm's by more than 0.05 where depths in front of the receiver's "
                           "layer are clamped onto its near end, toward the receiver "
                           "(src/techniques/lvsm/README.md, \"Where layering cannot help\")";
    }
    if (buffer.name == "vsm_comparison")
    {
      buffer.flagAtOrAbove = static_cast<double>(LvsmVsmComparison::SameLayer);
      buffer.flagWarning = "where vsm leaks more than 0.05, the layered bound leaks as much or more: the box lies in one "
                           "layer, both bounds are 1, no layer's bound is below vsm's (layer_bound=tightest), or depths in front of the "
                           "layer were clamped toward the receiver "
                           "(src/techniques/lvsm/README.md, \"Where layering cannot help\")";
    }
  }
  descriptor.lightSpaceRequest = [](const ParameterValues& values) {
    return LightSpaceRequest{ "prefilter_texels", static_cast<double>(LvsmSettings::from(values).prefilterTexels) };
  };
  descriptor.createPass = [] { return vtkSmartPointer<vtkSLTechniquePass>(vtkSmartPointer<vtkSLLvsmPass>::New()); };
  descriptor.probe = [](const ProbeContext& context, glm::ivec2 pixel, ProbeRecorder& recorder) {
    const LvsmSettings settings = lvsmSettingsOf(*context.frame);
    const ShadowMapInputs inputs = shadowMapInputsOf(*context.frame, *context.scene, context.lightIndex);
    const LvsmSample sample = lvsmReference(inputs, settings, pixel.x, pixel.y, &recorder);
    // LvsmTest.MatchesTheCpuTwin: within 2e-3 at every pixel but those at a texel edge of the map or a layer boundary
    // (the warped moments lie in [0, 1] and need no exclusion for small variance, unlike vsm's).
    ProbeOutcome outcome =
      probeOutcome(sample.sample, 2e-3, "lvsmReference (lvsm/LvsmTechnique.h), double precision");
    if (sample.sample.evaluated)
    {
      const ShadowLookup lookup = prepareShadowLookup(inputs, settings.bias, pixel.x, pixel.y);
      noteMomentTexelEdge(outcome.ambiguity, lookup.sm.uvTexels);
      double fromBoundary = 1e300;
      for (const double end : lvsmLayerEnds(inputs, settings))
      {
        fromBoundary = std::min(fromBoundary, std::abs(lookup.comparisonDepth - end));
      }
      noteAmbiguity(outcome.ambiguity, "receiver depth from a layer boundary (layers, layer_placement)",
        fromBoundary / (inputs.lightView.farDepth - inputs.lightView.nearDepth), 1e-5);
    }
    return outcome;
  };
  descriptor.accuracy = prefilteredCentreShadowAccuracy();
  return descriptor;
}

FilteredMoments layeredBoxMoments(const ShadowMapInputs& inputs, const glm::dvec2& uvTexels, int width, int layer,
  int layers, ProbeRecorder* recorder)
{
  return layeredBoxMoments(inputs, uvTexels, width,
    depthLayer(layer, layers, inputs.lightView.nearDepth, inputs.lightView.farDepth), recorder);
}

FilteredMoments layeredBoxMoments(const ShadowMapInputs& inputs, const glm::dvec2& uvTexels, int width,
  const DepthLayer& interval, ProbeRecorder* recorder)
{
  const double weight = 1.0 / (static_cast<double>(width) * width);
  FilteredMoments moments;
  visitPrefilterBox(inputs, uvTexels, width, [&](double z, const glm::ivec2& texel) {
    const double warped = warpIntoLayer(z, interval);
    moments.mean += warped * weight;
    moments.second += warped * warped * weight;
    if (recorder)
    {
      recorder->texel({ texel, "moment box", z, std::numeric_limits<double>::quiet_NaN(), false, weight });
    }
  });
  return moments;
}

LvsmVsmComparison lvsmVsmComparison(const LvsmSample& sample)
{
  const double vsmLeak = sample.vsmPMax - sample.pcf;
  if (!sample.sample.evaluated || !(vsmLeak > lvsmVsmLeakThreshold))
  {
    return LvsmVsmComparison::VsmBelowThreshold;
  }
  if (sample.texelsInFront + sample.texelsBehind == 0)
  {
    return LvsmVsmComparison::SameLayer;
  }
  if (sample.pMax >= 1.0 && sample.vsmPMax >= 1.0)
  {
    return LvsmVsmComparison::Saturated;
  }
  if (sample.lightLeak < vsmLeak)
  {
    return LvsmVsmComparison::LeaksLess;
  }
  // layer_bound=tightest (layerPMax filled): p_max is vsm's bound, no layer's is lower.
  if (!sample.layerPMax.empty() && sample.pMax >= sample.vsmPMax)
  {
    return LvsmVsmComparison::VsmBoundTightest;
  }
  return sample.texelsInFront > 0 ? LvsmVsmComparison::ClampedInFront : LvsmVsmComparison::Unexplained;
}

LvsmSample lvsmReference(const ShadowMapInputs& inputs, const LvsmSettings& settings, int x, int y,
  ProbeRecorder* recorder)
{
  LvsmSample result;
  const ShadowLookup lookup = prepareShadowLookup(inputs, settings.bias, x, y, recorder);
  result.sample = lookup.sample;
  if (!lookup.sample.evaluated)
  {
    return result;
  }
  const int width = settings.prefilterTexels;
  const double t = lookup.comparisonDepth;
  const double d = lookup.sm.depthLin;
  const std::vector<double> ends = lvsmLayerEnds(inputs, settings);
  result.layer = depthLayerIndex(t, ends);
  const DepthLayer interval = depthLayer(result.layer, ends);
  result.layerNear = interval.nearEnd;
  result.layerFar = interval.farEnd;
  result.warpedDepth = warpIntoLayer(t, interval);
  if (recorder)
  {
    recordMomentBox(*recorder, inputs, lookup, width);
  }
  const FilteredMoments moments = layeredBoxMoments(inputs, lookup.sm.uvTexels, width, interval, recorder);
  result.mean = moments.mean;
  result.second = moments.second;
  // Chebyshev's one-tailed bound on layer `layer`'s moments at phi_j(t), with vsm's floor rescaled into its units
  // (phi_j is affine inside the layer, slope 1 / (q_j - p_j)).
  const auto layerBound = [&](const DepthLayer& layer, const FilteredMoments& layerMoments, double* floorOut,
                            double* varianceOut) {
    const double varianceFloor = settings.minVariance * d * d / (layer.width() * layer.width());
    const double variance = std::max(layerMoments.second - layerMoments.mean * layerMoments.mean, varianceFloor);
    const double warped = warpIntoLayer(t, layer);
    if (floorOut)
    {
      *floorOut = varianceFloor;
      *varianceOut = variance;
    }
    return warped <= layerMoments.mean ? 1.0
                                       : variance / (variance + (warped - layerMoments.mean) * (warped - layerMoments.mean));
  };
  result.ownPMax = layerBound(interval, moments, &result.varianceFloor, &result.variance);
  const double warpedT = result.warpedDepth;
  // vsm's bound over the same box (the comparison of vsm_comparison; with layer_bound=tightest also a candidate).
  {
    const FilteredMoments plain = boxMoments(inputs, lookup.sm.uvTexels, width, 0.0);
    const double variance = std::max(plain.second - plain.mean * plain.mean, settings.minVariance * d * d);
    result.vsmPMax = t <= plain.mean ? 1.0 : variance / (variance + (t - plain.mean) * (t - plain.mean));
    // The box's depths outside the layer (clamped by phi_i).
    visitPrefilterBox(inputs, lookup.sm.uvTexels, width, [&](double z, const glm::ivec2&) {
      result.texelsInFront += z < interval.nearEnd ? 1 : 0;
      result.texelsBehind += z > interval.farEnd ? 1 : 0;
    });
  }
  result.pMax = result.ownPMax;
  result.boundSource = result.layer;
  if (settings.layerBound == LvsmLayerBound::Tightest)
  {
    // Every phi_j is monotone: z >= t implies phi_j(z) >= phi_j(t), so P(z >= t) <= P(phi_j(z) >= phi_j(t)), which
    // Chebyshev bounds on layer j's moments; the least of these bounds and vsm's still bounds the lit fraction
    // (README.md, "Bound from several layers"; ours, not LM08's). Same order and ties as the shader.
    result.layerPMax.assign(static_cast<std::size_t>(settings.layers), 1.0);
    for (int j = 0; j < settings.layers; ++j)
    {
      if (j == result.layer)
      {
        result.layerPMax[static_cast<std::size_t>(j)] = result.ownPMax;
        continue;
      }
      const DepthLayer other = depthLayer(j, ends);
      const double bound =
        layerBound(other, layeredBoxMoments(inputs, lookup.sm.uvTexels, width, other), nullptr, nullptr);
      result.layerPMax[static_cast<std::size_t>(j)] = bound;
      if (bound < result.pMax)
      {
        result.pMax = bound;
        result.boundSource = j;
      }
    }
    if (result.vsmPMax < result.pMax)
    {
      result.pMax = result.vsmPMax;
      result.boundSource = -1;
    }
  }
  const double amount = settings.lightBleedingReduction;
  result.sample.visibility = std::clamp((result.pMax - amount) / (1.0 - amount), 0.0, 1.0);
  if (recorder)
  {
    recorder->beginGroup("layer");
    recorder->quantity("layer", result.layer, "", "Lauritzen & McCool 2008: the layer whose interval holds the receiver's depth");
    recorder->quantity("layer_interval", glm::dvec2(interval.nearEnd, interval.farEnd), "linear depth",
      "Lauritzen & McCool 2008: [p_i, q_i], disjoint intervals of the light's depth range");
    recorder->quantity("layer_placement", settings.layerPlacement == LayerPlacement::Gaps ? 1.0 : 0.0, "code",
      settings.layerPlacement == LayerPlacement::Gaps
        ? "ShadowLab: boundaries in the widest empty runs of the depth histogram (layeredGapEnds)"
        : "uniform: equal intervals of [near, far]");
    for (std::size_t i = 0; i < ends.size(); ++i)
    {
      recorder->quantity(format("layer_end_", i), ends[i], "linear depth", "the layers' ends, as the shader receives them");
    }
    recorder->quantity("compared_depth", t, "linear depth", "the receiver's depth minus the bias (0 by default, as vsm)");
    recorder->quantity("warped_depth", warpedT, "", "Lauritzen & McCool 2008: phi_i(t) = (t - p_i) / (q_i - p_i)");
    recorder->beginGroup("moments");
    recorder->quantity("mean", moments.mean, "warped depth", "Lauritzen & McCool 2008: E[phi_i(z)] over the box");
    recorder->quantity("second_moment", moments.second, "warped depth^2", "Lauritzen & McCool 2008: E[phi_i(z)^2]");
    recorder->quantity("variance_unfloored", moments.second - moments.mean * moments.mean, "warped depth^2",
      "Donnelly & Lauritzen 2006: sigma^2 = E[z^2] - E[z]^2, of the warped depths");
    recorder->quantity("variance_floor", result.varianceFloor, "warped depth^2",
      "ShadowLab (min_variance): min_variance d^2 / (q_i - p_i)^2, vsm's floor in the layer's units");
    recorder->quantity("variance", result.variance, "warped depth^2", "the floored variance");
    recorder->beginGroup("chebyshev");
    recorder->quantity("own_layer_p_max", result.ownPMax, "",
      "Donnelly & Lauritzen 2006 on the warped depths: sigma^2 / (sigma^2 + (phi_i(t) - mu)^2) for phi_i(t) > mu, else 1");
    for (std::size_t j = 0; j < result.layerPMax.size(); ++j)
    {
      recorder->quantity(format("layer", j, "_p_max"), result.layerPMax[j], "",
        "ShadowLab (layer_bound=tightest): layer j's bound at phi_j(t), floor rescaled into its units");
    }
    recorder->quantity("bound_source", result.boundSource, "layer",
      settings.layerBound == LvsmLayerBound::Tightest
        ? "layer_bound=tightest: the layer whose bound is p_max, -1 where vsm's bound is the least"
        : "layer_bound=own: the receiver's layer");
    recorder->quantity("p_max", result.pMax, "",
      settings.layerBound == LvsmLayerBound::Tightest
        ? "ShadowLab: min(every layer's bound, vsm's bound): an upper bound of the lit fraction (README.md)"
        : "Lauritzen & McCool 2008: the own layer's bound");
    recorder->quantity("light_bleeding_reduction", amount, "", "Lauritzen 2007 (GPU Gems 3 ch. 8): [amount, 1] -> [0, 1]");
    recorder->quantity("visibility", result.sample.visibility, "", "Lauritzen 2007: clamp((p_max - amount) / (1 - amount), 0, 1)");
    recorder->quantity("vsm_p_max", result.vsmPMax, "", "Donnelly & Lauritzen 2006: vsm's bound on the unwarped depths of the same box");
    recorder->beginGroup("light leak");
  }
  // The leak's PCF compares as `pcf` does (its default bias), as vsm's light_leak.
  const double leakDepth = prepareShadowLookup(inputs, defaultBiasSettings(), x, y).comparisonDepth;
  result.pcf = boxPcf(inputs, lookup.sm.uvTexels, leakDepth, width, recorder);
  result.lightLeak = result.pMax - result.pcf;
  result.comparison = lvsmVsmComparison(result);
  result.clampedAboveVsm = result.texelsInFront > 0 && result.pMax > result.vsmPMax + lvsmVsmLeakThreshold;
  if (recorder)
  {
    recordLightLeak(*recorder, result.pMax, result.pcf,
      boxPcfRange(inputs, lookup.sm.uvTexels, leakDepth, width, probeDepthAmbiguity),
      "Lauritzen 2007 (light bleeding): p_max - PCF over the same box");
    recorder->beginGroup("vsm comparison");
    recorder->quantity("vsm_light_leak", result.vsmPMax - result.pcf, "", "vsm's p_max - PCF over the same box");
    recorder->quantity("texels_in_front_of_layer", result.texelsInFront, "count", "Lauritzen & McCool 2008: z < p_i, clamped to phi = 0");
    recorder->quantity("texels_behind_layer", result.texelsBehind, "count", "Lauritzen & McCool 2008: z > q_i, clamped to phi = 1");
    recorder->quantity("clamped_above_vsm", result.clampedAboveVsm ? 1.0 : 0.0, "",
      "ShadowLab: depths in front of the layer clamped onto its near end and p_max above vsm's by more than 0.05");
    recorder->quantity("vsm_comparison", static_cast<double>(result.comparison), "code",
      lvsmVsmComparisonCategories[static_cast<int>(result.comparison)].label);
  }
  return result;
}

} // namespace sl
