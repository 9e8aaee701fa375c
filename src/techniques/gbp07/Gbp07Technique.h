// Technique `gbp07`: contour-based soft shadow mapping (Guennebaud, Barthe and Paulin 2007), the baseline of
// the packet paper (Yang et al. 2009, §6: adaptive-precision strategies off, MSSM kernels on). Per pixel:
// the kernel of Eq. 1 (Yang 2009) tightened by the minimum occluder depth from the min-max structure
// (Schwarz and Stamminger 2007), lit / umbra from the same structure, then every dual cell of the kernel:
// marching squares, back-projection and radial integration (techniques/backprojection). Square area lights.
// Math: gbp07/shaders/Gbp07Visibility.glsl; CPU mirror below.
// Parameters: the shadow-map ones, receiver_plane_bias, hsm (nbuffers = the MSSM's exact ranges, default;
// mipmap = a conservative HSM; ysm = the HSM plus an MSSM of its ~256^2 level, SS08 §6), kernel_refinements.
// Buffers: kernel_texels, contour_edges, visited_cells, classification (not tested / lit / umbra / penumbra /
// penumbra over the loop budget).
#pragma once

#include "lightspace/HierarchicalShadowMap.h"
#include "techniques/ContourReceiver.h"
#include "techniques/ShadowMapReference.h"
#include "frame/TechniqueDescriptor.h"

namespace sl
{

TechniqueDescriptor gbp07Technique();

// Dual cells of a penumbra kernel past which the twin classifies the pixel OverLoopBudget: what llvmpipe, which
// caps loop iterations per invocation at 65535 (all loops together), would cut short. The shader detects the
// cut itself (its last cell not reached), so a GL without a cap flags nothing.
constexpr int gbp07LoopBudgetCells = 60000;

// gbp07's parameters, typed (parsed once, by from()); the min-max structure's own are HierarchicalShadowMapSettings,
// the sub-lights TechniqueDescriptor::subLightsPerSide.
struct Gbp07Settings
{
  ContourReceiverSettings receiver;

  static Gbp07Settings from(const ParameterValues& values);
};

struct Gbp07Sample : BackprojectionPixel
{
  int contourEdges = 0;
  int visitedCells = 0;
};

// CPU reference (double precision) of Gbp07Visibility.glsl at pixel (x, y); `hsm` is the min-max structure
// the technique's `hsm` parameter names, built from inputs.shadowMapLinear. `recorder` (optional, `shadowlab
// probe`): the contour receiver's steps, the light centre's status, the kernel's samples (role "contour
// sample"), every contour edge with its back-projection and signed area, and the visibility.
Gbp07Sample gbp07Reference(const ShadowMapInputs& inputs, const HierarchicalShadowMap& hsm,
  const Gbp07Settings& settings, int x, int y, ProbeRecorder* recorder = nullptr);

} // namespace sl
