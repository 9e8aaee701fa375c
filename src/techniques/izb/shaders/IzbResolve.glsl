// Irregular z-buffer, step 3 (full screen): each pixel's visibility and buffers from its sample's bits.
#include "common/GBufferInputs.glsl"
#include "common/LightModel.glsl"
#include "izb/IzbCommon.glsl"

layout(std430, binding = 1) readonly buffer IzbCounts
{
  uint counts[];
};
uniform int imageWidth;

layout(location = OUT_VISIBILITY) out float outVisibility;
layout(location = OUT_IZB_LIST_LENGTH) out float outListLength;
layout(location = OUT_IZB_TRIANGLE_TESTS) out float outTriangleTests;
layout(location = OUT_IZB_AMBIGUOUS) out float outAmbiguous;
layout(location = OUT_IZB_STATUS) out float outStatus;

void main()
{
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  Surface surface = readSurface(pixel);
  outVisibility = 0.0;
  outListLength = 0.0;
  outTriangleTests = 0.0;
  outAmbiguous = 0.0;
  outStatus = float(IZB_STATUS_NO_TEST);
  if (!surface.covered)
  {
    return;
  }
  if (!surface.receivesShadows)
  {
    outVisibility = 1.0;
    return;
  }
  uint index = uint(pixel.y * imageWidth + pixel.x);
  uvec4 state = izbPixels[2u * index];
  uvec4 edges = izbPixels[2u * index + 1u];
  uint flags = state.x;
  // Two triangles sharing the one edge their tests were unsure of cover the sample from both sides of it.
  bool paired = izbEdgePairCovers(state.w, edges.x, edges.y);
  // Ambiguous: the texel placement within rounding, or some triangle's test within rounding and none certain.
  bool ambiguous = (flags & uint(IZB_FLAG_AMBIGUOUS_PLACEMENT)) != 0u ||
    ((flags & uint(IZB_FLAG_UNCERTAIN)) != 0u && (flags & uint(IZB_FLAG_DEFINITE)) == 0u && !paired);
  outAmbiguous = ambiguous ? 1.0 : 0.0;
  if ((flags & uint(IZB_FLAG_TESTED)) == 0u)
  {
    return; // the light cannot reach the point
  }
  outListLength = float(counts[state.z]);
  outTriangleTests = float(state.y);
  outVisibility = ((flags & uint(IZB_FLAG_SHADOW)) != 0u || paired) ? 0.0 : 1.0;
  outStatus = (flags & uint(IZB_FLAG_CUT_SHORT)) != 0u ? float(IZB_STATUS_CUT_SHORT) : float(IZB_STATUS_TESTED);
}
