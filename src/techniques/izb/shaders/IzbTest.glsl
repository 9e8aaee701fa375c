// Irregular z-buffer, step 2 (Johnson et al. 2005; Sintorn et al. 2008): one invocation per (caster triangle,
// texel it overlaps) pair, the texels from the conservative cover (IzbGrid::triangleTexels); it walks the texel's
// list and tests every sample against the triangle exactly (izbSampleTest), setting the sample's bits with atomicOr
// and counting the test. A list holds at most listBudget samples (step 1 flags the rest), so the walk stays under
// llvmpipe's 65535 loop iterations.
layout(local_size_x = 64) in;

#include "izb/IzbCommon.glsl"

uniform int pairCount;
uniform int groupsX;
uniform int listBudget;
uniform float normalOffset; // world units: its rounding enters the bounds

layout(std430, binding = 0) readonly buffer IzbHeads
{
  uint heads[];
};
struct IzbNode
{
  vec4 point;
  uint pixel;
  uint next;
  uint pad0;
  uint pad1;
};
layout(std430, binding = 2) readonly buffer IzbNodes
{
  IzbNode nodes[];
};
layout(std430, binding = 5) readonly buffer IzbTriangles
{
  vec4 triangleVertices[]; // 3 per triangle, world xyz
};
layout(std430, binding = 6) readonly buffer IzbPairs
{
  uvec2 pairs[]; // x: triangle, y: texel
};
layout(std430, binding = 7) readonly buffer IzbVertexIds
{
  uint triangleVertexIds[]; // 3 per triangle, global over the casters (izbCasterVertexIds)
};

void main()
{
  uint pairIndex = (gl_WorkGroupID.y * uint(groupsX) + gl_WorkGroupID.x) * 64u + gl_LocalInvocationIndex;
  if (pairIndex >= uint(pairCount))
  {
    return;
  }
  uvec2 pair = pairs[pairIndex];
  vec3 a = triangleVertices[3u * pair.x].xyz;
  vec3 b = triangleVertices[3u * pair.x + 1u].xyz;
  vec3 c = triangleVertices[3u * pair.x + 2u].xyz;
  uint link = heads[pair.y];
  for (int walked = 0; walked < listBudget && link != 0u; ++walked)
  {
    uint node = link - 1u;
    uint pixel = nodes[node].pixel;
    int loneEdge;
    int orientation;
    uint bits = izbSampleTest(a, b, c, nodes[node].point.xyz, normalOffset, loneEdge, orientation);
    atomicAdd(izbPixels[2u * pixel].y, 1u);
    if (bits != 0u)
    {
      atomicOr(izbPixels[2u * pixel].x, bits);
    }
    if (loneEdge >= 0)
    {
      // izbEdgeEvent: the edge's lower id (top bit: listed from the higher), its higher id (top bit: orientation).
      uint from = triangleVertexIds[3u * pair.x + uint(loneEdge)];
      uint to = triangleVertexIds[3u * pair.x + uint((loneEdge + 1) % 3)];
      uint first = min(from, to) | (from > to ? (1u << IZB_EDGE_TOP_BIT_SHIFT) : 0u);
      uint second = max(from, to) | (orientation > 0 ? (1u << IZB_EDGE_TOP_BIT_SHIFT) : 0u);
      atomicAdd(izbPixels[2u * pixel].w, 1u);
      atomicXor(izbPixels[2u * pixel + 1u].x, first);
      atomicXor(izbPixels[2u * pixel + 1u].y, second);
    }
    link = nodes[node].next;
  }
}
