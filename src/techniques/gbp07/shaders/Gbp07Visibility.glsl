// GBP07 contour-based soft shadow mapping, per pixel (the packet paper's baseline): Eq. 1's kernel tightened
// by the minimum depth inside it (MSSM kernels), lit / umbra from the min-max structure, then marching
// squares over every dual cell with a corner in the kernel, back-projection and radial integration.
// CPU mirror: src/techniques/gbp07/Gbp07Technique.cpp.
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
layout(location = OUT_CONTOUR_EDGES) out float outContourEdges;
layout(location = OUT_VISITED_CELLS) out float outVisitedCells;
layout(location = OUT_CLASSIFICATION) out float outClassification;

// `classification` codes CLASSIFICATION_* come from the preamble (Gbp07Technique.cpp, from
// BackprojectionClass). Where the GL caps loop iterations per invocation (llvmpipe: 65535, all loops together;
// common/ContourBackprojection.glsl), a kernel of more dual cells than that is cut short: the pixel is then
// flagged CLASSIFICATION_OVER_LOOP_BUDGET, detected (its last cell not reached), so results on such GLs can be
// told apart and GLs without a cap flag nothing.

// Status and depth of sample (i, j); outside the map samples never occlude (contours close there).
float sampleAt(ivec2 texel, float d, float bias, out bool occluding)
{
  occluding = false;
  if (any(lessThan(texel, ivec2(0))) || any(greaterThanEqual(texel, ivec2(shadowMapSize))))
  {
    return 0.0;
  }
  float z = texelFetch(shadowMapLinear, texel, 0).r;
  occluding = z < tapComparisonDepth(vec2(texel) + 0.5, d, bias);
  return z;
}

// Unrolled by hand (see common/ContourBackprojection.glsl on llvmpipe's loop limit).
void cellCorners(ivec2 cell, float d, float bias, out bool occluding[4], out float depths[4])
{
  bool occludes;
  depths[0] = sampleAt(cell, d, bias, occludes);
  occluding[0] = occludes;
  depths[1] = sampleAt(cell + ivec2(1, 0), d, bias, occludes);
  occluding[1] = occludes;
  depths[2] = sampleAt(cell + ivec2(1, 1), d, bias, occludes);
  occluding[2] = occludes;
  depths[3] = sampleAt(cell + ivec2(0, 1), d, bias, occludes);
  occluding[3] = occludes;
}

void main()
{
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  ShadowReceiver receiver = prepareShadowReceiver(pixel);
  outVisibility = receiver.visibility;
  outKernelTexels = 0.0;
  outContourEdges = 0.0;
  outVisitedCells = 0.0;
  outClassification = CLASSIFICATION_NOT_TESTED;
  if (!receiver.needsShadowTest)
  {
    return;
  }
  float d = receiver.depthLin;
  float bias = receiver.bias;
  vec2 uv = receiver.uvTexels;
  ContourKernel kernel = prepareContourKernel(receiver);
  ivec2 lo = kernel.lo;
  ivec2 hi = kernel.hi;
  outKernelTexels = kernel.kernelTexels;
  if (kernel.decision != KERNEL_PENUMBRA)
  {
    outVisibility = kernel.decision == KERNEL_LIT ? 1.0 : 0.0;
    outClassification = kernel.decision == KERNEL_LIT ? CLASSIFICATION_LIT : CLASSIFICATION_UMBRA;
    return;
  }

  // Radial integration around the light centre, f(O) from the cell holding uv.
  float halfSize = 0.5 * lightSizeWorld;
  vec2 receiverXy = (shadowWindowMin + uv * shadowTexelTangent) * d;
  ivec2 centreCell = ivec2(floor(uv - 0.5));
  bool occluding[4];
  float depths[4];
  cellCorners(centreCell, d, bias, occluding, depths);
  float occludedArea = insideReconstructedOccluder(occluding, vec2(centreCell) + 0.5, uv) ? 4.0 * halfSize * halfSize : 0.0;
  int edgeCount = 0;
  int cellCount = 0;
  // Row by row; the at most two edges of a cell are handled without a loop. A GL's cap on loop iterations
  // ends the loops without their exits being taken, so a kernel whose last cell was never reached was cut short.
  bool reachedLastCell = false;
  for (int j = lo.y - 1; j <= hi.y; ++j)
  {
    for (int i = lo.x - 1; i <= hi.x; ++i)
    {
      reachedLastCell = i == hi.x && j == hi.y;
      ++cellCount;
      cellCorners(ivec2(i, j), d, bias, occluding, depths);
      ContourEdge edges[2];
      int count = marchingSquaresEdges(occluding, depths, vec2(i, j) + 0.5, edges);
      if (count > 0)
      {
        occludedArea += radialEdgeArea(backProject(shadowWindowMin + edges[0].a * shadowTexelTangent, edges[0].depthA, receiverXy, d),
          backProject(shadowWindowMin + edges[0].b * shadowTexelTangent, edges[0].depthB, receiverXy, d), halfSize);
      }
      if (count > 1)
      {
        occludedArea += radialEdgeArea(backProject(shadowWindowMin + edges[1].a * shadowTexelTangent, edges[1].depthA, receiverXy, d),
          backProject(shadowWindowMin + edges[1].b * shadowTexelTangent, edges[1].depthB, receiverXy, d), halfSize);
      }
      edgeCount += count;
    }
  }
  outContourEdges = float(edgeCount);
  outVisitedCells = float(cellCount);
  outVisibility = clamp(1.0 - occludedArea / (4.0 * halfSize * halfSize), 0.0, 1.0);
  outClassification = reachedLastCell ? CLASSIFICATION_PENUMBRA : CLASSIFICATION_OVER_LOOP_BUDGET;
}
