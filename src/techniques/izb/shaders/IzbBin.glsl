// Irregular z-buffer, step 1 (Johnson et al. 2005): every visible sample, moved off its surface by the normal
// offset, is listed in the light-space texel it projects to: a head pointer per texel, a node per sample from one
// atomic counter (vtkSLIzbPass.h says why lists rather than counting + prefix sum). A sample beyond the list budget
// of its texel or beyond the node budget is not listed and is flagged IZB_FLAG_CUT_SHORT.
layout(local_size_x = 8, local_size_y = 8) in;

#include "common/GBufferInputs.glsl"
#include "common/LightModel.glsl"
#include "izb/IzbCommon.glsl"

uniform int imageWidth;
uniform int imageHeight;
uniform float normalOffset; // world units
uniform int nodeBudget;     // nodes allocated
uniform int listBudget;     // samples a texel's list may hold

layout(std430, binding = 0) buffer IzbHeads
{
  uint heads[]; // node + 1, 0: empty
};
layout(std430, binding = 1) buffer IzbCounts
{
  uint counts[]; // samples projecting to the texel, listed or not
};
struct IzbNode
{
  vec4 point; // xyz: the sample point
  uint pixel;
  uint next;  // node + 1, 0: end
  uint pad0;
  uint pad1;
};
layout(std430, binding = 2) buffer IzbNodes
{
  IzbNode nodes[];
};
layout(std430, binding = 4) buffer IzbCounter
{
  uint nodeCounter;
};

void main()
{
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= imageWidth || pixel.y >= imageHeight)
  {
    return;
  }
  uint index = uint(pixel.y * imageWidth + pixel.x);
  Surface surface = readSurface(pixel);
  uint flags = 0u;
  uint texel = 0u;
  if (surface.covered && surface.receivesShadows)
  {
    if (lightCanReach(surface.pWs, surface.nWs))
    {
      flags |= uint(IZB_FLAG_TESTED);
      vec3 q = surface.pWs + normalOffset * surface.nWs;
      IzbPlace place = izbPlace(q);
      texel = place.texel;
      flags |= place.errorTexels > 0.5 / float(IZB_COVERAGE_MARGIN_INVERSE) ? uint(IZB_FLAG_AMBIGUOUS_PLACEMENT) : 0u;
      uint slot = atomicAdd(counts[texel], 1u);
      uint node = slot < uint(listBudget) ? atomicAdd(nodeCounter, 1u) : uint(nodeBudget);
      if (node < uint(nodeBudget))
      {
        nodes[node].point = vec4(q, 0.0);
        nodes[node].pixel = index;
        nodes[node].next = atomicExchange(heads[texel], node + 1u);
      }
      else
      {
        flags |= uint(IZB_FLAG_CUT_SHORT);
      }
    }
  }
  izbPixels[2u * index] = uvec4(flags, 0u, texel, 0u);
  izbPixels[2u * index + 1u] = uvec4(0u);
}
