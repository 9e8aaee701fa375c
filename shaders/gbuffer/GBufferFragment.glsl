// G-buffer layout: see src/passes/FrameResources.h.
#include "common/AlphaMask.glsl"

in vec3 pWs;
in vec3 nWs;
in vec2 uv;
in float viewDepth;

uniform vec3 objectAlbedo;
uniform int objectReceivesShadows;
uniform vec2 alphaTestOffset; // pixels: FrameResources::alphaTestOffset

layout(location = 0) out vec4 outPosition;
layout(location = 1) out vec4 outNormal;
layout(location = 2) out vec4 outAlbedoDepth;

void main()
{
  // At the pixel centre of a multisampled frame (uv extended linearly over the fraction of a pixel).
  if (isPerforated(uv + dFdx(uv) * alphaTestOffset.x + dFdy(uv) * alphaTestOffset.y))
  {
    discard;
  }
  // Surfaces are two-sided: the normal stored is the one facing the camera.
  vec3 normal = normalize(nWs);
  if (!gl_FrontFacing)
  {
    normal = -normal;
  }
  outPosition = vec4(pWs, 1.0);
  outNormal = vec4(normal, objectReceivesShadows != 0 ? 1.0 : 0.0);
  outAlbedoDepth = vec4(objectAlbedo, viewDepth);
}
