// The wedges of technique dcs and penumbra-wedge as the wedge pass's fragment shader reads them (the CPU side:
// src/objectspace/DcsGeometry.h and WedgeDrawer.h): the edge and its triangles' third corners per wedge, the light's
// frame and outline, and wedgeContains, the test that the point lies in the wedge's region R_e.
// The records of the drawn polygons: per wedge, WEDGE_RECORD_VEC4 vec4 (WedgeDrawer.h WedgeRecord: (v0, number of
// triangles), (v1, 0), (w_k, 0) per triangle k); per STSV, STSV_RECORD_VEC4 (StsvDrawer.h StsvRecord).
layout(std430, binding = 0) readonly buffer DcsWedges
{
  vec4 wedgeData[];
};

// The vec4 at offset `field` (WEDGE_RECORD_<FIELD>) of wedge `wedge`'s record.
vec4 wedgeRecordVec4(int wedge, int field)
{
  return wedgeData[WEDGE_RECORD_VEC4 * wedge + field];
}

uniform vec3 dcsLightCenter;
uniform vec3 dcsLightRight;
uniform vec3 dcsLightUp;
uniform vec3 dcsLightNormal; // toward the scene
uniform vec3 dcsOutline[DCS_MAX_OUTLINE_CORNERS];
uniform int dcsOutlineCorners;

flat in int wedgeIndex;

// Cyrus-Beck clipping of e = v0 + t (v1 - v0) by one half-space (inside where the value <= 0); false once empty.
bool clipEdge(float atV0, float atV1, inout vec2 range)
{
  if (atV0 > 0.0 && atV1 > 0.0)
  {
    return false;
  }
  if (atV0 > 0.0 || atV1 > 0.0)
  {
    float t = atV0 / (atV0 - atV1);
    if (atV0 > 0.0)
    {
      range.x = max(range.x, t);
    }
    else
    {
      range.y = min(range.y, t);
    }
  }
  return range.x <= range.y;
}

// wedgeContains (DcsGeometry.h): e meets the pyramid with apex p over the light's outline.
bool wedgeContains(vec3 p, vec3 v0, vec3 v1)
{
  vec2 range = vec2(0.0, 1.0);
  vec3 corner0 = dcsOutline[0];
  if (!clipEdge(-dot(dcsLightNormal, v0 - corner0), -dot(dcsLightNormal, v1 - corner0), range))
  {
    return false;
  }
  vec3 outlineCentre = vec3(0.0);
  for (int i = 0; i < dcsOutlineCorners; ++i)
  {
    outlineCentre += dcsOutline[i];
  }
  outlineCentre /= float(dcsOutlineCorners);
  bool inside = true;
  for (int i = 0; i < dcsOutlineCorners; ++i)
  {
    vec3 normal = cross(dcsOutline[i] - p, dcsOutline[(i + 1) % dcsOutlineCorners] - p);
    normal = dot(normal, outlineCentre - p) > 0.0 ? -normal : normal;
    inside = inside && clipEdge(dot(normal, v0 - p), dot(normal, v1 - p), range);
  }
  float heightP = dot(dcsLightNormal, p - corner0);
  return inside && clipEdge(dot(dcsLightNormal, v0 - corner0) - heightP, dot(dcsLightNormal, v1 - corner0) - heightP, range);
}

