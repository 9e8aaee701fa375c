// The custom multisample resolve of Schwarz and Stamminger 2008 §7 (CPU twin: techniques/MsaaResolve.h):
// the technique ran once per pixel from the first sample (s_z = sample 0's view depth, §7). A covered sample
// whose view depth d is within tau of s_z (relative: |d - s_z| <= tau s_z, the project's reading of the paper's
// threshold tau, which has no value, §7) takes the pixel's visibility; any other takes the visibility of the
// pixel or 4-neighbour (-x, +x, -y, +y; ties keep the first) whose s_z is closest to d (§7). Pixels whose sample
// 0 is uncovered have no s_z: their covered samples all take a neighbour's visibility (or 0 where no neighbour is
// covered). `visibility` is the mean over the covered samples where sample 0 is covered, else 0 (the frame's
// coverage is sample 0's).
#ifndef MSAA_SAMPLES
#error MSAA_SAMPLES must be defined
#endif
uniform sampler2D pixelVisibility;
uniform sampler2D gbufferPosition;     // sample 0: w = coverage
uniform sampler2D gbufferAlbedoDepth;  // sample 0: w = s_z
uniform sampler2DMS multisamplePosition;
uniform sampler2DMS multisampleAlbedoDepth;
uniform float depthTolerance;

layout(location = 0) out float outVisibility;
layout(location = 1) out vec4 outSampleVisibility;
layout(location = 2) out vec4 outSampleDepth;
layout(location = 3) out float outDistinctSamples;
layout(location = 4) out float outInterpolatedSamples;

bool firstSampleCovered(ivec2 pixel)
{
  return texelFetch(gbufferPosition, pixel, 0).w > 0.5;
}

void main()
{
  const ivec2 offsets[4] = ivec2[4](ivec2(-1, 0), ivec2(1, 0), ivec2(0, -1), ivec2(0, 1));
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  ivec2 size = textureSize(gbufferPosition, 0);
  bool covered = firstSampleCovered(pixel);
  float firstDepth = texelFetch(gbufferAlbedoDepth, pixel, 0).w;
  float visibility = covered ? texelFetch(pixelVisibility, pixel, 0).r : 0.0;

  vec4 sampleVisibility = vec4(0.0);
  vec4 sampleDepth = vec4(0.0);
  int distinct = 0;
  int interpolated = 0;
  int coveredSamples = 0;
  float sum = 0.0;
  for (int s = 0; s < MSAA_SAMPLES; ++s)
  {
    if (texelFetch(multisamplePosition, pixel, s).w <= 0.5)
    {
      continue;
    }
    float depth = texelFetch(multisampleAlbedoDepth, pixel, s).w;
    float value = visibility;
    if (!covered || abs(depth - firstDepth) > depthTolerance * firstDepth)
    {
      ++distinct;
      float best = covered ? abs(depth - firstDepth) : 3.0e38;
      bool fromNeighbour = false;
      value = covered ? visibility : 0.0;
      for (int n = 0; n < 4; ++n)
      {
        ivec2 neighbour = pixel + offsets[n];
        if (any(lessThan(neighbour, ivec2(0))) || any(greaterThanEqual(neighbour, size)) || !firstSampleCovered(neighbour))
        {
          continue;
        }
        float difference = abs(depth - texelFetch(gbufferAlbedoDepth, neighbour, 0).w);
        if (difference < best)
        {
          best = difference;
          value = texelFetch(pixelVisibility, neighbour, 0).r;
          fromNeighbour = true;
        }
      }
      interpolated += fromNeighbour ? 1 : 0;
    }
    sampleVisibility[s] = value;
    sampleDepth[s] = depth;
    sum += value;
    ++coveredSamples;
  }
  outVisibility = covered ? sum / float(coveredSamples) : 0.0;
  outSampleVisibility = sampleVisibility;
  outSampleDepth = sampleDepth;
  outDistinctSamples = float(distinct);
  outInterpolatedSamples = float(interpolated);
}
