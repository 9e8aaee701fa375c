// The camera ray through pixel position (x, y) is N + s R, both affine in the pixel position, s = 0 on the near
// plane (sl::CameraView; vtkSLTechniquePass sets these uniforms when a shader uses them).
uniform vec3 cameraNearOrigin;
uniform vec3 cameraNearStepX;
uniform vec3 cameraNearStepY;
uniform vec3 cameraRayOrigin;
uniform vec3 cameraRayStepX;
uniform vec3 cameraRayStepY;

vec3 cameraNearPoint(vec2 pixel)
{
  return cameraNearOrigin + pixel.x * cameraNearStepX + pixel.y * cameraNearStepY;
}

vec3 cameraRayDirection(vec2 pixel)
{
  return cameraRayOrigin + pixel.x * cameraRayStepX + pixel.y * cameraRayStepY;
}
