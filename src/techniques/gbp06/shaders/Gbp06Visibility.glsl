// GBP06 soft shadow mapping by back-projection of micropatches (Guennebaud et al. 2006), per pixel: the kernel
// of Eq. 1 (Yang et al. 2009) tightened by the minimum depth inside it and lit / umbra from the min-max
// structure (the preamble of gbp07/Gbp07Visibility.glsl), then every occluding texel of the kernel and its ring
// as a micropatch, back-projected onto the light and clipped to it, gap-filled toward its left and bottom
// neighbours in texture space as Schwarz & Stamminger 2008 (SS08 §3) describe GBP06's rule, or
// toward the right and top ones, the mirror convention (GAP_FILLING), found by a loop over the texels or by
// the DU07 walk of the min-max quadtree (TRAVERSAL). Conventions, the gap rule and the traversal:
// src/techniques/gbp06/Gbp06Technique.h.
// CPU mirror: src/techniques/gbp06/Gbp06Technique.cpp.
#include "common/GBufferInputs.glsl"
#include "common/LightModel.glsl"
#include "common/ShadowMapCommon.glsl"
#include "common/ShadowReceiver.glsl"
#include "common/SoftShadowKernels.glsl"
#include "common/HsmLookup.glsl"
#include "common/ContourBackprojection.glsl"
#include "common/ContourKernel.glsl"

layout(location = OUT_VISIBILITY) out float outVisibility;
layout(location = OUT_KERNEL_TEXELS) out float outKernelTexels;
layout(location = OUT_OCCLUDING_TEXELS) out float outOccludingTexels;
layout(location = OUT_VISITED_NODES) out float outVisitedNodes;
layout(location = OUT_CLASSIFICATION) out float outClassification;

// `classification` codes CLASSIFICATION_* come from the preamble (Gbp06Technique.cpp, from BackprojectionClass).
// Where the GL caps loop iterations (llvmpipe: 65535, all loops together, counted once per SIMD vector of
// pixels, so a pixel's loops are stopped by its neighbours' longer rows too), a pixel's loop is cut short: it is
// then flagged CLASSIFICATION_OVER_LOOP_BUDGET, detected (the texel loop never reached its last texel, the walk
// never took its exit), so on such GLs results can be told apart and GLs without a cap flag nothing. Counting
// iterations could not tell: a pixel sharing its vector with wider kernels was cut with far fewer of its own
// (measured: Gbp06.KernelsTheLoopCapCutsShortAreFlaggedExactly). The per-texel and per-node helpers below have
// no loops and no early returns, so they add no loop iterations.

// The receiver being shaded and what its micropatches add up to.
float receiverDepth;
float receiverBias;
vec2 receiverXy; // light view x, y
float halfSize;  // of the square light
ivec2 regionLo;  // the texels searched: the kernel plus one ring, clamped to the map
ivec2 regionHi;
float occludedArea;
int occludingTexels;
int visitedNodes;
bool traversalFinished; // the traversal ran to its end: no loop cap stopped it

// Whether texel (i, j) is an occluding micropatch for the receiver, and its depth; outside the map, never.
bool occludesAt(ivec2 texel, out float depth)
{
  depth = 0.0;
  bool occludes = false;
  if (all(greaterThanEqual(texel, ivec2(0))) && all(lessThan(texel, ivec2(shadowMapSize))))
  {
    depth = texelFetch(shadowMapLinear, texel, 0).r;
    occludes = depth < tapComparisonDepth(vec2(texel) + 0.5, receiverDepth, receiverBias);
  }
  return occludes;
}

// Texel (i, j) spans [i, i + 1) x [j, j + 1); its square at its depth back-projects to the rectangle between the
// back-projections of its corners (i, j) and (i + 1, j + 1) (backProject increases with the tangent).
void examineTexel(ivec2 texel)
{
  float depth;
  if (occludesAt(texel, depth))
  {
    vec2 tangentLo = shadowWindowMin + vec2(texel) * shadowTexelTangent;
    vec2 tangentHi = shadowWindowMin + vec2(texel + 1) * shadowTexelTangent;
    vec2 lo = backProject(tangentLo, depth, receiverXy, receiverDepth);
    vec2 hi = backProject(tangentHi, depth, receiverXy, receiverDepth);
    // Gap filling: out to an occluding neighbour's shared edge, back-projected at the neighbour's depth, when that
    // lies further out (never shrunk). The neighbours are read directly, also outside the searched region: a texel
    // beyond the ring shares with its ring neighbour an edge outside the kernel, which back-projects outside the
    // light at every depth the kernel allows, so no region bound depends on the direction.
#if GAP_FILLING == GAP_FILLING_LEFT_BOTTOM
    // SS08 §3: "extending a micropatch to its left and bottom neighbors in texture space" (GBP06). The left
    // neighbour's right edge and the bottom neighbour's top edge both pass through this texel's corner tangentLo.
    float neighbourDepth;
    if (occludesAt(texel - ivec2(1, 0), neighbourDepth))
    {
      lo.x = min(lo.x, backProject(tangentLo, neighbourDepth, receiverXy, receiverDepth).x);
    }
    if (occludesAt(texel - ivec2(0, 1), neighbourDepth))
    {
      lo.y = min(lo.y, backProject(tangentLo, neighbourDepth, receiverXy, receiverDepth).y);
    }
#elif GAP_FILLING == GAP_FILLING_RIGHT_TOP
    // The mirror convention: the right neighbour's left edge and the top neighbour's bottom edge (through tangentHi).
    float neighbourDepth;
    if (occludesAt(texel + ivec2(1, 0), neighbourDepth))
    {
      hi.x = max(hi.x, backProject(tangentHi, neighbourDepth, receiverXy, receiverDepth).x);
    }
    if (occludesAt(texel + ivec2(0, 1), neighbourDepth))
    {
      hi.y = max(hi.y, backProject(tangentHi, neighbourDepth, receiverXy, receiverDepth).y);
    }
#endif
    vec2 extent = max(min(hi, vec2(halfSize)) - max(lo, vec2(-halfSize)), vec2(0.0));
    occludedArea += extent.x * extent.y;
    ++occludingTexels;
  }
}

#if TRAVERSAL == TRAVERSAL_HSM
// The comparison depth at a texel-grid corner, for the receiver plane (tapComparisonDepth's formula).
float cornerComparison(vec2 position, inout bool unbounded)
{
  vec3 ray = vec3(shadowWindowMin + position * shadowTexelTangent, -1.0);
  float planeDepth = 1.0 / dot(receiverPlane, ray);
  unbounded = unbounded || !(planeDepth > 0.0);
  return clamp(planeDepth, 0.5 * receiverDepth, 2.0 * receiverDepth) - receiverBias;
}

// comparisonDepthRange(first, last, d, bias).y with its corner loop unrolled (llvmpipe's loop budget).
float maxComparisonDepth(ivec2 first, ivec2 last)
{
  float result = receiverDepth - receiverBias;
#if RECEIVER_PLANE_BIAS == RECEIVER_PLANE_BIAS_ON
  if (hasReceiverPlane)
  {
    bool unbounded = false;
    result = max(result, cornerComparison(vec2(first), unbounded));
    result = max(result, cornerComparison(vec2(last.x + 1, first.y), unbounded));
    result = max(result, cornerComparison(vec2(first.x, last.y + 1), unbounded));
    result = max(result, cornerComparison(vec2(last + 1), unbounded));
    if (unbounded)
    {
      result = 2.0 * receiverDepth - receiverBias;
    }
  }
#endif
  return result;
}

// Whether quadtree node (level, index), texels [index 2^level, (index + 1) 2^level), may hold an occluding texel
// of the region (DU07's pruning test): its minimum depth is in front of the largest comparison depth over its
// texels in the region (hsmNode: the same range in every layout of the structure).
bool mayOcclude(int level, ivec2 index)
{
  ++visitedNodes;
  ivec2 first = max(index << level, regionLo);
  ivec2 last = min(((index + 1) << level) - 1, regionHi);
  vec2 node = hsmNode(level, index);
  return node.x < maxComparisonDepth(first, last);
}
#endif

// Every occluding micropatch of the region, once. A GL's cap on loop iterations ends the loops without their
// exits being taken, so traversalFinished says whether the traversal ran to its end.
void accumulateMicropatches()
{
  occludedArea = 0.0;
  occludingTexels = 0;
  visitedNodes = 0;
  traversalFinished = false;
#if TRAVERSAL == TRAVERSAL_KERNEL
  // The region is never empty (the kernel's texel and its ring, clamped to the map): its last texel is examined
  // last, unless the cap stops the loops before.
  for (int j = regionLo.y; j <= regionHi.y; ++j)
  {
    for (int i = regionLo.x; i <= regionHi.x; ++i)
    {
      traversalFinished = i == regionHi.x && j == regionHi.y;
      ++visitedNodes;
      examineTexel(ivec2(i, j));
    }
  }
#else
  // DU07, depth first from the lowest node covering the region, entered as the one child of its parent that
  // meets the region. Stackless: a node's index is its path (bit k of x and y: the child taken below level
  // k + 1), so going up is a shift.
  int rootLevel = 0;
  while (any(notEqual(regionLo >> rootLevel, regionHi >> rootLevel)))
  {
    ++rootLevel;
  }
  int topLevel = rootLevel + 1;
  int level = topLevel; // the level of `node`, whose children are examined
  ivec2 node = regionLo >> topLevel;
  int child = 0;
  // The walk ends by the break below (the top node's children all examined), which a loop the cap stops never
  // takes. The bound on `step` is never reached (an entered node costs 5 iterations, its 4 children and the way
  // back up, and at most wh/3 + 2(w + h) + 4 topLevel nodes of a w x h region's quadtree meet it), but it
  // gives the loop a second way out: with `while (true)` the compiler knows the break is the only exit and folds
  // traversalFinished to true (measured on llvmpipe: no pixel flagged, 15-766 cut short per frame).
  ivec2 regionSize = regionHi - regionLo + 1;
  int stepBound = 5 * ((regionSize.x + 2) * (regionSize.y + 2) + 4 * topLevel);
  for (int step = 0; step < stepBound; ++step)
  {
    if (child == 4)
    {
      if (level == topLevel)
      {
        traversalFinished = true;
        break;
      }
      child = (node.x & 1) + 2 * (node.y & 1) + 1;
      node >>= 1;
      ++level;
      continue;
    }
    ivec2 index = 2 * node + ivec2(child & 1, child >> 1);
    ivec2 first = index << (level - 1);
    ivec2 last = ((index + 1) << (level - 1)) - 1;
    if (any(greaterThan(first, regionHi)) || any(lessThan(last, regionLo)) || !mayOcclude(level - 1, index))
    {
      ++child;
    }
    else if (level == 1)
    {
      examineTexel(index);
      ++child;
    }
    else
    {
      node = index;
      --level;
      child = 0;
    }
  }
#endif
}

void main()
{
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  ShadowReceiver receiver = prepareShadowReceiver(pixel);
  outVisibility = receiver.visibility;
  outKernelTexels = 0.0;
  outOccludingTexels = 0.0;
  outVisitedNodes = 0.0;
  outClassification = CLASSIFICATION_NOT_TESTED;
  if (!receiver.needsShadowTest)
  {
    return;
  }
  float d = receiver.depthLin;
  float bias = receiver.bias;
  vec2 uv = receiver.uvTexels;
  ContourKernel kernel = prepareContourKernel(receiver); // as gbp07
  ivec2 ringLo = kernel.ringLo;
  ivec2 ringHi = kernel.ringHi;
  outKernelTexels = kernel.kernelTexels;
  if (kernel.decision != KERNEL_PENUMBRA)
  {
    outVisibility = kernel.decision == KERNEL_LIT ? 1.0 : 0.0;
    outClassification = kernel.decision == KERNEL_LIT ? CLASSIFICATION_LIT : CLASSIFICATION_UMBRA;
    return;
  }

  receiverDepth = d;
  receiverBias = bias;
  receiverXy = (shadowWindowMin + uv * shadowTexelTangent) * d;
  halfSize = 0.5 * lightSizeWorld;
  regionLo = ringLo;
  regionHi = ringHi;
  accumulateMicropatches();
  outOccludingTexels = float(occludingTexels);
  outVisitedNodes = float(visitedNodes);
  outVisibility = clamp(1.0 - occludedArea / (4.0 * halfSize * halfSize), 0.0, 1.0);
  outClassification = traversalFinished ? CLASSIFICATION_PENUMBRA : CLASSIFICATION_OVER_LOOP_BUDGET;
}
