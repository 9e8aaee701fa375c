// ss08, pass 1 of 4 (Schwarz & Stamminger 2008, Fig. 3 step 1): the search of ss08/Ss08Search.glsl per pixel,
// written to the LOQ map the smoothing passes read: x = l_raw, y = the smoothing state (LOQ_STATE_*: the pixel
// needs no back-projection, is smoothed, or back-projects at a level smoothing must keep: unlimited budget or
// force_level).
// CPU mirror: src/techniques/ss08/Ss08Technique.cpp (ss08Search: Ss08Search::state).
#include "common/GBufferInputs.glsl"
#include "common/LightModel.glsl"
#include "common/ShadowMapCommon.glsl"
#include "common/ShadowReceiver.glsl"
#include "common/SoftShadowKernels.glsl"
#include "common/HsmLookup.glsl"
#include "common/ContourKernel.glsl"
#include "ss08/Ss08Search.glsl"

layout(location = 0) out vec2 outLoq;

void main()
{
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  ShadowReceiver receiver = prepareShadowReceiver(pixel);
  outLoq = vec2(0.0, float(LOQ_STATE_NONE));
  if (!receiver.needsShadowTest)
  {
    return;
  }
  Ss08Search search = ss08Search(receiver, pixel);
  bool backProjects = search.decision == CLASSIFICATION_PENUMBRA ||
    (GROWTH == GROWTH_ON && search.decision == CLASSIFICATION_GROWTH_PENUMBRA);
  int state = !backProjects ? LOQ_STATE_NONE
    : search.budget == 0 || param_force_level >= 0.0 ? LOQ_STATE_FIXED : LOQ_STATE_SMOOTHED;
  outLoq = vec2(search.levelRaw, float(state));
}
