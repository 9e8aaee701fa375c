// Polygon-id shadow maps (Hourcade & Nicolas 1985, survey §5): the id of the triangle each pixel sees from the camera,
// numbered as the light's map numbers them (MeshDrawer's meshTriangleBase + gl_PrimitiveID + 1; 0: background). Drawn
// with the G-buffer's vertex shader, matrices, depth test and alpha test, so it keeps the G-buffer's surface.
#include "common/AlphaMask.glsl"

in vec3 pWs;
in vec3 nWs;
in vec2 uv;
in float viewDepth;

uniform int meshTriangleBase;
uniform vec2 alphaTestOffset; // pixels: FrameResources::alphaTestOffset, as the G-buffer's

layout(location = 0) out uint outPolygonId;

void main()
{
  if (isPerforated(uv + dFdx(uv) * alphaTestOffset.x + dFdy(uv) * alphaTestOffset.y))
  {
    discard;
  }
  outPolygonId = uint(meshTriangleBase + gl_PrimitiveID + 1);
}
