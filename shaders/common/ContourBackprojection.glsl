// Contour-based back-projection (Guennebaud et al. 2007; Yang et al. 2009 §4): marching squares on the dual
// grid, back-projection onto the light plane, radial integration over a square light around its centre.
// Conventions and the integration identity: src/techniques/ContourBackprojection.h, the
// double-precision mirror of every function here.

// Corner k of a dual cell (counter-clockwise from the lower left) and the midpoint of side k (corners k, k+1).
const vec2 CELL_CORNERS[4] = vec2[4](vec2(0.0, 0.0), vec2(1.0, 0.0), vec2(1.0, 1.0), vec2(0.0, 1.0));
const vec2 SIDE_MIDPOINTS[4] = vec2[4](vec2(0.5, 0.0), vec2(1.0, 0.5), vec2(0.5, 1.0), vec2(0.0, 0.5));

struct ContourEdge
{
  vec2 a; // texel coordinates; the occluder on the left of a -> b
  vec2 b;
  float depthA;
  float depthB;
};

float cross2(vec2 u, vec2 v)
{
  return u.x * v.y - u.y * v.x;
}

// llvmpipe caps the loop iterations of one shader invocation at 65535 (gallivm's loop limiter, all loops
// together, and counted once for the SIMD lanes running together: a loop runs until its last active lane is
// done; measured: a flattened or nested cell loop stops at ~65k cells). The per-cell helpers below therefore
// use no loops, so a kernel costs about one iteration per dual cell. Issue 13: the back-projection's clipping
// had loops of constant bound (3 planes x up to 7 vertices), which cost ~25 counted iterations for every leaf
// cell where any lane integrated an edge, and cut yfgl09's traversal of 256-texel kernels short. (Processing 4 x 4 cells per
// iteration through macros lifted the cap but made the shader ~30x slower on llvmpipe.)

// The edge that leaves the occluding run at side `leave` (corner leave occluding, leave + 1 free), if any:
// it ends at the side where that run entered, found walking clockwise (at most three corners back).
bool edgeLeavingAt(int leave, bool occluding[4], float depths[4], vec2 cellOrigin, out ContourEdge edge)
{
  if (!(occluding[leave] && !occluding[(leave + 1) % 4]))
  {
    return false;
  }
  int enter = (leave + 3) % 4;
  if (occluding[enter])
  {
    enter = (enter + 3) % 4;
  }
  if (occluding[enter])
  {
    enter = (enter + 3) % 4;
  }
  edge.a = cellOrigin + SIDE_MIDPOINTS[leave];
  edge.b = cellOrigin + SIDE_MIDPOINTS[enter];
  edge.depthA = depths[leave];
  edge.depthB = depths[(enter + 1) % 4];
  return true;
}

// 0, 1 or 2 edges of a cell whose lower-left sample sits at `cellOrigin` (saddles keep occluders apart).
int marchingSquaresEdges(bool occluding[4], float depths[4], vec2 cellOrigin, out ContourEdge edges[2])
{
  int count = 0;
  ContourEdge edge;
  if (edgeLeavingAt(0, occluding, depths, cellOrigin, edge))
  {
    edges[count++] = edge;
  }
  if (edgeLeavingAt(1, occluding, depths, cellOrigin, edge))
  {
    edges[count++] = edge;
  }
  if (edgeLeavingAt(2, occluding, depths, cellOrigin, edge))
  {
    edges[count++] = edge;
  }
  if (edgeLeavingAt(3, occluding, depths, cellOrigin, edge))
  {
    edges[count++] = edge;
  }
  return count;
}

// Whether `position` lies in the reconstructed occluder: the lower-left corner's status, flipped at each of
// the cell's edges crossed on the way from that corner.
bool insideReconstructedOccluder(bool occluding[4], vec2 cellOrigin, vec2 position)
{
  float depths[4] = float[4](0.0, 0.0, 0.0, 0.0);
  ContourEdge edges[2];
  int count = marchingSquaresEdges(occluding, depths, cellOrigin, edges);
  bool inside = occluding[0];
  vec2 start = cellOrigin;
  for (int e = 0; e < 2; ++e)
  {
    if (e >= count)
    {
      break;
    }
    float d1 = cross2(edges[e].b - edges[e].a, start - edges[e].a);
    float d2 = cross2(edges[e].b - edges[e].a, position - edges[e].a);
    float d3 = cross2(position - start, edges[e].a - start);
    float d4 = cross2(position - start, edges[e].b - start);
    if (((d1 > 0.0) != (d2 > 0.0)) && ((d3 > 0.0) != (d4 > 0.0)))
    {
      inside = !inside;
    }
  }
  return inside;
}

// The point at `depth` seen at `tangent` from the receiver (receiverXy, receiverDepth), on the light plane.
vec2 backProject(vec2 tangent, float depth, vec2 receiverXy, float receiverDepth)
{
  return receiverXy + (tangent * depth - receiverXy) * (receiverDepth / (receiverDepth - depth));
}

// Where the ray from O through d (d != 0) leaves the square [-h, h]^2.
vec2 squareBoundaryHit(vec2 d, float halfSize)
{
  return d * (halfSize / max(abs(d.x), abs(d.y)));
}

// The square's corner reached first walking counter-clockwise along its boundary from the side that the ray
// through d meets (sides 0..3 = right, top, left, bottom), then `step` corners on.
vec2 nextSquareCorner(vec2 d, int step, float halfSize)
{
  int side = abs(d.x) >= abs(d.y) ? (d.x > 0.0 ? 0 : 2) : (d.y > 0.0 ? 1 : 3);
  int corner = (side + step) % 4;
  return halfSize * vec2(corner == 0 || corner == 3 ? 1.0 : -1.0, corner <= 1 ? 1.0 : -1.0);
}

// One edge u -> v of a convex polygon clipped to {x: dot(away, x) >= offset}: its shoelace term, and where the
// boundary leaves and re-enters the half-plane.
void clipEdgeBeyondLine(vec2 u, vec2 v, vec2 away, float offset, inout float twiceArea, inout vec2 exitPoint,
  inout vec2 entryPoint)
{
  float su = dot(away, u) - offset;
  float sv = dot(away, v) - offset;
  if (su >= 0.0 && sv >= 0.0)
  {
    twiceArea += cross2(u, v);
  }
  else if (su >= 0.0)
  {
    exitPoint = u + (v - u) * (su / (su - sv));
    twiceArea += cross2(u, exitPoint);
  }
  else if (sv >= 0.0)
  {
    entryPoint = u + (v - u) * (su / (su - sv));
    twiceArea += cross2(entryPoint, v);
  }
}

// |L ∩ {the sector from `first` counter-clockwise to `second`, beyond the line first-second}|, cross(first,
// second) > 0: the square ∩ sector polygon (O, the two ray hits, the corners between them) clipped by the one
// line. A fixed vertex list with no loops and no indexed arrays: llvmpipe counts every loop iteration of an
// invocation against its cap, for every SIMD lane together, and a Sutherland-Hodgman clip here cost ~25 of them
// per edge (it cut yfgl09's traversal of 256-texel kernels short, issue 13). Mirror: sl::sectorBeyondEdgeArea.
float sectorBeyondEdgeArea(vec2 first, vec2 second, float halfSize)
{
  vec2 hitFirst = squareBoundaryHit(first, halfSize);
  vec2 hitSecond = squareBoundaryHit(second, halfSize);
  vec2 corner1 = nextSquareCorner(first, 0, halfSize);
  vec2 corner2 = nextSquareCorner(first, 1, halfSize);
  if (!(cross2(first, corner1) >= 0.0 && cross2(corner1, second) >= 0.0))
  {
    corner1 = hitSecond; // absent corners become zero-length edges
    corner2 = hitSecond;
  }
  else if (!(cross2(first, corner2) >= 0.0 && cross2(corner2, second) >= 0.0))
  {
    corner2 = hitSecond;
  }
  vec2 direction = second - first;
  vec2 away = vec2(direction.y, -direction.x); // right of first -> second, where O is not
  float offset = dot(away, first);
  float twiceArea = 0.0;
  vec2 exitPoint = vec2(0.0);
  vec2 entryPoint = vec2(0.0);
  clipEdgeBeyondLine(vec2(0.0), hitFirst, away, offset, twiceArea, exitPoint, entryPoint);
  clipEdgeBeyondLine(hitFirst, corner1, away, offset, twiceArea, exitPoint, entryPoint);
  clipEdgeBeyondLine(corner1, corner2, away, offset, twiceArea, exitPoint, entryPoint);
  clipEdgeBeyondLine(corner2, hitSecond, away, offset, twiceArea, exitPoint, entryPoint);
  clipEdgeBeyondLine(hitSecond, vec2(0.0), away, offset, twiceArea, exitPoint, entryPoint);
  twiceArea += cross2(exitPoint, entryPoint); // O lies outside: the boundary crosses the line twice or never
  return 0.5 * abs(twiceArea);
}

// s_e |L ∩ (the edge's sector beyond it)| for a back-projected edge a -> b (occluder on its left).
float radialEdgeArea(vec2 a, vec2 b, float halfSize)
{
  float sweep = cross2(a, b);
  if (sweep == 0.0)
  {
    return 0.0;
  }
  float area = sectorBeyondEdgeArea(sweep > 0.0 ? a : b, sweep > 0.0 ? b : a, halfSize); // one inlined copy
  return cross2(b - a, -a) < 0.0 ? area : -area;
}
