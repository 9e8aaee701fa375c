// The point whose crossings shadow volumes (and dcs's light samples) are counted for: the visible point moved
// receiver_offset toward the camera along its pixel's camera ray N + s R, so its own caster's near cap lies behind
// it (src/techniques/shadowvolume/vtkSLShadowVolumePass.h says why).
uniform float receiverOffsetS;
uniform float receiverOffsetPerS;

// The ray parameter of the counted point, from the receiver's `sReceiver`.
float countedPointS(float sReceiver)
{
  return sReceiver - (receiverOffsetS + receiverOffsetPerS * sReceiver);
}
