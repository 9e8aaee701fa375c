// The point whose crossings shadow volumes (and dcs's light samples) are counted for: the visible point moved
// receiver_offset toward the camera along its pixel's camera ray N + s R, so its own caster's near cap lies behind
// it (src/techniques/vtkSLShadowVolumePass.h says why).
uniform float receiverOffsetS;
uniform float receiverOffsetPerS;

// The ray parameter of the counted point, from the receiver's `sReceiver`.
float countedPointS(float sReceiver)
{
  return sReceiver - (receiverOffsetS + receiverOffsetPerS * sReceiver);
}

// The counted point of the visible point `pWs` seen through this fragment's pixel (a shader that calls it includes
// common/CameraRay.glsl first): the wedge and STSV passes evaluate their rules there.
vec3 countedPoint(vec3 pWs)
{
  vec3 nearPoint = cameraNearPoint(gl_FragCoord.xy);
  vec3 ray = cameraRayDirection(gl_FragCoord.xy);
  float sReceiver = dot(pWs - nearPoint, ray) / dot(ray, ray);
  return nearPoint + countedPointS(sReceiver) * ray;
}
