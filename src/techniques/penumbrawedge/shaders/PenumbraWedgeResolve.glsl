// Technique penumbra-wedge, resolve (full screen): AAM03's occlusion is the centre's hard-shadow status (the shadow
// volumes' count, `volumeCount`) plus what the wedges added (`occlusionDelta`, PenumbraWedgeArea.glsl); visibility
// = 1 - clamp(occlusion, 0, 1) (src/techniques/penumbrawedge/PenumbraWedgeGeometry.h). The perforated casters' share,
// the popcount of the STSVs' light-sample mask over N, is added to it (Forest et al. 2009 §3.1). pw_occlusion_raw keeps the value
// before clamping: < 0 or > 1 where overlapping silhouettes were counted twice (Forest et al. 2009 §3.1).
#include "common/GBufferInputs.glsl"
#include "common/LightModel.glsl"
#include "common/LightSampleSet.glsl"

uniform sampler2D volumeCount;
uniform sampler2D occlusionDelta;
uniform sampler2D wedgesCovering;
uniform sampler2D stsvCovering;
uniform sampler2D stsvEmptyHits;
layout(r32ui, binding = 1) uniform readonly uimage2DArray stsvMask;

layout(location = OUT_VISIBILITY) out float outVisibility;
layout(location = OUT_PW_OCCLUSION_RAW) out float outOcclusionRaw;
layout(location = OUT_DEPTH_COMPLEXITY_CENTER) out float outDepthComplexityCenter;
layout(location = OUT_WEDGES_COVERING) out float outWedgesCovering;
layout(location = OUT_STSV_COVERING) out float outStsvCovering;
layout(location = OUT_STSV_EMPTY_HITS) out float outStsvEmptyHits;
layout(location = OUT_STSV_OCCLUDED_SAMPLES) out float outStsvOccludedSamples;

void main()
{
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  Surface surface = readSurface(pixel);
  outVisibility = 0.0;
  outOcclusionRaw = 0.0;
  outDepthComplexityCenter = 0.0;
  outWedgesCovering = 0.0;
  outStsvCovering = 0.0;
  outStsvEmptyHits = 0.0;
  outStsvOccludedSamples = 0.0;
  if (!surface.covered)
  {
    return;
  }
  float count = texelFetch(volumeCount, pixel, 0).r;
  outDepthComplexityCenter = count;
  outWedgesCovering = texelFetch(wedgesCovering, pixel, 0).r;
  outStsvCovering = texelFetch(stsvCovering, pixel, 0).r;
  outStsvEmptyHits = texelFetch(stsvEmptyHits, pixel, 0).r;
  int hidden = 0;
  for (int layer = 0; layer < (lightSampleCount + 31) / 32; ++layer)
  {
    hidden += bitCount(imageLoad(stsvMask, ivec3(pixel, layer)).r);
  }
  outStsvOccludedSamples = float(hidden);
  outOcclusionRaw = (abs(count) > 0.5 ? 1.0 : 0.0) + texelFetch(occlusionDelta, pixel, 0).r +
    float(hidden) / float(lightSampleCount);
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
