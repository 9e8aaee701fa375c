// Percentage-closer filtering (Reeves et al. 1987; survey §6): the average of depth comparisons over a
// kernel around the receiver's shadow-map position. Kernel: a grid of kernel_texels x kernel_texels taps
// one texel apart, or poisson_samples taps of a fixed Poisson disk of diameter kernel_texels, rotated per
// pixel by a hash of the pixel position. Each tap is one texel comparison (filter = nearest) or the
// hardware's bilinearly weighted 2x2 comparison (filter = hardware_bilinear, survey Fig. 23).
// CPU mirror: pcfReference in src/techniques/pcf/PcfTechnique.cpp.
#include "common/GBufferInputs.glsl"
#include "common/LightModel.glsl"
#include "common/ShadowMapCommon.glsl"
#include "common/ShadowReceiver.glsl"
#include "common/TexelRatio.glsl"
#include "common/SamplingPatterns.glsl"

uniform sampler2DShadow shadowMapCompare;      // hardware depth, GL_LINEAR + GL_COMPARE_REF_TO_TEXTURE (LEQUAL)

layout(location = OUT_VISIBILITY) out float outVisibility;
layout(location = OUT_KERNEL_TEXELS) out float outKernelTexels;
layout(location = OUT_TAPS) out float outTaps;
layout(location = OUT_TEXEL_RATIO) out float outTexelRatio;
layout(location = OUT_DEPTH_BIAS) out float outDepthBias;

float tap(vec2 uvTexels, float comparisonDepthLin)
{
#if FILTER == FILTER_HARDWARE_BILINEAR
  return texture(shadowMapCompare, vec3(uvTexels / float(shadowMapSize), windowDepth(comparisonDepthLin)));
#else
  return shadowTest(uvTexels, comparisonDepthLin);
#endif
}

void main()
{
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  ShadowReceiver receiver = prepareShadowReceiver(pixel);
  outVisibility = receiver.visibility;
  outKernelTexels = 0.0;
  outTaps = 0.0;
  outTexelRatio = 0.0;
  outDepthBias = 0.0;
  if (!receiver.needsShadowTest)
  {
    return;
  }
  vec2 uvTexels = receiver.uvTexels;
  float comparisonDepth = receiver.comparisonDepth;
  int kernelTexels = int(param_kernel_texels);
  float litSum = 0.0;
#if PATTERN == PATTERN_GRID
  int tapCount = kernelTexels * kernelTexels;
  float firstOffset = -0.5 * float(kernelTexels - 1);
  for (int j = 0; j < kernelTexels; ++j)
  {
    for (int i = 0; i < kernelTexels; ++i)
    {
      litSum += tap(uvTexels + vec2(firstOffset + float(i), firstOffset + float(j)), comparisonDepth);
    }
  }
#else
  int tapCount = int(param_poisson_samples);
  mat2 rotation = pixelRotation(uvec2(pixel));
  float radiusTexels = 0.5 * float(kernelTexels);
  for (int k = 0; k < tapCount; ++k)
  {
    litSum += tap(uvTexels + radiusTexels * (rotation * poissonDisk[k]), comparisonDepth);
  }
#endif
  outVisibility = litSum / float(tapCount);
#if FILTER == FILTER_HARDWARE_BILINEAR
  outKernelTexels = float(kernelTexels + 1); // the bilinear footprint adds one texel
  outTaps = float(4 * tapCount);
#else
  outKernelTexels = float(kernelTexels);
  outTaps = float(tapCount);
#endif
  outTexelRatio = texelRatio(gl_FragCoord.xy, receiver.pWs, receiver.nWs);
  outDepthBias = receiver.bias;
}
