// reference-sm, one light sample: the hard shadow test against this sample's shadow map (the same
// receiver preamble and bias as `hard`), weighted by 1/K and added into the accumulation target by
// GL_ONE/GL_ONE blending. Samples below the receiver's tangent plane count as hidden (LightModel), as in
// the ray-traced reference.
#include "common/GBufferInputs.glsl"
#include "common/LightModel.glsl"
#include "common/ShadowMapCommon.glsl"
#include "common/ShadowReceiver.glsl"

uniform float sampleWeight;

layout(location = 0) out float outWeightedVisibility;

void main()
{
  ShadowReceiver receiver = prepareShadowReceiver(ivec2(gl_FragCoord.xy));
  float visibility = receiver.needsShadowTest ? shadowTest(receiver.uvTexels, receiver.comparisonDepth)
                                              : receiver.visibility;
  outWeightedVisibility = sampleWeight * visibility;
}
