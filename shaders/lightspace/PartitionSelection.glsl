// Views that partition the pixels (survey §4.3, lightspace/PartitionViews.h): which view's map each covered pixel
// reads, and the blend across a border. Writes (primary view, secondary view, primary's weight, 0) per pixel; uncovered
// pixels (0, 0, 1, 0). The CPU twin is sl::selectView (src/lightspace/PartitionViews.cpp), by partitionKind.
// Cascades (survey §4.3.1, sl::selectCascade in src/lightspace/Cascades.cpp): depth selection by the eye depth's
// slice, blended over the last cascadeBlend of it into the next; containment: the first map that holds the point
// marginTexels inside its edge and within its depth range (its own slice's map holds it by construction), blended over
// the outer cascadeBlend of its half-width into the next holder.
// Cube faces (survey §2, sl::selectCubeFace in src/lightspace/CubeFaces.cpp): the face of the dominant axis of
// p - light centre (ties to x, then y), unblended; the fourth channel holds the face (-1 uncovered or no map).
// Driver: vtkSLFocusPass (src/structures/shadowmap/vtkSLFocusPass.cxx).
layout(local_size_x = 8, local_size_y = 8) in;

#include "common/GBufferInputs.glsl"

#define MAX_CASCADES 8
layout(rgba32f, binding = 0) uniform writeonly image2D selection;
uniform int partitionKind; // PARTITION_CASCADES | PARTITION_CUBE_FACES (sl::PartitionKind, defined by the driver)
uniform int cascadeCount;
uniform int selectByContainment; // 0: depth, 1: containment
uniform float cascadeBlend;
uniform float marginTexels;
uniform int shadowMapSize;
uniform vec4 eyeDepthRow; // eye depth = dot(eyeDepthRow, (pWs, 1))
uniform float splitDepths[MAX_CASCADES + 1];
uniform mat4 cascadeClipFromWorld[MAX_CASCADES];
uniform mat4 cascadeViewFromWorld[MAX_CASCADES];
uniform float cascadeNearDepth[MAX_CASCADES];
uniform float cascadeFarDepth[MAX_CASCADES];
uniform vec3 lightCenterWs;
uniform int faceView[6]; // each face's view (+x, -x, +y, -y, +z, -z); -1: the face has no map

// Containment's test (sl::mapHolds); edgeFraction: distance to the inner window's edge over its half-width.
bool mapHolds(int cascade, vec3 pWs, out float edgeFraction)
{
  edgeFraction = 0.0;
  vec4 clip = cascadeClipFromWorld[cascade] * vec4(pWs, 1.0);
  float depthLin = -(cascadeViewFromWorld[cascade] * vec4(pWs, 1.0)).z;
  if (!(clip.w > 0.0) || depthLin < cascadeNearDepth[cascade] || depthLin > cascadeFarDepth[cascade])
  {
    return false;
  }
  float inner = 1.0 - 2.0 * marginTexels / float(shadowMapSize);
  float distance = inner - max(abs(clip.x / clip.w), abs(clip.y / clip.w));
  if (distance < 0.0)
  {
    return false;
  }
  edgeFraction = distance / inner;
  return true;
}

// Cascades: (primary, secondary, primary's weight, 0) at a covered pixel's point (sl::selectCascade).
vec4 selectCascade(vec3 pWs)
{
  float depth = dot(eyeDepthRow, vec4(pWs, 1.0));
  int slice = 0;
  while (slice < cascadeCount - 1 && depth >= splitDepths[slice + 1])
  {
    ++slice;
  }
  vec4 result = vec4(float(slice), float(slice), 1.0, 0.0);
  if (selectByContainment == 0)
  {
    float band = cascadeBlend * (splitDepths[slice + 1] - splitDepths[slice]);
    float toEnd = splitDepths[slice + 1] - depth;
    if (slice < cascadeCount - 1 && band > 0.0 && toEnd < band)
    {
      result = vec4(float(slice), float(slice + 1), max(0.0, toEnd / band), 0.0);
    }
  }
  else
  {
    // The pixel's own slice's map holds it by construction: only the finer maps are tested.
    for (int j = 0; j <= slice; ++j)
    {
      float edge;
      if (!mapHolds(j, pWs, edge) && j != slice)
      {
        continue;
      }
      result = vec4(float(j), float(j), 1.0, 0.0);
      if (cascadeBlend > 0.0 && edge < cascadeBlend)
      {
        for (int next = j + 1; next < cascadeCount; ++next)
        {
          float nextEdge;
          if (mapHolds(next, pWs, nextEdge) || next == slice)
          {
            result = vec4(float(j), float(next), edge / cascadeBlend, 0.0);
            break;
          }
        }
      }
      break;
    }
  }
  return result;
}

// sl::dominantCubeFace
int dominantCubeFace(vec3 direction)
{
  vec3 size = abs(direction);
  if (size.x >= size.y && size.x >= size.z)
  {
    return direction.x >= 0.0 ? 0 : 1;
  }
  if (size.y >= size.z)
  {
    return direction.y >= 0.0 ? 2 : 3;
  }
  return direction.z >= 0.0 ? 4 : 5;
}

vec4 selectCubeFace(vec3 pWs)
{
  int face = dominantCubeFace(pWs - lightCenterWs);
  int view = faceView[face];
  return view >= 0 ? vec4(float(view), float(view), 1.0, float(face)) : vec4(0.0, 0.0, 1.0, -1.0);
}

void main()
{
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(selection);
  if (pixel.x >= size.x || pixel.y >= size.y)
  {
    return;
  }
  Surface surface = readSurface(pixel);
  vec4 result = vec4(0.0, 0.0, 1.0, partitionKind == PARTITION_CUBE_FACES ? -1.0 : 0.0);
  if (surface.covered && partitionKind == PARTITION_CASCADES)
  {
    result = selectCascade(surface.pWs);
  }
  else if (surface.covered && partitionKind == PARTITION_CUBE_FACES)
  {
    result = selectCubeFace(surface.pWs);
  }
  imageStore(selection, pixel, result);
}
