// Reading the prefiltered moment map (structures/moments), and, through common/LeakPcf.glsl, the true PCF over
// the same box it averages (the reference of the light-leak buffers). Needs common/ShadowMapCommon.glsl and
// common/ShadowReceiver.glsl; PREFILTER_* come from the technique's `prefilter` parameter.
#include "common/LeakPcf.glsl"

uniform sampler2D momentMap;
uniform float momentLod; // prefilter = mipmap: log2(prefilter_texels)

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
