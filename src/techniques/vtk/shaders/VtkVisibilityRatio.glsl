// The `vtk` technique: VTK's vtkShadowMapPass does not expose a visibility, only shaded colour, so the
// scene is rendered by VTK twice with a white, purely diffuse material: with shadows (S) and without
// (U). Where the light reaches the surface, S = U * shadowFactor, so visibility = S / U. The same reach
// rules as every other technique apply (GBufferInputs / LightModel), so buffers compare pixel by pixel.
#include "common/GBufferInputs.glsl"
#include "common/LightModel.glsl"

uniform sampler2D vtkShadowedRadiance;
uniform sampler2D vtkUnshadowedRadiance;

layout(location = OUT_VISIBILITY) out float outVisibility;
layout(location = OUT_VTK_SHADOWED) out float outShadowed;
layout(location = OUT_VTK_UNSHADOWED) out float outUnshadowed;

void main()
{
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  Surface surface = readSurface(pixel);
  float shadowed = texelFetch(vtkShadowedRadiance, pixel, 0).g;
  float unshadowed = texelFetch(vtkUnshadowedRadiance, pixel, 0).g;
  outShadowed = surface.covered ? shadowed : 0.0;
  outUnshadowed = surface.covered ? unshadowed : 0.0;
  outVisibility = 0.0;
  if (!surface.covered)
  {
    return;
  }
  if (!surface.receivesShadows)
  {
    outVisibility = 1.0;
    return;
  }
  // Below 1e-3 of full irradiance the ratio is noise (and VTK may cover the pixel differently at a
  // silhouette); such pixels face away from the light almost completely.
  if (!lightCanReach(surface.pWs, surface.nWs) || unshadowed < 1e-3)
  {
    return;
  }
  outVisibility = clamp(shadowed / unshadowed, 0.0, 1.0);
}
