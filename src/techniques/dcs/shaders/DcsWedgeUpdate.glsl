// Technique dcs (Forest, Barthe & Paulin 2008 via Forest et al. 2009 §3.2): for a pixel inside a wedge's screen
// polygon, the wedge's edge e = (v0, v1) changes the depth complexity of every light sample s whose segment from the
// light's centre c crosses e's projection from the counted point p -- the rule of src/objectspace/DcsGeometry.h,
// in float, relative to v0:
//   count(s) += sign(g(s)) M_e(p)  when e crosses triangle (p, c, s),
//   g(x) = orient(v0, v1, p, x),  M_e(p) = sum over e's triangles of sign(orient(v0, v1, p, w_T)).
// Each orientation is linear in s = c + a right + b up, so it is evaluated per sample from its value at c and its two
// slopes.
#include "common/CameraRay.glsl"
#include "common/GBufferInputs.glsl"
#include "common/LightSampleSet.glsl"
#include "shadowvolume/ReceiverOffset.glsl"
#include "dcs/DcsSampleCounters.glsl"
#include "dcs/DcsWedgeCommon.glsl"

layout(r32ui, binding = 0) uniform coherent uimage2DArray sampleCounters;

void main()
{
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
  imageAtomicAdd(sampleCounters, ivec3(pixel, DCS_COVERING_LAYER), 1u);

  // Relative to v0 (float differences of nearby points, not of large coordinates).
  vec3 p = pWs - v0;
  vec3 edge = v1 - v0;
  vec3 c = dcsLightCenter - v0;
  vec3 planeNormal = cross(edge, p); // g(x) = dot(x - v0, planeNormal)
  int multiplicity = 0;
  for (int k = 0; k < triangles; ++k)
  {
    multiplicity += int(sign(dot(wedgeRecordVec4(wedgeIndex, WEDGE_RECORD_OPPOSITE + k).xyz - v0, planeNormal)));
  }
  if (multiplicity == 0)
  {
    return; // the edge's triangles lie on both sides of Pi(p, e): no count changes
  }
  float gCentre = dot(c, planeNormal);
  vec2 gSlope = vec2(dot(dcsLightRight, planeNormal), dot(dcsLightUp, planeNormal));
  vec3 centreNormal = cross(edge, c); // orient(v0, v1, c, s) = dot(s - v0, centreNormal), 0 at s = c
  vec2 centreSlope = vec2(dot(dcsLightRight, centreNormal), dot(dcsLightUp, centreNormal));
  vec3 toCentre = c - p;
  vec3 normal0 = cross(-p, toCentre);       // orient(p, c, s, v0) = dot(s - p, normal0), 0 at s = c
  vec3 normal1 = cross(edge - p, toCentre); // orient(p, c, s, v1)
  vec2 slope0 = vec2(dot(dcsLightRight, normal0), dot(dcsLightUp, normal0));
  vec2 slope1 = vec2(dot(dcsLightRight, normal1), dot(dcsLightUp, normal1));

  int checksum = 0;
  int weightedChecksum = 0;
  for (int word = 0; word < DCS_SAMPLE_COUNTER_LAYERS; ++word)
  {
    uint wordChange = 0u;
    for (int field = 0; field < DCS_COUNTERS_PER_LAYER; ++field)
    {
      int index = DCS_COUNTERS_PER_LAYER * word + field;
      vec2 ab = lightSampleOffset(lightSampleUnit(pixel, index));
      float g = gCentre + dot(gSlope, ab);
      bool crosses = g * gCentre < 0.0 && dot(centreSlope, ab) * gCentre > 0.0 && dot(slope0, ab) * dot(slope1, ab) < 0.0;
      int change = crosses ? int(sign(g)) * multiplicity : 0;
      wordChange += uint(change) << dcsCounterShift(index); // two's complement: a negative change borrows, as it should
      checksum += change;
      weightedChecksum += (index + 1) * change;
    }
    if (wordChange != 0u)
    {
      imageAtomicAdd(sampleCounters, ivec3(pixel, word), wordChange);
    }
  }
  if (checksum != 0)
  {
    imageAtomicAdd(sampleCounters, ivec3(pixel, DCS_CHECKSUM_LAYER), uint(checksum));
  }
  if (weightedChecksum != 0)
  {
    imageAtomicAdd(sampleCounters, ivec3(pixel, DCS_WEIGHTED_CHECKSUM_LAYER), uint(weightedChecksum));
  }
}
