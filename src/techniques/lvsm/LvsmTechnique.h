// Technique `lvsm`: layered variance shadow maps (Lauritzen & McCool 2008; survey §6). The light's depth range is
// split into `layers` disjoint layers (layer_placement: equal, or boundaries in the depth histogram's gaps), each a
// variance shadow map of the depths warped into it (structures/layeredmoments); a receiver applies Chebyshev's bound
// to its own layer's moments at its warped depth (layer_bound=own, LM08) or takes the least of every layer's bound and
// vsm's (tightest, ours: still an upper bound, README.md). Math: lvsm/shaders/LvsmVisibility.glsl.
// Parameters: the shadow-map ones, layers, layer_placement, layer_bound, prefilter_texels, light_bleeding_reduction,
// min_variance.
// Buffers: p_max, light_leak (p_max - pcf over the same box, pcf's default bias, as vsm), layer, warped_depth,
// clamped_above_vsm (clamping nearer depths lifted the bound above vsm's), vsm_comparison (where vsm leaks, whether
// layering leaks less) and depth_bias: eight outputs, the GL's draw buffers, so the box width (prefilter_texels) is
// no buffer.
#pragma once

#include "techniques/MomentReference.h"
#include "techniques/ShadowMapReference.h"
#include "frame/TechniqueDescriptor.h"
#include "lightspace/LayeredMoments.h"

#include <vector>

namespace sl
{

TechniqueDescriptor lvsmTechnique();

// The claim (issue 30): layering leaks less than vsm wherever vsm leaks by more than this against the PCF
// over the same texels (the shader's LVSM_VSM_LEAK_THRESHOLD).
inline constexpr double lvsmVsmLeakThreshold = 0.05;

// The buffer vsm_comparison: where vsm leaks more than lvsmVsmLeakThreshold, whether lvsm leaks less, and if not,
// which of LM08's own limits holds the bound up (src/techniques/lvsm/README.md, "Where layering cannot help").
// Decided in the order same layer, saturated (both exact ties with vsm's leak, whatever float rounding says), leaks
// less, vsm's bound the tightest (layer_bound=tightest), clamped in front, unexplained; codes 2 and above are the pixels where the claim fails (stats.json
// vsm_comparison_flagged_pixels).
enum class LvsmVsmComparison
{
  VsmBelowThreshold, // no shadow test, or vsm leaks at most the threshold
  LeaksLess,         // the layered bound leaks less than vsm's
  SameLayer,         // every depth of the box lies in the receiver's layer: phi is affine there, the bound is vsm's
  Saturated,         // both bounds are 1: the receiver lies at or in front of the mean in both depth spaces
  ClampedInFront,    // depths in front of the layer, clamped onto its near end, moved toward the receiver
  VsmBoundTightest,  // layer_bound=tightest and no layer's bound is below vsm's: p_max is vsm's bound
  Unexplained,       // none of the above (the tests require none)
};
inline const Category<LvsmVsmComparison> lvsmVsmComparisonCategories[] = {
  { LvsmVsmComparison::VsmBelowThreshold, "VSM_BELOW_THRESHOLD", "vsm leaks <= 0.05" },
  { LvsmVsmComparison::LeaksLess, "LEAKS_LESS", "lvsm leaks less than vsm" },
  { LvsmVsmComparison::SameLayer, "SAME_LAYER", "box within the receiver's layer: the bound is vsm's" },
  { LvsmVsmComparison::Saturated, "SATURATED", "both bounds 1 (receiver at or before the mean)" },
  { LvsmVsmComparison::ClampedInFront, "CLAMPED_IN_FRONT", "depths before the layer clamped toward the receiver" },
  { LvsmVsmComparison::VsmBoundTightest, "VSM_BOUND_TIGHTEST", "tightest: no layer's bound below vsm's" },
  { LvsmVsmComparison::Unexplained, "UNEXPLAINED", "not less, unexplained" },
};

// layer_bound: which layers' Chebyshev bounds the receiver takes (README.md, "Bound from several layers").
enum class LvsmLayerBound
{
  Own,      // LM08: the layer holding the receiver's depth
  Tightest, // ShadowLab: the least of every layer's bound at phi_j(t) and vsm's bound on the unwarped depths
};

// lvsm's parameters, typed (parsed once, by from()).
struct LvsmSettings
{
  BiasSettings bias;
  int layers{};
  LvsmLayerBound layerBound = LvsmLayerBound::Own;
  LayerPlacement layerPlacement = LayerPlacement::Uniform;
  // The layers' ends (layers + 1 linear depths) the frame used: from its stats (lvsmSettingsOf). Empty: the uniform
  // partition of the light's depth range (layer_placement=uniform only).
  std::vector<double> layerEnds;
  int prefilterTexels{};
  double lightBleedingReduction{};
  double minVariance{}; // relative to d^2, in linear depth (rescaled into each layer's warped units)

  static LvsmSettings from(const ParameterValues& values);
};

// The settings of a rendered frame: its parameters and the layers' ends it published (stats.json layer_end_<i>).
LvsmSettings lvsmSettingsOf(const FrameResult& frame);
// The ends the twin uses: settings.layerEnds, or the uniform partition of the light's depth range.
std::vector<double> lvsmLayerEnds(const ShadowMapInputs& inputs, const LvsmSettings& settings);

struct LvsmSample
{
  ReferenceSample sample;
  int layer = -1;
  double layerNear = 0.0; // p_i
  double layerFar = 0.0;  // q_i
  double warpedDepth = 0.0;     // phi_i(t)
  double mean = 0.0;            // E[phi_i(z)] over the box
  double second = 0.0;          // E[phi_i(z)^2]
  double varianceFloor = 0.0;   // min_variance d^2 / (q_i - p_i)^2
  double variance = 0.0;        // floored
  double ownPMax = 0.0;         // the bound of the receiver's own layer (LM08)
  // layer_bound=tightest: each layer j's bound at phi_j(t) (index j), and which bound p_max is: a layer, or -1 for vsm's.
  std::vector<double> layerPMax;
  int boundSource = -1;
  double pMax = 0.0;
  double pcf = 0.0;             // the light-leak PCF (pcf's default bias) over the same box
  double lightLeak = 0.0;       // pMax - pcf
  double vsmPMax = 0.0;         // Chebyshev's bound on the unwarped depths of the same box (vsm's p_max)
  int texelsInFront = 0;        // box texels in front of the layer (z < p_i), clamped to phi = 0
  int texelsBehind = 0;         // box texels behind it (z > q_i), clamped to phi = 1
  // Depths in front of the layer were clamped onto its near end and p_max exceeds vsm's by more than
  // lvsmVsmLeakThreshold (buffer clamped_above_vsm).
  bool clampedAboveVsm = false;
  LvsmVsmComparison comparison = LvsmVsmComparison::VsmBelowThreshold;
};

// The moments (E[phi], E[phi^2]) of the box of `width` texels around uvTexels's texel (clamp to edge), each depth
// warped into `layer` (lightspace/LayeredMoments.h): the CPU mirror of the layered moment map.
FilteredMoments layeredBoxMoments(const ShadowMapInputs& inputs, const glm::dvec2& uvTexels, int width,
  const DepthLayer& interval, ProbeRecorder* recorder = nullptr);
// The same for layer `layer` of the uniform partition into `layers`.
FilteredMoments layeredBoxMoments(const ShadowMapInputs& inputs, const glm::dvec2& uvTexels, int width, int layer,
  int layers, ProbeRecorder* recorder = nullptr);

// The pixel's vsm_comparison code from its evaluated sample (the order of LvsmVsmComparison).
LvsmVsmComparison lvsmVsmComparison(const LvsmSample& sample);

// CPU reference (double precision) of LvsmVisibility.glsl. `recorder` (optional, `shadowlab probe`): the receiver,
// its layer and warped depth, the box and the layer's moments, the bound and the light-bleeding reduction, and the
// light leak against the true PCF over the same box.
LvsmSample lvsmReference(const ShadowMapInputs& inputs, const LvsmSettings& settings, int x, int y,
  ProbeRecorder* recorder = nullptr);

} // namespace sl
