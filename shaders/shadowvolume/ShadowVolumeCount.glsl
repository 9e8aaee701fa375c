// Technique shadow-volume: z-fail counting (Everitt & Kilgard 2002) of the volume triangles that lie at or
// behind the visible point, along the pixel's camera ray. Where the ray meets a triangle is computed from the
// triangle's plane (exact to float rounding) rather than taken from rasterised depth, and the point is the
// G-buffer's own position (vtkSLShadowVolumePass.h says why). A fragment in front of the point is discarded;
// the others update the two-sided stencil (back faces +1, front faces -1, wrapping) and add the same +1/-1
// exactly into an R32F target (additive blending), since the stencil has 8 bits.
// Volume triangles are wound counter-clockwise around their outward normal: a back face seen by the camera is
// where the ray, beyond the point, leaves a volume.
#include "common/CameraRay.glsl"
#include "common/GBufferInputs.glsl"
#include "shadowvolume/ReceiverOffset.glsl"

flat in vec4 volumePlane;
// The eye (w = 1); orthographic views have none (w = 0): there every crossing is decided by its parameter.
uniform vec4 eyePoint;

// x: the z-fail count; y: every face's +1/-1 (the second draw, VOLUME_TOTAL, no depth decision), for the self-check
// (vtkSLShadowVolumePass.h). The colour mask picks the component each draw writes.
layout(location = 0) out vec2 outVolumeCount;

void main()
{
  Surface surface = readSurface(ivec2(gl_FragCoord.xy));
  if (!surface.covered)
  {
    discard; // no receiver: the resolve writes 0 there
  }
#ifndef VOLUME_TOTAL
  vec3 nearPoint = cameraNearPoint(gl_FragCoord.xy);
  vec3 ray = cameraRayDirection(gl_FragCoord.xy);
  float sReceiver = dot(surface.pWs - nearPoint, ray) / dot(ray, ray);
  if (volumePlane.xyz != vec3(0.0)) // a far cap at infinity lies behind every receiver
  {
    // A ray parallel, to float rounding, to the plane of a side quad (at the quad's vanishing line, where it meets
    // the far cap at infinity) meets it at infinity, yet the float `along` is 0 or of either sign and the crossing
    // came out behind the eye: the exit from the volume was discarded (a whole image row of ground once read -1). A
    // rasterised fragment meets its triangle in front of the eye, so a crossing behind an eye that lies clearly off
    // the plane is such a one, at infinity: counted. An eye within rounding of the plane decides nothing (the
    // triangle is seen edge-on, its crossing anywhere along the ray): discarded as before.
    float along = dot(volumePlane.xyz, ray);
    float sVolume = along == 0.0 ? -1e30 : (volumePlane.w - dot(volumePlane.xyz, nearPoint)) / along;
    float eyeSide = volumePlane.w - dot(volumePlane.xyz, eyePoint.xyz);
    bool eyeOffPlane = abs(eyeSide) > 1e-5 * (abs(volumePlane.w) + abs(dot(volumePlane.xyz, eyePoint.xyz)));
    bool atInfinity = eyePoint.w > 0.5 && eyeOffPlane && (along == 0.0 || eyeSide / along < 0.0);
    if (!atInfinity && sVolume < countedPointS(sReceiver))
    {
      discard; // in front of the receiver: z-fail does not count it
    }
  }
#endif
  outVolumeCount = vec2(gl_FrontFacing ? -1.0 : 1.0);
}
