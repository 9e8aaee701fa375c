// Technique penumbra-wedge (AAM03 as Forest et al. 2009 §3.1 uses it): for a pixel inside a centre-silhouette
// wedge's screen polygon, the wedge's signed share of the light, added (blending one, one) to the pixel's occlusion.
// The rule of src/techniques/penumbrawedge/PenumbraWedgeGeometry.h, in float, relative to v0: the far region F_e(p)
// = the light's square clipped by
//   -sign(g(c)) g(s) >= 0                   (beyond the projection of e from p: g(x) = orient(v0, v1, p, x)),
//    sign(g(c)) orient(v0, v1, c, s) >= 0,
//   and to one half of the double sector between orient(p, c, s, v0) and orient(p, c, s, v1) (both halves tried),
// each linear in s = c + a right + b up; the count changes there by -sign(g(c)) M_e(p), and AAM03 adds its sign times
// |F_e(p)| / |L| to the occlusion.
#include "common/CameraRay.glsl"
#include "common/GBufferInputs.glsl"
#include "shadowvolume/ReceiverOffset.glsl"
#include "dcs/DcsWedgeCommon.glsl"

uniform float lightHalfSize;

layout(location = 0) out float outOcclusionDelta;
layout(location = 1) out float outWedgesCovering;

// A convex polygon clipped from the square by four lines: at most 4 + 4 corners.
const int MAX_CORNERS = 8;

// Sutherland-Hodgman: the part of polygon[0 .. count) where dot(f.xy, x) + f.z >= 0; returns the new count.
int clipPolygon(inout vec2 polygon[MAX_CORNERS], int count, vec3 f)
{
  vec2 clipped[MAX_CORNERS];
  int kept = 0;
  for (int i = 0; i < count; ++i)
  {
    vec2 a = polygon[i];
    vec2 b = polygon[(i + 1) % count];
    float fa = dot(f.xy, a) + f.z;
    float fb = dot(f.xy, b) + f.z;
    if (fa >= 0.0 && kept < MAX_CORNERS)
    {
      clipped[kept++] = a;
    }
    if ((fa >= 0.0) != (fb >= 0.0) && kept < MAX_CORNERS)
    {
      clipped[kept++] = a + (fa / (fa - fb)) * (b - a);
    }
  }
  polygon = clipped;
  return kept;
}

float polygonArea(vec2 polygon[MAX_CORNERS], int count)
{
  float twice = 0.0;
  for (int i = 0; i < count; ++i)
  {
    vec2 a = polygon[i];
    vec2 b = polygon[(i + 1) % count];
    twice += a.x * b.y - a.y * b.x;
  }
  return count >= 3 ? 0.5 * abs(twice) : 0.0;
}

void main()
{
  outOcclusionDelta = 0.0;
  outWedgesCovering = 0.0;
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  Surface surface = readSurface(pixel);
  if (!surface.covered)
  {
    return;
  }
  vec3 pWs = countedPoint(surface.pWs);

  vec3 v0 = wedgeRecordVec4(wedgeIndex, WEDGE_RECORD_V0).xyz;
  int triangles = int(wedgeRecordVec4(wedgeIndex, WEDGE_RECORD_V0).w);
  vec3 v1 = wedgeRecordVec4(wedgeIndex, WEDGE_RECORD_V1).xyz;
  if (!wedgeContains(pWs, v0, v1))
  {
    return;
  }
  outWedgesCovering = 1.0;

  vec3 p = pWs - v0;
  vec3 edge = v1 - v0;
  vec3 c = dcsLightCenter - v0;
  vec3 planeNormal = cross(edge, p);
  int multiplicity = 0;
  for (int k = 0; k < triangles; ++k)
  {
    multiplicity += int(sign(dot(wedgeRecordVec4(wedgeIndex, WEDGE_RECORD_OPPOSITE + k).xyz - v0, planeNormal)));
  }
  float gCentre = dot(c, planeNormal);
  if (multiplicity == 0 || gCentre == 0.0)
  {
    return;
  }
  float side = sign(gCentre);
  vec2 gSlope = vec2(dot(dcsLightRight, planeNormal), dot(dcsLightUp, planeNormal));
  vec3 centreNormal = cross(edge, c);
  vec2 centreSlope = vec2(dot(dcsLightRight, centreNormal), dot(dcsLightUp, centreNormal));
  vec3 toCentre = c - p;
  vec3 normal0 = cross(-p, toCentre);
  vec3 normal1 = cross(edge - p, toCentre);
  vec2 slope0 = vec2(dot(dcsLightRight, normal0), dot(dcsLightUp, normal0));
  vec2 slope1 = vec2(dot(dcsLightRight, normal1), dot(dcsLightUp, normal1));

  float area = 0.0;
  for (int halfSector = 0; halfSector < 2; ++halfSector)
  {
    float sectorSide = halfSector == 0 ? 1.0 : -1.0;
    vec2 region[MAX_CORNERS];
    region[0] = vec2(-lightHalfSize, -lightHalfSize);
    region[1] = vec2(lightHalfSize, -lightHalfSize);
    region[2] = vec2(lightHalfSize, lightHalfSize);
    region[3] = vec2(-lightHalfSize, lightHalfSize);
    int corners = 4;
    corners = clipPolygon(region, corners, vec3(-side * gSlope, -side * gCentre));
    corners = clipPolygon(region, corners, vec3(side * centreSlope, 0.0));
    corners = clipPolygon(region, corners, vec3(sectorSide * slope0, 0.0));
    corners = clipPolygon(region, corners, vec3(-sectorSide * slope1, 0.0));
    area += polygonArea(region, corners);
  }
  int change = -int(side) * multiplicity;
  outOcclusionDelta = float(sign(change)) * min(1.0, area / (4.0 * lightHalfSize * lightHalfSize));
}
