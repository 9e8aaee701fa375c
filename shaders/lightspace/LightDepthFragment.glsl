// Writes linear depth along the light axis (R32F) besides the hardware depth. Linear depth keeps the
// comparison precision uniform over the range (Brabec et al., survey §5) and is exactly what the CPU
// reference compares against. CASTER_FACES selects first-depth (front faces, the default) or second-depth
// shadow mapping (Wang & Molnar, survey §5: only faces turned away from the light are stored, which acts
// as an adaptive bias of the caster's thickness; needs closed casters).
#include "common/AlphaMask.glsl"

// WARPED_DEPTH (a perspective warp, survey §4.2): clip z / w of the warped matrix mixes depth with the warp's w,
// so the depth buffer gets the unwarped orthographic window depth instead, linear along every light ray (which
// the warp keeps a texel column): the nearest caster wins as before and LightView::windowDepth stays exact.
in vec2 uv;
in float depthLin;
#if WARPED_DEPTH
uniform float lightNearDepth;
uniform float lightFarDepth;
#endif

#if DEPTH_PEEL
// The layer before (depth peeling, survey §5's midpoint and dual maps): a fragment at or before its depth is peeled
// off, so the depth test keeps the nearest surface strictly behind it. The same surface rasterizes to the same depth
// at the same texel, so it never counts as its own second layer.
uniform sampler2D firstLayerLinear;
#endif

layout(location = 0) out float outDepthLin;
#if POLYGON_ID
// Polygon-id shadow maps (Hourcade & Nicolas 1985, survey §5): the nearest triangle's id, unique in the scene
// (MeshDrawer's meshTriangleBase + gl_PrimitiveID + 1; 0 = no caster), 32 bits (the survey: 8 bits are insufficient).
uniform int meshTriangleBase;
layout(location = 1) out uint outPolygonId;
#endif

void main()
{
  if (isPerforated(uv))
  {
    discard;
  }
#if CASTER_FACES == CASTER_FACES_BACK
  if (gl_FrontFacing)
  {
    discard;
  }
#endif
#if DEPTH_PEEL
  if (depthLin <= texelFetch(firstLayerLinear, ivec2(gl_FragCoord.xy), 0).r)
  {
    discard;
  }
#endif
  outDepthLin = depthLin;
#if POLYGON_ID
  outPolygonId = uint(meshTriangleBase + gl_PrimitiveID + 1);
#endif
#if WARPED_DEPTH
  gl_FragDepth = (depthLin - lightNearDepth) / (lightFarDepth - lightNearDepth);
#endif
}
