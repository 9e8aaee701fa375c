// reference-sm, one light sample: the hard shadow test against this sample's shadow map (the same
// receiver preamble and bias as `hard`), weighted by 1/K and added into the accumulation target by
// GL_ONE/GL_ONE blending, with the share of samples whose test a neighbouring texel decides otherwise. Samples below the receiver's tangent plane count as hidden (LightModel), as in
// the ray-traced reference.
#include "common/GBufferInputs.glsl"
#include "common/LightModel.glsl"
#include "common/ShadowMapCommon.glsl"
#include "common/ShadowReceiver.glsl"

uniform float sampleWeight;

// x: the visibility; y: 1 where a neighbouring texel of this map decides the test otherwise (a caster's edge
// within a texel, placed by the map only to within one), published as edge_samples.
layout(location = 0) out vec2 outWeighted;

// Whether one of the four texels next to the receiver's decides its test otherwise (clamped at the map's border).
float edgeWithinATexel(vec2 uvTexels, float comparisonDepth, float visibility)
{
  const ivec2 neighbours[4] = ivec2[4](ivec2(1, 0), ivec2(-1, 0), ivec2(0, 1), ivec2(0, -1));
  ivec2 texel = shadowMapTexel(uvTexels);
  float edge = 0.0;
  for (int i = 0; i < 4; ++i)
  {
    ivec2 neighbour = clamp(texel + neighbours[i], ivec2(0), ivec2(shadowMapSize - 1));
    float lit = comparisonDepth <= texelFetch(shadowMapLinear, neighbour, 0).r ? 1.0 : 0.0;
    edge = max(edge, abs(lit - visibility));
  }
  return edge;
}

void main()
{
  ShadowReceiver receiver = prepareShadowReceiver(ivec2(gl_FragCoord.xy));
  float visibility = receiver.needsShadowTest ? shadowTest(receiver.uvTexels, receiver.comparisonDepth)
                                              : receiver.visibility;
  float edge = receiver.needsShadowTest ? edgeWithinATexel(receiver.uvTexels, receiver.comparisonDepth, visibility)
                                        : 0.0;
  outWeighted = sampleWeight * vec2(visibility, edge);
}
