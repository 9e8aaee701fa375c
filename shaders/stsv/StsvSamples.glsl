// Soft textured shadow volumes (Forest et al. 2009 §2, Alg. 1; the CPU twin is src/objectspace/StsvGeometry.h): for a
// pixel inside an STSV's screen polygon, whether its point p lies in the volume (the three outer planes and the front
// cap plane, §2.3), then for every light sample on this STSV's side of the triangle's plane the transmittance test of
// Eq. 1-5 on the homogeneous barycentrics. The hidden samples are OR-ed into the pixel's light-sample mask (the
// LS_buffer, §3.1; image atomics instead of the fixed-function logic op: technique penumbra-wedge), or with
// STSV_DCS_COUNTERS defined increment the depth-complexity counters of those samples (§3.2, STSV_DCS:
// technique dcs, whose range check they join).
//   Eq. 2-3: (a, b, e) = M (v0 - p), W = [1 0 -a/e; 0 1 -b/e; 0 0 1/e];  Eq. 1: h = W M (s - p)
//   occluded iff h.x >= 0, h.y >= 0, h.z >= h.x + h.y (the paper, §2.4), h.z > 1 (ShadowLab's added check: s and
//   p on opposite sides of the plane; parameter stsv_opposite_side_check), and the texel at (S h).xy / h.z is opaque
//   (Eq. 4-5; nearest, repeat, alpha < 0.5 is a hole: common/AlphaMask.glsl's rule).
#include "common/CameraRay.glsl"
#include "common/GBufferInputs.glsl"
#include "common/LightSampleSet.glsl"
#include "common/AlphaMask.glsl"
#include "shadowvolume/ReceiverOffset.glsl"
#include "dcs/DcsWedgeCommon.glsl"

#ifdef STSV_DCS_COUNTERS
#include "dcs/DcsSampleCounters.glsl"
layout(r32ui, binding = 0) uniform coherent uimage2DArray sampleCounters;
#else
// The hidden samples, 32 per layer (sample i: layer i / 32, bit i % 32).
layout(r32ui, binding = 1) uniform coherent uimage2DArray stsvMask;
#endif
uniform int stsvOppositeSideCheck;

layout(location = 0) out float outStsvCovering;
layout(location = 1) out float outStsvEmptyHits;

// One STSV's record, read from wedgeData (WedgeDrawer's records; the layout: StsvDrawer.h StsvRecord, whose offsets
// the preamble's STSV_RECORD_* are).
struct StsvRecord
{
  vec4 planes[STSV_RECORD_PLANE_COUNT]; // the three outer planes and the front cap plane, inside positive
  vec3 v0;
  float lightSide;      // the side of the triangle's plane whose light samples are this STSV's
  vec3 normal;
  float onPlaneDistance;
  mat3 triangleFromWorld; // M
  vec3 textureRow0;       // S
  vec3 textureRow1;
};

// The vec4 at offset `field` (STSV_RECORD_<FIELD>) of STSV `index`'s record.
vec4 stsvRecordVec4(int index, int field)
{
  return wedgeData[STSV_RECORD_VEC4 * index + field];
}

StsvRecord readStsvRecord(int index)
{
  StsvRecord record;
  for (int k = 0; k < STSV_RECORD_PLANE_COUNT; ++k)
  {
    record.planes[k] = stsvRecordVec4(index, STSV_RECORD_PLANES + k);
  }
  record.v0 = stsvRecordVec4(index, STSV_RECORD_V0).xyz;
  record.lightSide = stsvRecordVec4(index, STSV_RECORD_V0).w;
  record.normal = stsvRecordVec4(index, STSV_RECORD_NORMAL).xyz;
  record.onPlaneDistance = stsvRecordVec4(index, STSV_RECORD_NORMAL).w;
  for (int column = 0; column < 3; ++column)
  {
    record.triangleFromWorld[column] = stsvRecordVec4(index, STSV_RECORD_TRIANGLE_FROM_WORLD + column).xyz;
  }
  record.textureRow0 = stsvRecordVec4(index, STSV_RECORD_TEXTURE_ROW0).xyz;
  record.textureRow1 = stsvRecordVec4(index, STSV_RECORD_TEXTURE_ROW1).xyz;
  return record;
}

// §2.3: p inside the three outer planes and the front cap plane.
bool insideStsv(StsvRecord record, vec3 pWs)
{
  bool inside = true;
  for (int k = 0; k < STSV_RECORD_PLANE_COUNT; ++k)
  {
    inside = inside && dot(record.planes[k].xyz, pWs) + record.planes[k].w >= 0.0;
  }
  return inside;
}

// The transmittance test of Eq. 1-5 for the 32 light samples of mask word `word`: a bit per sample of this STSV's
// light piece that the textured triangle hides from p. `planeOffset` is (a, b, e) of Eq. 3.
uint hiddenSampleBits(StsvRecord record, ivec2 pixel, vec3 pWs, vec3 planeOffset, int word)
{
  float e = planeOffset.z;
  uint bits = 0u;
  for (int bit = 0; bit < 32 && 32 * word + bit < lightSampleCount; ++bit)
  {
    vec3 s = lightSamplePoint(pixel, 32 * word + bit);
    // Only this STSV's light piece: a sample on the other side is the other STSV's (Forest et al. 2009 §6).
    if (sign(dot(record.normal, s - record.v0)) != record.lightSide)
    {
      continue;
    }
    vec3 md = record.triangleFromWorld * (s - pWs);
    vec3 h = vec3(md.x - (planeOffset.x / e) * md.z, md.y - (planeOffset.y / e) * md.z, md.z / e); // Eq. 1
    bool inside = h.x >= 0.0 && h.y >= 0.0 && h.z >= h.x + h.y;
    bool opposite = h.z > 1.0;
    if (inside && (opposite || stsvOppositeSideCheck == 0))
    {
      vec2 uv = vec2(dot(record.textureRow0, h), dot(record.textureRow1, h)) / h.z; // Eq. 4-5
      if (texture(alphaTexture, uv).r >= 0.5)
      {
        bits |= 1u << uint(bit);
      }
    }
  }
  return bits;
}

void main()
{
  outStsvCovering = 0.0;
  outStsvEmptyHits = 0.0;
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  Surface surface = readSurface(pixel);
  if (!surface.covered)
  {
    return;
  }
  vec3 pWs = countedPoint(surface.pWs);
  StsvRecord record = readStsvRecord(wedgeIndex);
  if (!insideStsv(record, pWs))
  {
    return;
  }
  outStsvCovering = 1.0;

  vec3 planeOffset = record.triangleFromWorld * (record.v0 - pWs); // (a, b, e), Eq. 3
  bool anyHidden = false;
  int checksum = 0;
  int weightedChecksum = 0;
  if (abs(planeOffset.z) > record.onPlaneDistance)
  {
    for (int word = 0; word < (lightSampleCount + 31) / 32; ++word)
    {
      uint bits = hiddenSampleBits(record, pixel, pWs, planeOffset, word);
      if (bits != 0u)
      {
        anyHidden = true;
#ifdef STSV_DCS_COUNTERS
        // One more occluder crossed for each hidden sample: +1 in its counter.
        for (int bit = 0; bit < 32; ++bit)
        {
          if ((bits & (1u << uint(bit))) != 0u)
          {
            int index = 32 * word + bit;
            imageAtomicAdd(sampleCounters, ivec3(pixel, dcsCounterLayer(index)), 1u << dcsCounterShift(index));
            checksum += 1;
            weightedChecksum += index + 1;
          }
        }
#else
        imageAtomicOr(stsvMask, ivec3(pixel, word), bits);
#endif
      }
    }
  }
#ifdef STSV_DCS_COUNTERS
  if (checksum != 0)
  {
    imageAtomicAdd(sampleCounters, ivec3(pixel, DCS_CHECKSUM_LAYER), uint(checksum));
    imageAtomicAdd(sampleCounters, ivec3(pixel, DCS_WEIGHTED_CHECKSUM_LAYER), uint(weightedChecksum));
  }
#endif
  outStsvEmptyHits = anyHidden ? 0.0 : 1.0;
}
