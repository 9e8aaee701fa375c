// ss08, pass 4 of 4 (Schwarz & Stamminger 2008, Fig. 3 step 3): soft shadow mapping with a per-pixel level of
// quality. The search of ss08/Ss08Search.glsl (recomputed), then the micro-occluders of levels floor(l) and
// ceil(l) of the smoothed LOQ map, back-projected onto the square light, clipped to it and accumulated by area
// (SS08 §3), alpha-blended: V = (1 - a) V(floor l) + a V(ceil l) (§4.2; the band of BLEND_BAND
// below). Micro-occluders (MICRO_OCCLUDER): micropatches, level-j texels of the min-max pyramid at their
// minimum depth (SS08 §3, §5.1; gbp06's back-projection and gap filling), or microrects (SS08 §5.2, the
// extents and depths of structures/microrect). A micro-occluder occludes when its depth is in front of the
// receiver's comparison depth at its centre, less (LEVEL_BIAS) how much nearer the receiver's tangent plane comes
// over the micro-occluder's footprint: min aggregation puts coarse texels in front of tilted receivers.
// Both levels go through one loop and one back-projection call site (llvmpipe compiles each call site and
// caps loop iterations per invocation at 65535: the loop notes its last iteration, so a pixel the cap cut is
// flagged CLASSIFICATION_CUT_SHORT, exactly).
// ACCUMULATION: area (above) or bitmask, SS07's occlusion bitmask (SS08 §3, §8): 256 bits, one per
// light sample of the shared stratified 16 x 16 set (ss08BitmaskSamples in Ss08Technique.h), OR-ed over a level's
// micro-occluders, V = 1 - popcount / 256. Each back-projection is an axis-aligned rectangle, so its bits are set
// without a table and without a loop: the cells strictly inside it in x (or y) hold only samples inside it in x
// (or y), and only the <= 2 boundary columns and rows are tested sample by sample (four vec4 compares each).
// Outputs: the first eight as fragment outputs, the rest (IMAGE_OUTPUT_FIRST and after) by image stores.
// CPU mirror: src/techniques/ss08/Ss08Technique.cpp (ss08Reference).
#include "common/GBufferInputs.glsl"
#include "common/LightModel.glsl"
#include "common/ShadowMapCommon.glsl"
#include "common/ShadowReceiver.glsl"
#include "common/SoftShadowKernels.glsl"
#include "common/HsmLookup.glsl"
#include "common/ContourBackprojection.glsl"
#include "common/ContourKernel.glsl"
// Before the conditional include below: includes are expanded once, whatever the #if around them.
#include "common/MipAtlasLayout.glsl"
#if MICRO_OCCLUDER == MICRO_OCCLUDER_MICRORECT
#include "common/MicrorectLookup.glsl"
#endif
#include "ss08/Ss08Search.glsl"

layout(location = OUT_VISIBILITY) out float outVisibility;
layout(location = OUT_BUDGET) out float outBudget;
layout(location = OUT_SEARCH_AREA_TEXELS) out float outSearchAreaTexels;
layout(location = OUT_LOQ_RAW) out float outLoqRaw;
layout(location = OUT_LOQ) out float outLoq;
layout(location = OUT_LEVEL_FLOOR) out float outLevelFloor;
layout(location = OUT_BLEND_ALPHA) out float outBlendAlpha;
layout(location = OUT_MICRO_OCCLUDERS) out float outMicroOccluders;
layout(r32f, binding = OUT_CLASSIFICATION - IMAGE_OUTPUT_FIRST) uniform writeonly image2D classificationImage;
layout(r32f, binding = OUT_LOQ_BUDGET_VIOLATION - IMAGE_OUTPUT_FIRST) uniform writeonly image2D budgetViolationImage;
layout(r32f, binding = OUT_QUERY_GROWTH_TEXELS - IMAGE_OUTPUT_FIRST) uniform writeonly image2D queryGrowthImage;
layout(r32f, binding = OUT_MICRO_OCCLUDERS_FLOOR - IMAGE_OUTPUT_FIRST) uniform writeonly image2D floorSlotsImage;
layout(r32f, binding = OUT_MICRO_OCCLUDERS_CEIL - IMAGE_OUTPUT_FIRST) uniform writeonly image2D ceilSlotsImage;
layout(r32f, binding = OUT_OCCLUDED_BITS - IMAGE_OUTPUT_FIRST) uniform writeonly image2D occludedBitsImage;
layout(r32f, binding = OUT_AREA_OVERCOUNT - IMAGE_OUTPUT_FIRST) uniform writeonly image2D areaOvercountImage;

uniform sampler2D loqSmoothed; // x: l after smoothing (ss08/Ss08LoqSmoothing.glsl)

// The receiver being shaded.
float receiverDepth;
float receiverBias;
vec2 receiverXy; // light view x, y
float halfSize;  // of the square light

// The receiver's tangent plane's depth along the light ray through `texels`, clamped as tapComparisonDepth does
// (0.5 d where the plane turns away).
float clampedPlaneDepth(vec2 texels)
{
  vec3 ray = vec3(shadowWindowMin + texels * shadowTexelTangent, -1.0);
  float planeDepth = 1.0 / dot(receiverPlane, ray);
  return planeDepth > 0.0 ? clamp(planeDepth, 0.5 * receiverDepth, 2.0 * receiverDepth) : 0.5 * receiverDepth;
}

// LEVEL_BIAS (SS08 §9 leaves biasing across levels as future work): min aggregation gives a level-j micro-occluder
// the nearest depth of its 2^j block, so a receiver's own tilted surface inside the block comes nearer than the
// receiver's tangent plane at the block's centre by the plane's drop over the block. That drop, taken at the
// block's corners (the plane's depth is 1 / linear, its extremes lie there), is added to the bias above level 0.
// It grows with the receiver's slope and the block's size, not with the bias itself: a receiver facing the light
// gets none, so occluders close to the light (blocks of 2^7 texels and more) still occlude. No loop, no early
// return (llvmpipe's loop cap, see microOccluderArea).
float footprintDrop(int level, ivec2 lo, ivec2 hi)
{
  float drop = 0.0;
#if LEVEL_BIAS == LEVEL_BIAS_ON
  if (level > 0 && hasReceiverPlane)
  {
    vec2 a = vec2(lo);
    vec2 b = vec2(hi + 1);
    float nearest = min(min(clampedPlaneDepth(a), clampedPlaneDepth(vec2(b.x, a.y))),
      min(clampedPlaneDepth(vec2(a.x, b.y)), clampedPlaneDepth(b)));
    drop = max(clampedPlaneDepth(0.5 * (a + b)) - nearest, 0.0);
  }
#endif
  return drop;
}

// The micro-occluder of `slot` at `level`: its level-0 texel rectangle [lo, hi] and its depth.
void microOccluder(int level, ivec2 slot, out ivec2 lo, out ivec2 hi, out float depth)
{
#if MICRO_OCCLUDER == MICRO_OCCLUDER_MICRORECT
  ivec4 extent;
  microrectAt(level, slot, extent, depth);
  lo = extent.xy;
  hi = extent.zw;
#else
  int side = 1 << level;
  lo = slot * side;
  hi = min(lo + side - 1, ivec2(shadowMapSize - 1));
  depth = hsmNode(level, slot).x;
#endif
}

// Whether the micro-occluder [lo, hi] at `depth` is in front of the receiver (at its centre, less the footprint's
// drop with LEVEL_BIAS).
bool microOccludes(int level, ivec2 lo, ivec2 hi, float depth)
{
  return depth < tapComparisonDepth(0.5 * vec2(lo + hi + 1), receiverDepth, receiverBias) - footprintDrop(level, lo, hi);
}

#if MICRO_OCCLUDER == MICRO_OCCLUDER_MICROPATCH
// A neighbouring slot of the same level that occludes too, and its depth (gap filling; outside the level: no).
bool neighbourOccludes(int level, ivec2 slot, out float depth)
{
  depth = 0.0;
  bool occludes = false;
  int levelSize = mipAtlasLevelSize(shadowMapSize, level);
  if (all(greaterThanEqual(slot, ivec2(0))) && all(lessThan(slot, ivec2(levelSize))))
  {
    ivec2 lo;
    ivec2 hi;
    microOccluder(level, slot, lo, hi, depth);
    occludes = microOccludes(level, lo, hi, depth);
  }
  return occludes;
}
#endif

// The light area the micro-occluder of `slot` at `level` hides: its rectangle at its depth back-projected
// from the receiver onto the light (an axis-aligned rectangle, backProject of two opposite corners), gap-filled
// as gbp06 (micropatches), clipped to the light. No loops and no early returns: llvmpipe's cap counts every
// loop iteration, and Mesa may lower an early return from a function called in a loop to a loop exit that
// costs one (measured here: with early returns the slot loop was cut at about a third of the cap; gbp06's
// per-texel returns cost nothing, so it depends on the code around them).
// `rectangleLo`, `rectangleHi`: the back-projection on the unit square (u = x / size + 1/2, not clipped) when the
// micro-occluder occludes, an empty rectangle outside the square otherwise.
float microOccluderArea(int level, ivec2 slot, out vec2 rectangleLo, out vec2 rectangleHi)
{
  rectangleLo = vec2(2.0);
  rectangleHi = vec2(-1.0);
  ivec2 texelLo;
  ivec2 texelHi;
  float depth;
  microOccluder(level, slot, texelLo, texelHi, depth);
  float area = 0.0;
  if (microOccludes(level, texelLo, texelHi, depth))
  {
    vec2 tangentLo = shadowWindowMin + vec2(texelLo) * shadowTexelTangent;
    vec2 tangentHi = shadowWindowMin + vec2(texelHi + 1) * shadowTexelTangent;
    vec2 lo = backProject(tangentLo, depth, receiverXy, receiverDepth);
    vec2 hi = backProject(tangentHi, depth, receiverXy, receiverDepth);
#if MICRO_OCCLUDER == MICRO_OCCLUDER_MICROPATCH
    float neighbourDepth;
#if GAP_FILLING == GAP_FILLING_LEFT_BOTTOM
    if (neighbourOccludes(level, slot - ivec2(1, 0), neighbourDepth))
    {
      lo.x = min(lo.x, backProject(tangentLo, neighbourDepth, receiverXy, receiverDepth).x);
    }
    if (neighbourOccludes(level, slot - ivec2(0, 1), neighbourDepth))
    {
      lo.y = min(lo.y, backProject(tangentLo, neighbourDepth, receiverXy, receiverDepth).y);
    }
#elif GAP_FILLING == GAP_FILLING_RIGHT_TOP
    if (neighbourOccludes(level, slot + ivec2(1, 0), neighbourDepth))
    {
      hi.x = max(hi.x, backProject(tangentHi, neighbourDepth, receiverXy, receiverDepth).x);
    }
    if (neighbourOccludes(level, slot + ivec2(0, 1), neighbourDepth))
    {
      hi.y = max(hi.y, backProject(tangentHi, neighbourDepth, receiverXy, receiverDepth).y);
    }
#endif
#endif
    vec2 extent = max(min(hi, vec2(halfSize)) - max(lo, vec2(-halfSize)), vec2(0.0));
    area = extent.x * extent.y;
    rectangleLo = lo / (2.0 * halfSize) + 0.5;
    rectangleHi = hi / (2.0 * halfSize) + 0.5;
  }
  return area;
}

#if ACCUMULATION == ACCUMULATION_BITMASK
// The samples by column and by row (vtkSLSs08Pass): [4 i + q] holds the x of rows 4q..4q+3 of column i, and
// bitmaskSampleY[4 j + q] the y of columns 4q..4q+3 of row j. Sample (i, j) lies in cell (i, j) of the grid.
uniform vec4 bitmaskSampleX[BITMASK_GRID_SIDE * BITMASK_GRID_SIDE / 4];
uniform vec4 bitmaskSampleY[BITMASK_GRID_SIDE * BITMASK_GRID_SIDE / 4];

// Bit c of the result: component c of `inside` (c = 0..3).
uint packFour(bvec4 inside)
{
  uvec4 bits = uvec4(inside) << uvec4(0u, 1u, 2u, 3u);
  return bits.x | bits.y | bits.z | bits.w;
}

// The 16-bit mask of the four vec4 `values` (components in order) inside [lo, hi): lo <= v < hi, as the twin.
uint insideMask(vec4 v0, vec4 v1, vec4 v2, vec4 v3, float lo, float hi)
{
  return packFour(bvec4(uvec4(greaterThanEqual(v0, vec4(lo))) & uvec4(lessThan(v0, vec4(hi))))) |
    (packFour(bvec4(uvec4(greaterThanEqual(v1, vec4(lo))) & uvec4(lessThan(v1, vec4(hi))))) << 4u) |
    (packFour(bvec4(uvec4(greaterThanEqual(v2, vec4(lo))) & uvec4(lessThan(v2, vec4(hi))))) << 8u) |
    (packFour(bvec4(uvec4(greaterThanEqual(v3, vec4(lo))) & uvec4(lessThan(v3, vec4(hi))))) << 12u);
}

// Bits a..b (0..15) set; none when a > b.
uint bitRun(int a, int b)
{
  int first = clamp(a, 0, 15);
  int last = clamp(b, 0, 15);
  return a > b ? 0u : (0xFFFFu >> uint(15 - last)) & (0xFFFFu << uint(first));
}

// Four words of rectangleBits, rows firstRow .. firstRow + 7: a sample is inside when it is inside in x (the run of
// columns strictly inside, or its boundary column's bit for its row) and in y (a row strictly inside, or its
// boundary row's bit for its column).
uvec4 rectangleWords(int firstRow, uint columnRun, uint loColumnRows, uint hiColumnRows, uint loShift, uint hiShift,
  ivec2 rowCells, uint loRowColumns, uint hiRowColumns)
{
  ivec4 evenRows = ivec4(0, 2, 4, 6) + firstRow;
  ivec4 oddRows = evenRows + 1;
  uvec4 xEven = uvec4(columnRun) | (((uvec4(loColumnRows) >> uvec4(evenRows)) & 1u) << loShift) |
    (((uvec4(hiColumnRows) >> uvec4(evenRows)) & 1u) << hiShift);
  uvec4 xOdd = uvec4(columnRun) | (((uvec4(loColumnRows) >> uvec4(oddRows)) & 1u) << loShift) |
    (((uvec4(hiColumnRows) >> uvec4(oddRows)) & 1u) << hiShift);
  uvec4 yEven = (uvec4(greaterThan(evenRows, ivec4(rowCells.x))) & uvec4(lessThan(evenRows, ivec4(rowCells.y)))) * 0xFFFFu |
    uvec4(equal(evenRows, ivec4(rowCells.x))) * loRowColumns | uvec4(equal(evenRows, ivec4(rowCells.y))) * hiRowColumns;
  uvec4 yOdd = (uvec4(greaterThan(oddRows, ivec4(rowCells.x))) & uvec4(lessThan(oddRows, ivec4(rowCells.y)))) * 0xFFFFu |
    uvec4(equal(oddRows, ivec4(rowCells.x))) * loRowColumns | uvec4(equal(oddRows, ivec4(rowCells.y))) * hiRowColumns;
  return (xEven & yEven) | ((xOdd & yOdd) << 16u);
}

// The rectangle [lo, hi) on the unit square as bits: word w of the 8 (w < 4: `lowWords`[w], else `highWords`[w - 4])
// holds row 2w in bits 0..15 and row 2w + 1 in bits 16..31, bit i of a row being the sample of column i.
void rectangleBits(vec2 lo, vec2 hi, out uvec4 lowWords, out uvec4 highWords)
{
  // The cells holding lo and hi (exact: a power-of-two scale), clamped before the int conversion.
  ivec2 cellLo = ivec2(clamp(floor(lo * float(BITMASK_GRID_SIDE)), -1.0, float(BITMASK_GRID_SIDE)));
  ivec2 cellHi = ivec2(clamp(floor(hi * float(BITMASK_GRID_SIDE)), -1.0, float(BITMASK_GRID_SIDE)));
  ivec2 fetchLo = 4 * clamp(cellLo, 0, BITMASK_GRID_SIDE - 1);
  ivec2 fetchHi = 4 * clamp(cellHi, 0, BITMASK_GRID_SIDE - 1);
  // Columns strictly between the two hold samples inside in x; the boundary columns by test (rows as bits).
  uint columnRun = bitRun(cellLo.x + 1, cellHi.x - 1);
  bool loColumnIn = cellLo.x >= 0 && cellLo.x < BITMASK_GRID_SIDE;
  bool hiColumnIn = cellHi.x >= 0 && cellHi.x < BITMASK_GRID_SIDE && cellHi.x != cellLo.x;
  uint loColumnRows = loColumnIn ? insideMask(bitmaskSampleX[fetchLo.x], bitmaskSampleX[fetchLo.x + 1],
    bitmaskSampleX[fetchLo.x + 2], bitmaskSampleX[fetchLo.x + 3], lo.x, hi.x) : 0u;
  uint hiColumnRows = hiColumnIn ? insideMask(bitmaskSampleX[fetchHi.x], bitmaskSampleX[fetchHi.x + 1],
    bitmaskSampleX[fetchHi.x + 2], bitmaskSampleX[fetchHi.x + 3], lo.x, hi.x) : 0u;
  // The same in y: whole rows strictly between, the boundary rows by test (columns as bits).
  bool loRowIn = cellLo.y >= 0 && cellLo.y < BITMASK_GRID_SIDE;
  bool hiRowIn = cellHi.y >= 0 && cellHi.y < BITMASK_GRID_SIDE && cellHi.y != cellLo.y;
  uint loRowColumns = loRowIn ? insideMask(bitmaskSampleY[fetchLo.y], bitmaskSampleY[fetchLo.y + 1],
    bitmaskSampleY[fetchLo.y + 2], bitmaskSampleY[fetchLo.y + 3], lo.y, hi.y) : 0u;
  uint hiRowColumns = hiRowIn ? insideMask(bitmaskSampleY[fetchHi.y], bitmaskSampleY[fetchHi.y + 1],
    bitmaskSampleY[fetchHi.y + 2], bitmaskSampleY[fetchHi.y + 3], lo.y, hi.y) : 0u;
  uint loShift = uint(clamp(cellLo.x, 0, 15));
  uint hiShift = uint(clamp(cellHi.x, 0, 15));
  // Two calls, not a loop: llvmpipe counts every loop iteration against its cap.
  lowWords = rectangleWords(0, columnRun, loColumnRows, hiColumnRows, loShift, hiShift, ivec2(cellLo.y, cellHi.y),
    loRowColumns, hiRowColumns);
  highWords = rectangleWords(8, columnRun, loColumnRows, hiColumnRows, loShift, hiShift, ivec2(cellLo.y, cellHi.y),
    loRowColumns, hiRowColumns);
}

uint popcount(uvec4 words)
{
  uvec4 counts = uvec4(bitCount(words));
  return counts.x + counts.y + counts.z + counts.w;
}
#endif

// The blend weight of ceil(l) for the fractional part `fraction` (§4.2): with band 1 (the paper's
// choice, "we always perform alpha-blending") the fraction itself; with band < 1 only its last `band` of each
// level (GBP07's suggestion, 0.1); band 0: no blending, ceil(l) alone.
float blendWeight(float fraction)
{
  if (param_blend_band <= 0.0)
  {
    return fraction > 0.0 ? 1.0 : 0.0;
  }
  return clamp((fraction - (1.0 - param_blend_band)) / param_blend_band, 0.0, 1.0);
}

int slotCount(ivec2 first, ivec2 last)
{
  ivec2 side = max(last - first + 1, ivec2(0));
  return side.x * side.y;
}

// Fig. 3 step 2 (§4.2): the two levels the smoothed LOQ selects, floor(l) weighted 1 - a and ceil(l) weighted a;
// a level of weight 0 is skipped, and an integer l is one level of weight 1. CPU twin: selectLevels.
struct Ss08Levels
{
  float level;
  int levels[2];
  float weights[2];
  float alpha;
};

Ss08Levels selectLevels(ivec2 pixel)
{
  Ss08Levels selected;
  selected.level = texelFetch(loqSmoothed, pixel, 0).x;
  int levelFloor = int(floor(selected.level));
  int levelCeil = int(ceil(selected.level));
  selected.alpha = blendWeight(selected.level - float(levelFloor));
  selected.levels = int[2](levelFloor, levelCeil);
  selected.weights = float[2](1.0 - selected.alpha, selected.alpha);
  if (levelCeil == levelFloor)
  {
    selected.weights = float[2](1.0, 0.0);
  }
  return selected;
}

// Fig. 3 step 3 (§3, §8): both levels' micro-occluders back-projected onto the light and accumulated (summed areas,
// or SS07's occlusion bitmask), blended as §4.2 blends the levels. One loop over the slots of both levels: it is
// the loop llvmpipe counts, and its helpers have no loops and no early returns. CPU twin: accumulateMicroOccluders.
struct Ss08Accumulation
{
  float visibility;
  int floorSlots;    // slots floor(l) alone examines, examined or not
  int ceilSlots;
  int examined;      // slots examined, both levels (fewer than their total where the loop cap cut it)
  bool reachedLast;
  float occludedBits;
  float areaOvercount;
};

Ss08Accumulation accumulateMicroOccluders(ShadowReceiver receiver, Ss08Search search, Ss08Levels selected)
{
  Ss08Accumulation result;
  ivec2 first[2];
  ivec2 last[2];
  int counts[2];
  for (int k = 0; k < 2; ++k)
  {
    ss08SlotRange(selected.levels[k], search.lo, search.hi, first[k], last[k]);
    counts[k] = selected.weights[k] > 0.0 ? slotCount(first[k], last[k]) : 0;
  }
  result.floorSlots = slotCount(first[0], last[0]);
  result.ceilSlots = slotCount(first[1], last[1]);

  receiverDepth = receiver.depthLin;
  receiverBias = receiver.bias;
  receiverXy = (shadowWindowMin + receiver.uvTexels * shadowTexelTangent) * receiverDepth;
  halfSize = 0.5 * lightSizeWorld;
  float areas[2] = float[2](0.0, 0.0);
  int total = counts[0] + counts[1];
  result.reachedLast = total == 0;
  result.examined = 0; // total, unless the cap cut the loop
#if ACCUMULATION == ACCUMULATION_BITMASK
  // The two levels' bitmasks (rectangleBits' word layout), OR-ed.
  uvec4 floorMask[2] = uvec4[2](uvec4(0u), uvec4(0u));
  uvec4 ceilMask[2] = uvec4[2](uvec4(0u), uvec4(0u));
#endif
  for (int k = 0; k < total; ++k)
  {
    int which = k < counts[0] ? 0 : 1;
    int local = k - which * counts[0];
    int width = last[which].x - first[which].x + 1;
    ivec2 slot = first[which] + ivec2(local % width, local / width);
    vec2 rectangleLo;
    vec2 rectangleHi;
    areas[which] += microOccluderArea(selected.levels[which], slot, rectangleLo, rectangleHi);
#if ACCUMULATION == ACCUMULATION_BITMASK
    uvec4 lowWords;
    uvec4 highWords;
    rectangleBits(rectangleLo, rectangleHi, lowWords, highWords);
    uvec4 toFloor = uvec4(which == 0 ? 0xFFFFFFFFu : 0u);
    floorMask[0] |= lowWords & toFloor;
    floorMask[1] |= highWords & toFloor;
    ceilMask[0] |= lowWords & ~toFloor;
    ceilMask[1] |= highWords & ~toFloor;
#endif
    result.reachedLast = k == total - 1;
    result.examined = k + 1;
  }
  float lightArea = 4.0 * halfSize * halfSize;
  float weights[2] = selected.weights;
#if ACCUMULATION == ACCUMULATION_BITMASK
  // V = 1 - popcount / N per level (SS07, SS08 §8), blended as the areas.
  float sampleCount = float(BITMASK_GRID_SIDE * BITMASK_GRID_SIDE);
  float bits[2] = float[2](float(popcount(floorMask[0]) + popcount(floorMask[1])),
    float(popcount(ceilMask[0]) + popcount(ceilMask[1])));
  result.visibility = weights[0] * (1.0 - bits[0] / sampleCount) + weights[1] * (1.0 - bits[1] / sampleCount);
  result.occludedBits = weights[0] * bits[0] + weights[1] * bits[1];
  result.areaOvercount = weights[0] * (areas[0] / lightArea - bits[0] / sampleCount) +
    weights[1] * (areas[1] / lightArea - bits[1] / sampleCount);
#else
  result.visibility = weights[0] * clamp(1.0 - areas[0] / lightArea, 0.0, 1.0) +
    weights[1] * clamp(1.0 - areas[1] / lightArea, 0.0, 1.0);
  result.occludedBits = 0.0;
  result.areaOvercount = 0.0;
#endif
  return result;
}

void main()
{
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  ShadowReceiver receiver = prepareShadowReceiver(pixel);
  outVisibility = receiver.visibility;
  outBudget = 0.0;
  outSearchAreaTexels = 0.0;
  outLoqRaw = 0.0;
  outLoq = 0.0;
  outLevelFloor = 0.0;
  outBlendAlpha = 0.0;
  outMicroOccluders = 0.0;
  int classification = CLASSIFICATION_NOT_TESTED;
  int budgetViolation = 0;
  int queryGrowth = 0;
  int floorSlots = 0;
  int ceilSlots = 0;
  float occludedBits = 0.0;
  float areaOvercount = 0.0;
  if (receiver.needsShadowTest)
  {
    // Fig. 3 step 1: the search (Ss08Search.glsl).
    Ss08Search search = ss08Search(receiver, pixel);
    classification = search.decision;
    outBudget = float(search.budget);
    outSearchAreaTexels = float(search.span + 1);
    outLoqRaw = search.levelRaw;
    outLoq = search.levelRaw;
    ivec2 growth = max(search.lo - search.queryLo, search.queryHi - search.hi);
    queryGrowth = max(growth.x, growth.y);
    bool backProjects = search.decision == CLASSIFICATION_PENUMBRA ||
      (GROWTH == GROWTH_ON && search.decision == CLASSIFICATION_GROWTH_PENUMBRA);
    if (!backProjects)
    {
      outVisibility = search.decision == CLASSIFICATION_UMBRA ? 0.0 : 1.0;
    }
    else
    {
      Ss08Levels selected = selectLevels(pixel);
      outLoq = selected.level;
      outLevelFloor = float(selected.levels[0]);
      outBlendAlpha = selected.alpha;
      budgetViolation = max(search.levelCeil - selected.levels[1], 0);
      Ss08Accumulation accumulation = accumulateMicroOccluders(receiver, search, selected);
      outVisibility = accumulation.visibility;
      floorSlots = accumulation.floorSlots;
      ceilSlots = accumulation.ceilSlots;
      occludedBits = accumulation.occludedBits;
      areaOvercount = accumulation.areaOvercount;
      outMicroOccluders = float(accumulation.examined);
      if (!accumulation.reachedLast)
      {
        classification = CLASSIFICATION_CUT_SHORT;
      }
    }
  }
  imageStore(classificationImage, pixel, vec4(float(classification)));
  imageStore(budgetViolationImage, pixel, vec4(float(budgetViolation)));
  imageStore(queryGrowthImage, pixel, vec4(float(queryGrowth)));
  imageStore(floorSlotsImage, pixel, vec4(float(floorSlots)));
  imageStore(ceilSlotsImage, pixel, vec4(float(ceilSlots)));
  imageStore(occludedBitsImage, pixel, vec4(occludedBits));
  imageStore(areaOvercountImage, pixel, vec4(areaOvercount));
}
