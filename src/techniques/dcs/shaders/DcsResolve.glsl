// Technique dcs, resolve (full screen): each light sample's depth complexity is the centre's (shadow volumes,
// `volumeCount`) plus its counter's change (dcs/DcsSampleCounters.glsl); a sample is hidden when it is behind an
// occluder (count > 0) or on or below the receiver's tangent plane (the reference's rule,
// src/reference/ReferenceRenderer.h). Visibility is the fraction of samples not hidden (the v_coef of Forest et al. 2009 §3.2).
#include "common/GBufferInputs.glsl"
#include "common/LightModel.glsl"
#include "common/LightSampleSet.glsl"
#include "dcs/DcsSampleCounters.glsl"

uniform sampler2D volumeCount;
layout(r32ui, binding = 0) uniform readonly uimage2DArray sampleCounters;
// The hidden samples as bits, 32 per layer (sample i: layer i / 32, bit i % 32); read back as light_sample_mask.
layout(r32ui, binding = 1) uniform writeonly uimage2DArray sampleMask;

layout(location = OUT_VISIBILITY) out float outVisibility;
layout(location = OUT_VISIBILITY_STDERR) out float outVisibilityStderr;
layout(location = OUT_DEPTH_COMPLEXITY_CENTER) out float outDepthComplexityCenter;
layout(location = OUT_OCCLUDED_SAMPLES) out float outOccludedSamples;
layout(location = OUT_DC_MIN) out float outDcMin;
layout(location = OUT_DC_MAX) out float outDcMax;
layout(location = OUT_WEDGES_COVERING) out float outWedgesCovering;
layout(location = OUT_COUNTER_STATUS) out float outCounterStatus;

void main()
{
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  Surface surface = readSurface(pixel);
  outVisibility = 0.0;
  outVisibilityStderr = 0.0;
  outDepthComplexityCenter = 0.0;
  outOccludedSamples = 0.0;
  outDcMin = 0.0;
  outDcMax = 0.0;
  outWedgesCovering = 0.0;
  outCounterStatus = float(COUNTER_STATUS_EXACT);
  for (int layer = 0; layer < (lightSampleCount + 31) / 32; ++layer)
  {
    imageStore(sampleMask, ivec3(pixel, layer), uvec4(0u));
  }
  if (!surface.covered)
  {
    return;
  }
  int centre = int(round(texelFetch(volumeCount, pixel, 0).r));
  outDepthComplexityCenter = float(centre);
  outWedgesCovering = float(imageLoad(sampleCounters, ivec3(pixel, DCS_COVERING_LAYER)).r);

  // Decode every counter and check the range: the two checksums the wedges added must equal the decoded changes'.
  int dcMin = 1 << 30;
  int dcMax = -(1 << 30);
  int occluded = 0;
  int checksum = 0;
  int weightedChecksum = 0;
  bool reachable = lightCanReach(surface.pWs, surface.nWs);
  int hidden = 0;
  uint word = 0u;
  for (int layer = 0; layer < (lightSampleCount + 31) / 32; ++layer)
  {
    uint bits = 0u;
    for (int bit = 0; bit < 32 && 32 * layer + bit < lightSampleCount; ++bit)
    {
      int index = 32 * layer + bit;
      if (index % DCS_COUNTERS_PER_LAYER == 0)
      {
        word = imageLoad(sampleCounters, ivec3(pixel, dcsCounterLayer(index))).r; // a word's counters: read once
      }
      int change = int((word >> dcsCounterShift(index)) & uint(DCS_COUNTER_MASK)) - DCS_COUNTER_BIAS;
      checksum += change;
      weightedChecksum += (index + 1) * change;
      int count = centre + change;
      dcMin = min(dcMin, count);
      dcMax = max(dcMax, count);
      bool blocked = count > 0;
      occluded += blocked ? 1 : 0;
      bool belowHorizon = dot(surface.nWs, lightSamplePoint(pixel, index) - surface.pWs) <= 0.0;
      if (blocked || belowHorizon)
      {
        bits |= 1u << uint(bit);
        ++hidden;
      }
    }
    imageStore(sampleMask, ivec3(pixel, layer), uvec4(bits));
  }
  outDcMin = float(dcMin);
  outDcMax = float(dcMax);
  outOccludedSamples = float(occluded);
  bool inRange = uint(checksum) == imageLoad(sampleCounters, ivec3(pixel, DCS_CHECKSUM_LAYER)).r &&
    uint(weightedChecksum) == imageLoad(sampleCounters, ivec3(pixel, DCS_WEIGHTED_CHECKSUM_LAYER)).r;
  outCounterStatus = float(inRange ? COUNTER_STATUS_EXACT : COUNTER_STATUS_RANGE_EXCEEDED);
  if (!surface.receivesShadows)
  {
    outVisibility = 1.0;
    return;
  }
  if (!reachable)
  {
    return;
  }
  float n = float(lightSampleCount);
  float v = float(lightSampleCount - hidden) / n;
  outVisibility = v;
  outVisibilityStderr = lightSampleCount > 1 ? sqrt(v * (1.0 - v) / (n - 1.0)) : 0.5;
}
