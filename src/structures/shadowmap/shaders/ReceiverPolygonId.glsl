// Polygon-id shadow maps (Hourcade & Nicolas 1985, survey §5): the id of the triangle each pixel sees from the camera,
// numbered as the light's map numbers them (MeshDrawer's meshTriangleBase + gl_PrimitiveID + 1; 0: background). Drawn
// with the G-buffer's vertex shader, matrices, depth test and alpha test, so it keeps the G-buffer's surface. A pixel
// of an object that casts no shadow gets 0: Hourcade & Nicolas number the polygons of one map, and a receiver absent
// from it is compared by depth.
#include "common/AlphaMask.glsl"

in vec3 pWs;
in vec3 nWs;
in vec2 uv;
in float viewDepth;

uniform int meshTriangleBase;
// 0 for objects that cast no shadow: they are not in the light's map, so their pixels keep the depth test (id 0).
uniform int writePolygonIds;
uniform vec2 alphaTestOffset; // pixels: FrameResources::alphaTestOffset, as the G-buffer's

layout(location = 0) out uint outPolygonId;

void main()
{
  if (isPerforated(uv + dFdx(uv) * alphaTestOffset.x + dFdy(uv) * alphaTestOffset.y))
  {
    discard;
  }
  outPolygonId = writePolygonIds != 0 ? uint(meshTriangleBase + gl_PrimitiveID + 1) : 0u;
}
