// The depth layers of layered variance shadow maps (Lauritzen & McCool 2008, survey §6), in double precision:
// the CPU mirror of layeredmoments/LayeredMomentsLayout.glsl, which the build (vtkSLLayeredMomentsPass) and the
// lvsm technique's shader share.
//
// The light view's linear depth range [near, far] is partitioned into `layers` disjoint intervals [p_i, q_i], given
// by their `layers + 1` ends (near = e_0 < e_1 < ... < e_layers = far). Layer i stores the moments of the warped depth
//   phi_i(z) = 0 for z <= p_i,  (z - p_i) / (q_i - p_i) for p_i < z < q_i,  1 for z >= q_i,
// a monotone map, so a receiver whose depth t lies in layer i has phi_i(z) >= phi_i(t) exactly where z >= t
// (for t strictly inside the interval), and Chebyshev's bound on the warped moments still bounds its lit
// fraction; occluders of other layers collapse onto the interval's ends and add no variance among themselves.
//
// Where the ends lie (layer_placement): uniform, equal intervals; gaps (ours, not LM08's: their iterative placement
// was not available here), the interior boundaries in the widest empty runs of the shadow map's depth histogram, so
// that surfaces separated in depth fall into different layers (layeredGapEnds).
#pragma once

#include <cstdint>
#include <vector>

namespace sl
{

struct DepthLayer
{
  double nearEnd = 0.0; // p_i, linear depth
  double farEnd = 1.0;  // q_i
  double width() const { return farEnd - nearEnd; }
};

enum class LayerPlacement
{
  Uniform, // equal intervals of [near, far]
  Gaps,    // boundaries in the widest empty depth intervals of the shadow map (layeredGapEnds)
};

// The depth histogram the gaps placement reads: this many equal bins over [near, far] (LayeredMomentsHistogram.glsl).
inline constexpr int layeredHistogramBins = 256;

// The ends of the uniform partition of [nearDepth, farDepth] into `layers`.
std::vector<double> layeredUniformEnds(int layers, double nearDepth, double farDepth);
// The bin of `depth` in the histogram over [nearDepth, farDepth], or -1 for a depth beyond far (the shadow map's empty
// texels hold 2 far) or before near.
int layeredHistogramBin(double depth, double nearDepth, double farDepth);
// The histogram of `depths` (every texel of the shadow map) as the GPU counts it.
std::vector<std::uint32_t> layeredDepthHistogram(const std::vector<float>& depths, double nearDepth, double farDepth);
// The gaps placement: among the runs of empty bins between the first and the last occupied bin, the `layers - 1`
// widest (ties: the nearer) each get a boundary at their middle; when there are fewer runs, the widest layer so far is
// halved until there are `layers`. Each end is rounded to float, as the shader receives it, so the twin and the GPU
// share the same intervals.
std::vector<double> layeredGapEnds(const std::vector<std::uint32_t>& histogram, int layers, double nearDepth,
  double farDepth);

// Interval `layer` (0 = nearest the light) of the partition with ends `ends`.
DepthLayer depthLayer(int layer, const std::vector<double>& ends);
// The layer holding `depth`: the last layer whose near end is at or before it (a depth on a boundary belongs to the
// farther layer; depths outside [near, far] to the first or last layer).
int depthLayerIndex(double depth, const std::vector<double>& ends);
// Interval `layer` of the uniform partition of [nearDepth, farDepth] into `layers`, and the layer holding `depth`.
DepthLayer depthLayer(int layer, int layers, double nearDepth, double farDepth);
int depthLayerIndex(double depth, int layers, double nearDepth, double farDepth);
// phi_i(depth), in [0, 1].
double warpIntoLayer(double depth, const DepthLayer& layer);

} // namespace sl
