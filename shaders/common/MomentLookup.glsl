// Reading the prefiltered moment map (passes/vtkSLMomentMapPass), and the true PCF over the same box it
// averages (the reference of the light-leak buffers). Needs common/ShadowMapCommon.glsl and
// common/ShadowReceiver.glsl; PREFILTER_* come from the technique's `prefilter` parameter.
uniform sampler2D momentMap;
uniform float momentLod; // prefilter = mipmap: log2(prefilter_texels)
// The bias `pcf` applies at its defaults (constant, slope, max slope; texel footprints, survey §5): the light-leak
// PCF compares with it whatever the technique's own bias is, since vsm's is 0 and an unbiased test shadows a
// receiver with its own texels wherever it slopes in depth.
uniform vec3 leakBiasTexels;

// The prefiltered value of any map built by the moment prefilter (structures/moments/MomentPrefilter: the moment
// map, the power moment map, CSM's basis images) at the receiver's texel.
vec4 prefilteredFetch(sampler2D prefiltered, vec2 uvTexels)
{
#if PREFILTER == PREFILTER_MIPMAP
  return textureLod(prefiltered, uvTexels / float(shadowMapSize), momentLod);
#else
  // blur: the texel containing the receiver holds the average over the box centred on it
  return texelFetch(prefiltered, shadowMapTexel(uvTexels), 0);
#endif
}

vec4 filteredMoments(vec2 uvTexels)
{
  return prefilteredFetch(momentMap, uvTexels);
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

// The depth the light-leak PCF compares against: the receiver's depth minus `pcf`'s default bias, as `pcf` does.
float leakComparisonDepth(ShadowReceiver receiver)
{
  float tanTheta = tanAngleToLight(receiver.nWs, directionToLight(receiver.pWs));
  float biasWs = texelWorldSize(receiver.depthLin) *
    (leakBiasTexels.x + leakBiasTexels.y * min(tanTheta, leakBiasTexels.z));
  return receiver.depthLin - biasWs;
}
