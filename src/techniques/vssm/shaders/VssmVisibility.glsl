// Variance soft shadow mapping (Yang et al. 2010), Alg. 1 with the kernel subdivision of §5:
//   L7      initial kernel w_i: the light frustum through the receiver cut by the map's near plane;
//   L8-10   lit / umbra early-out from the min-max HSM over w_i (common/HsmLookup.glsl);
//   L11-15  average blocker depth by Eq. 4 (z_unocc = t) over the sub-kernels of w_i, uniform m x m by
//           default (§6.3): sub-kernels with E(x) < t pool their moments (Eq. 5), the "non-planar" ones
//           (E(x) >= t) are lit when their variance is under the threshold (§5.2, §6.5) or sampled by
//           k x k PCF;
//   §6.4    contact shadows, two readings (contact_test): blocker_average tests d - z_occ < eps r once per pixel
//           with Eq. 4's average blocker depth and then filters all of w_p by 3 x 3 jittered bilinear PCF;
//           subkernel_mean tests each normal sub-kernel of w_p, t_c - E(x)_ci < eps r with the sub-kernel's own
//           SAT mean, and filters that sub-kernel alone by 3 x 3 jittered bilinear PCF (its area joins
//           Alg. 2's PCFArea);
//   L16     penumbra kernel w_p from z_avg (similar triangles);
//   L17-20  visibility over w_p by Alg. 2 (adaptive, height H, the default) or uniform n x n subdivision:
//           L = Chebyshev over the pooled normal sub-kernels, lit area, and k x k PCF in non-planar leaves,
//           weighted by their areas (Alg. 2 L29-32).
// The quad-tree of Alg. 2 is traversed without a stack through each node's Child and Next pointers
// (Bunnell 2005, §5.3, Fig. 5), computed from the node's (x, y, level).
// Comparison depths: a sub-kernel is compared at t_c = its centre's receiver-plane depth (or d) minus the
// depth bias and half a fixed-point step of the int32 SAT, i.e. in offsets z - t_c, so that a lit flat
// receiver never counts as its own blocker; with one t for all sub-kernels this is exactly Eq. 4 and 5.
// CPU mirror (double precision): src/techniques/vssm/VssmTechnique.cpp.
#include "common/GBufferInputs.glsl"
#include "common/LightModel.glsl"
#include "common/ShadowMapCommon.glsl"
#include "common/ShadowReceiver.glsl"
#include "common/SamplingPatterns.glsl"
#include "common/SoftShadowKernels.glsl"
#include "common/SatLookup.glsl"
#include "common/HsmLookup.glsl"
#include "common/Chebyshev.glsl"

// Eight outputs, GL's guaranteed MAX_DRAW_BUFFERS (llvmpipe's too): visibility and the issue's seven.
layout(location = OUT_VISIBILITY) out float outVisibility;
layout(location = OUT_BLOCKER_KERNEL_TEXELS) out float outBlockerKernelTexels;
layout(location = OUT_PENUMBRA_KERNEL_TEXELS) out float outPenumbraKernelTexels;
layout(location = OUT_AVG_BLOCKER_DEPTH) out float outAvgBlockerDepth;
layout(location = OUT_CLASSIFICATION) out float outClassification;
layout(location = OUT_SUBKERNELS_MEAN_NOT_IN_FRONT) out float outSubkernelsMeanNotInFront;
layout(location = OUT_QUADTREE_NODES_VISITED) out float outQuadtreeNodesVisited;
layout(location = OUT_PCF_SAMPLES) out float outPcfSamples;

uniform float sceneRadius;   // r, the scene's bounding-sphere radius (§6.4, §6.5)
uniform float satHalfStep;   // int32 SAT: half a fixed-point step of the depth range; float: 0

// From the preamble (VssmTechnique.cpp): the `classification` codes CLASSIFICATION_* (sl::VssmClass) and the
// subdivision schemes SCHEME_NONE, SCHEME_UNIFORM, SCHEME_ADAPTIVE (the values of the blocker_subdivision and
// shadow_subdivision choices).

int subkernelsMeanNotInFront = 0;
int quadtreeNodesVisited = 0;
int pcfSamples = 0;
int contactSubkernels = 0; // contact_test = subkernel_mean: sub-kernels filtered by §6.4's PCF
mat2 contactJitter = mat2(1.0); // §6.4's per-pixel rotation of the 3 x 3 grid, set in main()

// Area-weighted sums of one step (Alg. 2 L1-2): normal sub-kernels' moments of z - t_c (Eq. 5), lit area,
// PCF area with its blocked part and the blocked taps' depth sum (area-weighted, for Eq. 4's combination).
struct Accumulation
{
  float vsmArea;
  float vsmSum;
  float vsmSumSquares;
  float litArea;
  float pcfArea;
  float pcfBlockedArea;
  float pcfBlockerDepthSum;
};

Accumulation emptyAccumulation()
{
  return Accumulation(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
}

// 1 = lit, bilinearly weighted over the 2 x 2 texels around a tap (Bavoil 2008's bilinear PCF).
float bilinearShadowTest(vec2 tap, float d, float bias)
{
  vec2 position = tap - 0.5;
  vec2 base = floor(position);
  vec2 weight = position - base;
  float comparison = tapComparisonDepth(tap, d, bias);
  float lit = 0.0;
  for (int corner = 0; corner < 4; ++corner)
  {
    ivec2 offset = ivec2(corner & 1, corner >> 1);
    float test = shadowTest(base + vec2(offset) + 0.5, comparison);
    lit += test * (offset.x == 1 ? weight.x : 1.0 - weight.x) * (offset.y == 1 ? weight.y : 1.0 - weight.y);
  }
  return lit;
}

// §6.4: 3 x 3 bilinear PCF over a kernel of half extent filterHalf around uvTexels (w_p, or one sub-kernel),
// the grid rotated per pixel (jitter); the rotated grid's taps stay within 0.943 filterHalf of the centre.
float contactShadow(vec2 uvTexels, vec2 filterHalf, float d, float bias, mat2 rotation)
{
  float lit = 0.0;
  for (int j = 0; j < 3; ++j)
  {
    for (int i = 0; i < 3; ++i)
    {
      vec2 offset = (vec2(i, j) - 1.0) * (2.0 / 3.0) * filterHalf;
      lit += bilinearShadowTest(uvTexels + rotation * offset, d, bias);
    }
  }
  pcfSamples += 36;
  return lit / 9.0;
}

// k x k nearest-texel PCF inside a non-planar leaf [lo, hi] (§5.1 option 2, Alg. 2 L23-26).
void pcfLeaf(ivec2 lo, ivec2 hi, float area, float d, float bias, inout Accumulation acc)
{
  int taps = int(param_nonplanar_pcf_taps);
  vec2 spacing = vec2(hi - lo + 1) / float(taps);
  int blocked = 0;
  float blockerDepthSum = 0.0;
  for (int j = 0; j < taps; ++j)
  {
    for (int i = 0; i < taps; ++i)
    {
      vec2 tap = vec2(lo) + (vec2(i, j) + 0.5) * spacing;
      float z = storedDepth(tap);
      if (z < tapComparisonDepth(tap, d, bias))
      {
        ++blocked;
        blockerDepthSum += z;
      }
    }
  }
  float tapCount = float(taps * taps);
  pcfSamples += taps * taps;
  acc.pcfArea += area;
  acc.pcfBlockedArea += area * float(blocked) / tapCount;
  acc.pcfBlockerDepthSum += area * blockerDepthSum / tapCount;
}

// One sub-kernel [lo, hi] (Alg. 2 L6-27). Returns true when it must be refined (non-planar, above the
// variance threshold, not a leaf). `nonPlanarIsLit`: the VSM assumption, for subdivision = none (Fig. 3a).
// `detectContact`: §6.4 per sub-kernel (contact_test = subkernel_mean, visibility step only).
bool visitSubKernel(ivec2 lo, ivec2 hi, bool isLeaf, bool nonPlanarIsLit, bool detectContact, float d, float bias,
  inout Accumulation acc)
{
  vec2 moments = satBoxMoments(lo, hi);
  float area = float((hi.x - lo.x + 1) * (hi.y - lo.y + 1));
  float t = tapComparisonDepth(0.5 * vec2(lo + hi + 1), d, bias + satHalfStep);
  float meanOffset = moments.x - t;
  if (meanOffset < 0.0)
  {
    if (detectContact && -meanOffset < param_contact_threshold * sceneRadius)
    {
      // §6.4: "the contact shadow sub-kernels are detected by checking the difference between zAvg and d",
      // zAvg = this sub-kernel's mean E(x)_ci (as in §5.1); 3 x 3 jittered bilinear PCF over the sub-kernel
      // replaces its SAT moments, and it counts as PCF area in Alg. 2 L29-32.
      ++contactSubkernels;
      float lit = contactShadow(0.5 * vec2(lo + hi + 1), 0.5 * vec2(hi - lo + 1), d, bias, contactJitter);
      acc.pcfArea += area;
      acc.pcfBlockedArea += area * (1.0 - lit);
      return false;
    }
    // Normal sub-kernel: pool E(z - t) and E((z - t)^2) (Eq. 5; Alg. 2 L14-17).
    acc.vsmArea += area;
    acc.vsmSum += area * meanOffset;
    acc.vsmSumSquares += area * (moments.y + meanOffset * meanOffset);
    return false;
  }
  ++subkernelsMeanNotInFront;
  if (nonPlanarIsLit || moments.y < param_lit_variance_threshold * sceneRadius)
  {
    acc.litArea += area; // Alg. 2 L10-12 (§6.5 threshold)
    return false;
  }
  if (!isLeaf)
  {
    return true;
  }
  pcfLeaf(lo, hi, area, d, bias, acc);
  return false;
}

// The sub-kernels of [lo, hi] by `scheme`: none (the kernel itself, non-planar = lit), uniform
// (cells x cells equal parts, empty ones skipped) or adaptive (Alg. 2, quad-tree of height `height`).
Accumulation subdivide(ivec2 lo, ivec2 hi, int scheme, int cells, int height, bool detectContact, float d, float bias)
{
  Accumulation acc = emptyAccumulation();
  ivec2 extent = hi - lo + 1;
  if (scheme == SCHEME_NONE)
  {
    visitSubKernel(lo, hi, true, true, detectContact, d, bias, acc);
  }
  else if (scheme == SCHEME_UNIFORM)
  {
    for (int j = 0; j < cells; ++j)
    {
      for (int i = 0; i < cells; ++i)
      {
        ivec2 subLo = lo + (extent * ivec2(i, j)) / cells;
        ivec2 subHi = lo + (extent * ivec2(i + 1, j + 1)) / cells - 1;
        if (all(greaterThanEqual(subHi, subLo)))
        {
          visitSubKernel(subLo, subHi, true, false, detectContact, d, bias, acc);
        }
      }
    }
  }
  else
  {
    // Linear quad-tree traversal (Alg. 2 L4-28): node = (x, y, level), level 0 the root; its sub-kernel
    // splits each axis of the kernel into 2^level integer parts.
    ivec3 node = ivec3(0);
    while (true)
    {
      ++quadtreeNodesVisited;
      int parts = 1 << node.z;
      ivec2 subLo = lo + (extent * node.xy) / parts;
      ivec2 subHi = lo + (extent * (node.xy + 1)) / parts - 1;
      bool refine = all(greaterThanEqual(subHi, subLo)) &&
        visitSubKernel(subLo, subHi, node.z == height, false, detectContact, d, bias, acc);
      if (refine)
      {
        node = ivec3(2 * node.xy, node.z + 1); // Child: the first of the four children
        continue;
      }
      // Next: the next sibling (order (0,0), (1,0), (0,1), (1,1)), else that of the nearest ancestor
      // that has one; past the root's last descendant, Null.
      while (node.z > 0 && (node.x & 1) == 1 && (node.y & 1) == 1)
      {
        node = ivec3(node.xy >> 1, node.z - 1);
      }
      if (node.z == 0)
      {
        break;
      }
      node.xy = (node.x & 1) == 0 ? node.xy + ivec2(1, 0) : node.xy + ivec2(-1, 1);
    }
  }
  return acc;
}

void writeCounters()
{
  outSubkernelsMeanNotInFront = float(subkernelsMeanNotInFront);
  outQuadtreeNodesVisited = float(quadtreeNodesVisited);
  outPcfSamples = float(pcfSamples);
}

// Chebyshev's P(x >= t) (Eq. 1) over a step's pooled offset moments (Eq. 5), the variance floored.
float pooledChebyshev(Accumulation acc, float d)
{
  float mean = acc.vsmSum / acc.vsmArea;
  float variance = max(acc.vsmSumSquares / acc.vsmArea - mean * mean, param_min_variance * d * d);
  return chebyshevUpperBound(mean, variance, 0.0);
}

// Alg. 1 L7: the blocker search kernel w_i, the light's extent seen from the receiver at the near plane.
void initialKernel(ShadowReceiver receiver, out ivec2 lo, out ivec2 hi)
{
  vec2 searchHalf = kernelHalfTexels(receiver.depthLin, lightNearDepth);
  outBlockerKernelTexels = 2.0 * max(searchHalf.x, searchHalf.y);
  kernelRectangle(receiver.uvTexels, searchHalf, lo, hi);
}

#if HSM_EARLY_OUT == HSM_EARLY_OUT_ON
// Alg. 1 L8-10: lit when no texel of w_i can be nearer than its comparison depth, umbra when all are (the
// HSM's min-max over w_i, §6.1). True when decided, its visibility and class written.
bool hsmEarlyOut(ivec2 lo, ivec2 hi, float d, float bias)
{
  vec2 depthRange = hsmRange(lo, hi);
  vec2 comparisonRange = comparisonDepthRange(lo, hi, d, bias);
  if (depthRange.x >= comparisonRange.y)
  {
    outVisibility = 1.0;
    outClassification = CLASSIFICATION_LIT;
    return true;
  }
  if (depthRange.y < comparisonRange.x)
  {
    outVisibility = 0.0;
    outClassification = CLASSIFICATION_UMBRA;
    return true;
  }
  return false;
}
#endif

// Alg. 1 L11-15: the average blocker depth over w_i, Eq. 4 with z_unocc = t over the normal sub-kernels,
// combined with the PCF-sampled blockers of the non-planar ones, weighted by their blocked areas (§5.2).
// §6.4's test is not applied here: it is "applied for evaluating soft shadow", and the blocker depth "is
// less sensitive to precision" (§6.2). False when w_i holds no blocker (the pixel is lit).
bool estimateAverageBlockerDepth(ivec2 lo, ivec2 hi, float d, float bias, out float averageBlockerDepth)
{
  Accumulation blockers = subdivide(lo, hi, BLOCKER_SUBDIVISION, int(param_blocker_uniform_m),
    int(param_blocker_tree_height), false, d, bias);
  float blockedArea = blockers.pcfBlockedArea;
  float blockerDepthSum = blockers.pcfBlockerDepthSum;
  if (blockers.vsmArea > 0.0)
  {
    float occludedArea = blockers.vsmArea * (1.0 - pooledChebyshev(blockers, d));
    // Eq. 4 in offsets from t: z_occ - t = E(z - t) / (1 - P), so the blockers' depth sum is
    // occludedArea t + vsmArea E(z - t), with t the receiver's own comparison depth.
    blockedArea += occludedArea;
    blockerDepthSum += occludedArea * (d - bias - satHalfStep) + blockers.vsmSum;
  }
  float kernelArea = float((hi.x - lo.x + 1) * (hi.y - lo.y + 1));
  averageBlockerDepth = 0.0;
  if (!(blockedArea > 1e-5 * kernelArea))
  {
    return false;
  }
  averageBlockerDepth = clamp(blockerDepthSum / blockedArea, lightNearDepth, d);
  return true;
}

// Alg. 1 L16: the penumbra kernel w_p, the light's extent seen from the receiver at z_avg (similar
// triangles). Returns its half extent in texels.
vec2 penumbraKernel(float d, float averageBlockerDepth)
{
  vec2 filterHalf = kernelHalfTexels(d, averageBlockerDepth);
  outPenumbraKernelTexels = 2.0 * max(filterHalf.x, filterHalf.y);
  return filterHalf;
}

#if CONTACT_TEST == CONTACT_TEST_BLOCKER_AVERAGE
// §6.4 (contact_test = blocker_average): d - z_occ < eps r, once per pixel with Eq. 4's average. Contact
// shadows are small: PCF over w_p avoids the SAT's precision there.
bool contactTest(float d, float averageBlockerDepth)
{
  return d - averageBlockerDepth < param_contact_threshold * sceneRadius;
}
#endif

// Alg. 1 L17-20: the visibility over w_p, L = Chebyshev (Eq. 1) over the pooled normal sub-kernels (Eq. 5),
// the lit area and the PCF leaves, weighted by their areas (Alg. 2 L29-32).
float filterPenumbraKernel(vec2 uvTexels, vec2 filterHalf, float d, float bias)
{
  ivec2 lo;
  ivec2 hi;
  kernelRectangle(uvTexels, filterHalf, lo, hi);
  Accumulation shadow = subdivide(lo, hi, SHADOW_SUBDIVISION, int(param_shadow_uniform_n),
    int(param_shadow_tree_height), CONTACT_TEST == CONTACT_TEST_SUBKERNEL_MEAN, d, bias);
  float chebyshevLit = 0.0;
  if (shadow.vsmArea > 0.0)
  {
    chebyshevLit = pooledChebyshev(shadow, d);
  }
  float totalArea = shadow.vsmArea + shadow.litArea + shadow.pcfArea;
  return clamp((chebyshevLit * shadow.vsmArea + shadow.litArea + shadow.pcfArea - shadow.pcfBlockedArea) / totalArea, 0.0, 1.0);
}

// Alg. 1 L7-20 for one pixel (the twin's vssmReference, same step names).
void main()
{
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  ShadowReceiver receiver = prepareShadowReceiver(pixel);
  outVisibility = receiver.visibility;
  outBlockerKernelTexels = 0.0;
  outPenumbraKernelTexels = 0.0;
  outAvgBlockerDepth = 0.0;
  outClassification = CLASSIFICATION_NOT_TESTED;
  writeCounters();
  if (!receiver.needsShadowTest)
  {
    return;
  }
  float d = receiver.depthLin;
  float bias = receiver.bias;
  contactJitter = pixelRotation(uvec2(pixel));
  setReceiverPlane(receiver.pWs, receiver.nWs);
  ivec2 lo;
  ivec2 hi;
  initialKernel(receiver, lo, hi);
#if HSM_EARLY_OUT == HSM_EARLY_OUT_ON
  if (hsmEarlyOut(lo, hi, d, bias))
  {
    return;
  }
#endif
  float averageBlockerDepth;
  if (!estimateAverageBlockerDepth(lo, hi, d, bias, averageBlockerDepth))
  {
    outVisibility = 1.0;
    outClassification = CLASSIFICATION_LIT;
    writeCounters();
    return;
  }
  outAvgBlockerDepth = averageBlockerDepth;
  vec2 filterHalf = penumbraKernel(d, averageBlockerDepth);
#if CONTACT_TEST == CONTACT_TEST_BLOCKER_AVERAGE
  if (contactTest(d, averageBlockerDepth))
  {
    outVisibility = contactShadow(receiver.uvTexels, filterHalf, d, bias, contactJitter);
    outClassification = CLASSIFICATION_CONTACT;
    writeCounters();
    return;
  }
#endif
  outVisibility = filterPenumbraKernel(receiver.uvTexels, filterHalf, d, bias);
  // A pixel with at least one §6.4 contact sub-kernel is classified contact.
  outClassification = contactSubkernels > 0 ? CLASSIFICATION_CONTACT : CLASSIFICATION_PENUMBRA;
  writeCounters();
}
