// Packet-based hierarchical soft shadow mapping (Yang, Feng, Guennebaud and Liu 2009), two full-screen
// fragment passes (vtkSLYfgl09Pass):
//  - YFGL09_PACKET_PASS, one fragment per packet of packetSize = w x h pixels (Alg. 1 steps 5-7): each pixel's
//    kernel and lit / umbra class; the packet's coherence (Eq. 2, 4, 5, 6); for coherent packets the contour
//    traversal of Alg. 2 / 3 with the statuses of Eq. 3. A packet writes its pixels through image stores (a
//    fragment owns wh pixels, more than the 8 colour outputs GL guarantees) and its own class, Eq. 2, P_d and
//    per-pixel share of visited nodes to its fragment of the packet target.
//  - otherwise, one fragment per pixel (Alg. 1 step 8): the pixels of packets not computed packet-wise, alone
//    over their own kernel; every other pixel is discarded, keeping what the packet pass stored.
// Fragment shaders rather than compute: both passes reuse the technique passes' program setup (G-buffer,
// light, shadow map, parameters), and image stores give a fragment the w x h outputs of a packet.
//
// Written for the shader compiler as much as for the GPU: every GLSL function is inlined, so the back-projection
// (radialEdgeArea) has exactly one call site in the packet pass, the traversal one leaf site, and the loops over a packet's pixels have a uniform bound (packetSize) the compiler cannot unroll.
// One program per pass then serves every packet size (llvmpipe compiled the unrolled 3 x 3 variant for over
// ten minutes). Loops over pixels count against llvmpipe's 65535 loop iterations per invocation: a packet
// whose work outgrows PACKET_BUDGET is finished pixel-wise.
//
// Exactness (the paper's claim: the same contours as GBP07): a pixel integrates only the edges of the dual
// cells of its own kernel; a sample's status holds for every pixel when it lies outside the node's
// [z_pmin, z_pmax] (Eq. 3: the comparison depths, with receiver-plane bias, of the pixels sharing the node),
// and inside it is resolved per pixel: null only where the pixels sharing the cell disagree.
// CPU mirror: src/techniques/yfgl09/Yfgl09Technique.cpp.
#include "common/GBufferInputs.glsl"
#include "common/LightModel.glsl"
#include "common/ShadowMapCommon.glsl"
#include "common/ShadowReceiver.glsl"
#include "common/SoftShadowKernels.glsl"
#include "common/HsmLookup.glsl"
#include "common/ContourBackprojection.glsl"
#include "common/ContourKernel.glsl"

// From the preamble (Yfgl09Technique.cpp): the `packet_class` codes PACKET_CLASS_* (sl::PacketClass),
// PACKET_BUDGET (yfgl09PacketBudget) and MAX_PACKET_PIXELS (the largest packet the parameters allow).

uniform ivec2 imageSize;
uniform ivec2 packetSize; // w x h (§4.1)

#ifdef YFGL09_PACKET_PASS
const int MAX_PIXELS = MAX_PACKET_PIXELS;
layout(location = 0) out vec4 outPacket; // class, Eq. 2, P_d, visited nodes per pixel
layout(r32f, binding = OUT_VISIBILITY) uniform writeonly image2D visibilityImage;
layout(r32f, binding = OUT_KERNEL_TEXELS) uniform writeonly image2D kernelTexelsImage;
layout(r32f, binding = OUT_COHERENCE) uniform writeonly image2D coherenceImage;
layout(r32f, binding = OUT_PACKET_CLASS) uniform writeonly image2D packetClassImage;
layout(r32f, binding = OUT_DIVERGENCE_PROBABILITY) uniform writeonly image2D divergenceImage;
layout(r32f, binding = OUT_VISITED_NODES) uniform writeonly image2D visitedNodesImage;
layout(r32f, binding = OUT_CONTOUR_EDGES) uniform writeonly image2D contourEdgesImage;
// Loops over the packet's receivers: a uniform bound in the packet pass (counted by llvmpipe's loop limiter,
// so the packet's budget counts them too); none in the pixel pass, so that a pixel costs about one loop
// iteration per node, as in gbp07 (even loops of one constant iteration count there: measured, a brute-force
// kernel stopped at 3300 cells with them and ran its 5544 without).
#define FOR_EACH_RECEIVER(p) for (int p = 0; p < pixelCount; ++p)
#else
const int MAX_PIXELS = 1;
#define FOR_EACH_RECEIVER(p) const int p = 0;
uniform sampler2D packetTexture; // the packet pass's outPacket
layout(location = OUT_VISIBILITY) out float outVisibility;
layout(location = OUT_KERNEL_TEXELS) out float outKernelTexels;
layout(location = OUT_COHERENCE) out float outCoherence;
layout(location = OUT_PACKET_CLASS) out float outPacketClass;
layout(location = OUT_DIVERGENCE_PROBABILITY) out float outDivergence;
layout(location = OUT_VISITED_NODES) out float outVisitedNodes;
layout(location = OUT_CONTOUR_EDGES) out float outContourEdges;
#endif

// The receivers being traversed together (the packet's penumbra pixels, or one pixel).
int pixelCount;
float pixelDepth[MAX_PIXELS];
float pixelBias[MAX_PIXELS];
vec3 pixelPlane[MAX_PIXELS];
bool pixelHasPlane[MAX_PIXELS];
vec2 pixelXy[MAX_PIXELS];    // light view x, y
ivec2 pixelCellLo[MAX_PIXELS]; // the dual cells of the pixel's own kernel
ivec2 pixelCellHi[MAX_PIXELS];
float pixelArea[MAX_PIXELS]; // occluded light area
// Eq. 3's [z_pmin, z_pmax] for the node being examined: the comparison depths, over the node's samples, of
// the receivers whose kernels share a cell with it (set by nodeComparisonRange).
vec2 nodeComparison;
int visitedNodes;
int contourEdges;
int packetWork; // loop iterations spent on the packet's pixels (statuses resolved per pixel, edges integrated)

// Makes receiver p current for tapComparisonDepth / comparisonDepthRange (common/SoftShadowKernels.glsl).
void selectReceiver(int p)
{
  receiverPlane = pixelPlane[p];
  hasReceiverPlane = pixelHasPlane[p];
}

// One pixel's kernel and class (common/ContourKernel.glsl, the mirror of sl::prepareContourReceiver).
struct Contour
{
  ShadowReceiver receiver;
  ivec2 lo;     // kernel texels
  ivec2 hi;
  ivec2 ringLo; // plus one ring, clamped
  ivec2 ringHi;
  float kernelTexels;
  float classification; // PACKET_CLASS_NOT_TESTED, _TRIVIAL (visibility final) or _COHERENT (penumbra)
};

Contour prepareContour(ivec2 pixel)
{
  Contour contour;
  contour.receiver = prepareShadowReceiver(pixel);
  contour.lo = ivec2(0);
  contour.hi = ivec2(0);
  contour.ringLo = ivec2(0);
  contour.ringHi = ivec2(0);
  contour.kernelTexels = 0.0;
  contour.classification = PACKET_CLASS_NOT_TESTED;
  if (!contour.receiver.needsShadowTest)
  {
    return contour;
  }
  ContourKernel kernel = prepareContourKernel(contour.receiver);
  contour.lo = kernel.lo;
  contour.hi = kernel.hi;
  contour.ringLo = kernel.ringLo;
  contour.ringHi = kernel.ringHi;
  contour.kernelTexels = kernel.kernelTexels;
  contour.classification = kernel.decision == KERNEL_PENUMBRA ? PACKET_CLASS_COHERENT : PACKET_CLASS_TRIVIAL;
  if (kernel.decision != KERNEL_PENUMBRA)
  {
    contour.receiver.visibility = kernel.decision == KERNEL_LIT ? 1.0 : 0.0;
  }
  return contour;
}

// Adds a penumbra pixel to the receivers traversed together, with f(O), its light centre's status, from the
// cell holding its own map position.
void addReceiver(Contour contour)
{
  int p = pixelCount++;
  float d = contour.receiver.depthLin;
  pixelDepth[p] = d;
  pixelBias[p] = contour.receiver.bias;
  setReceiverPlane(contour.receiver.pWs, contour.receiver.nWs);
  pixelPlane[p] = receiverPlane;
  pixelHasPlane[p] = hasReceiverPlane;
  pixelCellLo[p] = contour.lo - 1;
  pixelCellHi[p] = contour.hi;
  vec2 uv = contour.receiver.uvTexels;
  pixelXy[p] = (shadowWindowMin + uv * shadowTexelTangent) * d;
  ivec2 cell = ivec2(floor(uv - 0.5));
  bool occluding[4];
  for (int k = 0; k < 4; ++k)
  {
    ivec2 samplePosition = cell + ivec2(CELL_CORNERS[k]);
    bool inside = all(greaterThanEqual(samplePosition, ivec2(0))) && all(lessThan(samplePosition, ivec2(shadowMapSize)));
    occluding[k] = inside && texelFetch(shadowMapLinear, samplePosition, 0).r < tapComparisonDepth(vec2(samplePosition) + 0.5, d, pixelBias[p]);
  }
  float halfSize = 0.5 * lightSizeWorld;
  pixelArea[p] = insideReconstructedOccluder(occluding, vec2(cell) + 0.5, uv) ? 4.0 * halfSize * halfSize : 0.0;
}

bool cellOfPixel(int p, ivec2 cell)
{
  return all(greaterThanEqual(cell, pixelCellLo[p])) && all(lessThanEqual(cell, pixelCellHi[p]));
}

// Status of a corner of `cell` over the receivers (Eq. 3): 1 occluding, 0 not, -1 null. Outside the map: 0.
// Outside the cell's [z_pmin, z_pmax] the status holds for every receiver; inside, each receiver whose kernel
// holds the cell decides, and null means they disagree.
int sampleStatus(ivec2 cell, ivec2 samplePosition, out float depth)
{
  depth = 0.0;
  if (any(lessThan(samplePosition, ivec2(0))) || any(greaterThanEqual(samplePosition, ivec2(shadowMapSize))))
  {
    return 0;
  }
  depth = texelFetch(shadowMapLinear, samplePosition, 0).r;
  if (depth < nodeComparison.x)
  {
    return 1;
  }
  if (depth >= nodeComparison.y)
  {
    return 0;
  }
  int occluded = 0;
  int sharing = 0;
  FOR_EACH_RECEIVER(p)
  {
    if (cellOfPixel(p, cell))
    {
      selectReceiver(p);
      ++sharing;
      occluded += depth < tapComparisonDepth(vec2(samplePosition) + 0.5, pixelDepth[p], pixelBias[p]) ? 1 : 0;
    }
  }
  packetWork += pixelCount;
  return occluded == 0 ? 0 : occluded == sharing ? 1 : -1;
}

void integrateEdge(ContourEdge edge, int p)
{
  pixelArea[p] += radialEdgeArea(backProject(shadowWindowMin + edge.a * shadowTexelTangent, edge.depthA, pixelXy[p], pixelDepth[p]),
    backProject(shadowWindowMin + edge.b * shadowTexelTangent, edge.depthB, pixelXy[p], pixelDepth[p]), 0.5 * lightSizeWorld);
}

// Marching squares on one dual cell with the receivers' common statuses, each edge back-projected and radially
// integrated for every receiver whose kernel holds the cell (Alg. 2); false on a null status.
bool leafCell(ivec2 cell)
{
  bool occluding[4];
  float depths[4];
  int status0 = sampleStatus(cell, cell, depths[0]);
  int status1 = sampleStatus(cell, cell + ivec2(1, 0), depths[1]);
  int status2 = sampleStatus(cell, cell + ivec2(1, 1), depths[2]);
  int status3 = sampleStatus(cell, cell + ivec2(0, 1), depths[3]);
  if (min(min(status0, status1), min(status2, status3)) < 0)
  {
    return false;
  }
  occluding[0] = status0 == 1;
  occluding[1] = status1 == 1;
  occluding[2] = status2 == 1;
  occluding[3] = status3 == 1;
  ContourEdge edges[2];
  int count = marchingSquaresEdges(occluding, depths, vec2(cell) + 0.5, edges);
#ifdef YFGL09_PACKET_PASS
  // One call site of the back-projection for every edge and receiver: a loop the compiler cannot unroll.
  for (int k = 0; k < count * pixelCount; ++k)
  {
    int e = k / pixelCount;
    int p = k - e * pixelCount;
    if (cellOfPixel(p, cell))
    {
      integrateEdge(edges[e], p);
    }
  }
#else
  // No loop in the pixel pass (as gbp07): llvmpipe's limiter would count it, one kernel cell at a time.
  if (count > 0)
  {
    integrateEdge(edges[0], 0);
  }
  if (count > 1)
  {
    integrateEdge(edges[1], 0);
  }
#endif
  packetWork += count * pixelCount;
  contourEdges += count;
  return true;
}

// comparisonDepthRange's corner term, without its loop (llvmpipe counts every loop iteration).
void cornerComparison(vec2 position, float d, float bias, inout vec2 range, inout bool unbounded)
{
  vec3 ray = vec3(shadowWindowMin + position * shadowTexelTangent, -1.0);
  float planeDepth = 1.0 / dot(receiverPlane, ray);
  unbounded = unbounded || !(planeDepth > 0.0);
  float depth = clamp(planeDepth, 0.5 * d, 2.0 * d) - bias;
  range = vec2(min(range.x, depth), max(range.y, depth));
}

// [z_pmin, z_pmax] over the samples of the cells [firstCell, lastCell]: the comparison depths
// (comparisonDepthRange, without its loop) of the receivers whose kernels share a cell with them; false when
// none does (no receiver integrates an edge there).
bool comparisonRangeOverCells(ivec2 firstCell, ivec2 lastCell)
{
  ivec2 lo = clamp(firstCell, ivec2(0), ivec2(shadowMapSize - 1));
  ivec2 hi = clamp(lastCell + 1, ivec2(0), ivec2(shadowMapSize - 1));
  nodeComparison = vec2(1e30, -1e30);
  bool anyShares = false;
  FOR_EACH_RECEIVER(p)
  {
    if (all(lessThanEqual(max(firstCell, pixelCellLo[p]), min(lastCell, pixelCellHi[p]))))
    {
      anyShares = true;
      selectReceiver(p);
      float d = pixelDepth[p];
      float bias = pixelBias[p];
      vec2 range = vec2(d - bias);
#if RECEIVER_PLANE_BIAS == RECEIVER_PLANE_BIAS_ON
      if (hasReceiverPlane)
      {
        bool unbounded = false;
        cornerComparison(vec2(lo), d, bias, range, unbounded);
        cornerComparison(vec2(hi.x + 1, lo.y), d, bias, range, unbounded);
        cornerComparison(vec2(lo.x, hi.y + 1), d, bias, range, unbounded);
        cornerComparison(vec2(hi + 1), d, bias, range, unbounded);
        if (unbounded)
        {
          range = vec2(0.5 * d, 2.0 * d) - bias;
        }
      }
#endif
      nodeComparison = vec2(min(nodeComparison.x, range.x), max(nodeComparison.y, range.y));
    }
  }
  packetWork += pixelCount;
  return anyShares;
}

// The same over a node: the 2^level x 2^level cells from firstCell.
bool nodeComparisonRange(int level, ivec2 firstCell)
{
  return comparisonRangeOverCells(firstCell, firstCell + (1 << level) - 1);
}

// Fig. 6: false when the node's samples are all behind the comparison depths (case 4) or all in front of them
// (case 5), so that it holds no edge for any receiver.
bool nodeOverlaps(int level, ivec2 firstCell)
{
  if (!nodeComparisonRange(level, firstCell))
  {
    return false;
  }
  vec2 node = hsmTexel(level, firstCell);
  return !(node.x >= nodeComparison.y || node.y < nodeComparison.x);
}

bool overBudget()
{
  return pixelCount > 1 && visitedNodes + packetWork > PACKET_BUDGET;
}

const int TRAVERSAL_DONE = 0;
const int TRAVERSAL_NULL = 1;
const int TRAVERSAL_OVER_BUDGET = 2;
// The GL's loop cap stopped the traversal (llvmpipe: 65535 loop iterations per invocation, counted for the SIMD
// lanes together). The cap ends a loop without any of its exits being taken: the hierarchical loop below has
// none but its returns, and the brute force notes its last cell, so falling out of either is detected exactly.
const int TRAVERSAL_CUT_SHORT = 3;

#if HIERARCHY == HIERARCHY_OFF
// Alg. 2's loop over every 2 x 2 block of the extended kernel [regionLo, regionHi] (hierarchy off, the
// MSSM-only brute force): a cell no receiver's kernel holds is skipped.
int traverseEveryCell(ivec2 regionLo, ivec2 regionHi)
{
  ivec2 extent = regionHi - regionLo + 1;
  bool reachedLastCell = false;
  for (int k = 0; k < extent.x * extent.y; ++k)
  {
    reachedLastCell = k == extent.x * extent.y - 1;
    ++visitedNodes;
    ivec2 cell = regionLo + ivec2(k % extent.x, k / extent.x);
    if (nodeComparisonRange(0, cell) && !leafCell(cell))
    {
      return TRAVERSAL_NULL;
    }
    if (overBudget())
    {
      return TRAVERSAL_OVER_BUDGET;
    }
  }
  return reachedLastCell ? TRAVERSAL_DONE : TRAVERSAL_CUT_SHORT;
}
#else
// Alg. 3 below one root, the node of `rootLevel` whose first cell is `rootCell`: depth first over its children
// inside the region, pruning the nodes of Fig. 6 cases 4 and 5; the path of child indices (2 bits per level)
// replaces the stack.
int traverseMssmRoot(int rootLevel, ivec2 rootCell, ivec2 regionHi)
{
  ++visitedNodes;
  if (!nodeOverlaps(rootLevel, rootCell))
  {
    return TRAVERSAL_DONE;
  }
  int level = rootLevel; // the node whose children are examined
  ivec2 origin = rootCell;
  uint path = 0u;
  int child = 0;
  while (true)
  {
    if (child == 4)
    {
      if (level == rootLevel)
      {
        return TRAVERSAL_DONE;
      }
      int index = int((path >> uint(2 * level)) & 3u);
      origin -= ivec2(CELL_CORNERS[index]) << level;
      ++level;
      child = index + 1;
      continue;
    }
    ivec2 first = origin + (ivec2(CELL_CORNERS[child]) << (level - 1));
    if (first.x > regionHi.x || first.y > regionHi.y)
    {
      ++child;
      continue;
    }
    ++visitedNodes;
    if (!nodeOverlaps(level - 1, first))
    {
      ++child;
    }
    else if (level == 1)
    {
      if (!leafCell(first))
      {
        return TRAVERSAL_NULL;
      }
      ++child;
    }
    else
    {
      uint shift = uint(2 * (level - 1));
      path = (path & ~(3u << shift)) | (uint(child) << shift);
      origin = first;
      --level;
      child = 0;
    }
    if (overBudget())
    {
      return TRAVERSAL_OVER_BUDGET;
    }
  }
  return TRAVERSAL_CUT_SHORT; // only the loop cap leaves the loop without returning
}

// Alg. 3 through the dual-grid MSSM (§4.2): from the lowest node covering [regionLo, regionHi] with the same
// first cell. Where that node lies above the MSSM's top level (built only up to the frame's widest kernel,
// mssm_levels), the region is covered by the top level's nodes from regionLo, row by row.
int traverseMssm(ivec2 regionLo, ivec2 regionHi)
{
  ivec2 extent = regionHi - regionLo + 1;
  int rootLevel = 1;
  while (rootLevel < hsmTopLevel && (1 << rootLevel) < max(extent.x, extent.y))
  {
    ++rootLevel;
  }
  int side = 1 << rootLevel;
  ivec2 roots = (extent + side - 1) / side;
  bool reachedLastRoot = false;
  for (int k = 0; k < roots.x * roots.y; ++k)
  {
    reachedLastRoot = k == roots.x * roots.y - 1;
    int outcome = traverseMssmRoot(rootLevel, regionLo + side * ivec2(k % roots.x, k / roots.x), regionHi);
    if (outcome != TRAVERSAL_DONE)
    {
      return outcome;
    }
  }
  return reachedLastRoot ? TRAVERSAL_DONE : TRAVERSAL_CUT_SHORT;
}
#endif

// Alg. 2 over the cells [regionLo, regionHi] (at least 2 x 2: a kernel has a texel), by every cell or by
// Alg. 3 (the hierarchy parameter). The twin's PacketTraversal::run.
int traverse(ivec2 regionLo, ivec2 regionHi)
{
  visitedNodes = 0;
  contourEdges = 0;
  packetWork = 0;
#if HIERARCHY == HIERARCHY_OFF
  int outcome = traverseEveryCell(regionLo, regionHi);
#else
  int outcome = traverseMssm(regionLo, regionHi);
#endif
  return outcome;
}

float finalVisibility(int p)
{
  float halfSize = 0.5 * lightSizeWorld;
  return clamp(1.0 - pixelArea[p] / (4.0 * halfSize * halfSize), 0.0, 1.0);
}

#ifdef YFGL09_PACKET_PASS
// Every output of a pixel but its kernel width.
void storePacketResult(ivec2 pixel, float visibility, float coherence, float packetClass, float divergence,
  float visited, float edges)
{
  imageStore(visibilityImage, pixel, vec4(visibility));
  imageStore(coherenceImage, pixel, vec4(coherence));
  imageStore(packetClassImage, pixel, vec4(packetClass));
  imageStore(divergenceImage, pixel, vec4(divergence));
  imageStore(visitedNodesImage, pixel, vec4(visited));
  imageStore(contourEdgesImage, pixel, vec4(edges));
}

int widthTexels(ivec2 lo, ivec2 hi)
{
  return max(hi.x - lo.x + 1, hi.y - lo.y + 1);
}

// Eq. 6's node term for a kernel w texels wide (Q_n = 1).
float nodeCost(int width)
{
  return log2(float(width)) * float(width);
}

// The packet (Alg. 1 step 5): its penumbra pixels with their kernels, the samples those kernels read (plus
// one ring), and the packet kernel (Alg. 2) with the packet's depth range and Eq. 6's pixel-wise cost.
ivec2 penumbraPixel[MAX_PIXELS];
ivec2 kernelLo[MAX_PIXELS];
ivec2 kernelHi[MAX_PIXELS];
ivec2 samplesLo;
ivec2 samplesHi;
ivec2 packetKernelLo;
ivec2 packetKernelHi;
vec2 packetDepth;
float pixelCost;

// Alg. 1 step 5 for each pixel of the packet whose first pixel is `base`: its kernel and lit / umbra class,
// stored at once (final unless it is penumbra); the penumbra pixels become the receivers traversed together.
// Returns the reference pixel of Eq. 2 (k_0: the packet's centre pixel, else its first penumbra pixel).
int computePixelKernels(ivec2 base)
{
  samplesLo = ivec2(1 << 30);
  samplesHi = ivec2(-1);
  pixelCount = 0;
  int reference = -1;
  for (int k = 0; k < packetSize.x * packetSize.y; ++k)
  {
    ivec2 pixel = base + ivec2(k % packetSize.x, k / packetSize.x);
    if (any(greaterThanEqual(pixel, imageSize)))
    {
      continue;
    }
    Contour contour = prepareContour(pixel);
    imageStore(kernelTexelsImage, pixel, vec4(contour.kernelTexels));
    storePacketResult(pixel, contour.receiver.visibility, 0.0, contour.classification, 0.0, 0.0, 0.0);
    if (contour.classification == PACKET_CLASS_COHERENT)
    {
      int p = pixelCount;
      penumbraPixel[p] = pixel;
      kernelLo[p] = contour.lo;
      kernelHi[p] = contour.hi;
      samplesLo = min(samplesLo, contour.ringLo);
      samplesHi = max(samplesHi, contour.ringHi);
      if (pixel == base + packetSize / 2)
      {
        reference = p;
      }
      addReceiver(contour);
    }
  }
  return reference < 0 ? 0 : reference;
}

// Alg. 2 "construct an extended kernel for the packet": the bounding box of its pixels' kernels. The same
// pass gathers the packet's depth range (§4.3: its pixels' comparison depths) and Eq. 6's denominator.
void constructPacketKernel()
{
  packetKernelLo = kernelLo[0];
  packetKernelHi = kernelHi[0];
  packetDepth = vec2(1e30, -1e30);
  pixelCost = 0.0;
  for (int p = 0; p < pixelCount; ++p)
  {
    packetKernelLo = min(packetKernelLo, kernelLo[p]);
    packetKernelHi = max(packetKernelHi, kernelHi[p]);
    float comparisonDepth = pixelDepth[p] - pixelBias[p];
    packetDepth = vec2(min(packetDepth.x, comparisonDepth), max(packetDepth.y, comparisonDepth));
    int w = widthTexels(kernelLo[p], kernelHi[p]);
    pixelCost += nodeCost(w) + (param_edge_cost + param_visibility_cost) * float(w);
  }
}

// Eq. 2: max_i |k_i \ k_0| / |k_i|, reported (the tests below decide).
float kernelCoherence(int reference)
{
  ivec2 referenceLo = kernelLo[reference];
  ivec2 referenceHi = kernelHi[reference];
  float coherence = 0.0;
  for (int p = 0; p < pixelCount; ++p)
  {
    ivec2 sharedLo = max(kernelLo[p], referenceLo);
    ivec2 sharedHi = min(kernelHi[p], referenceHi);
    float sharedArea = any(lessThan(sharedHi, sharedLo)) ? 0.0 : float((sharedHi.x - sharedLo.x + 1) * (sharedHi.y - sharedLo.y + 1));
    ivec2 extent = kernelHi[p] - kernelLo[p] + 1;
    coherence = max(coherence, 1.0 - sharedArea / float(extent.x * extent.y));
  }
  return coherence;
}

// What Alg. 1 step 6 decided for the packet, with the figures its buffers report.
struct PacketPrediction
{
  float coherence;    // Eq. 2
  float divergence;   // P_d, Eq. 5
  float packetClass;  // PACKET_CLASS_COHERENT or _NON_COHERENT
};

// Alg. 1 step 6 (§4.3): a packet of more than one penumbra pixel goes pixel-wise when its contours likely
// diverge (Eq. 4-5: P_d > T_d) or when Eq. 6 prefers the pixels; a packet of one pixel is coherent.
PacketPrediction classifyPacket(int reference)
{
  PacketPrediction prediction = PacketPrediction(0.0, 0.0, PACKET_CLASS_COHERENT);
  if (pixelCount <= 1)
  {
    return prediction;
  }
  prediction.coherence = kernelCoherence(reference);
  vec2 kernelRange = mssmSampleRange(samplesLo, samplesHi);
#if COHERENCE_DEPTH == COHERENCE_DEPTH_COMPARISON
  comparisonRangeOverCells(packetKernelLo - 1, packetKernelHi); // the statuses' range (Eq. 3) over the packet kernel
  packetDepth = nodeComparison;
#elif COHERENCE_DEPTH == COHERENCE_DEPTH_WINDOW
  packetDepth = vec2(windowDepth(packetDepth.x), windowDepth(packetDepth.y));
  kernelRange = vec2(windowDepth(kernelRange.x), windowDepth(kernelRange.y));
#endif
  float overlap = max(min(packetDepth.y, kernelRange.y) - max(packetDepth.x, kernelRange.x), 0.0);
  float nullProbability = kernelRange.y > kernelRange.x ? overlap / (kernelRange.y - kernelRange.x) : 0.0; // Eq. 4
  int packetWidth = widthTexels(packetKernelLo, packetKernelHi);
  prediction.divergence = 1.0 - pow(1.0 - nullProbability, float(packetWidth) * float(packetWidth)); // Eq. 5
#if PACKET_COST == PACKET_COST_PAPER
  float packetPixels = float(packetSize.x * packetSize.y); // Q_v w h
#else
  float packetPixels = float(pixelCount);
#endif
  float packetCost = nodeCost(packetWidth) + (param_edge_cost + param_visibility_cost * packetPixels) * float(packetWidth); // Eq. 6
#if COHERENCE_TEST == COHERENCE_TEST_BOTH || COHERENCE_TEST == COHERENCE_TEST_DIVERGENCE
  prediction.packetClass = prediction.divergence > param_divergence_threshold ? PACKET_CLASS_NON_COHERENT : prediction.packetClass;
#endif
#if COHERENCE_TEST == COHERENCE_TEST_BOTH || COHERENCE_TEST == COHERENCE_TEST_COST
  prediction.packetClass = packetCost > pixelCost ? PACKET_CLASS_NON_COHERENT : prediction.packetClass;
#endif
  return prediction;
}

// Alg. 1 step 7: the packet's traversal over its extended kernel; its pixels are stored when it completes.
// A null status (Eq. 3, §4.3: a misclassified packet is "caught during the packet contour extraction"), the
// packet budget or the loop cap leave them to the pixel pass (step 8). Returns the packet's class.
float evaluateCoherentPacket(PacketPrediction prediction, out float visitedShare)
{
  int outcome = traverse(packetKernelLo - 1, packetKernelHi);
  visitedShare = float(visitedNodes) / float(pixelCount);
  if (outcome != TRAVERSAL_DONE)
  {
    return outcome == TRAVERSAL_NULL ? PACKET_CLASS_CAUGHT_NULL : PACKET_CLASS_OVER_BUDGET;
  }
  for (int p = 0; p < pixelCount; ++p)
  {
    storePacketResult(penumbraPixel[p], finalVisibility(p), prediction.coherence, PACKET_CLASS_COHERENT,
      prediction.divergence, visitedShare, float(contourEdges));
  }
  return PACKET_CLASS_COHERENT;
}

// The packet pass: Alg. 1 steps 5-7 (the twin's evaluatePacket, same step names).
void main()
{
  ivec2 base = ivec2(gl_FragCoord.xy) * packetSize;
  int reference = computePixelKernels(base);
  outPacket = vec4(PACKET_CLASS_TRIVIAL, 0.0, 0.0, 0.0);
  if (pixelCount == 0)
  {
    return;
  }
  constructPacketKernel();
  PacketPrediction prediction = classifyPacket(reference);
  float visitedShare = 0.0;
  if (prediction.packetClass == PACKET_CLASS_COHERENT)
  {
    prediction.packetClass = evaluateCoherentPacket(prediction, visitedShare);
  }
  outPacket = vec4(prediction.packetClass, prediction.coherence, prediction.divergence, visitedShare);
}
#else
// The pixel pass: Alg. 1 step 8 (the twin's evaluateRemainingPixels), one pixel alone over its own kernel.
void main()
{
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 packet = texelFetch(packetTexture, pixel / packetSize, 0);
  if (packet.x < PACKET_CLASS_NON_COHERENT)
  {
    discard; // computed by the packet pass
  }
  Contour contour = prepareContour(pixel);
  if (contour.classification != PACKET_CLASS_COHERENT)
  {
    discard; // lit, umbra or not tested: stored by the packet pass
  }
  pixelCount = 0;
  addReceiver(contour);
  int outcome = traverse(contour.lo - 1, contour.hi);
  outVisibility = finalVisibility(0);
  outKernelTexels = contour.kernelTexels;
  outCoherence = packet.y;
  outPacketClass = outcome == TRAVERSAL_CUT_SHORT ? PACKET_CLASS_CUT_SHORT : packet.x;
  outDivergence = packet.z;
  outVisitedNodes = packet.w + float(visitedNodes);
  outContourEdges = float(contourEdges);
}
#endif
