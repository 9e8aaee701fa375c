#include "objectspace/StsvGeometry.h"

#include "core/Error.h"
#include "scene/AlphaTexture.h"
#include "objectspace/DcsGeometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sl
{

StsvTriangle makeStsvTriangle(const glm::dvec3& v0, const glm::dvec3& v1, const glm::dvec3& v2, const glm::dvec2& t0,
  const glm::dvec2& t1, const glm::dvec2& t2)
{
  StsvTriangle triangle;
  triangle.vertices = { v0, v1, v2 };
  triangle.texCoords = { t0, t1, t2 };
  const glm::dvec3 edge1 = v1 - v0;
  const glm::dvec3 edge2 = v2 - v0;
  const glm::dvec3 areaNormal = glm::cross(edge1, edge2);
  const double twiceArea = glm::length(areaNormal);
  SL_CHECK_MSG(std::isfinite(twiceArea) && twiceArea > 0.0, "STSV of a degenerate or non-finite triangle");
  triangle.normal = areaNormal / twiceArea;
  // Eq. 2: M = [ v0v1 | v0v2 | -n ]^-1 (columns). M d = (d_u, d_v, d_h) with d = d_u e1 + d_v e2 - d_h n.
  triangle.triangleFromWorld = glm::inverse(glm::dmat3(edge1, edge2, -triangle.normal));
  // Eq. 4: S maps homogeneous barycentrics (x, y, z) (u = x/z weights t1, v = y/z weights t2) to homogeneous
  // texture coordinates (t0 z + (t1 - t0) x + (t2 - t0) y, z).
  triangle.textureFromBarycentric =
    glm::dmat3(glm::dvec3(t1 - t0, 0.0), glm::dvec3(t2 - t0, 0.0), glm::dvec3(t0, 1.0));
  return triangle;
}

std::vector<StsvTriangle> perforatedTriangles(const Scene& scene)
{
  std::vector<StsvTriangle> triangles;
  for (std::size_t objectIndex = 0; objectIndex < scene.objects.size(); ++objectIndex)
  {
    const SceneObject& object = scene.objects[objectIndex];
    const TriangleMesh& mesh = object.mesh;
    if (!object.castShadows || !object.hasAlphaTexture || mesh.uvs.empty())
    {
      continue;
    }
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
    {
      const std::uint32_t i0 = mesh.indices[3 * t];
      const std::uint32_t i1 = mesh.indices[3 * t + 1];
      const std::uint32_t i2 = mesh.indices[3 * t + 2];
      const glm::dvec3 v0(mesh.positions[i0]);
      const glm::dvec3 v1(mesh.positions[i1]);
      const glm::dvec3 v2(mesh.positions[i2]);
      if (!(glm::length(glm::cross(v1 - v0, v2 - v0)) > 0.0))
      {
        continue; // no interior: hides nothing
      }
      StsvTriangle triangle = makeStsvTriangle(
        v0, v1, v2, glm::dvec2(mesh.uvs[i0]), glm::dvec2(mesh.uvs[i1]), glm::dvec2(mesh.uvs[i2]));
      triangle.objectIndex = objectIndex;
      triangle.triangleIndex = t;
      triangles.push_back(triangle);
    }
  }
  return triangles;
}

double stsvOnPlaneDistance(const StsvTriangle& triangle)
{
  const auto& v = triangle.vertices;
  const double longestEdge =
    std::max({ glm::length(v[1] - v[0]), glm::length(v[2] - v[1]), glm::length(v[0] - v[2]) });
  return kStsvOnPlaneRelative * longestEdge;
}

StsvPointTransform stsvPointTransform(const StsvTriangle& triangle, const glm::dvec3& p, double onPlaneDistance)
{
  StsvPointTransform transform;
  // Eq. 3: (a, b, e) = M (v0 - p). v0 - p = a e1 + b e2 - e n, so e = n . (p - v0), the signed distance of p
  // (the text's "orthogonal distance from p to t", §2.4, with its sign), and (-a, -b) are the barycentrics of p's
  // foot point on the plane.
  transform.planeOffset = triangle.triangleFromWorld * (triangle.vertices[0] - p);
  const double e = transform.planeOffset.z;
  if (!(std::abs(e) > onPlaneDistance))
  {
    transform.onPlane = true; // p on t (or a non-finite p): t hides nothing from it, and e is never divided by
    return transform;
  }
  // W = [[1, 0, -a/e], [0, 1, -b/e], [0, 0, 1/e]] (rows); glm takes columns. The last entry is 1/e, not the text's
  // 1 (see the header; decided by StsvEq1.HomogeneousBarycentricsEqualRayTriangleAndDecideW).
  transform.projection = glm::dmat3(glm::dvec3(1.0, 0.0, 0.0), glm::dvec3(0.0, 1.0, 0.0),
    glm::dvec3(-transform.planeOffset.x / e, -transform.planeOffset.y / e, 1.0 / e));
  // J = W M (Forest et al. 2009 §2.4), once per p.
  transform.barycentricFromSample = transform.projection * triangle.triangleFromWorld;
  return transform;
}

StsvSampleEvaluation evaluateStsvSample(const StsvTriangle& triangle, const StsvPointTransform& transform,
  const ImageF& alpha, const glm::dvec3& p, const glm::dvec3& sample, StsvOcclusionTest test)
{
  StsvSampleEvaluation result;
  if (transform.onPlane)
  {
    return result;
  }
  // Eq. 1 without S: s*_h = J (s - p). z = 1/lambda, lambda the line parameter of the plane hit from p towards s.
  const glm::dvec3 sh = transform.barycentricFromSample * (sample - p);
  result.homogeneousBarycentric = sh;
  // The paper's test (§2.4, Appendix A's SUB.CC0 / LT.xyzz): u >= 0, v >= 0, u + v <= 1 in homogeneous form;
  // it implies z >= 0, i.e. lambda > 0, but not lambda < 1.
  result.insideTriangle = sh.x >= 0.0 && sh.y >= 0.0 && sh.z >= sh.x + sh.y;
  // ShadowLab's added check: lambda < 1 <=> z > 1, the sample beyond the plane seen from p.
  result.oppositeSides = sh.z > 1.0;
  const bool passes =
    result.insideTriangle && (test == StsvOcclusionTest::Paper || result.oppositeSides);
  if (!passes)
  {
    return result;
  }
  // Eq. 4 and 5: homogeneous texture coordinates, then the projection.
  const glm::dvec3 texHomogeneous = triangle.textureFromBarycentric * sh;
  result.texCoord = glm::dvec2(texHomogeneous.x, texHomogeneous.y) / texHomogeneous.z;
  result.hole = alphaHoleAt(alpha, result.texCoord);
  result.occluded = !result.hole;
  return result;
}

std::vector<bool> perforatedTriangleOcclusion(const StsvTriangle& triangle, const ImageF& alpha, const glm::dvec3& p,
  const std::vector<glm::dvec3>& samples, StsvOcclusionTest test)
{
  std::vector<bool> occluded(samples.size(), false);
  const StsvPointTransform transform = stsvPointTransform(triangle, p, stsvOnPlaneDistance(triangle));
  if (transform.onPlane)
  {
    return occluded;
  }
  for (std::size_t i = 0; i < samples.size(); ++i)
  {
    occluded[i] = evaluateStsvSample(triangle, transform, alpha, p, samples[i], test).occluded;
  }
  return occluded;
}

int triangleSideOf(const StsvTriangle& triangle, const glm::dvec3& point)
{
  const double height = glm::dot(triangle.normal, point - triangle.vertices[0]);
  return (height > 0.0) - (height < 0.0);
}

namespace
{

StsvPlane planeThrough(const glm::dvec3& unitNormal, const glm::dvec3& point)
{
  return StsvPlane{ unitNormal, -glm::dot(unitNormal, point) };
}

// The corners of `outline` (a convex polygon) with side * height >= 0, height_k = n . (outline_k - v0): Sutherland-
// Hodgman against one plane. The cut points lie on the plane up to rounding.
std::vector<glm::dvec3> clipOutline(const std::vector<glm::dvec3>& outline, const std::vector<double>& heights, int side)
{
  std::vector<glm::dvec3> piece;
  const std::size_t count = outline.size();
  for (std::size_t k = 0; k < count; ++k)
  {
    const std::size_t next = (k + 1) % count;
    const double here = side * heights[k];
    const double there = side * heights[next];
    if (here >= 0.0)
    {
      piece.push_back(outline[k]);
    }
    if ((here > 0.0 && there < 0.0) || (here < 0.0 && there > 0.0))
    {
      piece.push_back(outline[k] + (here / (here - there)) * (outline[next] - outline[k]));
    }
  }
  return piece;
}

// The STSV of `triangle` for the light piece `piece` (corners, convex) on side `side`, centre `centre`.
// Step 1 (§2.2): the front cap t', the triangle t with its vertices moved towards the light piece's centre c to the
// closest one's distance (t itself where t' would not be conservative); returns the cap's normal, away from c.
glm::dvec3 buildFrontCap(Stsv& stsv, const StsvTriangle& triangle, const std::vector<glm::dvec3>& piece,
  const glm::dvec3& centre, int side)
{
  const auto& v = triangle.vertices;
  // The vertex closest to c stays, the others move towards c to its distance.
  std::array<double, 3> distance{};
  for (int i = 0; i < 3; ++i)
  {
    distance[static_cast<std::size_t>(i)] = glm::length(v[static_cast<std::size_t>(i)] - centre);
  }
  const double closest = *std::min_element(distance.begin(), distance.end());
  std::array<glm::dvec3, 3> moved{};
  for (std::size_t i = 0; i < 3; ++i)
  {
    moved[i] = distance[i] == closest ? v[i] : centre + (v[i] - centre) * (closest / distance[i]);
  }
  // The cap's normal away from c. t' is conservative when the whole piece lies on c's side of its plane (header).
  glm::dvec3 capNormal = glm::cross(moved[1] - moved[0], moved[2] - moved[0]);
  bool capValid = closest > 0.0 && glm::length(capNormal) > 0.0;
  if (capValid)
  {
    capNormal = glm::normalize(capNormal);
    if (glm::dot(capNormal, centre - moved[0]) > 0.0)
    {
      capNormal = -capNormal;
    }
    capValid = glm::dot(capNormal, centre - moved[0]) < 0.0;
    for (const glm::dvec3& corner : piece)
    {
      capValid = capValid && glm::dot(capNormal, corner - moved[0]) <= 0.0;
    }
  }
  if (!capValid)
  {
    // t's plane has the piece on its near side (it was cut there), so t is a conservative front cap.
    stsv.frontCapIsTriangle = true;
    moved = v;
    capNormal = -double(side) * triangle.normal;
  }
  // Fig. 6's winding: (0, 1, 2) counter-clockwise seen from beyond the cap (away from the light), so the strip's
  // triangles all face outwards (StsvVolume.StripOfFigure6IsClosedAndFacesOutwards).
  std::array<int, 3> order{ 0, 1, 2 };
  if (glm::dot(glm::cross(moved[1] - moved[0], moved[2] - moved[0]), capNormal) < 0.0)
  {
    order = { 0, 2, 1 };
  }
  for (std::size_t i = 0; i < 3; ++i)
  {
    stsv.frontCapVertexOfTriangle[i] = order[i];
    stsv.frontCap[i] = moved[static_cast<std::size_t>(order[i])];
  }
  stsv.frontCapPlane = planeThrough(capNormal, stsv.frontCap[0]);

  return capNormal;
}

// Step 2 (§2.2): the outer plane of each cap edge, tangent to the light piece.
void buildOuterPlanes(Stsv& stsv, const std::vector<glm::dvec3>& piece)
{
  const auto& cap = stsv.frontCap;
  // The outer plane of each cap edge (i, i + 1). In the section across the edge, the piece's
  // corners are directions from the edge; the outer tangent goes through the corner whose direction is closest to
  // the cap's own direction (towards the opposite vertex o): every other corner is then on one side, o on the other.
  for (std::size_t i = 0; i < 3; ++i)
  {
    const glm::dvec3& a = cap[i];
    const glm::dvec3 edge = cap[(i + 1) % 3] - a;
    const glm::dvec3 opposite = cap[(i + 2) % 3] - a;
    const glm::dvec3 along = glm::normalize(edge);
    const glm::dvec3 towardOpposite = opposite - glm::dot(opposite, along) * along;
    const double towardOppositeLength = glm::length(towardOpposite);
    int best = -1;
    double bestCosine = -std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < piece.size(); ++k)
    {
      const glm::dvec3 toCorner = piece[k] - a;
      const glm::dvec3 across = toCorner - glm::dot(toCorner, along) * along;
      const double acrossLength = glm::length(across);
      if (!(acrossLength > 0.0))
      {
        continue; // a corner on the edge's line lies in every plane through the edge
      }
      const double cosine = glm::dot(across, towardOpposite) / (acrossLength * towardOppositeLength);
      if (cosine > bestCosine)
      {
        bestCosine = cosine;
        best = static_cast<int>(k);
      }
    }
    // Only a light collapsed onto the edge's line has no corner off it, and then the light would lie in the cap's
    // plane (t' is at one distance from c) or in t's (no STSV is built): excluded above.
    SL_CHECK_MSG(best >= 0, "STSV outer plane: every light corner on the edge's line");
    glm::dvec3 normal = glm::normalize(glm::cross(edge, piece[static_cast<std::size_t>(best)] - a));
    // Inside positive: o on the positive side, the piece on the negative one. Either alone decides except in the
    // degenerate cases (o in the plane when the tangent is the cap's plane itself; the piece in it when flat), so
    // their sum of evidence decides.
    double cornerSum = 0.0;
    for (const glm::dvec3& corner : piece)
    {
      cornerSum += glm::dot(normal, corner - a);
    }
    if (glm::dot(normal, opposite) - cornerSum < 0.0)
    {
      normal = -normal;
    }
    stsv.outerPlanes[i] = planeThrough(normal, a);
    stsv.outerPlaneCorner[i] = best;
  }

}

// Step 3 (§2.2): each vertex's extrusion direction, along the intersection of its two outer planes.
void buildExtrusions(Stsv& stsv, const glm::dvec3& capNormal)
{
  // Vertex i is shared by the planes of edges (i - 1, i) and (i, i + 1); its extrusion runs along
  // their intersection, away from the cone's apex: where the third plane's distance grows. m_prev x m_next . m_opp
  // = det(m_0, m_1, m_2) for every i, so one sign serves all three; when the planes share a direction (a prism, det
  // = 0) the cap's normal orients each.
  const glm::dvec3& m0 = stsv.outerPlanes[0].normal;
  const glm::dvec3& m1 = stsv.outerPlanes[1].normal;
  const glm::dvec3& m2 = stsv.outerPlanes[2].normal;
  const double determinant = glm::dot(glm::cross(m0, m1), m2);
  for (std::size_t i = 0; i < 3; ++i)
  {
    const glm::dvec3 direction = glm::cross(stsv.outerPlanes[(i + 2) % 3].normal, stsv.outerPlanes[i].normal);
    const double length = glm::length(direction);
    if (!(length > 1e-12))
    {
      // Two adjacent outer planes coincide: both are the cap's plane, which happens when t is the cap and the light
      // piece touches t's plane inside t's angle at that vertex (t cuts through the light: all three coincide when
      // the cut chord crosses t itself). The four planes then bound a region unbounded along the plane (all of the
      // far half-space in the last case), which they still test exactly; no finite closed volume holds it.
      stsv.extrusion[i] = capNormal;
      stsv.closedVolumeTruncated = true;
      continue;
    }
    double orientation = std::abs(determinant) > 1e-12 ? determinant : glm::dot(direction, capNormal);
    stsv.extrusion[i] = (orientation < 0.0 ? -1.0 : 1.0) * direction / length;
  }

}

// Step 4 (§2.2, §4.2): the back cap beyond the scene's box.
void buildBackCap(Stsv& stsv, const glm::dvec3& capNormal, const Bounds& sceneBounds)
{
  const auto& cap = stsv.frontCap;
  // The back cap at the level of the scene box along the cap's normal, just beyond the
  // box's farthest corner, so every scene point inside the outer planes and the front cap is inside the closed
  // volume. Extrusions that would have to run further than kStsvMaxExtrusion are cut and flagged.
  const glm::dvec3 boxMin = sceneBounds.empty() ? glm::dvec3(0.0) : sceneBounds.min;
  const glm::dvec3 boxMax = sceneBounds.empty() ? glm::dvec3(0.0) : sceneBounds.max;
  const double diagonal = glm::length(boxMax - boxMin);
  double farthestLevel = -std::numeric_limits<double>::infinity();
  for (int corner = 0; corner < 8; ++corner)
  {
    const glm::dvec3 boxCorner((corner & 1) ? boxMax.x : boxMin.x, (corner & 2) ? boxMax.y : boxMin.y,
      (corner & 4) ? boxMax.z : boxMin.z);
    farthestLevel = std::max(farthestLevel, stsv.frontCapPlane.distance(boxCorner));
  }
  const double margin = 1e-6 * diagonal + 1e-9 * std::max(1.0, glm::length(cap[0]));
  const glm::dvec3 boxCentre = 0.5 * (boxMin + boxMax);
  for (std::size_t i = 0; i < 3; ++i)
  {
    const double slope = glm::dot(capNormal, stsv.extrusion[i]);
    const double needed = std::max(farthestLevel - stsv.frontCapPlane.distance(cap[i]), 0.0) + margin;
    const double longest = kStsvMaxExtrusion * (diagonal + glm::length(cap[i] - boxCentre)) + margin;
    if (slope > 0.0 && needed <= slope * longest)
    {
      stsv.extrusionLength[i] = needed / slope;
    }
    else
    {
      stsv.extrusionLength[i] = longest;
      stsv.closedVolumeTruncated = true;
    }
    stsv.backCap[i] = cap[i] + stsv.extrusionLength[i] * stsv.extrusion[i];
  }
  glm::dvec3 backNormal = glm::cross(stsv.backCap[1] - stsv.backCap[0], stsv.backCap[2] - stsv.backCap[0]);
  if (glm::length(backNormal) > 0.0)
  {
    backNormal = glm::normalize(backNormal);
    const glm::dvec3 capCentroid = (cap[0] + cap[1] + cap[2]) / 3.0;
    if (glm::dot(backNormal, capCentroid - stsv.backCap[0]) < 0.0)
    {
      backNormal = -backNormal;
    }
  }
  else
  {
    backNormal = -capNormal;
    stsv.closedVolumeTruncated = true;
  }
  stsv.backCapPlane = planeThrough(backNormal, stsv.backCap[0]);
}

Stsv buildStsv(const StsvTriangle& triangle, const std::vector<glm::dvec3>& piece, const glm::dvec3& centre, int side,
  bool straddles, const Bounds& sceneBounds)
{
  Stsv stsv;
  stsv.lightSide = side;
  stsv.lightStraddlesPlane = straddles;
  stsv.lightPiece = piece;
  stsv.lightPieceCentre = centre;
  stsv.trianglePlane = planeThrough(-double(side) * triangle.normal, triangle.vertices[0]);
  const glm::dvec3 capNormal = buildFrontCap(stsv, triangle, piece, centre, side);
  buildOuterPlanes(stsv, piece);
  buildExtrusions(stsv, capNormal);
  buildBackCap(stsv, capNormal, sceneBounds);
  return stsv;
}

} // namespace

std::vector<Stsv> buildStsvs(const StsvTriangle& triangle, const Light& light, const Bounds& sceneBounds)
{
  const std::vector<glm::dvec3> outline = lightOutline(light);
  std::vector<double> heights;
  bool above = false;
  bool below = false;
  for (const glm::dvec3& corner : outline)
  {
    const double height = glm::dot(triangle.normal, corner - triangle.vertices[0]);
    heights.push_back(height);
    above = above || height > 0.0;
    below = below || height < 0.0;
  }
  std::vector<Stsv> volumes;
  if (above && below)
  {
    // Forest et al. 2009 §6: both faces of t are lit; one STSV per side, each for its own piece of the light, whose
    // centre is the piece's corner mean (inside it: the piece is convex).
    for (const int side : { 1, -1 })
    {
      const std::vector<glm::dvec3> piece = clipOutline(outline, heights, side);
      glm::dvec3 centre(0.0);
      for (const glm::dvec3& corner : piece)
      {
        centre += corner;
      }
      centre /= double(piece.size());
      volumes.push_back(buildStsv(triangle, piece, centre, side, true, sceneBounds));
    }
  }
  else if (above || below)
  {
    volumes.push_back(buildStsv(triangle, outline, light.center, above ? 1 : -1, false, sceneBounds));
  }
  return volumes;
}

bool stsvContains(const Stsv& stsv, const glm::dvec3& p)
{
  return stsv.outerPlanes[0].distance(p) >= 0.0 && stsv.outerPlanes[1].distance(p) >= 0.0 &&
    stsv.outerPlanes[2].distance(p) >= 0.0 && stsv.frontCapPlane.distance(p) >= 0.0;
}

bool stsvClosedVolumeContains(const Stsv& stsv, const glm::dvec3& p)
{
  return stsvContains(stsv, p) && stsv.backCapPlane.distance(p) >= 0.0;
}

std::vector<bool> stsvOcclusion(const Stsv& stsv, const StsvTriangle& triangle, const ImageF& alpha,
  const glm::dvec3& p, const std::vector<glm::dvec3>& samples, StsvOcclusionTest test, bool onlyThisSide)
{
  std::vector<bool> occluded(samples.size(), false);
  if (!stsvContains(stsv, p))
  {
    return occluded;
  }
  const StsvPointTransform transform = stsvPointTransform(triangle, p, stsvOnPlaneDistance(triangle));
  if (transform.onPlane)
  {
    return occluded;
  }
  for (std::size_t i = 0; i < samples.size(); ++i)
  {
    if (onlyThisSide && triangleSideOf(triangle, samples[i]) != stsv.lightSide)
    {
      continue;
    }
    occluded[i] = evaluateStsvSample(triangle, transform, alpha, p, samples[i], test).occluded;
  }
  return occluded;
}

std::array<glm::dvec3, 10> stsvStrip(const Stsv& stsv)
{
  std::array<glm::dvec3, 10> strip{};
  for (std::size_t k = 0; k < strip.size(); ++k)
  {
    const int vertex = kStsvStripOrder[k];
    strip[k] = vertex < 3 ? stsv.frontCap[static_cast<std::size_t>(vertex)]
                          : stsv.backCap[static_cast<std::size_t>(vertex - 3)];
  }
  return strip;
}

StsvSet buildStsvSet(const Scene& scene, const Light& light)
{
  StsvSet set;
  set.triangles = perforatedTriangles(scene);
  for (const StsvTriangle& triangle : set.triangles)
  {
    set.volumes.push_back(buildStsvs(triangle, light, scene.bounds()));
  }
  return set;
}

StsvPointOcclusion stsvPointOcclusion(const StsvSet& set, const Scene& scene, const glm::dvec3& p,
  const std::vector<glm::dvec3>& samples, StsvOcclusionTest test)
{
  StsvPointOcclusion result;
  result.hiddenBy.assign(samples.size(), 0);
  for (std::size_t t = 0; t < set.triangles.size(); ++t)
  {
    const StsvTriangle& triangle = set.triangles[t];
    const ImageF& alpha = scene.objects[triangle.objectIndex].alphaTexture.alpha;
    for (const Stsv& stsv : set.volumes[t])
    {
      if (!stsvContains(stsv, p))
      {
        continue;
      }
      ++result.covering;
      const std::vector<bool> hidden = stsvOcclusion(stsv, triangle, alpha, p, samples, test);
      bool any = false;
      for (std::size_t i = 0; i < hidden.size(); ++i)
      {
        result.hiddenBy[i] += hidden[i] ? 1 : 0;
        any = any || hidden[i];
      }
      result.emptyHits += any ? 0 : 1;
    }
  }
  return result;
}

} // namespace sl
