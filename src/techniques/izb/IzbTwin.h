// The irregular z-buffer's light-space math (Johnson, Mark & Burns 2004; Aila & Laine 2004): the grid the samples
// are listed in, the texels a caster triangle overlaps, and the per-sample coverage and depth test, in double. The
// pass (vtkSLIzbPass.h) takes the grid and each triangle's texels from here; izb/shaders/IzbCommon.glsl is the
// float copy of izbSampleTest, which the tests compare pixel by pixel against izbTwin on read-back buffers.
#pragma once

#include "frame/FrameResult.h"
#include "scene/Scene.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace sl
{

// float's unit roundoff: the GPU computes in float, and the ambiguity bands are written in units of it.
inline constexpr double izbFloatRoundoff = 1.0 / 16777216.0; // 2^-24
// How far (in texels) a sample's float light-space position may lie from its double one before the pass flags the
// sample (its texel may then miss a triangle's conservative cover); also the margin that cover is widened by.
inline constexpr int izbCoverageMarginInverse = 64; // margin = 1/64 texel

// The light-space grid: one face for a directional light (an orthographic window over the scene's bounds), six cube
// faces around a point or spot light (texel = (face, x, y), the face the direction's major axis picks).
struct IzbGrid
{
  bool directional = false;
  int size = 0;  // texels per side of a face
  int faces = 1; // 1 or 6
  glm::dvec3 lightPosition{ 0.0 };  // point / spot
  glm::dvec3 lightDirection{ 0.0 }; // directional: the direction light travels (unit)
  glm::dvec3 axisU{ 0.0 }, axisV{ 0.0 }; // directional: the window's axes, orthonormal to lightDirection
  glm::dvec2 windowMin{ 0.0 };      // directional: window corner (u, v)
  glm::dvec2 texelsPerUnit{ 0.0 };  // directional: texels per world unit along u, v

  static IzbGrid fit(const Light& light, const Bounds& sceneBounds, int size);
  std::size_t texelCount() const { return static_cast<std::size_t>(faces) * size * size; }

  // Face and continuous texel coordinates of a world point (cube: the major axis of point - light, ties to the lower
  // axis as the GLSL picks it).
  struct Place
  {
    int face = 0;
    glm::dvec2 texels{ 0.0 }; // in [0, size] (clamped to the face)
    int texel = 0;            // index: face * size^2 + y * size + x
  };
  Place place(const glm::dvec3& point) const;
  // A bound (texels) on how far the float placement of `point` (izb/IzbCommon.glsl) lies from place()'s; over half
  // the coverage margin the pixel is flagged ambiguous (its texel might miss a triangle's cover).
  double placementErrorTexels(const glm::dvec3& point) const;

  // Every texel whose square a caster triangle overlaps even partially, widened by 1/izbCoverageMarginInverse texel
  // (conservative rasterisation in double: the polygon the triangle projects to on each face, clipped to that face's
  // slightly widened pyramid for a cube, its bounding box of texels, minus the texels a polygon edge separates from
  // the polygon by more than the margin). Texels on the border of a face stand for everything beyond it.
  // `wanted(texel)` filters (the pass keeps only texels that list samples); appends to `texels`.
  template <class Wanted>
  void triangleTexels(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const Wanted& wanted,
    std::vector<std::uint32_t>& texels) const;

  // The polygon a triangle covers on `face`, in texel coordinates (empty: none; `wholeFace`: the triangle passes
  // within rounding of the light, every texel of the face is kept).
  std::vector<glm::dvec2> facePolygon(
    const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, int face, bool& wholeFace) const;
  // Whether the texel (x, y) of a face can meet `polygon` (counter-clockwise or clockwise, convex), with the margin.
  bool texelMeetsPolygon(int x, int y, const std::vector<glm::dvec2>& polygon) const;
};

// The light a sample is tested against: for a point (or spot) light its position, for a directional light the
// direction the light travels.
struct IzbLight
{
  bool directional = false;
  glm::dvec3 position{ 0.0 };
  glm::dvec3 direction{ 0.0 };
  static IzbLight from(const Light& light);
};

// One triangle against one sample point q (the receiver moved off its surface by the normal offset), Johnson et al.
// 2005; Aila & Laine 2004: is q inside the triangle in light space (the line from the light through q crosses
// it: the three edge functions e_ab = det(a - q, b - q, D), D = q - light or the light's direction, share a sign), and
// does the triangle's plane separate q from the light (the crossing lies between them)? Each quantity carries the
// bound of its float rounding on the GPU (README.md, "Ambiguity"); a decision any of them could flip within its bound
// is `uncertain`.
struct IzbSampleTest
{
  bool shadows = false;   // the decision from the quantities' signs
  bool definite = false;  // shadows, and no quantity it rests on lies within its rounding bound
  bool uncertain = false; // within rounding of an edge or of the plane: float may decide either way
  // Uncertain through one edge alone (the other two edges and the plane certain): that edge (0: ab, 1: bc, 2: ca)
  // and the sign the certain edges share; -1 / 0 otherwise. Its neighbour across that edge, listed the other way
  // round with the same orientation, then covers the other side exactly (README.md, "Shared edges").
  int loneEdge = -1;
  int orientation = 0;
};

// One lone-edge test of a sample, as the pass accumulates it per pixel (a count and the XOR of each word): the edge's
// lower vertex id with the top bit set when listed from the higher, and its higher id with the top bit set for a
// positive orientation. Vertex ids are global over the casters (izbCasterVertexIds).
inline constexpr int izbEdgeTopBitShift = 31;
inline constexpr std::uint32_t izbEdgeTopBit = 1u << izbEdgeTopBitShift;
struct IzbEdgeEvent
{
  std::uint32_t first = 0, second = 0;
};
IzbEdgeEvent izbEdgeEvent(std::uint32_t fromVertex, std::uint32_t toVertex, int orientation);
// Whether a pixel's lone-edge events are exactly two triangles sharing one edge in opposite directions with the
// same orientation: together they cover the sample whichever side of the edge it lies on (the pass then counts the
// sample shadowed and definite).
bool izbEdgePairCovers(std::uint32_t events, std::uint32_t xorFirst, std::uint32_t xorSecond);
// `offsetWorld`: the normal offset q was moved by (its rounding enters the bounds).
IzbSampleTest izbSampleTest(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& q,
  const IzbLight& light, double offsetWorld);

// The receiver point a pixel tests: pWs + offset nWs (the ray tracer's origin, test::RayCaster::pointVisibility).
inline glm::dvec3 izbSamplePoint(const glm::dvec3& pWs, const glm::dvec3& nWs, double offsetWorld)
{
  return pWs + offsetWorld * nWs;
}

// Below this, lightCanReach's decisions (facing, spot cone) are within float rounding (the project's threshold,
// ProbeSupport.h probeReachAmbiguity). The shared reach rule is every technique's, not the IZB's: the pass does not
// flag it (izb_ambiguous), the probe notes it and the tests leave such pixels out as GpuCpuTest does.
inline constexpr double izbReachAmbiguity = 1e-5;
double izbReachMargin(const Light& light, const glm::dvec3& pWs, const glm::dvec3& nWs);

// The caster triangles the pass tests, in scene order (objects that cast shadows), as three world points each.
std::vector<glm::dvec3> izbCasterTriangles(const Scene& scene);

// Per caster triangle (as izbCasterTriangles), its three vertices' ids: the object's index plus the vertex counts of
// the casters before it.
std::vector<std::uint32_t> izbCasterVertexIds(const Scene& scene);

// The whole frame replayed on the CPU from its read-back G-buffer (position, normal, coverage, receives_shadows):
// per pixel the grid texel, every caster triangle whose conservative cover holds that texel, tested in double.
struct IzbTwinPixel
{
  bool tested = false;      // covered, receives shadows, light can reach
  double visibility = 0.0;  // as the pass resolves it
  bool ambiguous = false;   // some test uncertain and none definite, or the placement within rounding
  bool reachAmbiguous = false; // izbReachMargin below izbReachAmbiguity
  int triangleTests = 0;    // triangles whose cover holds the sample's texel
  int texel = -1;
  double texelMargin = 0.0; // distance (texels) from the sample's position to its texel's border
};
struct IzbTwinFrame
{
  int width = 0, height = 0;
  std::vector<IzbTwinPixel> pixels;
  std::vector<int> listLength; // per texel: samples listed
};
// `offsetWorld`: the normal offset in world units (IzbSettings::offsetWorld).
IzbTwinFrame izbTwin(
  const FrameResult& frame, const Scene& scene, const Light& light, int gridSize, double offsetWorld);

// --- template definition -----------------------------------------------------------------------------------------

template <class Wanted>
void IzbGrid::triangleTexels(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const Wanted& wanted,
  std::vector<std::uint32_t>& texels) const
{
  const double margin = 1.0 / izbCoverageMarginInverse;
  for (int face = 0; face < faces; ++face)
  {
    bool wholeFace = false;
    const std::vector<glm::dvec2> polygon = facePolygon(a, b, c, face, wholeFace);
    if (polygon.empty() && !wholeFace)
    {
      continue;
    }
    int x0 = 0, y0 = 0, x1 = size - 1, y1 = size - 1;
    if (!wholeFace)
    {
      glm::dvec2 low(1e300), high(-1e300);
      for (const glm::dvec2& point : polygon)
      {
        low = glm::min(low, point);
        high = glm::max(high, point);
      }
      const auto clampTexel = [&](double value) {
        return static_cast<int>(glm::clamp(std::floor(value), 0.0, static_cast<double>(size - 1)));
      };
      x0 = clampTexel(low.x - margin);
      y0 = clampTexel(low.y - margin);
      x1 = clampTexel(high.x + margin);
      y1 = clampTexel(high.y + margin);
    }
    const std::uint32_t faceBase = static_cast<std::uint32_t>(face) * size * size;
    for (int y = y0; y <= y1; ++y)
    {
      for (int x = x0; x <= x1; ++x)
      {
        const std::uint32_t texel = faceBase + static_cast<std::uint32_t>(y * size + x);
        if (wanted(texel) && (wholeFace || texelMeetsPolygon(x, y, polygon)))
        {
          texels.push_back(texel);
        }
      }
    }
  }
}

} // namespace sl
