// reference-sm, after all K samples: visibility is the accumulated average (edge_samples the count of samples
// whose test a neighbouring texel decides otherwise); its standard error is the
// Bernoulli bound sqrt(v (1 - v) / (K - 1)) (the Hammersley samples are stratified, so the true error is
// smaller).
#include "common/GBufferInputs.glsl"

uniform sampler2D accumulatedVisibility;
uniform int sampleCount;

layout(location = OUT_VISIBILITY) out float outVisibility;
layout(location = OUT_VISIBILITY_STDERR) out float outStandardError;
layout(location = OUT_SAMPLE_COUNT) out float outSampleCount;
layout(location = OUT_EDGE_SAMPLES) out float outEdgeSamples;

void main()
{
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  Surface surface = readSurface(pixel);
  vec2 accumulated = texelFetch(accumulatedVisibility, pixel, 0).rg;
  float visibility = clamp(accumulated.r, 0.0, 1.0);
  outVisibility = visibility;
  outSampleCount = surface.covered ? float(sampleCount) : 0.0;
  // K weights 1/K summed in float: within K 2^-24 of the count / K, so rounding recovers the count.
  outEdgeSamples = surface.covered ? round(accumulated.g * float(sampleCount)) : 0.0;
  outStandardError = (surface.covered && sampleCount > 1)
    ? sqrt(visibility * (1.0 - visibility) / float(sampleCount - 1))
    : 0.0;
}
