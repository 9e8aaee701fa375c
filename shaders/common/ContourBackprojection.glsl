// Contour-based back-projection (Guennebaud et al. 2007; Yang et al. 2009 §4): marching squares on the dual
// grid, back-projection onto the light plane, radial integration over a square light around its centre.
// Conventions and the integration identity: src/techniques/backprojection/ContourBackprojection.h, the
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
// together; measured: a flattened or nested cell loop stops at ~65k cells). The per-cell helpers below
// therefore use no loops, so a kernel costs about one iteration per dual cell. (Processing 4 x 4 cells per
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

// Area of [-h, h]^2 clipped by the half-planes dot(planes[k].xy, x) <= planes[k].z (Sutherland-Hodgman).
float clippedSquareArea(float halfSize, vec3 planes[3])
{
  vec2 polygon[8];
  polygon[0] = vec2(-halfSize, -halfSize);
  polygon[1] = vec2(halfSize, -halfSize);
  polygon[2] = vec2(halfSize, halfSize);
  polygon[3] = vec2(-halfSize, halfSize);
  int count = 4;
  for (int k = 0; k < 3; ++k)
  {
    vec2 clipped[8];
    int clippedCount = 0;
    for (int i = 0; i < 7; ++i)
    {
      if (i >= count)
      {
        break;
      }
      vec2 current = polygon[i];
      vec2 following = polygon[(i + 1) % count];
      float currentSide = dot(planes[k].xy, current) - planes[k].z;
      float followingSide = dot(planes[k].xy, following) - planes[k].z;
      if (currentSide <= 0.0)
      {
        clipped[clippedCount++] = current;
      }
      if ((currentSide <= 0.0) != (followingSide <= 0.0))
      {
        clipped[clippedCount++] = current + (following - current) * (currentSide / (currentSide - followingSide));
      }
    }
    polygon = clipped;
    count = clippedCount;
  }
  float twiceArea = 0.0;
  for (int i = 0; i < 7; ++i)
  {
    if (i >= count)
    {
      break;
    }
    twiceArea += cross2(polygon[i], polygon[(i + 1) % count]);
  }
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
  vec2 first = sweep > 0.0 ? a : b;
  vec2 second = sweep > 0.0 ? b : a;
  vec2 direction = second - first;
  vec2 awayFromO = vec2(direction.y, -direction.x);
  vec3 planes[3] = vec3[3](vec3(first.y, -first.x, 0.0), vec3(-second.y, second.x, 0.0),
    vec3(-awayFromO, -dot(awayFromO, first)));
  float area = clippedSquareArea(halfSize, planes);
  return cross2(b - a, -a) < 0.0 ? area : -area;
}
