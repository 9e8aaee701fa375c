// The per-pixel search of ss08 (Schwarz & Stamminger 2008, Fig. 3 step 1), shared by its LOQ pass
// (ss08/Ss08Loq.glsl) and its visibility pass (ss08/Ss08Visibility.glsl), which recomputes it rather than
// storing the search region (the result is the same, bit for bit: the same code on the same inputs):
//  - the budget b_mo(x, y) of the pixel (SS08 §4.2): uniform, a ramp in x (Fig. 1 d) or an image;
//  - the search area of Fig. 2 b, refined param_kernel_refinements times (SS08 §3; gbp06's kernel plus one
//    ring), with the depth-range query grown before each query to the whole support of every level-j
//    micro-occluder the area partly covers (SS08 §6, "over-precision", Fig. 7; GROWTH);
//  - the fractional level l from the search area and the budget (the project's rule, SS08 gives none):
//    span = the search area's larger side minus 1 (level-0 texels), l = clamp(log2(span / (b - 1)), 0, L) for
//    micropatches: at level j the slots examined per axis (the level-j texels over the area) are at most
//    ceil(span / 2^j) + 1, so ceil(l) holds at most b per axis and floor(l) at most 2b - 1 (SS08 §8:
//    "(2 b_mo)^2" and "(b_mo)^2"). Microrects may need one slot more on the high side (ss08SlotRange), at most
//    ceil((span + 2^j - 1) / 2^j) + 1, so for them l = log2((span - 1) / (b - 2)): at most b at ceil(l) and
//    2b - 2 at floor(l). b = 1 (b = 2 with microrects) is met only by the top level; b = 0 (unlimited) is
//    level 0 (Table 2's caption: no smoothing, no blending);
//  - lit / umbra from the (grown) area's depth range (SS08 §3), and the class of a pixel only the grown
//    query makes penumbra.
// CPU mirror: src/techniques/ss08/Ss08Technique.cpp (ss08Search). Needs common/GBufferInputs.glsl,
// LightModel.glsl, ShadowMapCommon.glsl, ShadowReceiver.glsl, SoftShadowKernels.glsl, HsmLookup.glsl.
#include "common/MipAtlasLayout.glsl"

uniform int ss08TopLevel; // L = ceil(log2 N): the level of one texel for the whole map
uniform ivec2 imageSize;
#if BUDGET_MAP == BUDGET_MAP_IMAGE
uniform sampler2D budgetMapTexture; // budget per pixel (0 = unlimited), the image resampled to the frame
#endif

// b_mo(x, y), micro-occluders per light axis; 0 = unlimited.
int pixelBudget(ivec2 pixel)
{
#if BUDGET_MAP == BUDGET_MAP_UNIFORM
  return int(param_budget);
#elif BUDGET_MAP == BUDGET_MAP_RAMP_X
  // Fig. 1 d: `budget` at the centre column falling linearly to `budget_border` at the left and right borders,
  // rounded to the nearest integer, in integers so the CPU mirror agrees exactly.
  int centre = int(param_budget);
  int border = int(param_budget_border);
  if (centre == 0)
  {
    return 0;
  }
  int fromEdge = imageSize.x - abs(2 * pixel.x + 1 - imageSize.x); // 1 .. W: distance to the nearer border
  int numerator = (centre - border) * fromEdge;
  int step = numerator >= 0 ? (numerator + imageSize.x / 2) / imageSize.x : -((-numerator + imageSize.x / 2) / imageSize.x);
  return max(border + step, 1);
#else
  return int(texelFetch(budgetMapTexture, pixel, 0).r + 0.5);
#endif
}

// The slot a microrect's range may take beyond a micropatch's on the high side (ss08SlotRange): the level-j
// slots over a span of s texels are at most ceil(s / 2^j) + 1 per axis for micropatches and
// ceil((s + 2^j - 1) / 2^j) + 1 for microrects, so b of them hold s - EXTRA_SLOT <= (b - 1 - EXTRA_SLOT) 2^j.
#if MICRO_OCCLUDER == MICRO_OCCLUDER_MICRORECT
const int EXTRA_SLOT = 1;
#else
const int EXTRA_SLOT = 0;
#endif

// The smallest level j whose slots over `span` fit the budget: level 0 when span <= b - 1 (span + 1 slots),
// else s - EXTRA_SLOT <= (b - 1 - EXTRA_SLOT) 2^j; the top level (one texel for the map) when no level fits by
// that rule (b = 1; b = 2 with microrects). One return: an early return can cost a counted loop
// iteration on llvmpipe (see Ss08Visibility.glsl, microOccluderArea).
int ceilLevel(int span, int budget)
{
  int reach = budget - 1 - EXTRA_SLOT;
  int level = 0;
  if (budget != 0 && span > budget - 1)
  {
    level = ss08TopLevel;
    if (reach > 0)
    {
      level = 0;
      while (level < ss08TopLevel && span - EXTRA_SLOT > reach << level)
      {
        ++level;
      }
    }
  }
  return level;
}

// l for a search area of `span` and budget b, and its ceiling (exact, integer): l = log2((span - EXTRA_SLOT) /
// (b - 1 - EXTRA_SLOT)) clamped to [ceil - 1, ceil], integer where the rule gives one; force_level overrides both.
float fractionalLevel(int span, int budget, out int levelCeil)
{
  float level;
  if (param_force_level >= 0.0)
  {
    levelCeil = min(int(param_force_level), ss08TopLevel);
    level = float(levelCeil);
  }
  else
  {
    levelCeil = ceilLevel(span, budget);
    int reach = budget - 1 - EXTRA_SLOT;
    level = float(levelCeil);
    if (levelCeil > 0 && reach > 0 && span - EXTRA_SLOT != reach << levelCeil)
    {
      level = clamp(log2(float(span - EXTRA_SLOT) / float(reach)), float(levelCeil - 1), float(levelCeil));
    }
  }
  return level;
}

// The slots (level-`level` texels) whose micro-occluders can cover the area [lo, hi]: micropatches, the
// level-j texels over it; microrects, whose extents lie strictly between the neighbouring level-j reference
// points (2^j a): a in [floor(lo / 2^j), ceil(hi / 2^j)].
void ss08SlotRange(int level, ivec2 lo, ivec2 hi, out ivec2 first, out ivec2 last)
{
  int levelSize = mipAtlasLevelSize(shadowMapSize, level);
  first = lo >> level;
#if MICRO_OCCLUDER == MICRO_OCCLUDER_MICRORECT
  last = min((hi + (1 << level) - 1) >> level, ivec2(levelSize - 1));
#else
  last = hi >> level;
#endif
}

// The area [lo, hi] grown to the whole support of the level-j slots covering it (SS08 §6): micropatches,
// their 2^j blocks; microrects, the boxes between their neighbouring reference points. Clamped to the map.
void grownArea(int level, ivec2 lo, ivec2 hi, out ivec2 grownLo, out ivec2 grownHi)
{
  ivec2 first;
  ivec2 last;
  ss08SlotRange(level, lo, hi, first, last);
  int side = 1 << level;
#if MICRO_OCCLUDER == MICRO_OCCLUDER_MICRORECT
  grownLo = first * side - (side - 1);
  grownHi = last * side + (side - 1);
#else
  grownLo = first * side;
  grownHi = (last + 1) * side - 1;
#endif
  grownLo = max(min(grownLo, lo), ivec2(0));
  grownHi = min(max(grownHi, hi), ivec2(shadowMapSize - 1));
}

struct Ss08Search
{
  ivec2 lo; // the search area: kernel texels plus one ring, clamped to the map
  ivec2 hi;
  ivec2 queryLo; // the area whose depth range decided lit / umbra (grown with GROWTH_ON)
  ivec2 queryHi;
  int budget;       // b_mo, 0 = unlimited
  int span;         // larger side of [lo, hi] minus 1
  float levelRaw;   // l before smoothing
  int levelCeil;    // ceil(l_raw), the growth level
  int decision;     // CLASSIFICATION_LIT, _UMBRA, _PENUMBRA or _GROWTH_PENUMBRA
};

int areaSpan(ivec2 lo, ivec2 hi)
{
  return max(hi.x - lo.x, hi.y - lo.y);
}

// The depth range the refinement and the decision use for the area [lo, hi]: of the area grown for its level
// (GROWTH_ON) or of the area itself.
vec2 searchRange(ivec2 lo, ivec2 hi, int budget, out ivec2 queryLo, out ivec2 queryHi)
{
  queryLo = lo;
  queryHi = hi;
#if GROWTH == GROWTH_ON
  int levelCeil;
  fractionalLevel(areaSpan(lo, hi), budget, levelCeil);
  grownArea(levelCeil, lo, hi, queryLo, queryHi);
#endif
  return hsmRange(queryLo, queryHi);
}

bool litFor(vec2 range, ivec2 lo, ivec2 hi, float d, float bias)
{
  return range.x >= comparisonDepthRange(lo, hi, d, bias).y;
}

// For a receiver that needs a shadow test.
Ss08Search ss08Search(ShadowReceiver receiver, ivec2 pixel)
{
  Ss08Search search;
  float d = receiver.depthLin;
  vec2 uv = receiver.uvTexels;
  search.budget = pixelBudget(pixel);
  setReceiverPlane(receiver.pWs, receiver.nWs);
  ivec2 kernelLo;
  ivec2 kernelHi;
  kernelRectangle(uv, kernelHalfTexels(d, lightNearDepth), kernelLo, kernelHi);
  ringed(kernelLo, kernelHi, search.lo, search.hi);
  vec2 range = searchRange(search.lo, search.hi, search.budget, search.queryLo, search.queryHi);
  for (int refinement = 0; refinement < int(param_kernel_refinements); ++refinement)
  {
    kernelRectangle(uv, kernelHalfTexels(d, clamp(range.x, lightNearDepth, d)), kernelLo, kernelHi);
    ringed(kernelLo, kernelHi, search.lo, search.hi);
    range = searchRange(search.lo, search.hi, search.budget, search.queryLo, search.queryHi);
  }
  search.span = areaSpan(search.lo, search.hi);
  search.levelRaw = fractionalLevel(search.span, search.budget, search.levelCeil);
  vec2 comparison = comparisonDepthRange(search.queryLo, search.queryHi, d, receiver.bias);
  // Umbra only when the ring lies inside the map: beyond it the micro-occluders are missing.
  bool ringInsideMap = search.lo == kernelLo - 1 && search.hi == kernelHi + 1;
  if (range.x >= comparison.y)
  {
    search.decision = CLASSIFICATION_LIT;
  }
  else if (ringInsideMap && range.y < comparison.x)
  {
    search.decision = CLASSIFICATION_UMBRA;
  }
  else
  {
    search.decision = CLASSIFICATION_PENUMBRA;
  }
  // Over-precision (Fig. 7): penumbra only because the query grew (GROWTH_ON), or lit only because it did not
  // (GROWTH_OFF, where the pixel stays lit; the class shows where growth would back-project).
  ivec2 otherLo;
  ivec2 otherHi;
#if GROWTH == GROWTH_ON
  otherLo = search.lo;
  otherHi = search.hi;
  bool litOther = search.decision == CLASSIFICATION_PENUMBRA && litFor(hsmRange(otherLo, otherHi), otherLo, otherHi, d, receiver.bias);
  if (litOther)
  {
    search.decision = CLASSIFICATION_GROWTH_PENUMBRA;
  }
#else
  if (search.decision == CLASSIFICATION_LIT)
  {
    grownArea(search.levelCeil, search.lo, search.hi, otherLo, otherHi);
    if (!litFor(hsmRange(otherLo, otherHi), otherLo, otherHi, d, receiver.bias))
    {
      search.decision = CLASSIFICATION_GROWTH_PENUMBRA;
    }
  }
#endif
  return search;
}
