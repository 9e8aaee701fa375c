// Reading the prefiltered moment map (passes/vtkSLMomentMapPass), and the true PCF over the same box it
// averages (the reference of the light-leak buffers). Needs common/ShadowMapCommon.glsl; PREFILTER_* come
// from the technique's `prefilter` parameter.
uniform sampler2D momentMap;
uniform float momentLod; // prefilter = mipmap: log2(prefilter_texels)

vec4 filteredMoments(vec2 uvTexels)
{
#if PREFILTER == PREFILTER_MIPMAP
  return textureLod(momentMap, uvTexels / float(shadowMapSize), momentLod);
#else
  // blur: the texel containing the receiver holds the average over the box centred on it
  return texelFetch(momentMap, shadowMapTexel(uvTexels), 0);
#endif
}

// Fraction of the width x width texels around the receiver's texel (the blur's box, clamp to edge) that
// pass the depth test: what a filtered moment map approximates.
float boxPcf(vec2 uvTexels, float comparisonDepthLin, int width)
{
  ivec2 center = shadowMapTexel(uvTexels);
  int first = -(width - 1) / 2;
  float lit = 0.0;
  for (int j = 0; j < width; ++j)
  {
    for (int i = 0; i < width; ++i)
    {
      ivec2 texel = clamp(center + ivec2(first + i, first + j), ivec2(0), ivec2(shadowMapSize - 1));
      lit += comparisonDepthLin <= texelFetch(shadowMapLinear, texel, 0).r ? 1.0 : 0.0;
    }
  }
  return lit / float(width * width);
}
