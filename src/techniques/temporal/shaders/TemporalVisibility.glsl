// Temporal reprojection with shadow-test confidence (Scherzer, Jeschke & Wimmer 2007; survey §4.6), one frame: the
// single depth comparison of `hard` in this frame's jittered map, its confidence, and the history update.
// CPU twin: shadowTestConfidence, updateTemporalHistory and resolvedVisibility in
// src/techniques/temporal/TemporalTechnique.cpp.
#include "common/GBufferInputs.glsl"
#include "common/LightModel.glsl"
#include "common/ShadowMapCommon.glsl"
#include "common/ShadowReceiver.glsl"

layout(location = OUT_VISIBILITY) out float outVisibility;
layout(location = OUT_DEPTH_BIAS) out float outDepthBias;
// The pass's targets: x history_visibility, y history_weight, z history_frames, w confidence; and x history_depth,
// y sample_visibility, z sample_confidence.
layout(location = TEMPORAL_HISTORY_LOCATION) out vec4 outHistory;
layout(location = TEMPORAL_SAMPLE_LOCATION) out vec4 outSample;

// The previous frame's two targets (ignored in frame 0).
uniform sampler2D historyTarget;
uniform sampler2D historySampleTarget;
uniform int temporalFrameIndex;
uniform mat4 historyClipFromWorld; // the camera the history was written with
uniform mat4 historyViewFromWorld;
uniform mat4 currentViewFromWorld;

// Survey §4.6: 1 at the texel centre, 0 on its border.
float shadowTestConfidence(vec2 uvTexels)
{
  vec2 fromCentre = abs(uvTexels - floor(uvTexels) - 0.5);
  return clamp(1.0 - 2.0 * max(fromCentre.x, fromCentre.y), 0.0, 1.0);
}

void main()
{
  ShadowReceiver receiver = prepareShadowReceiver(ivec2(gl_FragCoord.xy));
  outVisibility = receiver.visibility;
  outDepthBias = 0.0;
  outHistory = vec4(receiver.visibility, 0.0, 0.0, 0.0);
  outSample = vec4(0.0, receiver.visibility, 0.0, 0.0);
  if (!receiver.needsShadowTest)
  {
    return;
  }
  float sampleVisibility = shadowTest(receiver.uvTexels, receiver.comparisonDepth);
  float confidence = shadowTestConfidence(receiver.uvTexels);
  float depth = -(currentViewFromWorld * vec4(receiver.pWs, 1.0)).z;

  // The history at the surface's position in the history's camera (nearest pixel), dropped outside that image or
  // where its depth is not the surface's reprojected depth (a disocclusion).
  vec4 kept = vec4(0.0);
  if (temporalFrameIndex > 0)
  {
    ivec2 historySize = textureSize(historyTarget, 0);
    vec4 clip = historyClipFromWorld * vec4(receiver.pWs, 1.0);
    ivec2 historyPixel = ivec2(floor((clip.xy / clip.w * 0.5 + 0.5) * vec2(historySize)));
    if (clip.w > 0.0 && all(greaterThanEqual(historyPixel, ivec2(0))) && all(lessThan(historyPixel, historySize)))
    {
      vec4 history = texelFetch(historyTarget, historyPixel, 0);
      float storedDepth = texelFetch(historySampleTarget, historyPixel, 0).x;
      float reprojectedDepth = -(historyViewFromWorld * vec4(receiver.pWs, 1.0)).z;
      if (history.z > 0.0 && abs(storedDepth - reprojectedDepth) <= param_disocclusion_threshold * abs(reprojectedDepth))
      {
        kept = history;
      }
    }
  }
  // pow(0, 0) is undefined in GLSL: m = 0 weighs every frame 1, as the twin's std::pow does.
  float weight = param_confidence_exponent == 0.0 ? 1.0 : pow(confidence, param_confidence_exponent);
  float total = kept.y + weight;
  float mean = total > 0.0 ? (kept.y * kept.x + weight * sampleVisibility) / total : sampleVisibility;
  outHistory = vec4(mean, total, kept.z + 1.0, max(kept.w, confidence));
  outSample = vec4(depth, sampleVisibility, confidence, 0.0);
#if RESOLVE == RESOLVE_THRESHOLD
  outVisibility = mean >= 0.5 ? 1.0 : 0.0;
#else
  outVisibility = mean;
#endif
  outDepthBias = receiver.bias;
}
