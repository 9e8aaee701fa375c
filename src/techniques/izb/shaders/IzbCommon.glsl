// The irregular z-buffer's light-space grid and per-sample test in float: the GPU copy of izb/IzbTwin.cpp
// (IzbGrid::place, placementErrorTexels, izbSampleTest), which the tests compare it with pixel by pixel.
// Needs IZB_FLAG_* and IZB_COVERAGE_MARGIN_INVERSE from the C++ preamble (IzbTechnique.cpp).
uniform int izbDirectional;        // 1: one orthographic face; 0: six cube faces around izbLightPosition
uniform int izbGridSize;           // texels per side of a face
uniform vec3 izbLightPosition;
uniform vec3 izbLightDirection;    // directional: the direction light travels
uniform vec3 izbAxisU;
uniform vec3 izbAxisV;
uniform vec4 izbWindow;           // directional: xy the window's corner (u, v), zw texels per world unit
uniform float izbRoundoff;         // float's unit roundoff, 2^-24 (izbFloatRoundoff)

struct IzbPlace
{
  uint texel;
  float errorTexels; // bound on the float placement's error
};

IzbPlace izbPlace(vec3 q)
{
  IzbPlace place;
  vec2 texels;
  uint face = 0u;
  if (izbDirectional == 1)
  {
    texels = (vec2(dot(q, izbAxisU), dot(q, izbAxisV)) - izbWindow.xy) * izbWindow.zw;
    place.errorTexels = 8.0 * izbRoundoff * (length(q) + length(izbWindow.xy)) * max(izbWindow.z, izbWindow.w);
  }
  else
  {
    vec3 d = q - izbLightPosition;
    vec3 m = abs(d);
    // The major axis, ties to the lower axis; the face's two other axes follow it cyclically.
    int major = (m.x >= m.y && m.x >= m.z) ? 0 : (m.y >= m.z ? 1 : 2);
    face = uint(2 * major + (d[major] < 0.0 ? 1 : 0));
    float extent = m[major];
    vec2 st = extent > 0.0 ? vec2(d[(major + 1) % 3], d[(major + 2) % 3]) / extent : vec2(0.0);
    texels = (st + 1.0) * (0.5 * float(izbGridSize));
    float error = 8.0 * izbRoundoff * (length(q) + length(izbLightPosition));
    place.errorTexels = extent > 0.0 ? 2.0 * error / extent * float(izbGridSize) : 1e30;
  }
  texels = clamp(texels, vec2(0.0), vec2(float(izbGridSize)));
  ivec2 texel = min(ivec2(texels), ivec2(izbGridSize - 1));
  place.texel = face * uint(izbGridSize * izbGridSize) + uint(texel.y * izbGridSize + texel.x);
  return place;
}

float izbDet(vec3 x, vec3 y, vec3 z)
{
  return dot(cross(x, y), z);
}

// The rounding bound of det(x, y, z) from operands with componentwise absolute errors ex, ey, ez (izbDetBound in
// IzbTwin.cpp; README.md, "Ambiguity").
vec3 izbAbsCross(vec3 x, vec3 y)
{
  return abs(x.yzx * y.zxy) + abs(x.zxy * y.yzx);
}

float izbDetBound(vec3 x, vec3 ex, vec3 y, vec3 ey, vec3 z, vec3 ez)
{
  return 2.0 * (dot(ex, abs(cross(y, z))) + dot(ey, abs(cross(z, x))) + dot(ez, abs(cross(x, y))) +
    5.0 * izbRoundoff * dot(izbAbsCross(x, y), abs(z)));
}

int izbCertainSign(float value, float bound)
{
  return value > bound ? 1 : (value < -bound ? -1 : 0);
}

// Johnson et al. 2005; Aila & Laine 2004: does triangle abc cover q in light space (the edge functions share
// a sign) and lie between q and the light (its plane separates them)? IZB_FLAG_SHADOW for the decision,
// IZB_FLAG_DEFINITE when no quantity it rests on lies within its rounding bound, IZB_FLAG_UNCERTAIN when one could
// flip it.
uint izbSampleTest(vec3 a, vec3 b, vec3 c, vec3 q, float offset, out int loneEdge, out int orientation)
{
  float u = izbRoundoff;
  vec3 eq = 2.0 * u * (abs(q) + offset);
  vec3 qa = a - q, qb = b - q, qc = c - q;
  vec3 ea = eq + u * abs(qa), eb = eq + u * abs(qb), ec = eq + u * abs(qc);
  bool directional = izbDirectional == 1;
  vec3 d = directional ? izbLightDirection : q - izbLightPosition;
  vec3 ed = directional ? 2.0 * u * abs(d) : eq + u * abs(izbLightPosition) + u * abs(d);
  float e0 = izbDet(qa, qb, d), e1 = izbDet(qb, qc, d), e2 = izbDet(qc, qa, d);
  int s0 = izbCertainSign(e0, izbDetBound(qa, ea, qb, eb, d, ed));
  int s1 = izbCertainSign(e1, izbDetBound(qb, eb, qc, ec, d, ed));
  int s2 = izbCertainSign(e2, izbDetBound(qc, ec, qa, ea, d, ed));
  vec3 edge1 = b - a, edge2 = c - a, aq = q - a;
  vec3 ee1 = u * abs(edge1), ee2 = u * abs(edge2);
  float fq = izbDet(edge1, edge2, aq);
  int planeAtQ = izbCertainSign(fq, izbDetBound(edge1, ee1, edge2, ee2, aq, eq + u * abs(aq)));
  vec3 al = directional ? d : izbLightPosition - a;
  float fl = izbDet(edge1, edge2, al);
  int planeAtLight = izbCertainSign(fl, izbDetBound(edge1, ee1, edge2, ee2, al,
    directional ? ed : u * abs(izbLightPosition) + u * abs(al)));

  bool inside = (e0 > 0.0 && e1 > 0.0 && e2 > 0.0) || (e0 < 0.0 && e1 < 0.0 && e2 < 0.0);
  bool between = directional ? ((fq > 0.0 && fl > 0.0) || (fq < 0.0 && fl < 0.0))
                             : ((fq > 0.0 && fl < 0.0) || (fq < 0.0 && fl > 0.0));
  int positive = (s0 > 0 ? 1 : 0) + (s1 > 0 ? 1 : 0) + (s2 > 0 ? 1 : 0);
  int negative = (s0 < 0 ? 1 : 0) + (s1 < 0 ? 1 : 0) + (s2 < 0 ? 1 : 0);
  int wanted = directional ? 1 : -1;
  bool betweenCertain = planeAtQ * planeAtLight == wanted;
  bool definite = (positive == 3 || negative == 3) && betweenCertain;
  bool possible = (positive == 0 || negative == 0) && planeAtQ * planeAtLight != -wanted;
  // Uncertain through one edge alone (IzbSampleTest::loneEdge): which edge, and the certain edges' sign.
  loneEdge = -1;
  orientation = 0;
  if (possible && !definite && betweenCertain && (positive == 2 || negative == 2))
  {
    loneEdge = s0 == 0 ? 0 : (s1 == 0 ? 1 : 2);
    orientation = positive == 2 ? 1 : -1;
  }
  uint flags = 0u;
  flags |= (inside && between) ? uint(IZB_FLAG_SHADOW) : 0u;
  flags |= definite ? uint(IZB_FLAG_DEFINITE) : 0u;
  flags |= (possible && !definite) ? uint(IZB_FLAG_UNCERTAIN) : 0u;
  return flags;
}

// The per-pixel state the passes share, two entries per pixel: [2 i] x flags, y triangles tested, z the sample's
// texel, w lone-edge events; [2 i + 1] x, y the XOR of the events' words (izbEdgeEvent), z, w unused.
layout(std430, binding = 3) buffer IzbPixels
{
  uvec4 izbPixels[];
};

// Whether a pixel's lone-edge events are one shared edge covered from both sides (izbEdgePairCovers).
bool izbEdgePairCovers(uint events, uint xorFirst, uint xorSecond)
{
  return events == 2u && xorFirst == (1u << IZB_EDGE_TOP_BIT_SHIFT) && xorSecond == 0u;
}
