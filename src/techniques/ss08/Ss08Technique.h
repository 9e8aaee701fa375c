// Technique `ss08`: quality-scalable soft shadow mapping (Schwarz and Stamminger 2008, SS08): soft shadow
// mapping by back-projection of micro-occluders whose shadow-map level varies per pixel under a budget, with a
// smoothed level-of-quality (LOQ) map and alpha blending between levels so that the quality changes without
// seams. Square area lights. Cited by section, figure
// and table as printed in the paper (docs/bibliography.md).
//
// Pipeline (Fig. 3), four full-screen passes (vtkSLSs08Pass):
//  1. search (ss08/shaders/Ss08Search.glsl): per pixel the budget b_mo(x, y) (§4.2; `budget_map`), the
//     search area of Fig. 2 b refined `kernel_refinements` times (§3) with each depth-range query grown to
//     the whole support of the level-j micro-occluders it partly covers (§6, Fig. 7; `growth`), lit /
//     umbra from that range (§3), and the fractional level l, written to the LOQ map. The rule for l is
//     the project's (the paper gives none): with span = the search area's larger side minus one, in level-0
//     texels, l = clamp(log2(span / (b - 1)), 0, L) for micropatches, whose slots examined per axis at level j
//     are at most ceil(span / 2^j) + 1, so level ceil(l) examines at most b per axis and floor(l) at most
//     2b - 1 (§8). Microrects may take one slot more on the high side (ss08SlotRange), at most
//     ceil((span + 2^j - 1) / 2^j) + 1, so for them l = log2((span - 1) / (b - 2)): at most b at ceil(l), 2b - 2
//     at floor(l). Either way level 0 when span <= b - 1. b = 0 is unlimited: level 0, no smoothing, no blending
//     (Table 2's caption). b = 1 (and b = 2 with microrects) is met by the top level L only (one texel for the
//     map). `force_level` sets l for experiments.
//  2-3. smoothing (Ss08LoqSmoothing.glsl): the LOQ map filtered by a separable 11 x 11 box whose runs stop at
//     camera-depth discontinuities (`smoothing_depth_threshold`) and at pixels that do not back-project
//     (§4.2, §8); `loq_floor` = raw keeps l >= l_raw (the budget); `none` lets smoothing lower it
//     and `loq_budget_violation` counts the levels lost.
//  4. visibility (Ss08Visibility.glsl): the micro-occluders of floor(l) and ceil(l) back-projected and
//     accumulated by area, blended V = (1 - a) V(floor l) + a V(ceil l) with a = l - floor(l) (§4.2);
//     `blend_band` < 1 blends only over the last band of each level (0.1 = GBP07's suggestion, §4.2), 0 does
//     not blend (ceil(l) alone).
// Micro-occluders (`micro_occluder`): micropatches, level-j texels of the min-max pyramid at their minimum depth
// (§3, §5.1), gap-filled as gbp06 (`gap_filling`); or microrects (§5.2, structures/microrect), whose
// extents may overlap (area accumulation then over-occludes; `accumulation=bitmask` counts each sample once).
// A micro-occluder occludes when its depth is in front of the receiver's comparison depth at its centre, less
// (`level_bias`, on by default, levels above 0) how much nearer the receiver's tangent plane comes over the
// micro-occluder's footprint: min aggregation puts coarse texels in front of a tilted receiver (SS08 §9 leaves
// biasing across levels to future work). It does not grow with the level alone: scaling the bias by 2^level lit
// the umbra of occluders close to the light, whose large kernels select levels 6 and more.
// Acceleration structure (`hsm`): mipmap = the HSM, nbuffers = the MSSM (SS07's multi-scale shadow map is
// N-buffers), ysm = the Y shadow map (§6, the paper's choice). Micropatches read the min-max pyramid's nodes.
// Buffers: budget, search_area_texels, loq_raw, loq, level_floor, blend_alpha, micro_occluders (slots
// examined, both levels: Table 2's count), classification (Ss08Class), loq_budget_violation,
// query_growth_texels, micro_occluders_floor / _ceil (the slots each level alone would examine: the blend
// overhead's baselines, §8); occluded_bits and area_overcount (accumulation=bitmask, 0 otherwise).
// Accumulation (`accumulation`): area (the clipped areas summed, overlaps counted twice) or bitmask (SS07's
// occlusion bitmask, §3, §8: one bit per light sample of ss08BitmaskSamples(), OR-ed over a level's
// micro-occluders, V = 1 - popcount / 256; each micro-occluder's back-projection is an axis-aligned rectangle,
// so its bits are whole runs of the 16 x 16 grid's cells plus the samples of its <= 2 boundary rows and columns).
#pragma once

#include "core/Image.h"
#include "frame/ProbeRecord.h"
#include "frame/TechniqueDescriptor.h"
#include "lightspace/HierarchicalShadowMap.h"
#include "lightspace/LightSampleSet.h"
#include "lightspace/Microrects.h"
#include "techniques/ContourReceiver.h"
#include "techniques/ShadowMapReference.h"
#include "techniques/SoftShadowSupport.h"

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <optional>

namespace sl
{

struct FrameResult; // frame/FrameResult.h

TechniqueDescriptor ss08Technique();

// The `budget_map` choices (§4.2, Fig. 1 d, Fig. 11).
enum class Ss08BudgetMap
{
  Uniform, // `budget` everywhere
  RampX,   // `budget` at the centre column falling linearly to `budget_border` at the left and right borders
  Image    // the grey values of `budget_image`
};

// ss08's parameters, typed (parsed once, by from()); the min-max structure's own are HierarchicalShadowMapSettings.
struct Ss08Settings
{
  ContourReceiverSettings receiver; // the bias, receiver_plane_bias, kernel_refinements
  int budget{};                     // b_mo, micro-occluders per light axis (0 = unlimited)
  int maxBudget{};                  // the top of `budget`'s range: budget_image's grey values must not pass it
  Ss08BudgetMap budgetMap{};
  std::string budgetImage;          // budget_image's path ("" when unset)
  int budgetBorder{};
  bool loqSmoothing{};
  double smoothingDepthThreshold{};
  bool loqFloorRaw{};               // loq_floor = raw
  double blendBand{};
  bool growth{};
  bool microrects{};                // micro_occluder = microrect
  GapFilling gapFilling{};
  bool levelBias{};
  int forceLevel{};                 // -1 = off
  bool bitmaskAccumulation{};       // accumulation = bitmask
  MultisampleSettings multisample;  // msaa, msaa_depth_tolerance (§7)

  static Ss08Settings from(const ParameterValues& values);
};

// The `classification` codes (shader CLASSIFICATION_*).
enum class Ss08Class
{
  NotTested = 0,
  Lit = 1,
  Umbra = 2,
  Penumbra = 3,
  // Lit by the area's own depth range, penumbra by the range grown to the micro-occluders' supports (Fig. 7):
  // back-projected with growth=on; with growth=off left lit (V = 1), which is the over-precision artifact.
  GrowthPenumbra = 4,
  CutShort = 5 // back-projection cut short by a GL's cap on loop iterations (llvmpipe: 65535), detected
};

// The LOQ map's smoothing state (shader LOQ_STATE_*).
enum class LoqState
{
  None = 0,     // no back-projection: a stop for the smoothing
  Smoothed = 1, // back-projects at a budget-derived level
  Fixed = 2     // back-projects at a level smoothing keeps (unlimited budget, force_level): a stop
};

constexpr int ss08SmoothingRadius = 5; // 11 x 11 support (§8)

// accumulation=bitmask: the light samples, the project's shared set (lightspace/LightSampleSet.h) as pattern
// `stratified`, N = 256, seed ss08BitmaskSeed, its base points only (no per-pixel shift): one jittered point per
// cell of a 16 x 16 grid on the unit square, "jittered 16 x 16" as the paper (§8). Sample (i, j) = base point
// j * 16 + i lies in cell (i, j); on the light it is at ((u - 1/2) size, (v - 1/2) size) in light view x, y.
constexpr int ss08BitmaskGridSide = 16;
constexpr int ss08BitmaskSampleCount = ss08BitmaskGridSide * ss08BitmaskGridSide;
constexpr std::uint32_t ss08BitmaskSeed = 1;
const LightSampleSet& ss08BitmaskSamples();

// The micro-occluder sources of the twin: the min-max pyramid the `hsm` parameter names (micropatches and the
// range queries) and, with micro_occluder=microrect, the microrects.
struct Ss08Structures
{
  const HierarchicalShadowMap* hsm = nullptr;
  const Microrects* microrects = nullptr;
};

// The search (pass 1) at one pixel, double precision: the mirror of ss08Search in Ss08Search.glsl.
struct Ss08Search
{
  ShadowLookup lookup;
  SoftShadowGeometry geometry;
  double bias = 0.0;
  TexelRectangle area;  // kernel + one ring, clamped
  TexelRectangle query; // the area whose depth range decided (grown with growth=on)
  int budget = 0;
  int span = 0;
  double levelRaw = 0.0;
  int levelCeil = 0;
  Ss08Class classification = Ss08Class::NotTested;
  bool backProjects = false;
  LoqState state = LoqState::None;
  double kernelEdgeMargin = 1e300; // kernel edges' distance to texel centres, in texels (float may round across)
  double decisionMargin = 1e300; // the lit / umbra tests and the growth class, relative to d
  double levelMargin = 1e300;    // |l_raw - nearest integer| where l_raw comes from log2 (float may round across)
};

// b_mo at pixel (x, y) of a width-W frame for budget_map = uniform / ramp_x (exact integers); image maps are
// read by the caller.
int ss08PixelBudget(const Ss08Settings& settings, int x, int y, int imageWidth, const ImageF* budgetImage);

// budget_map=image: the grey values (channel 0) of the PNG `budget_image`, nearest-resampled to width x height
// (0 = unlimited). Throws InputError naming the parameter or the file when it is missing, unreadable, or holds
// a value above the `budget` range.
ImageF ss08BudgetImage(const Ss08Settings& settings, int width, int height);

// `recorder` (optional, `shadowlab probe`): the budget, each refinement's search area and depth-range query
// (Fig. 2 b, Fig. 7), the lit / umbra / penumbra decision and its class, the span and the level rule's l_raw.
Ss08Search ss08Search(const ShadowMapInputs& inputs, const Ss08Structures& structures, const Ss08Settings& settings,
  int x, int y, const ImageF* budgetImage = nullptr, ProbeRecorder* recorder = nullptr);

// The slots (level-j texels) examined at `level` for the search area [lo, hi], inclusive per axis.
TexelRectangle ss08SlotRange(const Ss08Settings& settings, int mapSize, int level, const TexelRectangle& area);

// Passes 2-3: the smoothed LOQ map from the LOQ pass's output (x = l_raw, y = LoqState) and the camera depth.
ImageF ss08SmoothLoq(const ImageF& loqRawAndState, const ImageF& cameraDepth, const Ss08Settings& settings);

// Pass 4 at one pixel, given the search and the (smoothed) level `level` the GPU read.
struct Ss08Sample
{
  ReferenceSample sample;
  Ss08Search search;
  double level = 0.0;      // l used
  int levelFloor = 0;
  double blendAlpha = 0.0;
  int microOccluders = 0;  // slots examined, both levels
  glm::ivec2 slotsPerAxis[2]{ glm::ivec2(0), glm::ivec2(0) }; // at floor(l) and ceil(l), examined or not
  int budgetViolation = 0;
  int queryGrowth = 0;
  double occlusionMargin = 1e300; // the micro-occluders' depth tests, relative to d
  // accumulation=bitmask: the occluded samples of floor(l) / ceil(l) (examined levels only), the published
  // popcount sum(weight_k popcount_k) and area sum(weight_k (area_k / light area - popcount_k / 256)), and the
  // least distance (unit square) of a sample to a back-projected rectangle's edge (float may round across).
  std::array<int, 2> occludedBits{ 0, 0 };
  double occludedBitsBlended = 0.0;
  double areaOvercount = 0.0;
  double bitmaskMargin = 1e300;
};
// `evaluateLit`: back-project pixels the search classified lit as well, at level `level` (the over-precision
// test: with growth a lit pixel's micro-occluders hide nothing; the GPU never evaluates them).
// `recorder` (optional, `shadowlab probe`): the search (ss08Search), the level l used, floor / ceil and the blend
// weight, then per examined level every micro-occluder (a ProbeNode of structure "micropatch" or "microrect": its
// level, extent in level-0 texels, depth, whether it occludes) and each occluding one's back-projection onto the
// light (a ProbeLightPolygon in light coordinates, role "level <j> micro-occluder", signedArea = its area clipped
// to the light), the level's occluded area and visibility, and the buffers' values under their names.
Ss08Sample ss08Reference(const ShadowMapInputs& inputs, const Ss08Structures& structures, const Ss08Settings& settings,
  int x, int y, double level, const ImageF* budgetImage = nullptr, bool evaluateLit = false,
  ProbeRecorder* recorder = nullptr);

// The twin's inputs for a rendered frame (the tests and the probe): the read-back shadow map, the min-max structure
// `hsm` names and, with micro_occluder=microrect, the microrects, both built on the CPU from the shadow map (the
// GPU's equal them bit for bit: LightSpaceStructureGpuTest, MicrorectGpuTest), and the budget image with
// budget_map=image. `scene` must outlive it (ShadowMapInputs points to its light).
struct Ss08Twin
{
  ShadowMapInputs inputs;
  HierarchicalShadowMap hsm;
  std::optional<Microrects> microrects;
  std::optional<ImageF> budgetImage;

  Ss08Structures structures() const;
  const ImageF* budgets() const { return budgetImage ? &*budgetImage : nullptr; }
};
Ss08Twin ss08TwinOf(const FrameResult& frame, const Scene& scene, int lightIndex = 0);

// The twin's own passes 2-3 at pixel (x, y): ss08SmoothLoq over the pixel's 11 x 11 neighbourhood of ss08Search's
// raw levels and LOQ states, with the frame's camera depth `cameraDepth`. It equals the whole-image smoothing at
// (x, y): each separable run reaches at most ss08SmoothingRadius pixels along its axis.
double ss08SmoothedLevelAt(const Ss08Twin& twin, const Ss08Settings& settings, const ImageF& cameraDepth, int x, int y);

// llvmpipe's cap on the loop iterations of one invocation (the twin's CutShort rule: more slots than this). The
// slot loop costs one iteration a slot (its helpers have no loops and no early returns: with them llvmpipe cut
// this loop at 22922 slots, Mesa having lowered a return to a loop exit); the search's few loop iterations come on top, so llvmpipe cuts from ~65200-65440 slots on (measured,
// Ss08.PixelsOverTheLoopCapAreFlaggedAndTheOthersExact).
constexpr int ss08LoopCap = 65535;

} // namespace sl
