// Technique `gbp06`: soft shadow mapping by back-projection of micropatches (Guennebaud, Barthe and Paulin 2006,
// "GBP06"; Yang et al. 2009 §2.3), with an optional DU07 traversal (Dmitriev and Uralsky 2007, a depth-first
// walk of the min-max quadtree that prunes branches which cannot occlude). Square area lights.
// Per pixel:
//  1. the kernel of Eq. 1 (Yang 2009) tightened `kernel_refinements` times by the minimum depth inside it, and
//     lit / umbra from the min-max structure's range over it: the preamble of gbp07
//     (techniques/ContourReceiver), shared unchanged;
//  2. every texel of the kernel plus one ring (Eq. 1 keeps the texels whose *centres* back-project into the
//     light; a texel's square reaches half a texel further, so the ring is where the last partial micropatches
//     lie) whose depth is in front of its comparison depth (tapComparisonDepth) is a micropatch: the texel's
//     square at its depth, parallel to the light. Back-projected from the receiver onto the light plane it is an
//     axis-aligned rectangle in light view x, y (backProject of its two opposite corners), clipped to [-h, h]^2;
//     occluded area = the sum of the clipped areas, visibility = clamp(1 - occluded / (2h)^2, 0, 1). Overlaps
//     of the back-projections are counted twice, as in GBP06 (the clamp bounds the result).
//  3. gap_filling (GBP06's remedy for the gaps between adjacent micropatches at different depths). The stored
//     copies of GBP06 stop after its introduction; Schwarz & Stamminger 2008 (SS08 §3) state the
//     rule: "extending a micropatch to its left and bottom neighbors in texture space". `left_bottom` (the
//     default): when the left (resp. bottom) neighbour texel is an occluding micropatch too, the rectangle's
//     left (bottom) edge is moved out to the right (top) edge of that neighbour's back-projection, i.e. the
//     shared texel edge back-projected at the neighbour's depth, if that lies further out; the rectangle is
//     never shrunk (overlaps stay overlaps). Extending both edges also covers the corner between the three
//     patches. `right_top` is the mirror convention (right and top neighbours): mirroring the scene in light
//     x and y swaps the two, which gbp06/tests/Gbp06Test.cpp checks. Neighbours are read directly, also
//     outside the searched texels: a texel beyond the ring shares with its ring neighbour an edge beyond the
//     kernel, whose back-projection at any depth the kernel allows lies outside the light, so the search
//     region is the same for both conventions.
//  traversal: `kernel` examines every texel of step 2; `hsm` (DU07) walks the mip-map quadtree of the min-max
//     structure from the lowest node covering those texels, depth first and stackless (a node's index holds
//     the path to it: bit k of x and y is the child index taken below level k + 1), pruning a node whose
//     minimum depth is >= the largest comparison depth over its texels (none of them can occlude). Leaves are
//     texels; both traversals accumulate the same micropatches. With hsm=nbuffers the quadtree's node
//     (level k, index n) is the N-buffer texel n 2^k of level k (the same range); hsm=ysm walks its mip-map
//     levels and takes the kernel's ranges from its MSSM part (HierarchicalShadowMap::node / range).
// Math: gbp06/shaders/Gbp06Visibility.glsl; CPU mirror below (double precision).
// Parameters: the shadow-map ones, receiver_plane_bias, hsm, kernel_refinements (as gbp07), gap_filling
// (off / left_bottom / right_top), traversal (kernel / hsm).
// Buffers: kernel_texels, occluding_texels, visited_nodes, classification (not tested / lit / umbra / penumbra /
// penumbra cut short). Cut short: where a GL caps loop iterations per invocation (llvmpipe: 65535, all loops
// together, counted once per SIMD vector of pixels), the shader detects that its traversal never reached its end
// (the texel loop its last texel, the walk its exit) and flags the pixel exactly; GLs without a cap flag nothing.
#pragma once

#include "lightspace/HierarchicalShadowMap.h"
#include "techniques/ContourReceiver.h"
#include "techniques/ShadowMapReference.h"
#include "frame/TechniqueDescriptor.h"

namespace sl
{

TechniqueDescriptor gbp06Technique();

// Loop iterations of one pixel past which the CPU twin classifies it OverLoopBudget (kernel traversal: texels
// examined; hsm traversal: iterations of the walk), an estimate of what llvmpipe (65535 loop iterations per
// invocation, all loops together) cuts short. Only an estimate: llvmpipe counts iterations once per SIMD vector of
// pixels, so a texel loop sharing its vector with wider kernels runs its rows as long as theirs and is stopped with
// far fewer texels of its own (measured: from 44308), and one a little over the budget may finish. The
// shader does not count: it detects the cut (see Gbp06Visibility.glsl), so the GPU's flag is exact and can differ
// from the twin's near the budget; tests compare the twin's class only where it is under the budget.
constexpr int gbp06LoopBudget = 60000;

// The `traversal` choices.
enum class Gbp06Traversal
{
  Kernel, // every texel of the kernel plus one ring
  Hsm     // a depth-first walk of the min-max quadtree (Dmitriev & Uralsky 2007)
};

// gbp06's parameters, typed (parsed once, by from()); the min-max structure's own are HierarchicalShadowMapSettings.
struct Gbp06Settings
{
  ContourReceiverSettings receiver;
  GapFilling gapFilling{};
  Gbp06Traversal traversal{};

  static Gbp06Settings from(const ParameterValues& values);
};

struct Gbp06Sample : BackprojectionPixel
{
  int occludingTexels = 0;  // micropatches accumulated
  int visitedNodes = 0;     // kernel: texels examined; hsm: quadtree nodes examined, leaves included
  int loopIterations = 0;   // of the texel loop or of the walk (the twin's loop-budget estimate)
  double pruningMargin = 1e300;   // hsm: the node pruning tests, relative to d (decides visited_nodes only)
};

// CPU reference (double precision) of Gbp06Visibility.glsl at pixel (x, y); `hsm` is the min-max structure the
// technique's `hsm` parameter names (mip-map, N-buffers or YSM), built from inputs.shadowMapLinear.
// `recorder` (optional, `shadowlab probe`): the contour receiver's steps; every texel examined (role "examined",
// or "micropatch" when it occludes) and, for traversal=hsm, every quadtree node visited (ProbeNode "hsm" /
// "mssm", decision "pruned", "descend" or "leaf"); each micropatch's back-projection, gap-filled and clipped to
// the light, as a ProbeLightPolygon whose signed area is what it adds; the neighbours gap filling read; the
// occluded area and the visibility.
Gbp06Sample gbp06Reference(const ShadowMapInputs& inputs, const HierarchicalShadowMap& hsm,
  const Gbp06Settings& settings, int x, int y, ProbeRecorder* recorder = nullptr);

} // namespace sl
