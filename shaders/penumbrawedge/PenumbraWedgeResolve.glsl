// Technique penumbra-wedge, resolve (full screen): AAM03's occlusion is the centre's hard-shadow status (the shadow
// volumes' count, `volumeCount`) plus what the wedges added (`occlusionDelta`, PenumbraWedgeArea.glsl); visibility
// = 1 - clamp(occlusion, 0, 1) (src/techniques/penumbrawedge/PenumbraWedgeGeometry.h). pw_occlusion_raw keeps the
// value before clamping: < 0 or > 1 where overlapping silhouettes were counted twice (003 L384-387).
#include "common/GBufferInputs.glsl"
#include "common/LightModel.glsl"

uniform sampler2D volumeCount;
uniform sampler2D occlusionDelta;
uniform sampler2D wedgesCovering;

layout(location = OUT_VISIBILITY) out float outVisibility;
layout(location = OUT_PW_OCCLUSION_RAW) out float outOcclusionRaw;
layout(location = OUT_DEPTH_COMPLEXITY_CENTER) out float outDepthComplexityCenter;
layout(location = OUT_WEDGES_COVERING) out float outWedgesCovering;

void main()
{
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  Surface surface = readSurface(pixel);
  outVisibility = 0.0;
  outOcclusionRaw = 0.0;
  outDepthComplexityCenter = 0.0;
  outWedgesCovering = 0.0;
  if (!surface.covered)
  {
    return;
  }
  float count = texelFetch(volumeCount, pixel, 0).r;
  outDepthComplexityCenter = count;
  outWedgesCovering = texelFetch(wedgesCovering, pixel, 0).r;
  outOcclusionRaw = (abs(count) > 0.5 ? 1.0 : 0.0) + texelFetch(occlusionDelta, pixel, 0).r;
  if (!surface.receivesShadows)
  {
    outVisibility = 1.0;
    return;
  }
  if (!lightCanReach(surface.pWs, surface.nWs))
  {
    return;
  }
  outVisibility = 1.0 - clamp(outOcclusionRaw, 0.0, 1.0);
}
