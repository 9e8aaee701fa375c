// reference-sm, after all K samples: visibility is the accumulated average; its standard error is the
// Bernoulli bound sqrt(v (1 - v) / (K - 1)) (the Hammersley samples are stratified, so the true error is
// smaller).
#include "common/GBufferInputs.glsl"

uniform sampler2D accumulatedVisibility;
uniform int sampleCount;

layout(location = OUT_VISIBILITY) out float outVisibility;
layout(location = OUT_VISIBILITY_STDERR) out float outStandardError;
layout(location = OUT_SAMPLE_COUNT) out float outSampleCount;

void main()
{
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  Surface surface = readSurface(pixel);
  float visibility = clamp(texelFetch(accumulatedVisibility, pixel, 0).r, 0.0, 1.0);
  outVisibility = visibility;
  outSampleCount = surface.covered ? float(sampleCount) : 0.0;
  outStandardError = (surface.covered && sampleCount > 1)
    ? sqrt(visibility * (1.0 - visibility) / float(sampleCount - 1))
    : 0.0;
}
