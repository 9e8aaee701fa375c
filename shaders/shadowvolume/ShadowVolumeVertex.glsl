// Technique shadow-volume: the CPU-built volume triangles (src/objectspace/ShadowVolumeGeometry.h),
// homogeneous world positions (w = 1 on the casters, w = 0 at infinity) and each triangle's plane.
in vec4 volumePositionIn;
in vec4 volumePlaneIn;

uniform mat4 clipFromWorld;

flat out vec4 volumePlane;

void main()
{
  volumePlane = volumePlaneIn;
  gl_Position = clipFromWorld * volumePositionIn;
}
