// The depth layers of layered variance shadow maps (Lauritzen & McCool 2008, survey §6), in double precision:
// the CPU mirror of layeredmoments/LayeredMomentsLayout.glsl, which the build (vtkSLLayeredMomentsPass) and the
// lvsm technique's shader share.
//
// The light view's linear depth range [near, far] is partitioned into `layers` equal, disjoint intervals
// [p_i, q_i]. Layer i stores the moments of the warped depth
//   phi_i(z) = 0 for z <= p_i,  (z - p_i) / (q_i - p_i) for p_i < z < q_i,  1 for z >= q_i,
// a monotone map, so a receiver whose depth t lies in layer i has phi_i(z) >= phi_i(t) exactly where z >= t
// (for t strictly inside the interval), and Chebyshev's bound on the warped moments still bounds its lit
// fraction; occluders of other layers collapse onto the interval's ends and add no variance among themselves.
#pragma once

namespace sl
{

struct DepthLayer
{
  double nearEnd = 0.0; // p_i, linear depth
  double farEnd = 1.0;  // q_i
  double width() const { return farEnd - nearEnd; }
};

// Interval `layer` (0 = nearest the light) of the uniform partition of [nearDepth, farDepth] into `layers`.
DepthLayer depthLayer(int layer, int layers, double nearDepth, double farDepth);
// The layer holding `depth` (a depth on a boundary belongs to the farther layer; depths outside [near, far] to the
// first or last layer).
int depthLayerIndex(double depth, int layers, double nearDepth, double farDepth);
// phi_i(depth), in [0, 1].
double warpIntoLayer(double depth, const DepthLayer& layer);

} // namespace sl
