// Focusing on the GPU (survey §4.1): reduces the G-buffer's visible receivers (covered, receiving
// shadows, reachable by the light) to the few numbers the light-frustum fit needs, so only this result is
// read back. Mirrors sl::ImageReceivers (src/lightspace/LightView.cpp).
//
// FOCUS_PASS 0 (summary, point lights only): min world xyz, max world xyz, receiver count.
// FOCUS_PASS 1 (extent):  min/max light x, min/max light y, min/max linear depth over the receivers in
//                         front of the light, min cosine to the axis (perspective), receivers in front,
//                         all reachable receivers.
// Each invocation reduces a TILE x TILE block of pixels in registers, then merges its values into the
// result buffer with one atomic per slot: floats as order-preserving unsigned integers with
// atomicMin/atomicMax, counts with atomicAdd. No shared memory or barriers (which software rasterisers
// emulate slowly), and few enough atomics (one per slot per 64 pixels) that contention stays small on GPUs.
#define TILE 8
layout(local_size_x = 8, local_size_y = 8) in;

#include "common/GBufferInputs.glsl"
#include "common/LightModel.glsl"

uniform mat4 lightViewFromWorld;
uniform int lightIsPerspective;
uniform vec3 lightEyeWs;
uniform vec3 lightAxisWs;
// The receivers this view owns (a cascade's eye-depth slice, lightspace/Cascades.h): inside every plane.
#define MAX_OWNER_PLANES 4
uniform int ownerPlaneCount;
uniform vec4 ownerPlanes[MAX_OWNER_PLANES];

#if FOCUS_PASS == 0
#define SLOT_COUNT 7
// Kind of each slot: 0 = min, 1 = max, 2 = count.
const int slotKinds[SLOT_COUNT] = int[](0, 0, 0, 1, 1, 1, 2);
#else
#define SLOT_COUNT 9
const int slotKinds[SLOT_COUNT] = int[](0, 1, 0, 1, 0, 1, 0, 2, 2);
#endif

layout(std430, binding = 0) buffer FocusResult
{
  uint result[SLOT_COUNT];
};

float identity(int slot)
{
  return slotKinds[slot] == 0 ? 3.0e38 : (slotKinds[slot] == 1 ? -3.0e38 : 0.0);
}

uint orderedBits(float value)
{
  uint bits = floatBitsToUint(value);
  return (bits & 0x80000000u) != 0u ? ~bits : (bits | 0x80000000u);
}

void accumulate(ivec2 pixel, inout float values[SLOT_COUNT])
{
  Surface surface = readSurface(pixel);
  if (!surface.covered || !surface.receivesShadows || !lightCanReach(surface.pWs, surface.nWs))
  {
    return;
  }
  for (int plane = 0; plane < ownerPlaneCount; ++plane)
  {
    if (dot(ownerPlanes[plane], vec4(surface.pWs, 1.0)) < 0.0)
    {
      return;
    }
  }
#if FOCUS_PASS == 0
  for (int axis = 0; axis < 3; ++axis)
  {
    values[axis] = min(values[axis], surface.pWs[axis]);
    values[axis + 3] = max(values[axis + 3], surface.pWs[axis]);
  }
  values[6] += 1.0;
#else
  values[8] += 1.0;
  if (lightIsPerspective != 0)
  {
    values[6] = min(values[6], dot(lightAxisWs, normalize(surface.pWs - lightEyeWs)));
  }
  vec4 pLs = lightViewFromWorld * vec4(surface.pWs, 1.0);
  float depthLin = -pLs.z;
  if (depthLin > 0.0)
  {
    vec2 xy = lightIsPerspective != 0 ? pLs.xy / depthLin : pLs.xy;
    values[0] = min(values[0], xy.x);
    values[1] = max(values[1], xy.x);
    values[2] = min(values[2], xy.y);
    values[3] = max(values[3], xy.y);
    values[4] = min(values[4], depthLin);
    values[5] = max(values[5], depthLin);
    values[7] += 1.0;
  }
#endif
}

void main()
{
  float values[SLOT_COUNT];
  for (int slot = 0; slot < SLOT_COUNT; ++slot)
  {
    values[slot] = identity(slot);
  }
  ivec2 size = textureSize(gbufferPosition, 0);
  ivec2 tileOrigin = ivec2(gl_GlobalInvocationID.xy) * TILE;
  for (int y = 0; y < TILE; ++y)
  {
    for (int x = 0; x < TILE; ++x)
    {
      ivec2 pixel = tileOrigin + ivec2(x, y);
      if (all(lessThan(pixel, size)))
      {
        accumulate(pixel, values);
      }
    }
  }
  for (int slot = 0; slot < SLOT_COUNT; ++slot)
  {
    float value = values[slot];
    if (slotKinds[slot] == 2)
    {
      if (value > 0.0)
      {
        atomicAdd(result[slot], uint(value));
      }
    }
    else if (value != identity(slot))
    {
      if (slotKinds[slot] == 0)
      {
        atomicMin(result[slot], orderedBits(value));
      }
      else
      {
        atomicMax(result[slot], orderedBits(value));
      }
    }
  }
}
