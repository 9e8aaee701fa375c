// Technique shadow-volume, resolve (full screen): visibility and the volume count per pixel.
// `volumeCount` (R32F) is the exact z-fail count, `volumeStencil` the same count modulo 256 in the G-buffer's
// stencil (read through GL_DEPTH_STENCIL_TEXTURE_MODE = GL_STENCIL_INDEX). The count is the number of caster
// triangles the segment from the visible point to the light's centre crosses, the point taken receiver_offset
// toward the camera (so on the camera's side of its own surface).
#include "common/GBufferInputs.glsl"
#include "common/LightModel.glsl"

uniform sampler2D volumeCount;
uniform usampler2D volumeStencil;

layout(location = OUT_VISIBILITY) out float outVisibility;
layout(location = OUT_DEPTH_COMPLEXITY_CENTER) out float outDepthComplexityCenter;
layout(location = OUT_STENCIL_COUNT) out float outStencilCount;

void main()
{
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  Surface surface = readSurface(pixel);
  outVisibility = 0.0;
  outDepthComplexityCenter = 0.0;
  outStencilCount = 0.0;
  if (!surface.covered)
  {
    return;
  }
  float count = texelFetch(volumeCount, pixel, 0).r;
  uint stencil = texelFetch(volumeStencil, pixel, 0).r;
  outDepthComplexityCenter = count;
  outStencilCount = float(stencil);
  if (!surface.receivesShadows)
  {
    outVisibility = 1.0;
    return;
  }
  if (!lightCanReach(surface.pWs, surface.nWs))
  {
    return;
  }
  // Lit when no volume contains the point: the classic stencil test, and the exact count, which also
  // catches a count that wrapped the 8-bit stencil back to 0 at 256.
  outVisibility = (stencil == 0u && abs(count) < 0.5) ? 1.0 : 0.0;
}
