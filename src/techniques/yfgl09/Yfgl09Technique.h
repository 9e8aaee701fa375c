// Technique `yfgl09`: packet-based hierarchical soft shadow mapping (Yang, Feng, Guennebaud and Liu 2009).
// The same visibility as gbp07 (contour extraction on the dual grid, back-projection, radial integration),
// computed with fewer shadow-map reads:
//  - packets of w x h pixels (§4.1, Alg. 2): the kernels' bounding box is traversed once, each sample's status
//    taken over the whole packet (Eq. 3: 1 / null / 0); edges are extracted once and integrated per pixel;
//  - coherence (§4.3): a packet goes pixel-wise when its divergence probability P_d (Eq. 4-5) exceeds T_d or
//    the cost model (Eq. 6, Q_n = 1) prefers pixels; a null status met during traversal also sends it there;
//  - hierarchical contour extraction (§4.2, Alg. 3) through the dual-grid MSSM, starting at the lowest node
//    that covers the kernel with matching top-left corner; nodes whose range cannot produce an edge for any
//    pixel of the packet (Fig. 6 cases 4, 5) are pruned.
// Each is switchable (packet_width = packet_height = 1, hierarchy = off, coherence_test = off).
// Math: yfgl09/shaders/Yfgl09Visibility.glsl (two passes, see its header); CPU mirror below.
#pragma once

#include "core/Image.h"
#include "frame/ProbeRecord.h"
#include "lightspace/HierarchicalShadowMap.h"
#include "techniques/ContourReceiver.h"
#include "techniques/ShadowMapReference.h"
#include "frame/TechniqueDescriptor.h"

#include <vector>

namespace sl
{

TechniqueDescriptor yfgl09Technique();

// The depths Eq. 4's P_null compares (§4.3; issue 13).
enum class CoherenceDepth
{
  Linear,     // the packet's pixel depths minus bias against the kernel samples' linear light depths
  Comparison, // the receiver-plane comparison depths over the packet kernel
  Window      // the linear reading in the map's window depth
};

// yfgl09's parameters, typed (parsed once, by from()): what the packets read (§4.1-4.3) and the receivers' own; the
// sub-lights are TechniqueDescriptor::subLightsPerSide.
struct Yfgl09Settings
{
  ContourReceiverSettings receiver;
  int packetWidth{};
  int packetHeight{};
  bool hierarchy{};       // contour extraction through the dual-grid MSSM (§4.2, Alg. 3)
  bool divergenceTest{};  // coherence_test: both or divergence (Eq. 5 > T_d)
  bool costTest{};        // coherence_test: both or cost (Eq. 6 > 1)
  double divergenceThreshold{};
  double edgeCost{};
  double visibilityCost{};
  bool paperPacketCost{}; // packet_cost = paper (Q_v w h)
  CoherenceDepth coherenceDepth{};

  static Yfgl09Settings from(const ParameterValues& values);
};

// How a pixel was computed: the `packet_class` buffer's categories (code = the enumerator's value, shader
// identifier = its name in upper case: PACKET_CLASS_COHERENT, ...), generated into the shader from here.
enum class PacketClass
{
  NotTested = 0,
  Trivial = 1,     // the pixel is lit or umbra (Alg. 1 step 5)
  Coherent = 2,    // computed packet-wise
  NonCoherent = 3, // predicted non-coherent (P_d > T_d or Eq. 6 > 1), computed pixel-wise
  CaughtNull = 4,  // a null status (Eq. 3) met during the packet traversal, computed pixel-wise
  OverBudget = 5,  // the packet traversal outgrew yfgl09PacketBudget (or was cut short), computed pixel-wise
  CutShort = 6     // the pixel's own traversal was stopped by the GL's loop cap: its value is not exact (GPU only)
};
// Packet work (visited nodes plus the loop iterations over the packet's pixels: node ranges, resolved statuses,
// integrated edges) beyond which a packet is finished pixel-wise: GLs that cap loop iterations per invocation
// (llvmpipe: 65535) would cut the traversal short. It was 20000 while the back-projection's clipping loops made
// llvmpipe count ~1.6 times this; since issue 13 a cell costs about one counted iteration and a packet the cap
// stops anyway is detected and finished pixel-wise, so the budget only bounds wasted work: at 20000, 97-100 %
// of near-light's packets of 470-740-texel kernels (light 0.5-2, 1024^2 map) went pixel-wise for it alone
// (docs/bench/yfgl09-coherence-cost). The shader's PACKET_BUDGET.
constexpr int yfgl09PacketBudget = 60000;
// The flag vtkSLYfgl09Pass compiles the packet pass with (the pixel pass: without).
inline constexpr char yfgl09PacketPassFlag[] = "YFGL09_PACKET_PASS";

struct Yfgl09Frame
{
  ImageF visibility;
  ImageF kernelTexels;
  ImageF coherence;
  ImageF packetClass;
  ImageF divergenceProbability;
  ImageF visitedNodes;
  ImageF contourEdges;
  // Per pixel, for comparisons with the GPU: where float rounding may flip a decision.
  std::vector<ReferenceSample> samples;
  std::vector<double> kernelEdgeMargin;
  std::vector<double> decisionMargin;
};

// The dual-grid MSSM the GPU built for the frame, on the CPU: HierarchicalShadowMap::buildDual of
// inputs.shadowMapLinear with 2 x far outside, up to the frame's top level (mssm_levels, minMaxTopLevel).
HierarchicalShadowMap yfgl09Mssm(const ShadowMapInputs& inputs, const ParameterValues& values);

// CPU reference (double precision) of both passes over the whole image; `mssm` is yfgl09Mssm's.
Yfgl09Frame yfgl09Reference(const ShadowMapInputs& inputs, const HierarchicalShadowMap& mssm, const Yfgl09Settings& settings);

// What the twin computes for one pixel: Yfgl09Frame's values at it.
struct Yfgl09Pixel
{
  glm::ivec2 pixel{ 0 };
  ReferenceSample sample; // visibility and margins
  double kernelTexels = 0.0;
  double coherence = 0.0;
  PacketClass packetClass = PacketClass::NotTested;
  double divergenceProbability = 0.0;
  double visitedNodes = 0.0;
  double contourEdges = 0.0;
  double kernelEdgeMargin = 1e300;
  double decisionMargin = 1e300;
};

// One pixel of yfgl09Reference's frame, replayed: the packet that holds it is evaluated exactly as in the frame
// (the same code), and `recorder` (optional, `shadowlab probe`) records that pixel's steps: its contour receiver;
// the packet (origin and size in pixels, its kernel and its pixels' kernels as ProbeKernel "packet" / "packet
// pixel kernel"); Eq. 2, Eq. 4-6 and the prediction; every MSSM node the traversals that count toward the
// pixel's visited_nodes visited (ProbeNode "mssm", decision prefixed "packet traversal: " or "pixel traversal: ");
// the Eq. 3 statuses read (ProbeTexel role "Eq. 3 status ..."); every contour edge of the traversal that computed
// the pixel, with its back-projection from this pixel and the signed area it integrated (0 for edges outside
// this pixel's kernel); the packet class and the visibility. `packet` (optional) receives every pixel of the
// packet (the probe's ambiguity: one pixel near a boundary can change the packet's decisions).
Yfgl09Pixel yfgl09ReferencePixel(const ShadowMapInputs& inputs, const HierarchicalShadowMap& mssm,
  const Yfgl09Settings& settings, int x, int y, ProbeRecorder* recorder = nullptr, std::vector<Yfgl09Pixel>* packet = nullptr);

// The label of a PacketClass, as the packet_class buffer's categories.
std::string packetClassLabel(PacketClass packetClass);

} // namespace sl
