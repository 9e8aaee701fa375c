// The depth a midpoint or dual shadow map compares receivers with (survey §5, "depth biasing"), per texel, from the
// nearest caster depth z1 and the second-nearest z2 (depth peeling; both linear depth along the light axis, 2 x far
// where the texel holds no such surface). CPU twin: layerComparisonDepth (techniques/ShadowMapReference.h).
//   DEPTH_LAYER_MIDPOINT  (z1 + z2) / 2: Woo 1992, the midpoint of the first and second depth surfaces.
//   DEPTH_LAYER_DUAL      min((z1 + z2) / 2, z1 + dualMaxOffsetTexels x texel footprint at z1): Weiskopf & Ertl 2003's
//                         dual maps, as the survey §5 summarises them ("reintroduce a parameter that in effect limits
//                         the shadow caster thickness"); the hard README's "Bias alternatives" states the reading.
// The hardware depth gets the same depth (pcf's hardware comparison reads it).
uniform sampler2D firstLayerLinear;
uniform sampler2D secondLayerLinear;
uniform int lightIsPerspective;
uniform float shadowTexelExtent; // texel size in window units (tangent for perspective, world for ortho)
uniform float dualMaxOffsetTexels;
uniform vec4 lightDepthToClip; // clip.z = -x d + y, clip.w = -z d + w for linear depth d
#if WARPED_DEPTH
uniform float lightNearDepth;
uniform float lightFarDepth;
#endif

layout(location = 0) out float outDepthLin;

void main()
{
  ivec2 texel = ivec2(gl_FragCoord.xy);
  float first = texelFetch(firstLayerLinear, texel, 0).r;
  float second = texelFetch(secondLayerLinear, texel, 0).r;
  float compared = 0.5 * (first + second);
#if DEPTH_LAYER == DEPTH_LAYER_DUAL
  float texelWorld = lightIsPerspective != 0 ? shadowTexelExtent * first : shadowTexelExtent;
  compared = min(compared, first + dualMaxOffsetTexels * texelWorld);
#endif
  outDepthLin = compared;
#if WARPED_DEPTH
  gl_FragDepth = clamp((compared - lightNearDepth) / (lightFarDepth - lightNearDepth), 0.0, 1.0);
#else
  float clipZ = -lightDepthToClip.x * compared + lightDepthToClip.y;
  float clipW = -lightDepthToClip.z * compared + lightDepthToClip.w;
  gl_FragDepth = clipW > 0.0 ? clamp(0.5 * clipZ / clipW + 0.5, 0.0, 1.0) : 0.0;
#endif
}
