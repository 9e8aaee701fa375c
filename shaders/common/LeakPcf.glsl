// The light-leak buffers' reference: the true PCF over the box a prefiltered map averages (clamp to edge), compared as
// `pcf` compares at its defaults. Needs common/ShadowMapCommon.glsl and common/ShadowReceiver.glsl.
// The bias `pcf` applies at its defaults (constant, slope, max slope; texel footprints, survey §5): the light-leak
// PCF compares with it whatever the technique's own bias is, since vsm's is 0 and an unbiased test shadows a
// receiver with its own texels wherever it slopes in depth.
uniform vec3 leakBiasTexels;

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
