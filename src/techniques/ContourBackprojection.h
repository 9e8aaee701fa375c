// The core of contour-based soft shadow mapping (Guennebaud et al. 2007, "GBP07"; the visibility step of
// Yang et al. 2009), in double precision: the CPU mirror of shaders/common/ContourBackprojection.glsl.
//
// For a receiver point p, each shadow-map sample is an occluder when it is nearer the light than p. The
// occluders' contour is reconstructed by marching squares on the dual grid (cells joining four sample
// centres, edges through the midpoints of the cell sides whose corners differ, each endpoint at the depth of
// its occluding corner), each contour edge is back-projected from p onto the light plane, and the occluded
// part of the light is integrated radially around the light centre O (as penumbra wedges, Assarsson and
// Akenine-Möller 2003): along a ray from O the occluder status toggles at each edge, so
//   occluded area = f(O) A + sum over edges of s_e |L ∩ (the part of the edge's angular sector beyond it)|,
// with s_e = +1 where crossing the edge outwards enters the occluder and f(O) the status of the light centre
// seen from p, which is p's own position in the map, read from the same reconstruction. Edges outside the
// light contribute nothing, so contours need not close outside the kernel.
//
// Conventions: texel (i, j) spans [i, i+1) x [j, j+1); sample (i, j) sits at (i + 0.5, j + 0.5). Dual cell
// (i, j) has the corners samples (i, j), (i+1, j), (i+1, j+1), (i, j+1), counter-clockwise from the lower
// left. Light-plane coordinates are light view x, y (the square light's edges are along them), origin at the
// light centre.
#pragma once

#include <glm/glm.hpp>

#include <array>

namespace sl
{

// A contour edge in shadow-map texel coordinates, oriented with the occluder on its left, and the depths
// (along the light axis) of its endpoints.
struct ContourEdge
{
  glm::dvec2 a{ 0.0 };
  glm::dvec2 b{ 0.0 };
  double depthA = 0.0;
  double depthB = 0.0;
};

// Marching squares on one dual cell: corners counter-clockwise from the lower left (occluding?, depth).
// Writes 0, 1 or 2 edges (saddles keep the occluding corners apart) and returns their number. `cellOrigin`
// is the position of the lower-left corner's sample (i + 0.5, j + 0.5).
int marchingSquaresEdges(const std::array<bool, 4>& occluding, const std::array<double, 4>& depths,
  const glm::dvec2& cellOrigin, std::array<ContourEdge, 2>& edges);

// Whether `position` (texel coordinates, inside the cell) lies in the reconstructed occluder region: the
// lower-left corner's status, flipped at each of the cell's edges crossed on the way from that corner.
bool insideReconstructedOccluder(const std::array<bool, 4>& occluding, const glm::dvec2& cellOrigin,
  const glm::dvec2& position);

// Back-projection of a point at `depth` seen at tangent coordinates `tangent` (x / depth, y / depth) from the
// receiver at light-view position (receiverXy, receiverDepth) onto the light plane (depth 0).
glm::dvec2 backProject(const glm::dvec2& tangent, double depth, const glm::dvec2& receiverXy, double receiverDepth);

// Signed area s_e |L ∩ beyond(a, b)| of a back-projected edge a -> b (occluder on its left) for the square
// light [-h, h]^2 around O = (0, 0).
double radialEdgeArea(const glm::dvec2& a, const glm::dvec2& b, double halfSize);

// |L ∩ {x in the sector from `first` counter-clockwise to `second`, beyond the line first-second}| for the
// square light L = [-h, h]^2 around O, cross(first, second) > 0: the square ∩ sector polygon (at most five
// vertices, a fixed list) clipped by the one line, with no loops and no indexed arrays, so that the GLSL twin
// costs no loop iterations (llvmpipe caps them per invocation) and no per-lane scatters.
double sectorBeyondEdgeArea(const glm::dvec2& first, const glm::dvec2& second, double halfSize);

// Area of the convex polygon [-h, h]^2 ∩ {x: dot(n_k, x) <= c_k for k < planes} (Sutherland-Hodgman; the
// tests' closed form for sectorBeyondEdgeArea and radialEdgeArea).
double clippedSquareArea(double halfSize, const std::array<glm::dvec3, 3>& planes, int planeCount);

} // namespace sl
