#include "techniques/ss08/Ss08Technique.h"

#include "techniques/ApproximationRules.h"

#include "core/Error.h"
#include "frame/FrameResult.h"
#include "io/ImageIO.h"
#include "lightspace/Microrects.h"
#include "structures/hsm/HsmStructure.h"
#include "structures/microrect/MicrorectStructure.h"
#include "structures/shadowmap/ShadowMapStructure.h"
#include "techniques/ProbeSupport.h"
#include "techniques/ShadowMapParameters.h"
#include "techniques/ContourBackprojection.h"
#include "techniques/ContourReceiver.h"
#include "techniques/ss08/vtkSLSs08Pass.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace sl
{

namespace
{

// In code order (checked by categoricalBuffer).
const Category<Ss08Class> ss08Categories[] = {
  { Ss08Class::NotTested, "NOT_TESTED", "not tested" },
  { Ss08Class::Lit, "LIT", "lit" },
  { Ss08Class::Umbra, "UMBRA", "umbra" },
  { Ss08Class::Penumbra, "PENUMBRA", "penumbra" },
  { Ss08Class::GrowthPenumbra, "GROWTH_PENUMBRA", "penumbra by the grown query only" },
  { Ss08Class::CutShort, "CUT_SHORT", "penumbra cut short by the loop cap", true },
};

const char* budgetMapName(Ss08BudgetMap map)
{
  return map == Ss08BudgetMap::RampX ? "ramp_x" : map == Ss08BudgetMap::Image ? "image" : "uniform";
}

// Where in SS08 (section, figure or table as printed) a probe quantity comes from, as its source.
std::string cite(const std::string& where)
{
  return where + ", SS08 (Schwarz & Stamminger 2008)";
}

// A categorical quantity that a buffer publishes as a code: the code as its value, the label as its text.
void recordCode(ProbeRecorder& recorder, const std::string& name, int code, const std::string& label,
  const std::string& source)
{
  recorder.quantity(name, code, "code", source);
  recorder.record().quantities.back().text = label;
}

const char* const loqStateLabels[] = { "none (no back-projection: a stop for the smoothing)",
  "smoothed (back-projects at a budget-derived level)", "fixed (back-projects at a level smoothing keeps)" };

// msaa=4: a pixel's samples on its first sample's depth take the value computed once, at the pixel centre (§7).
// Where the visibility changes by more than `tolerance` from the pixel to a covered 4-neighbour, it also changes across
// the pixel's own samples (up to ~0.4 pixel from the centre), which that one value does not show.
void markSteepAcrossMultisampledPixels(const FrameResult& frame, ImageF& codes, float code, double tolerance)
{
  if (Ss08Settings::from(frame.parameters).multisample.samples != 4)
  {
    return;
  }
  const ImageF& visibility = frame.find("visibility")->image;
  const ImageF& coverage = frame.find("coverage")->image;
  const glm::ivec2 neighbours[] = { { 1, 0 }, { -1, 0 }, { 0, 1 }, { 0, -1 } };
  for (int y = 0; y < codes.height; ++y)
  {
    for (int x = 0; x < codes.width; ++x)
    {
      if (codes.at(x, y) != 0.0f || coverage.at(x, y) <= 0.5f)
      {
        continue;
      }
      for (const glm::ivec2& offset : neighbours)
      {
        const int nx = x + offset.x;
        const int ny = y + offset.y;
        if (nx >= 0 && ny >= 0 && nx < codes.width && ny < codes.height && coverage.at(nx, ny) > 0.5f &&
          std::abs(visibility.at(nx, ny) - visibility.at(x, y)) > tolerance)
        {
          codes.at(x, y) = code;
          break;
        }
      }
    }
  }
}

} // namespace

Ss08Settings Ss08Settings::from(const ParameterValues& values)
{
  Ss08Settings settings;
  settings.receiver = ContourReceiverSettings::from(values);
  settings.budget = values.getInt("budget");
  settings.maxBudget = static_cast<int>(findParameterSpec(values.specs(), "budget")->maxValue);
  settings.budgetMap = choiceOf<Ss08BudgetMap>(values, "budget_map",
    { { "uniform", Ss08BudgetMap::Uniform }, { "ramp_x", Ss08BudgetMap::RampX }, { "image", Ss08BudgetMap::Image } });
  settings.budgetImage = values.file("budget_image");
  settings.budgetBorder = values.getInt("budget_border");
  settings.loqSmoothing = values.choice("loq_smoothing") == "on";
  settings.smoothingDepthThreshold = values.get("smoothing_depth_threshold");
  settings.loqFloorRaw = values.choice("loq_floor") == "raw";
  settings.blendBand = values.get("blend_band");
  settings.growth = values.choice("growth") == "on";
  settings.microrects = values.choice("micro_occluder") == "microrect";
  settings.gapFilling = gapFillingOf(values);
  settings.levelBias = values.choice("level_bias") == "on";
  settings.forceLevel = values.getInt("force_level");
  settings.bitmaskAccumulation = values.choice("accumulation") == "bitmask";
  settings.multisample = MultisampleSettings{ values.choice("msaa") == "4" ? 4 : 1, values.get("msaa_depth_tolerance") };
  return settings;
}

TechniqueDescriptor ss08Technique()
{
  TechniqueDescriptor descriptor = describeShadowMapTechnique("ss08",
    "Quality-scalable soft shadow mapping: budget map, smoothed LOQ map, blended levels, microrects",
    "Schwarz & Stamminger 2008 (Fig. 3, §4.2, §5.2, §6); Guennebaud et al. 2006 (micropatches)", 1024);
  descriptor.parameters.push_back(receiverPlaneBiasParameter());
  descriptor.addParameters({
    { "hsm", 2, 0, 2, "", "acceleration structure for search-area pruning (SS08 §6, Fig. 8): mipmap = the HSM, nbuffers = the MSSM (N-buffers), ysm = the Y shadow map (HSM levels plus an MSSM of level log2(N/256), the paper's choice)", { "mipmap", "nbuffers", "ysm" }, true },
    hsmLevelsParameter("hsm_levels", "N-buffers"),
    { "kernel_refinements", 2, 0, 4, "iterations", "times the search area is shrunk to the minimum depth inside it (SS08 Fig. 2 b)", {}, true },
    { "budget", 12, 0, 64, "micro-occluders per axis", "b_mo: micro-occluders per light axis at level ceil(l) (SS08 §4.2); 0 = unlimited (level 0, no smoothing or blending); with budget_map=ramp_x the value at the centre column", {}, true },
    { "budget_map", 0, 0, 2, "", "the budget map b_mo(x, y): uniform `budget`; ramp_x, `budget` at the centre column falling linearly to `budget_border` at the left and right borders (SS08 Fig. 1 d: 12 to 5); image, the grey values of `budget_image` (0 = unlimited)", { "uniform", "ramp_x", "image" }, true },
    { "budget_image", 0, 0, 1, "", "budget_map=image: a PNG whose grey values (first channel) are b_mo per pixel, 0 = unlimited, resampled to the frame by nearest neighbour (SS08 Fig. 11: a lower budget where texture masking hides the shadow)", {}, false, true },
    { "budget_border", 5, 1, 64, "micro-occluders per axis", "budget_map=ramp_x: b_mo at the left and right borders (SS08 Fig. 1 d: 5)", {}, true },
    { "loq_smoothing", 1, 0, 1, "", "smooth the LOQ map (SS08 §4.2): a separable 11 x 11 box whose runs stop at depth discontinuities and at pixels that do not back-project", { "off", "on" }, true },
    { "smoothing_depth_threshold", 0.02, 0.0, 1.0, "relative depth", "the smoothing stops between neighbours whose camera depths differ by more than this times the smaller one (the paper's filter stops at depth discontinuities; its threshold is the project's)", {}, false },
    { "loq_floor", 0, 0, 1, "", "whether smoothing may lower l below the budget's level l_raw: none (the paper's plain smoothing; loq_budget_violation counts the levels lost) or raw (l = max(smoothed, l_raw): the budget holds)", { "none", "raw" }, true },
    { "blend_band", 1.0, 0.0, 1.0, "levels", "alpha blending between floor(l) and ceil(l) (SS08 §4.2): over the last blend_band of each level; 1 = always (the paper's choice), 0.1 = GBP07's band, 0 = off (ceil(l) alone)", {}, false },
    { "growth", 1, 0, 1, "", "grow each depth-range query to the whole support of the level-j micro-occluders it partly covers (SS08 §6, Fig. 7: without it pixels next to the penumbra are classified lit)", { "off", "on" }, true },
    { "micro_occluder", 1, 0, 1, "", "micropatches (min-aggregated level-j texels, SS08 §3) or microrects (SS08 §5.2: rectangles of level-0 texels merged by depth, structures/microrect)", { "micropatch", "microrect" }, true },
    { "gap_filling", 1, 0, 2, "", "micropatches: extend each back-projection to its occluding left and bottom neighbours (GBP06's rule, SS08 §3), right and top, or off; as gbp06", { "off", "left_bottom", "right_top" }, true },
    { "level_bias", 1, 0, 1, "", "above level 0, add to the depth bias how much nearer the receiver's tangent plane comes over the micro-occluder's footprint than at its centre (min aggregation puts coarse texels in front of tilted receivers; SS08 §9 leaves biasing across levels to future work)", { "off", "on" }, true },
    { "force_level", -1, -1, 13, "level", "experiments: use this level everywhere (no budget, smoothing or blending); -1 = off", {}, true },
    { "accumulation", 1, 0, 1, "", "how a level's back-projected micro-occluders combine (SS08 §3, §8): area, the sum of their clipped areas (overlaps count twice), or bitmask, SS07's occlusion bitmask over 256 light samples (the shared stratified 16 x 16 set, fixed seed), OR-ed, V = 1 - popcount / 256", { "area", "bitmask" }, true },
    { "msaa", 0, 0, 1, "samples", "multisampling (SS08 §7): 4 = a 4x multisampled G-buffer, soft shadows evaluated once per pixel from the first sample and a custom resolve (passes/vtkSLMsaaResolvePass.h: msaa_distinct_samples, msaa_interpolated_samples, msaa_sample_depth, msaa_sample_visibility)", { "1", "4" }, true },
    { "msaa_depth_tolerance", 0.001, 0.0, 1e30, "relative depth", "msaa=4: tau, the largest |d - s_z| / s_z at which a sample takes its pixel's visibility; others take the 4-neighbour's whose s_z is closest (SS08 §7, which gives tau no value). 0 = per sample (every sample off the first's depth interpolates), >= 1e30 = per pixel", {}, false },
  });
  descriptor.multisample = [](const ParameterValues& values) {
    return Ss08Settings::from(values).multisample;
  };
  descriptor.lightStructures = { &shadowMapStructure(), &hierarchicalShadowMapStructure(), &microrectStructure() };
  descriptor.structureNeeded = [](const LightSpaceStructure& structure, const ParameterValues& values) {
    return &structure != &microrectStructure() || Ss08Settings::from(values).microrects;
  };
  descriptor.buffers = {
    // Fragment outputs (at most eight).
    { "budget", "micro-occluders per axis", "b_mo(x, y) as used (0 = unlimited; SS08 §4.2)" },
    { "search_area_texels", "texels", "larger side of the refined search area (kernel plus one ring, SS08 Fig. 2 b)" },
    { "loq_raw", "levels", "l from the search area and the budget, before smoothing" },
    { "loq", "levels", "l after smoothing: the LOQ map (SS08 Fig. 3 step 2)" },
    { "level_floor", "level", "floor(l) of back-projecting pixels (SS08 Fig. 8, Fig. 13 a)" },
    { "blend_alpha", "", "weight of ceil(l) in the blend (SS08 §4.2; 0 where one level)" },
    { "micro_occluders", "micro-occluders", "slots examined, both levels (Table 2's count; where the loop cap cut the pixel, those it reached)", BufferKind::Continuous, {}, SubLightCombine::Sum },
    // Image stores (IMAGE_OUTPUT_FIRST and after).
    categoricalBuffer("classification", "how the pixel was decided; growth penumbra: lit by the search area's own range, penumbra by the grown one (SS08 Fig. 7)", ss08Categories),
    { "loq_budget_violation", "levels", "ceil(l_raw) - ceil(l) where smoothing lowered the level below the budget's (loq_floor=none)" },
    { "query_growth_texels", "texels", "how far the depth-range query was grown beyond the search area (SS08 §6)" },
    { "micro_occluders_floor", "micro-occluders", "slots level floor(l) alone examines (the blend overhead's baseline, SS08 §8)", BufferKind::Continuous, {}, SubLightCombine::Sum },
    { "micro_occluders_ceil", "micro-occluders", "slots level ceil(l) alone examines", BufferKind::Continuous, {}, SubLightCombine::Sum },
    { "occluded_bits", "light samples (of 256)", "accumulation=bitmask: popcount of the occlusion bitmask, blended as the visibility ((1 - a) floor + a ceil); 0 with area accumulation (SS08 §8)" },
    { "area_overcount", "fraction of light area", "accumulation=bitmask: summed clipped areas / light area minus popcount / 256, blended: where overlapping micro-occluders over-occlude under area accumulation; 0 with area accumulation", BufferKind::Signed },
  };
  descriptor.shaderConstants = contourKernelShaderConstants();
  descriptor.shaderConstants.insert(descriptor.shaderConstants.end(), {
    { "IMAGE_OUTPUT_FIRST", 8, "the first output written by image stores (GL guarantees eight colour outputs)" },
    { "LOQ_SMOOTHING_RADIUS", ss08SmoothingRadius, "neighbours each way of the LOQ smoothing (11 x 11, SS08 §8)" },
    { "LOQ_STATE_NONE", static_cast<int>(LoqState::None), "LOQ map: the pixel does not back-project" },
    { "LOQ_STATE_SMOOTHED", static_cast<int>(LoqState::Smoothed), "LOQ map: smoothed" },
    { "LOQ_STATE_FIXED", static_cast<int>(LoqState::Fixed), "LOQ map: back-projects at a level smoothing keeps" },
    { "BITMASK_GRID_SIDE", ss08BitmaskGridSide, "accumulation=bitmask: light samples per axis (one per cell, SS08 §8)" },
  });
  descriptor.supportedLights = { LightType::Area };
  descriptor.supportedAreaShapes = { LightShape::Square };
  descriptor.coversLightArea = true;
  // As gbp06: the registry-wide sweeps use 128^2 maps to bound the unlimited-budget kernels on llvmpipe.
  descriptor.sweepTestSettings = { "shadow_map_size=128" };
  descriptor.createPass = newTechniquePass<vtkSLSs08Pass>;
  descriptor.probe = [](const ProbeContext& context, glm::ivec2 pixel, ProbeRecorder& recorder) {
    const FrameResult& frame = *context.frame;
    const Ss08Twin twin = ss08TwinOf(frame, *context.scene, context.lightIndex);
    // Passes 2-3 smooth the whole LOQ map: the replay reads the level from the GPU's smoothed LOQ at the pixel, as
    // Ss08Test does; the twin's own smoothing of its raw levels over the 11 x 11 neighbourhood is recorded after.
    const double level = bufferValue(frame, "loq", pixel);
    const Ss08Sample sample = ss08Reference(
      twin.inputs, twin.structures(), Ss08Settings::from(frame.parameters), pixel.x, pixel.y, level, twin.budgets(), false, &recorder);
    // Ss08MatchesTheTwin: |GPU - twin| <= 1e-4 (area accumulated in float over up to ~1300 micro-occluders) on
    // pixels none of whose decisions lies within float rounding of its boundary: the receiver's (ambiguityOf), a
    // kernel edge within 1e-4 texel of a texel centre, a lit / umbra / growth test or a micro-occluder's depth
    // test within 1e-5 of d, l_raw within 1e-5 of an integer.
    ProbeOutcome outcome = probeOutcome(sample.sample, 1e-4,
      "ss08Reference (ss08/Ss08Technique.h), double precision, at the GPU's smoothed level (buffer loq at the pixel: "
      "passes 2-3 replayed from the frame, not recomputed; the twin's own 11 x 11 smoothing is recorded as "
      "loq_twin_smoothed), on the HSM / microrects rebuilt from the shadow map");
    if (sample.sample.evaluated)
    {
      const Ss08Search& search = sample.search;
      noteAmbiguity(outcome.ambiguity, "kernel edge from a texel centre (texels)", search.kernelEdgeMargin, 1e-4);
      noteAmbiguity(outcome.ambiguity, "lit / umbra / growth test from its boundary (relative to d)",
        search.decisionMargin, 1e-5);
      noteAmbiguity(outcome.ambiguity, "micro-occluder depth test from its boundary (relative to d)",
        sample.occlusionMargin, 1e-5);
      noteAmbiguity(outcome.ambiguity, "l_raw from an integer (levels)", search.levelMargin, 1e-5);
      const bool gpuCutShort = bufferValue(frame, "classification", pixel) == static_cast<double>(Ss08Class::CutShort);
      if (gpuCutShort || search.classification == Ss08Class::CutShort)
      {
        outcome.ambiguity += std::string(outcome.ambiguity.empty() ? "" : ", ") +
          (gpuCutShort ? "the GPU marked the pixel cut short" : "the twin puts the pixel over the loop cap") +
          format(" (", sample.microOccluders, " slots; llvmpipe stops the slot loop near ", ss08LoopCap,
            "): the GPU's value is partial");
      }
      recorder.beginGroup("smoothing (twin)");
      recorder.quantity("loq_twin_smoothed",
        ss08SmoothedLevelAt(twin, Ss08Settings::from(frame.parameters), frame.find("depth")->image, pixel.x, pixel.y), "levels",
        cite("§4.2, §8 (the twin's 11 x 11 depth-aware box over its own raw levels; beside loq, the GPU's)"));
    }
    return outcome;
  };
  // Quality-scalable (Schwarz & Stamminger 2008): a pixel evaluated above level 0 back-projects coarser
  // micro-occluders by design (its level of quality); at level 0 it is GBP06's back-projection, with its occluder
  // fusion where blockers lie at different depths.
  descriptor.accuracy.reference = ReferenceModel::AreaLight;
  descriptor.accuracy.tolerance = 0.05;
  descriptor.accuracy.approximations = { { "level of quality",
    "the pixel was evaluated above level 0 (loq > 0 or level_floor > 0)" }, occluderFusionApproximation(),
    coarseShadowMapApproximation(),
    { "multisample resolve", "msaa=4: a sample of the pixel lies off its first sample's depth (msaa_distinct_samples > "
      "0), or the visibility changes by more than the tolerance to a neighbouring pixel: the resolve gives the samples "
      "the pixel's or a neighbour's value, evaluated at another point (SS08 §7)" },
    perforatedCasterInMapApproximation() };
  descriptor.accuracy.markApproximations = [tolerance = descriptor.accuracy.tolerance](
    const ApproximationContext& context, ImageF& codes) {
    markWhere(*context.frame, "loq", [](float level) { return level > 0.0f; }, codes, 1.0f);
    markWhere(*context.frame, "level_floor", [](float level) { return level > 0.0f; }, codes, 1.0f);
    const ShadowMapFootprint footprint(context);
    markMultipleBlockerDepths(footprint, codes, 2.0f, tolerance);
    markCoarseShadowMap(footprint, codes, 3.0f, tolerance);
    markWhere(*context.frame, "msaa_distinct_samples", [](float samples) { return samples > 0.0f; }, codes, 4.0f);
    markSteepAcrossMultisampledPixels(*context.frame, codes, 4.0f, tolerance);
    markLightRaysThroughPerforatedCaster(context, codes, 5.0f);
  };
  return descriptor;
}

ImageF ss08BudgetImage(const Ss08Settings& settings, int width, int height)
{
  const std::string& path = settings.budgetImage;
  if (path.empty())
  {
    throw InputError("--set budget_map=image: needs --set budget_image=FILE.png (grey value = budget, 0 = unlimited)");
  }
  const PngImage png = readPngImage(path);
  const int maxBudget = settings.maxBudget;
  const double scale = png.bitDepth == 16 ? 255.0 / 65535.0 : 1.0; // 16-bit grey as 8-bit budgets
  ImageF budgets(width, height, 1);
  for (int y = 0; y < height; ++y)
  {
    for (int x = 0; x < width; ++x)
    {
      const int sourceX = std::min(static_cast<int>((x + 0.5) * png.samples.width / width), png.samples.width - 1);
      const int sourceY = std::min(static_cast<int>((y + 0.5) * png.samples.height / height), png.samples.height - 1);
      const int budget = static_cast<int>(std::lround(png.samples.at(sourceX, sourceY, 0) * scale));
      if (budget > maxBudget)
      {
        throw InputError(format(path, ": budget_image: grey value ", budget, " at pixel (", sourceX, ", ", sourceY,
          ") is above the budget range 0..", maxBudget));
      }
      budgets.at(x, y) = static_cast<float>(budget);
    }
  }
  return budgets;
}

int ss08PixelBudget(const Ss08Settings& settings, int x, int y, int imageWidth, const ImageF* budgetImage)
{
  const Ss08BudgetMap map = settings.budgetMap;
  if (map == Ss08BudgetMap::Image)
  {
    SL_CHECK_MSG(budgetImage, "budget_map=image needs the budget image");
    return static_cast<int>(std::floor(budgetImage->at(x, y) + 0.5f));
  }
  const int centre = settings.budget;
  if (map == Ss08BudgetMap::Uniform || centre == 0)
  {
    return centre;
  }
  // Fig. 1 d, in integers as Ss08Search.glsl's pixelBudget.
  const int border = settings.budgetBorder;
  const int fromEdge = imageWidth - std::abs(2 * x + 1 - imageWidth);
  const int numerator = (centre - border) * fromEdge;
  const int step = numerator >= 0 ? (numerator + imageWidth / 2) / imageWidth : -((-numerator + imageWidth / 2) / imageWidth);
  return std::max(border + step, 1);
}

namespace
{

int topLevel(int mapSize)
{
  return hsmLevelCount(mapSize);
}

int levelSize(int mapSize, int level)
{
  return level == 0 ? mapSize : hsmLevelSize(HsmLayout::MipMap, mapSize, level);
}

// EXTRA_SLOT / ceilLevel / fractionalLevel of Ss08Search.glsl: microrects may take one slot more per axis on
// the high side (ss08SlotRange), so b of them hold span - 1 <= (b - 2) 2^j where micropatches hold span <= (b - 1) 2^j.
int extraSlot(const Ss08Settings& settings)
{
  return settings.microrects ? 1 : 0;
}

int ceilLevel(int span, int budget, int extra, int top)
{
  if (budget == 0 || span <= budget - 1)
  {
    return 0; // span + 1 slots at level 0
  }
  const int reach = budget - 1 - extra;
  if (reach <= 0)
  {
    return top;
  }
  int level = 0;
  while (level < top && span - extra > reach << level)
  {
    ++level;
  }
  return level;
}

// `fromLog2`: whether l came from log2 (else it is an integer the float computation gives exactly).
double fractionalLevel(const Ss08Settings& settings, int span, int budget, int top, int& levelCeil, bool* fromLog2 = nullptr)
{
  if (fromLog2)
  {
    *fromLog2 = false;
  }
  const int forced = settings.forceLevel;
  if (forced >= 0)
  {
    levelCeil = std::min(forced, top);
    return levelCeil;
  }
  const int extra = extraSlot(settings);
  const int reach = budget - 1 - extra;
  levelCeil = ceilLevel(span, budget, extra, top);
  if (levelCeil == 0 || reach <= 0 || span - extra == reach << levelCeil)
  {
    return levelCeil;
  }
  if (fromLog2)
  {
    *fromLog2 = true;
  }
  return std::clamp(std::log2(static_cast<double>(span - extra) / reach), levelCeil - 1.0, static_cast<double>(levelCeil));
}

TexelRectangle grownArea(const Ss08Settings& settings, int mapSize, int level, const TexelRectangle& area)
{
  const TexelRectangle slots = ss08SlotRange(settings, mapSize, level, area);
  const int side = 1 << level;
  TexelRectangle grown;
  if (settings.microrects)
  {
    grown.lo = slots.lo * side - (side - 1);
    grown.hi = slots.hi * side + (side - 1);
  }
  else
  {
    grown.lo = slots.lo * side;
    grown.hi = (slots.hi + 1) * side - 1;
  }
  grown.lo = glm::max(glm::min(grown.lo, area.lo), glm::ivec2(0));
  grown.hi = glm::min(glm::max(grown.hi, area.hi), glm::ivec2(mapSize - 1));
  return grown;
}

int areaSpan(const TexelRectangle& area)
{
  return std::max(area.hi.x - area.lo.x, area.hi.y - area.lo.y);
}

} // namespace

TexelRectangle ss08SlotRange(const Ss08Settings& settings, int mapSize, int level, const TexelRectangle& area)
{
  TexelRectangle slots;
  slots.lo = area.lo >> level;
  if (settings.microrects)
  {
    slots.hi = glm::min((area.hi + (1 << level) - 1) >> level, glm::ivec2(levelSize(mapSize, level) - 1));
  }
  else
  {
    slots.hi = area.hi >> level;
  }
  return slots;
}

namespace
{

// The HSM's depth-range queries of one pixel's search (§3), each query's nodes kept for the probe until recorded
// with the decision they led to.
class Ss08RangeQueries
{
public:
  Ss08RangeQueries(const HierarchicalShadowMap& hsm, ProbeRecorder* recorder) : hsm_(hsm), recorder_(recorder) {}

  glm::dvec2 range(const TexelRectangle& area)
  {
    return hsm_.range(area.lo, area.hi, nullptr, recorder_ ? &nodes_ : nullptr);
  }
  void recordNodes(const std::string& decision)
  {
    recorder_->quantity("hsm_nodes_read", static_cast<double>(nodes_.size()), "count",
      "ShadowLab: nodes the range query read (HierarchicalShadowMap::range)");
    for (const HsmQueryNode& node : nodes_)
    {
      recorder_->node(probeNodeOf(node, decision));
    }
    nodes_.clear();
  }

private:
  const HierarchicalShadowMap& hsm_;
  ProbeRecorder* recorder_;
  std::vector<HsmQueryNode> nodes_;
};

// searchRange() of Ss08Search.glsl: the depth range of the area grown for its level (growth=on, §6) or of the area
// itself; `query` is the rectangle queried.
glm::dvec2 searchRange(const Ss08Settings& settings, const Ss08Search& search, Ss08RangeQueries& queries,
  const TexelRectangle& area, TexelRectangle& query)
{
  query = area;
  if (settings.growth)
  {
    int levelCeil = 0;
    fractionalLevel(settings, areaSpan(area), search.budget, topLevel(search.geometry.mapSize), levelCeil);
    query = grownArea(settings, search.geometry.mapSize, levelCeil, area);
  }
  return queries.range(query);
}

// One search area (kernel plus ring) and its depth-range query, recorded as a step of Fig. 2 b.
void recordSearchArea(ProbeRecorder* recorder, Ss08RangeQueries& queries, const Ss08Search& search, int refinement,
  const glm::dvec2& half, const glm::dvec2& depthRange, const std::string& decision)
{
  if (!recorder)
  {
    return;
  }
  recorder->beginGroup("search area " + std::to_string(refinement));
  recorder->quantity("kernel_half_texels", half, "texels",
    refinement == 0 ? cite("Fig. 2 b (the light seen from the receiver, at the near plane)")
                    : cite("Fig. 2 b, §3 (refined: at the minimum depth of the previous area)"));
  recorder->kernel({ "search area", glm::dvec2(search.area.lo), glm::dvec2(search.area.hi + 1),
    "refinement " + std::to_string(refinement), cite("Fig. 2 b (kernel plus one ring of texels)") });
  if (search.query.lo != search.area.lo || search.query.hi != search.area.hi)
  {
    recorder->kernel({ "grown query", glm::dvec2(search.query.lo), glm::dvec2(search.query.hi + 1),
      "refinement " + std::to_string(refinement), cite("§6, Fig. 7 (grown to the micro-occluders' support)") });
  }
  recorder->quantity("query_min_depth", depthRange.x, "linear depth", cite("§3 (min over the query, from the HSM)"));
  recorder->quantity("query_max_depth", depthRange.y, "linear depth", cite("§3 (max over the query, from the HSM)"));
  queries.recordNodes(decision);
}

// The search area of Fig. 2 b, refined kernel_refinements times at the previous area's minimum depth (§3): sets
// search.area and search.query, returns the final query's depth range, its kernel half-size and kernel.
struct SearchArea
{
  glm::dvec2 depthRange{ 0.0 };
  glm::dvec2 half{ 0.0 };
  TexelRectangle kernel;
};
SearchArea refineSearchArea(const Ss08Settings& settings, Ss08Search& search, Ss08RangeQueries& queries,
  ProbeRecorder* recorder)
{
  const SoftShadowGeometry& geometry = search.geometry;
  const glm::dvec2 uv = search.lookup.sm.uvTexels;
  SearchArea result;
  result.half = geometry.kernelHalfTexels(geometry.nearDepth);
  result.kernel = kernelRectangle(uv, result.half, geometry.mapSize, &search.kernelEdgeMargin);
  search.area = ringed(result.kernel, geometry.mapSize);
  result.depthRange = searchRange(settings, search, queries, search.area, search.query);
  const int refinements = settings.receiver.kernelRefinements;
  for (int refinement = 0; refinement < refinements; ++refinement)
  {
    recordSearchArea(recorder, queries, search, refinement, result.half, result.depthRange, "refine at its minimum depth");
    result.half = geometry.kernelHalfTexels(std::clamp(result.depthRange.x, geometry.nearDepth, geometry.d));
    result.kernel = kernelRectangle(uv, result.half, geometry.mapSize, &search.kernelEdgeMargin);
    search.area = ringed(result.kernel, geometry.mapSize);
    result.depthRange = searchRange(settings, search, queries, search.area, search.query);
  }
  return result;
}

// Lit / umbra / penumbra from the final query's depth range against the comparison depths over it (§3); an umbra
// needs the whole ring inside the map.
void decideFromDepthRange(const Ss08Settings& settings, Ss08Search& search, Ss08RangeQueries& queries,
  const SearchArea& area, ProbeRecorder* recorder)
{
  const double d = search.geometry.d;
  const glm::dvec2 comparison = search.geometry.comparisonDepthRange(search.query.lo, search.query.hi, search.bias);
  search.decisionMargin =
    std::min(std::abs(area.depthRange.x - comparison.y), std::abs(area.depthRange.y - comparison.x)) / d;
  const bool ringInsideMap = search.area.lo == area.kernel.lo - 1 && search.area.hi == area.kernel.hi + 1;
  if (area.depthRange.x >= comparison.y)
  {
    search.classification = Ss08Class::Lit;
  }
  else if (ringInsideMap && area.depthRange.y < comparison.x)
  {
    search.classification = Ss08Class::Umbra;
  }
  else
  {
    search.classification = Ss08Class::Penumbra;
  }
  const Ss08Class rangeClass = search.classification;
  recordSearchArea(recorder, queries, search, settings.receiver.kernelRefinements, area.half, area.depthRange,
    rangeClass == Ss08Class::Lit ? "lit" : rangeClass == Ss08Class::Umbra ? "umbra" : "penumbra");
  if (recorder)
  {
    recorder->beginGroup("depth range decision");
    recorder->quantity("comparison_depth_min", comparison.x, "linear depth",
      "ShadowLab: the smallest comparison depth over the query (receiver plane or d, minus the bias)");
    recorder->quantity("comparison_depth_max", comparison.y, "linear depth", "ShadowLab: the largest one");
    recorder->category("ring_inside_map", ringInsideMap ? "yes" : "no: no umbra decision (texels beyond the map unknown)",
      "ShadowLab (an umbra needs the whole ring inside the map)");
    recorder->category("range_decision",
      rangeClass == Ss08Class::Lit ? "lit: min >= every comparison depth"
        : rangeClass == Ss08Class::Umbra ? "umbra: max < every comparison depth" : "penumbra: back-project",
      cite("§3 (lit / umbra from the search area's depth range)"));
  }
}

// The over-precision class (§6, Fig. 7): penumbra only because the query grew (growth=on: back-projected), or lit
// only because it did not (growth=off: left lit, the class shows where growth would back-project).
void classifyOverPrecision(const Ss08Settings& settings, Ss08Search& search, Ss08RangeQueries& queries,
  ProbeRecorder* recorder)
{
  const bool growth = settings.growth;
  const double d = search.geometry.d;
  const auto litFor = [&](const TexelRectangle& area) {
    const glm::dvec2 otherRange = queries.range(area);
    const double otherComparison = search.geometry.comparisonDepthRange(area.lo, area.hi, search.bias).y;
    search.decisionMargin = std::min(search.decisionMargin, std::abs(otherRange.x - otherComparison) / d);
    const bool otherAreaLit = otherRange.x >= otherComparison;
    if (recorder)
    {
      recorder->beginGroup("growth test");
      recorder->kernel({ growth ? "area's own query" : "grown query", glm::dvec2(area.lo), glm::dvec2(area.hi + 1),
        otherAreaLit ? "lit" : "not lit", cite("§6, Fig. 7 (the other query decides the growth class)") });
      recorder->quantity("query_min_depth", otherRange.x, "linear depth", cite("§6, Fig. 7"));
      recorder->quantity("comparison_depth_max", otherComparison, "linear depth", "ShadowLab: the largest comparison depth over it");
      queries.recordNodes(otherAreaLit ? "lit" : "not lit");
    }
    return otherAreaLit;
  };
  if (growth && search.classification == Ss08Class::Penumbra && litFor(search.area))
  {
    search.classification = Ss08Class::GrowthPenumbra;
  }
  else if (!growth && search.classification == Ss08Class::Lit &&
    !litFor(grownArea(settings, search.geometry.mapSize, search.levelCeil, search.area)))
  {
    search.classification = Ss08Class::GrowthPenumbra;
  }
  search.backProjects = search.classification == Ss08Class::Penumbra ||
    (growth && search.classification == Ss08Class::GrowthPenumbra);
  search.state = !search.backProjects ? LoqState::None
    : search.budget == 0 || settings.forceLevel >= 0 ? LoqState::Fixed : LoqState::Smoothed;
}

void recordClassAndLevel(const Ss08Settings& settings, const Ss08Search& search, bool fromLog2,
  ProbeRecorder& recorder)
{
  recorder.beginGroup("class");
  if (search.classification == Ss08Class::GrowthPenumbra)
  {
    recorder.category("growth_class", settings.growth
        ? "penumbra only by the grown query (the area's own range says lit): back-projected"
        : "lit by the area's own range, penumbra by the grown one: left lit (the over-precision artifact)",
      cite("§6, Fig. 7 (over-precision)"));
  }
  recorder.category("class", ss08Categories[static_cast<int>(search.classification)].label, cite("§3, Fig. 7"));
  recorder.beginGroup("level of quality");
  recorder.quantity("span", search.span, "texels", "ShadowLab: the search area's larger side minus one, level-0 texels");
  recorder.quantity("search_area_texels", search.span + 1, "texels", cite("Fig. 2 b (the search area's larger side)"));
  const int extra = settings.forceLevel >= 0 ? 0 : extraSlot(settings);
  recorder.quantity("extra_slot", extra, "slots",
    "ShadowLab: microrects may take one slot more on the high side (ss08SlotRange)");
  recorder.quantity("level_ceil_raw", search.levelCeil, "level",
    "ShadowLab: the least level j with span - extra <= (b - 1 - extra) 2^j (at most b slots per axis at ceil(l))");
  recorder.quantity("loq_raw", search.levelRaw, "levels",
    settings.forceLevel >= 0 ? std::string("ShadowLab: force_level")
      : fromLog2 ? cite("§4.2, §8 (l = log2((span - extra) / (b - 1 - extra)), the project's rule)")
                 : cite("§4.2, §8 (an integer level: level 0 when span <= b - 1, the top level when b - 1 - extra <= 0)"));
  recorder.category("loq_state", loqStateLabels[static_cast<int>(search.state)],
    cite("§4.2, §8 (who the smoothing averages and where it stops)"));
}

} // namespace

// Fig. 3 step 1, in Ss08Search.glsl's steps: the pixel's budget (§4.2), the refined search area (Fig. 2 b, §3),
// the fractional level of quality (§4.2, §8), lit / umbra / penumbra from the depth range (§3) and the
// over-precision class (§6, Fig. 7).
Ss08Search ss08Search(const ShadowMapInputs& inputs, const Ss08Structures& structures, const Ss08Settings& settings,
  int x, int y, const ImageF* budgetImage, ProbeRecorder* recorder)
{
  SL_CHECK(structures.hsm);
  Ss08Search search;
  search.lookup = prepareShadowLookup(inputs, settings.receiver.bias, x, y, recorder);
  if (!search.lookup.sample.evaluated)
  {
    return search;
  }
  search.geometry = softShadowGeometry(inputs, search.lookup, settings.receiver.receiverPlaneBias, x, y);
  search.bias = search.lookup.sample.bias;
  search.budget = ss08PixelBudget(settings, x, y, inputs.camera.resolution.x, budgetImage);
  if (recorder)
  {
    recorder->beginGroup("budget");
    recorder->category("budget_map", budgetMapName(settings.budgetMap), cite("§4.2 (the budget map b_mo(x, y))"));
    recorder->quantity("budget", search.budget, "micro-occluders per axis",
      cite("§4.2 (b_mo at the pixel; 0 = unlimited, Table 2)"));
  }
  Ss08RangeQueries queries(*structures.hsm, recorder);
  const SearchArea area = refineSearchArea(settings, search, queries, recorder);

  search.span = areaSpan(search.area);
  bool fromLog2 = false;
  search.levelRaw =
    fractionalLevel(settings, search.span, search.budget, topLevel(search.geometry.mapSize), search.levelCeil, &fromLog2);
  // Only a level from log2 may round across an integer; the integer levels are exact in float too.
  search.levelMargin = fromLog2 ? std::abs(search.levelRaw - std::round(search.levelRaw)) : 1e300;

  decideFromDepthRange(settings, search, queries, area, recorder);
  classifyOverPrecision(settings, search, queries, recorder);
  if (recorder)
  {
    recordClassAndLevel(settings, search, fromLog2, *recorder);
  }
  return search;
}

ImageF ss08SmoothLoq(const ImageF& loqRawAndState, const ImageF& cameraDepth, const Ss08Settings& settings)
{
  const int width = loqRawAndState.width;
  const int height = loqRawAndState.height;
  ImageF current(width, height, 2);
  for (std::size_t i = 0; i < current.data.size(); ++i)
  {
    current.data[i] = loqRawAndState.data[i];
  }
  if (!settings.loqSmoothing)
  {
    return current;
  }
  const double threshold = settings.smoothingDepthThreshold;
  const auto smoothed = [](int state) { return state == static_cast<int>(LoqState::Smoothed); };
  for (int pass = 0; pass < 2; ++pass)
  {
    const glm::ivec2 step = pass == 0 ? glm::ivec2(1, 0) : glm::ivec2(0, 1);
    ImageF next = current;
    for (int y = 0; y < height; ++y)
    {
      for (int x = 0; x < width; ++x)
      {
        if (!smoothed(static_cast<int>(current.at(x, y, 1))))
        {
          continue;
        }
        const double centreDepth = cameraDepth.at(x, y);
        double sum = current.at(x, y, 0);
        double count = 1.0;
        for (int side = -1; side <= 1; side += 2)
        {
          double previousDepth = centreDepth;
          for (int k = 1; k <= ss08SmoothingRadius; ++k)
          {
            const glm::ivec2 neighbour = glm::ivec2(x, y) + side * k * step;
            if (neighbour.x < 0 || neighbour.y < 0 || neighbour.x >= width || neighbour.y >= height)
            {
              break;
            }
            const double depth = cameraDepth.at(neighbour.x, neighbour.y);
            if (!smoothed(static_cast<int>(current.at(neighbour.x, neighbour.y, 1))) ||
              std::abs(depth - previousDepth) > threshold * std::min(depth, previousDepth))
            {
              break;
            }
            sum += current.at(neighbour.x, neighbour.y, 0);
            count += 1.0;
            previousDepth = depth;
          }
        }
        double level = sum / count;
        if (pass == 1 && settings.loqFloorRaw)
        {
          level = std::max(level, static_cast<double>(loqRawAndState.at(x, y, 0)));
        }
        next.at(x, y, 0) = static_cast<float>(level);
      }
    }
    current = std::move(next);
  }
  return current;
}

namespace
{

struct MicroOccluder
{
  glm::ivec2 lo{ 0 };
  glm::ivec2 hi{ 0 };
  double depth = 0.0;
};

// microOccluder / microOccluderArea of Ss08Visibility.glsl.
struct Ss08Accumulator
{
  const Ss08Settings& settings;
  const Ss08Structures& structures;
  Ss08Search& search;
  Ss08Sample& result;
  glm::dvec2 receiverXy{ 0.0 };
  double halfSize = 0.0;
  bool microrects = false;
  bool levelBias = true;
  GapFilling gapFilling = GapFilling::LeftBottom;
  ProbeRecorder* recorder = nullptr;

  MicroOccluder at(int level, glm::ivec2 slot) const
  {
    MicroOccluder occluder;
    if (microrects)
    {
      const Microrect microrect = structures.microrects->at(level, slot);
      occluder.lo = microrect.lo;
      occluder.hi = microrect.hi;
      occluder.depth = microrect.depth;
      return occluder;
    }
    const int side = 1 << level;
    occluder.lo = slot * side;
    occluder.hi = glm::min(occluder.lo + side - 1, glm::ivec2(search.geometry.mapSize - 1));
    occluder.depth = structures.hsm->node(level, slot).x;
    return occluder;
  }

  // footprintDrop of Ss08Visibility.glsl: how much nearer than at the micro-occluder's centre the receiver's tangent
  // plane comes over its footprint (level_bias=on, levels above 0).
  double footprintDrop(int level, const MicroOccluder& occluder) const
  {
    const SoftShadowGeometry& geometry = search.geometry;
    if (!levelBias || level == 0 || !geometry.hasPlane)
    {
      return 0.0;
    }
    const glm::dvec2 a(occluder.lo);
    const glm::dvec2 b(occluder.hi + 1);
    const double nearest = std::min({ geometry.clampedPlaneDepth(a), geometry.clampedPlaneDepth(glm::dvec2(b.x, a.y)),
      geometry.clampedPlaneDepth(glm::dvec2(a.x, b.y)), geometry.clampedPlaneDepth(b) });
    return std::max(geometry.clampedPlaneDepth(0.5 * (a + b)) - nearest, 0.0);
  }

  bool occludes(int level, const MicroOccluder& occluder)
  {
    const double compared =
      search.geometry.tapComparisonDepth(0.5 * glm::dvec2(occluder.lo + occluder.hi + 1), search.bias) - footprintDrop(level, occluder);
    result.occlusionMargin = std::min(result.occlusionMargin, std::abs(occluder.depth - compared) / search.geometry.d);
    return occluder.depth < compared;
  }

  bool neighbourOccludes(int level, glm::ivec2 slot, double& depth)
  {
    depth = 0.0;
    const int size = levelSize(search.geometry.mapSize, level);
    if (slot.x < 0 || slot.y < 0 || slot.x >= size || slot.y >= size)
    {
      return false;
    }
    const MicroOccluder neighbour = at(level, slot);
    depth = neighbour.depth;
    return occludes(level, neighbour);
  }

  // The probe's record of a micro-occluder examined at `level`: a node (extent in level-0 texels, depth; a
  // micropatch's HSM node also holds its maximum) and whether it occludes.
  void recordOccluder(int level, glm::ivec2 slot, const MicroOccluder& occluder, bool occluding) const
  {
    const double maxDepth = microrects ? occluder.depth : structures.hsm->node(level, slot).y;
    recorder->node({ microrects ? "microrect" : "micropatch", level, occluder.lo, occluder.hi, occluder.depth, maxDepth,
      occluding ? "occludes" : "behind the receiver" });
  }

  // The clipped area the micro-occluder of `slot` hides; `rectangle` (if given) receives its back-projection
  // (lo, hi in light view x, y, not clipped) when it occludes, and is left empty (lo > hi) otherwise.
  double area(int level, glm::ivec2 slot, std::array<glm::dvec2, 2>* rectangle = nullptr)
  {
    if (rectangle)
    {
      *rectangle = { glm::dvec2(1.0), glm::dvec2(-1.0) };
    }
    const MicroOccluder occluder = at(level, slot);
    const bool occluding = occludes(level, occluder);
    if (recorder)
    {
      recordOccluder(level, slot, occluder, occluding);
    }
    if (!occluding)
    {
      return 0.0;
    }
    const SoftShadowGeometry& geometry = search.geometry;
    const double d = geometry.d;
    const glm::dvec2 tangentLo = geometry.windowMin + glm::dvec2(occluder.lo) * geometry.texelTangent;
    const glm::dvec2 tangentHi = geometry.windowMin + glm::dvec2(occluder.hi + 1) * geometry.texelTangent;
    glm::dvec2 lo = backProject(tangentLo, occluder.depth, receiverXy, d);
    glm::dvec2 hi = backProject(tangentHi, occluder.depth, receiverXy, d);
    if (!microrects)
    {
      double neighbourDepth = 0.0;
      if (gapFilling == GapFilling::LeftBottom)
      {
        if (neighbourOccludes(level, slot - glm::ivec2(1, 0), neighbourDepth))
        {
          lo.x = std::min(lo.x, backProject(tangentLo, neighbourDepth, receiverXy, d).x);
        }
        if (neighbourOccludes(level, slot - glm::ivec2(0, 1), neighbourDepth))
        {
          lo.y = std::min(lo.y, backProject(tangentLo, neighbourDepth, receiverXy, d).y);
        }
      }
      else if (gapFilling == GapFilling::RightTop)
      {
        if (neighbourOccludes(level, slot + glm::ivec2(1, 0), neighbourDepth))
        {
          hi.x = std::max(hi.x, backProject(tangentHi, neighbourDepth, receiverXy, d).x);
        }
        if (neighbourOccludes(level, slot + glm::ivec2(0, 1), neighbourDepth))
        {
          hi.y = std::max(hi.y, backProject(tangentHi, neighbourDepth, receiverXy, d).y);
        }
      }
    }
    const glm::dvec2 extent =
      glm::max(glm::min(hi, glm::dvec2(halfSize)) - glm::max(lo, glm::dvec2(-halfSize)), glm::dvec2(0.0));
    if (rectangle)
    {
      *rectangle = { lo, hi };
    }
    if (recorder)
    {
      // The back-projected rectangle as it lands (not clipped); its area over the light [-h, h]^2 is what counts.
      recorder->lightPolygon({ "level " + std::to_string(level) + " micro-occluder",
        { lo, glm::dvec2(hi.x, lo.y), hi, glm::dvec2(lo.x, hi.y) }, extent.x * extent.y });
    }
    return extent.x * extent.y;
  }
};

// accumulation=bitmask: OR into `mask` the samples inside the back-projected rectangle [lo, hi) (light view x, y)
// on a light of half side `halfSize`, by testing each sample (the shader sets whole runs of cells instead: the
// same set, since sample (i, j) lies in cell (i, j)); `margin` receives the least distance, on the unit square, of a
// sample to the rectangle's boundary (the float rectangle may put it on the other side).
void setBits(std::array<bool, ss08BitmaskSampleCount>& mask, const std::array<glm::dvec2, 2>& rectangle,
  double halfSize, double& margin)
{
  if (rectangle[0].x > rectangle[1].x)
  {
    return; // does not occlude
  }
  // The rectangle on the unit square (u = x / size + 1/2), as the shader maps it.
  const glm::dvec2 lo = rectangle[0] / (2.0 * halfSize) + 0.5;
  const glm::dvec2 hi = rectangle[1] / (2.0 * halfSize) + 0.5;
  const std::vector<glm::dvec2>& points = ss08BitmaskSamples().basePoints();
  for (int k = 0; k < ss08BitmaskSampleCount; ++k)
  {
    const glm::dvec2 p = points[static_cast<std::size_t>(k)];
    // Signed distance to the boundary (negative inside): a sample on an edge counts as inside on lo, outside on hi.
    const double outside = std::max(std::max(lo.x - p.x, p.x - hi.x), std::max(lo.y - p.y, p.y - hi.y));
    margin = std::min(margin, std::abs(outside));
    if (p.x >= lo.x && p.x < hi.x && p.y >= lo.y && p.y < hi.y)
    {
      mask[static_cast<std::size_t>(k)] = true;
    }
  }
}

double blendWeight(double fraction, double band)
{
  if (band <= 0.0)
  {
    return fraction > 0.0 ? 1.0 : 0.0;
  }
  return std::clamp((fraction - (1.0 - band)) / band, 0.0, 1.0);
}

} // namespace

namespace
{

// The buffers' values under their names (the probe sweep compares them with the GPU's at the pixel).
void recordSs08Result(const Ss08Sample& result, ProbeRecorder* recorder)
{
  if (!recorder)
  {
    return;
  }
  const Ss08Search& search = result.search;
  recorder->beginGroup("result");
  if (search.lookup.sample.evaluated)
  {
    recorder->quantity("level_floor", result.levelFloor, "level", cite("§4.2 (floor(l); 0 where no back-projection)"));
    recorder->quantity("blend_alpha", result.blendAlpha, "", cite("§4.2 (weight of ceil(l); 0 where one level)"));
    recorder->quantity("loq_budget_violation", result.budgetViolation, "levels",
      cite("§4.2 (levels the smoothing lowered ceil(l) below the budget's)"));
    recorder->quantity("query_growth_texels", result.queryGrowth, "texels", cite("§6, Fig. 7 (query grown by)"));
    recorder->quantity("micro_occluders", result.microOccluders, "count", cite("Table 2 (slots examined, both levels)"));
    recorder->quantity("micro_occluders_floor", result.slotsPerAxis[0].x * result.slotsPerAxis[0].y, "count",
      cite("§8 (slots floor(l) alone examines)"));
    recorder->quantity("micro_occluders_ceil", result.slotsPerAxis[1].x * result.slotsPerAxis[1].y, "count",
      cite("§8 (slots ceil(l) alone examines)"));
    recorder->quantity("occluded_bits", result.occludedBitsBlended, "light samples (of 256)",
      cite("§8 (the bitmask's popcount, blended as V; 0 with area accumulation)"));
    recorder->quantity("area_overcount", result.areaOvercount, "fraction of light area",
      cite("§3 (summed areas minus the bitmask's coverage: the overlaps area accumulation counts twice)"));
    if (search.classification == Ss08Class::CutShort)
    {
      recorder->category("cut_short", format("the GPU's slot loop stops near ", ss08LoopCap,
        " slots (llvmpipe's cap on loop iterations): its value and micro_occluders are partial, the twin's complete"),
        "ShadowLab (ss08LoopCap)");
    }
  }
  const int code = static_cast<int>(search.classification);
  recordCode(*recorder, "classification", code, ss08Categories[code].label, cite("§3, Fig. 7"));
  recorder->quantity("visibility", result.sample.visibility, "", cite("§4.2 (V = (1 - a) V(floor l) + a V(ceil l))"));
}

// selectLevels() of Ss08Visibility.glsl (§4.2): floor(l) weighted 1 - a and ceil(l) weighted a, a from the
// fractional part through the blend band; one level of weight 1 where l is an integer.
struct Ss08Levels
{
  int levels[2] = { 0, 0 };
  double weights[2] = { 1.0, 0.0 };
};
Ss08Levels selectLevels(const Ss08Settings& settings, double level, Ss08Sample& result, ProbeRecorder* recorder)
{
  result.level = level;
  result.levelFloor = static_cast<int>(std::floor(level));
  const int levelCeil = static_cast<int>(std::ceil(level));
  result.blendAlpha = blendWeight(level - result.levelFloor, settings.blendBand);
  result.budgetViolation = std::max(result.search.levelCeil - levelCeil, 0);
  Ss08Levels selected{ { result.levelFloor, levelCeil }, { 1.0 - result.blendAlpha, result.blendAlpha } };
  if (levelCeil == result.levelFloor)
  {
    selected.weights[0] = 1.0;
    selected.weights[1] = 0.0;
  }
  if (recorder)
  {
    recorder->beginGroup("blend");
    recorder->quantity("loq", level, "levels", cite("Fig. 3 step 2, §4.2 (the smoothed LOQ map at the pixel)"));
    recorder->quantity("level_ceil", levelCeil, "level", cite("§4.2 (ceil(l))"));
    recorder->quantity("blend_band", settings.blendBand, "levels", cite("§4.2 (1: always; GBP07: 0.1)"));
    recorder->quantity("weight_floor", selected.weights[0], "", cite("§4.2 (1 - a)"));
    recorder->quantity("weight_ceil", selected.weights[1], "", cite("§4.2 (a)"));
  }
  return selected;
}

// One level's slots (§8) back-projected onto the light and accumulated (§3: summed areas, or SS07's occlusion
// bitmask with accumulation=bitmask): the level's visibility.
double accumulateLevel(Ss08Accumulator& accumulator, const Ss08Levels& selected, int k, Ss08Sample& result,
  ProbeRecorder* recorder)
{
  const Ss08Search& search = result.search;
  const int level = selected.levels[k];
  const TexelRectangle slots = ss08SlotRange(accumulator.settings, search.geometry.mapSize, level, search.area);
  const double lightArea = 4.0 * accumulator.halfSize * accumulator.halfSize;
  const bool bitmask = accumulator.settings.bitmaskAccumulation;
  if (recorder)
  {
    recorder->beginGroup("level " + std::to_string(level) + (k == 0 ? " (floor)" : " (ceil)"));
    recorder->quantity("slot_lo", glm::dvec2(slots.lo), "level-j texels", cite("§8 (first slot examined)"));
    recorder->quantity("slot_hi", glm::dvec2(slots.hi), "level-j texels", cite("§8 (last slot examined)"));
    recorder->quantity("slots_per_axis", glm::dvec2(result.slotsPerAxis[k]), "slots",
      cite("§8 (at most b at ceil(l), 2b - 1 at floor(l))"));
    recorder->quantity("receiver_light_xy", accumulator.receiverXy, "world units",
      "ShadowLab: the receiver in light coordinates (light view x, y at its depth)");
    recorder->quantity("micro_occluder_bias", search.bias, "linear depth",
      "ShadowLab: the receiver's depth bias; with level_bias=on a micro-occluder above level 0 adds the receiver "
      "plane's drop over its footprint (SS08 §9 leaves biasing across levels to future work)");
  }
  double area = 0.0;
  std::array<bool, ss08BitmaskSampleCount> mask{};
  std::array<glm::dvec2, 2> rectangle;
  for (int j = slots.lo.y; j <= slots.hi.y; ++j)
  {
    for (int i = slots.lo.x; i <= slots.hi.x; ++i)
    {
      area += accumulator.area(level, { i, j }, bitmask ? &rectangle : nullptr);
      if (bitmask)
      {
        setBits(mask, rectangle, accumulator.halfSize, result.bitmaskMargin);
      }
      ++result.microOccluders;
    }
  }
  double levelVisibility = std::clamp(1.0 - area / lightArea, 0.0, 1.0);
  if (bitmask)
  {
    // SS07's occlusion bitmask (§8): V = 1 - popcount / N; area_overcount = the area's fraction minus it.
    const int bits = static_cast<int>(std::count(mask.begin(), mask.end(), true));
    result.occludedBits[static_cast<std::size_t>(k)] = bits;
    levelVisibility = 1.0 - static_cast<double>(bits) / ss08BitmaskSampleCount;
    result.occludedBitsBlended += selected.weights[k] * bits;
    result.areaOvercount +=
      selected.weights[k] * (area / lightArea - static_cast<double>(bits) / ss08BitmaskSampleCount);
  }
  if (recorder)
  {
    recorder->quantity("occluded_area", area, "world units^2",
      cite("§3 (back-projected micro-occluders' areas over the light, accumulated: overlaps count twice)"));
    recorder->quantity("light_area", lightArea, "world units^2", "scene (square light)");
    if (bitmask)
    {
      recorder->quantity("level_occluded_bits", result.occludedBits[static_cast<std::size_t>(k)], "light samples (of 256)",
        cite("§3, §8 (the occlusion bitmask's popcount: samples inside some back-projection)"));
    }
    recorder->quantity("level_visibility", levelVisibility, "", bitmask
        ? cite("§8 (1 - popcount / 256)") : cite("§3 (1 - occluded area / light area, clamped)"));
  }
  return levelVisibility;
}

// accumulateMicroOccluders() of Ss08Visibility.glsl: both levels' micro-occluders, blended (§4.2).
double accumulateMicroOccluders(const Ss08Settings& settings, const Ss08Structures& structures,
  const Ss08Levels& selected, Ss08Sample& result, ProbeRecorder* recorder)
{
  Ss08Search& search = result.search;
  Ss08Accumulator accumulator{ settings, structures, search, result };
  accumulator.receiverXy =
    (search.geometry.windowMin + search.lookup.sm.uvTexels * search.geometry.texelTangent) * search.geometry.d;
  accumulator.halfSize = 0.5 * search.geometry.lightSize;
  accumulator.microrects = settings.microrects;
  accumulator.levelBias = settings.levelBias;
  accumulator.gapFilling = settings.gapFilling;
  accumulator.recorder = recorder;
  double visibility = 0.0;
  for (int k = 0; k < 2; ++k)
  {
    const TexelRectangle slots = ss08SlotRange(settings, search.geometry.mapSize, selected.levels[k], search.area);
    result.slotsPerAxis[k] = glm::max(slots.hi - slots.lo + 1, glm::ivec2(0));
    if (selected.weights[k] > 0.0)
    {
      visibility += selected.weights[k] * accumulateLevel(accumulator, selected, k, result, recorder);
    }
  }
  return visibility;
}

} // namespace

// Fig. 3, in Ss08Visibility.glsl's steps: the search (step 1, ss08Search), the levels the smoothed LOQ selects
// (step 2, §4.2), and the micro-occluders of both levels back-projected and accumulated (step 3, §3, §8).
Ss08Sample ss08Reference(const ShadowMapInputs& inputs, const Ss08Structures& structures, const Ss08Settings& settings,
  int x, int y, double level, const ImageF* budgetImage, bool evaluateLit, ProbeRecorder* recorder)
{
  Ss08Sample result;
  result.search = ss08Search(inputs, structures, settings, x, y, budgetImage, recorder);
  Ss08Search& search = result.search;
  result.sample = search.lookup.sample;
  if (!search.lookup.sample.evaluated)
  {
    recordSs08Result(result, recorder);
    return result;
  }
  const glm::ivec2 growth = glm::max(search.area.lo - search.query.lo, search.query.hi - search.area.hi);
  result.queryGrowth = std::max(growth.x, growth.y);
  result.level = search.levelRaw;
  const bool lit = search.classification == Ss08Class::Lit || search.classification == Ss08Class::GrowthPenumbra;
  if (!search.backProjects && !(evaluateLit && lit))
  {
    result.sample.visibility = search.classification == Ss08Class::Umbra ? 0.0 : 1.0;
    if (recorder)
    {
      recorder->quantity("loq", result.level, "levels", cite("Fig. 3 step 2 (not smoothed: no back-projection)"));
    }
    recordSs08Result(result, recorder);
    return result;
  }
  SL_CHECK_MSG(!settings.microrects || structures.microrects, "micro_occluder=microrect needs the microrects");
  const Ss08Levels selected = selectLevels(settings, level, result, recorder);
  result.sample.visibility = accumulateMicroOccluders(settings, structures, selected, result, recorder);
  if (result.microOccluders > ss08LoopCap)
  {
    search.classification = Ss08Class::CutShort;
  }
  recordSs08Result(result, recorder);
  return result;
}

const LightSampleSet& ss08BitmaskSamples()
{
  static const LightSampleSet samples(
    lightSampleSetSettings("stratified", ss08BitmaskSampleCount, ss08BitmaskSeed));
  return samples;
}

Ss08Structures Ss08Twin::structures() const
{
  Ss08Structures result;
  result.hsm = &hsm;
  result.microrects = microrects ? &*microrects : nullptr;
  return result;
}

Ss08Twin ss08TwinOf(const FrameResult& frame, const Scene& scene, int lightIndex)
{
  Ss08Twin twin;
  twin.inputs = shadowMapInputsOf(frame, scene, lightIndex);
  twin.hsm = buildHierarchicalShadowMap(twin.inputs.shadowMapLinear, frame.parameters);
  const Ss08Settings settings = Ss08Settings::from(frame.parameters);
  if (settings.microrects)
  {
    twin.microrects = Microrects::build(twin.inputs.shadowMapLinear);
  }
  if (settings.budgetMap == Ss08BudgetMap::Image)
  {
    twin.budgetImage = ss08BudgetImage(settings, frame.resolution.x, frame.resolution.y);
  }
  return twin;
}

double ss08SmoothedLevelAt(const Ss08Twin& twin, const Ss08Settings& settings, const ImageF& cameraDepth, int x, int y)
{
  const glm::ivec2 lo = glm::max(glm::ivec2(x, y) - ss08SmoothingRadius, glm::ivec2(0));
  const glm::ivec2 hi = glm::min(glm::ivec2(x, y) + ss08SmoothingRadius, glm::ivec2(cameraDepth.width, cameraDepth.height) - 1);
  const glm::ivec2 extent = hi - lo + 1;
  ImageF rawAndState(extent.x, extent.y, 2);
  ImageF depth(extent.x, extent.y, 1);
  for (int j = 0; j < extent.y; ++j)
  {
    for (int i = 0; i < extent.x; ++i)
    {
      const Ss08Search search = ss08Search(twin.inputs, twin.structures(), settings, lo.x + i, lo.y + j, twin.budgets());
      rawAndState.at(i, j, 0) = static_cast<float>(search.levelRaw);
      rawAndState.at(i, j, 1) = static_cast<float>(search.state);
      depth.at(i, j) = cameraDepth.at(lo.x + i, lo.y + j);
    }
  }
  return ss08SmoothLoq(rawAndState, depth, settings).at(x - lo.x, y - lo.y, 0);
}

} // namespace sl
