#include "objectspace/DcsGeometry.h"

#include "core/Error.h"

#include <algorithm>
#include <cmath>

namespace sl
{

double orient(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& d)
{
  return glm::dot(d - a, glm::cross(b - a, c - a));
}

namespace
{

int signOf(double value)
{
  return (value > 0.0) - (value < 0.0);
}

// How the facing of a plane through `origin` with normal `normal` varies over the light: +1 or -1 when the whole
// light lies strictly on one side, 0 when the plane cuts it (or touches it).
int constantFacingOverLight(const glm::dvec3& origin, const glm::dvec3& normal, const Light& light,
  const std::vector<glm::dvec3>& outline)
{
  if (light.type == LightType::Area && light.shape == LightShape::Disk)
  {
    // Over a disk the signed distance ranges over d(c) ± r |n - (n . nL) nL|.
    const double atCentre = glm::dot(normal, light.center - origin);
    const glm::dvec3 inPlane = normal - glm::dot(normal, light.normal) * light.normal;
    const double spread = 0.5 * light.size * glm::length(inPlane);
    return std::abs(atCentre) > spread ? signOf(atCentre) : 0;
  }
  int common = 0;
  for (const glm::dvec3& corner : outline)
  {
    const int side = signOf(glm::dot(normal, corner - origin));
    if (side == 0 || (common != 0 && side != common))
    {
      return 0;
    }
    common = side;
  }
  return common;
}

} // namespace

std::vector<glm::dvec3> lightOutline(const Light& light)
{
  if (light.type != LightType::Area)
  {
    return { light.center };
  }
  const glm::dvec3 right = light.right();
  const glm::dvec3 up = light.up;
  std::vector<glm::dvec3> corners;
  if (light.shape == LightShape::Disk)
  {
    // The regular octagon around the disk: circumradius r / cos(pi / 8).
    const double circumradius = 0.5 * light.size / std::cos(M_PI / 8.0);
    for (int k = 0; k < 8; ++k)
    {
      const double angle = (k + 0.5) * M_PI / 4.0;
      corners.push_back(light.center + circumradius * (std::cos(angle) * right + std::sin(angle) * up));
    }
    return corners;
  }
  const double half = 0.5 * light.size;
  for (const glm::dvec2& corner : { glm::dvec2(-1, -1), glm::dvec2(1, -1), glm::dvec2(1, 1), glm::dvec2(-1, 1) })
  {
    corners.push_back(light.center + half * (corner.x * right + corner.y * up));
  }
  return corners;
}

std::vector<glm::dvec3> dcsSamplePoints(const Light& light, const LightSampleSet& samples, glm::ivec2 pixel)
{
  std::vector<glm::dvec3> points;
  for (int index = 0; index < samples.count(); ++index)
  {
    points.push_back(light.type == LightType::Area ? samples.point(light, pixel.x, pixel.y, index) : light.center);
  }
  return points;
}

DcsEdgeSet potentialSilhouetteWedges(const std::vector<WeldedMesh>& casters, const Light& light)
{
  DcsEdgeSet result;
  DcsEdgeStatistics& statistics = result.statistics;
  const std::vector<glm::dvec3> outline = lightOutline(light);
  const bool areaLight = light.type == LightType::Area;
  for (const WeldedMesh& mesh : casters)
  {
    statistics.casterTriangles += mesh.triangles.size();
    statistics.edges += mesh.edges.size();
    statistics.boundaryEdges += mesh.boundaryEdgeCount();
    statistics.nonManifoldEdges += mesh.nonManifoldEdgeCount();
    if (!areaLight)
    {
      continue;
    }
    for (const WeldedEdge& edge : mesh.edges)
    {
      const glm::dvec3 v0 = mesh.positions[edge.v0];
      const glm::dvec3 v1 = mesh.positions[edge.v1];
      // Heights below the light plane: an edge wholly at or above it is met by no segment from a receiver.
      const double h0 = glm::dot(light.normal, v0 - light.center);
      const double h1 = glm::dot(light.normal, v1 - light.center);
      bool potential = false;
      bool fromCentre = false;
      std::vector<DcsWedgeEdge> records;
      for (std::uint32_t first = 0; first < edge.useCount; first += 2)
      {
        DcsWedgeEdge record;
        record.objectIndex = mesh.objectIndex;
        record.v0 = v0;
        record.v1 = v1;
        record.incidentTriangles = edge.useCount;
        int constantSum = 0;
        bool varies = false;
        int centreSum = 0;
        for (std::uint32_t use = first; use < std::min(first + 2, edge.useCount); ++use)
        {
          const auto& corners = mesh.triangles[mesh.edgeUses[edge.firstUse + use].triangle];
          std::uint32_t third = corners[0];
          for (const std::uint32_t corner : corners)
          {
            if (corner != edge.v0 && corner != edge.v1)
            {
              third = corner;
            }
          }
          const glm::dvec3 w = mesh.positions[third];
          record.opposite[static_cast<std::size_t>(record.oppositeCount++)] = w;
          // orient(v0, v1, x, w) = (x - v0) . ((w - v0) x (v1 - v0)): the triangle's facing seen from x.
          const glm::dvec3 normal = glm::cross(w - v0, v1 - v0);
          const int facing = constantFacingOverLight(v0, normal, light, outline);
          varies = varies || facing == 0;
          constantSum += facing;
          centreSum += signOf(glm::dot(light.center - v0, normal));
        }
        record.silhouetteFromCentre = centreSum != 0;
        if (varies || constantSum != 0)
        {
          potential = true;
          fromCentre = fromCentre || record.silhouetteFromCentre;
          records.push_back(record);
        }
      }
      if (!potential)
      {
        continue;
      }
      if (h0 <= 0.0 && h1 <= 0.0)
      {
        ++statistics.edgesAtLightPlane;
        continue;
      }
      ++statistics.potentialSilhouetteEdges;
      statistics.centreSilhouetteEdges += fromCentre ? 1 : 0;
      statistics.wedges += records.size();
      result.wedges.insert(result.wedges.end(), records.begin(), records.end());
    }
  }
  return result;
}

int wedgeMultiplicity(const DcsWedgeEdge& wedge, const glm::dvec3& p)
{
  int multiplicity = 0;
  for (int k = 0; k < wedge.oppositeCount; ++k)
  {
    multiplicity += signOf(orient(wedge.v0, wedge.v1, p, wedge.opposite[static_cast<std::size_t>(k)]));
  }
  return multiplicity;
}

int sampleCountChange(const DcsWedgeEdge& wedge, const glm::dvec3& p, const glm::dvec3& c, const glm::dvec3& s)
{
  const double atCentre = orient(wedge.v0, wedge.v1, p, c);
  const double atSample = orient(wedge.v0, wedge.v1, p, s);
  // e crosses triangle (p, c, s): orient(v0, v1, p, c), orient(v0, v1, c, s) and orient(v0, v1, s, p) = -atSample
  // share a sign, and v0, v1 lie on opposite sides of the triangle's plane.
  if (!(atCentre * atSample < 0.0) || !(orient(wedge.v0, wedge.v1, c, s) * atCentre > 0.0))
  {
    return 0;
  }
  if (!(orient(p, c, s, wedge.v0) * orient(p, c, s, wedge.v1) < 0.0))
  {
    return 0;
  }
  return signOf(atSample) * wedgeMultiplicity(wedge, p);
}

bool wedgeContains(const DcsWedgeEdge& wedge, const glm::dvec3& p, const std::vector<glm::dvec3>& outline,
  const glm::dvec3& lightNormal)
{
  // Cyrus-Beck: the part of e = v0 + t (v1 - v0), t in [0, 1], inside every half-space "inside <= 0".
  double enter = 0.0;
  double leave = 1.0;
  const auto clip = [&](double atV0, double atV1) {
    if (atV0 > 0.0 && atV1 > 0.0)
    {
      return false;
    }
    if (atV0 > 0.0 || atV1 > 0.0)
    {
      const double t = atV0 / (atV0 - atV1);
      atV0 > 0.0 ? enter = std::max(enter, t) : leave = std::min(leave, t);
    }
    return enter <= leave;
  };
  // Below the light plane (the segment's far end): height > 0.
  const glm::dvec3& centreCorner = outline.front();
  if (!clip(-glm::dot(lightNormal, wedge.v0 - centreCorner), -glm::dot(lightNormal, wedge.v1 - centreCorner)))
  {
    return false;
  }
  // The pyramid's side planes (p, L_i, L_i+1), oriented so that the outline's centroid is inside.
  glm::dvec3 centroid(0.0);
  for (const glm::dvec3& corner : outline)
  {
    centroid += corner;
  }
  centroid /= static_cast<double>(outline.size());
  for (std::size_t i = 0; i < outline.size(); ++i)
  {
    const glm::dvec3& a = outline[i];
    const glm::dvec3& b = outline[(i + 1) % outline.size()];
    glm::dvec3 normal = glm::cross(a - p, b - p);
    if (glm::dot(normal, centroid - p) > 0.0)
    {
      normal = -normal;
    }
    if (!clip(glm::dot(normal, wedge.v0 - p), glm::dot(normal, wedge.v1 - p)))
    {
      return false;
    }
  }
  // And on the light's side of p: the part of e between p's height and the light (the pyramid's apex).
  const double heightP = glm::dot(lightNormal, p - centreCorner);
  return clip(glm::dot(lightNormal, wedge.v0 - centreCorner) - heightP, glm::dot(lightNormal, wedge.v1 - centreCorner) - heightP);
}

namespace
{

double cross2(const glm::dvec2& o, const glm::dvec2& a, const glm::dvec2& b)
{
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

// Andrew's monotone chain: the convex hull, counter-clockwise, without collinear points.
std::vector<glm::dvec2> convexHull(std::vector<glm::dvec2> points)
{
  std::sort(points.begin(), points.end(), [](const glm::dvec2& a, const glm::dvec2& b) {
    return a.x < b.x || (a.x == b.x && a.y < b.y);
  });
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 3)
  {
    return points;
  }
  std::vector<glm::dvec2> hull(2 * points.size());
  std::size_t k = 0;
  for (const glm::dvec2& point : points)
  {
    while (k >= 2 && cross2(hull[k - 2], hull[k - 1], point) <= 0.0)
    {
      --k;
    }
    hull[k++] = point;
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;)
  {
    while (k >= lower && cross2(hull[k - 2], hull[k - 1], points[i]) <= 0.0)
    {
      --k;
    }
    hull[k++] = points[i];
  }
  hull.resize(k - 1);
  return hull;
}

// Sutherland-Hodgman against the box |x|, |y| <= limit.
std::vector<glm::dvec2> clipToBox(std::vector<glm::dvec2> polygon, double limit)
{
  for (int axis = 0; axis < 2; ++axis)
  {
    for (const double sign : { 1.0, -1.0 })
    {
      std::vector<glm::dvec2> clipped;
      for (std::size_t i = 0; i < polygon.size(); ++i)
      {
        const glm::dvec2& a = polygon[i];
        const glm::dvec2& b = polygon[(i + 1) % polygon.size()];
        const double da = sign * a[axis] - limit;
        const double db = sign * b[axis] - limit;
        if (da <= 0.0)
        {
          clipped.push_back(a);
        }
        if ((da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0))
        {
          clipped.push_back(a + (da / (da - db)) * (b - a));
        }
      }
      polygon = std::move(clipped);
      if (polygon.empty())
      {
        return polygon;
      }
    }
  }
  return polygon;
}

} // namespace

std::vector<glm::dvec2> wedgeScreenPolygon(const DcsWedgeEdge& wedge, const Light& light,
  const std::vector<glm::dvec3>& outline, const CameraView& camera, bool perspective, const Bounds& sceneBounds)
{
  // The part of the edge below the light plane (a receiver's segments to the light stay below it).
  const double radius = std::max(sceneBounds.radius(), 1e-300);
  const double minHeight = 1e-7 * radius;
  glm::dvec3 a = wedge.v0;
  glm::dvec3 b = wedge.v1;
  double ha = glm::dot(light.normal, a - light.center);
  double hb = glm::dot(light.normal, b - light.center);
  if (ha < minHeight && hb < minHeight)
  {
    return {};
  }
  if (ha < minHeight || hb < minHeight)
  {
    const glm::dvec3 cut = a + ((minHeight - ha) / (hb - ha)) * (b - a);
    (ha < minHeight ? a : b) = cut;
    (ha < minHeight ? ha : hb) = minHeight;
  }
  // The outline widened by 1 % about the centre, so samples near its border are never at the hull's boundary.
  std::vector<glm::dvec3> corners;
  for (const glm::dvec3& corner : outline)
  {
    corners.push_back(light.center + 1.01 * (corner - light.center));
  }
  // Every receiver of the scene's box lies at most `deepest` below the light plane; a point p = y + t (q - y) of R_e
  // has height t h(q), so t <= deepest / h(q) <= scale, and the hull of the images at that scale, cut at `deepest`,
  // holds every such p (a convex hull cut by a plane is the hull of its points on the inner side and of the crossings
  // of the segments between them).
  double deepest = 0.0;
  for (int k = 0; k < 8; ++k)
  {
    const glm::dvec3 boxCorner((k & 1) ? sceneBounds.max.x : sceneBounds.min.x,
      (k & 2) ? sceneBounds.max.y : sceneBounds.min.y, (k & 4) ? sceneBounds.max.z : sceneBounds.min.z);
    deepest = std::max(deepest, glm::dot(light.normal, boxCorner - light.center));
  }
  deepest += 1e-6 * radius;
  const double scale = std::max(1.0, deepest / std::min(ha, hb));
  std::vector<glm::dvec3> hullPoints = { a, b };
  for (const glm::dvec3& corner : corners)
  {
    hullPoints.push_back(corner + scale * (a - corner));
    hullPoints.push_back(corner + scale * (b - corner));
  }
  std::vector<glm::dvec4> clip;
  const auto add = [&](const glm::dvec3& point) { clip.push_back(camera.clipFromWorld * glm::dvec4(point, 1.0)); };
  for (std::size_t i = 0; i < hullPoints.size(); ++i)
  {
    const double hi = glm::dot(light.normal, hullPoints[i] - light.center) - deepest;
    if (hi <= 0.0)
    {
      add(hullPoints[i]);
    }
    for (std::size_t j = i + 1; j < hullPoints.size(); ++j)
    {
      const double hj = glm::dot(light.normal, hullPoints[j] - light.center) - deepest;
      if (hi * hj < 0.0)
      {
        add(hullPoints[i] + (hi / (hi - hj)) * (hullPoints[j] - hullPoints[i]));
      }
    }
  }
  return convexScreenPolygon(clip, camera, perspective);
}

std::vector<glm::dvec2> convexScreenPolygon(const std::vector<glm::dvec4>& clip, const CameraView& camera, bool perspective)
{
  // Perspective: the hull's part in front of half the near plane's depth (every receiver lies beyond the near
  // plane), from the points there and the hull's edges' crossings of that plane.
  std::vector<glm::dvec4> kept;
  if (perspective)
  {
    const glm::dvec4 nearClip = camera.clipFromView * glm::dvec4(0.0, 0.0, -0.5 * camera.nearDepth, 1.0);
    const double minW = nearClip.w;
    for (std::size_t i = 0; i < clip.size(); ++i)
    {
      if (clip[i].w >= minW)
      {
        kept.push_back(clip[i]);
      }
      for (std::size_t j = i + 1; j < clip.size(); ++j)
      {
        if ((clip[i].w - minW) * (clip[j].w - minW) < 0.0)
        {
          kept.push_back(clip[i] + ((minW - clip[i].w) / (clip[j].w - clip[i].w)) * (clip[j] - clip[i]));
        }
      }
    }
  }
  else
  {
    kept = clip;
  }
  if (kept.empty())
  {
    return {};
  }
  // Widened by 1.5 pixels (a point's neighbourhood in NDC), so rounding never drops a pixel at the border.
  const glm::dvec2 pixel(2.0 / camera.resolution.x, 2.0 / camera.resolution.y);
  std::vector<glm::dvec2> projected;
  for (const glm::dvec4& point : kept)
  {
    const glm::dvec2 ndc = glm::dvec2(point) / point.w;
    for (const glm::dvec2& shift : { glm::dvec2(-1, -1), glm::dvec2(1, -1), glm::dvec2(1, 1), glm::dvec2(-1, 1) })
    {
      projected.push_back(ndc + 1.5 * shift * pixel);
    }
  }
  std::vector<glm::dvec2> polygon = clipToBox(convexHull(std::move(projected)), 1.0 + 4.0 * std::max(pixel.x, pixel.y));
  if (polygon.size() < 3)
  {
    return {};
  }
  return polygon;
}

std::array<int, 2> wedgeSupportingCorners(const DcsWedgeEdge& wedge, const std::vector<glm::dvec3>& outline)
{
  std::array<int, 2> supporting{ -1, -1 };
  int found = 0;
  for (std::size_t i = 0; i < outline.size() && found < 2; ++i)
  {
    int positive = 0;
    int negative = 0;
    for (std::size_t j = 0; j < outline.size(); ++j)
    {
      if (j == i)
      {
        continue;
      }
      const double side = orient(wedge.v0, wedge.v1, outline[i], outline[j]);
      positive += side > 0.0;
      negative += side < 0.0;
    }
    if (positive == 0 || negative == 0)
    {
      supporting[static_cast<std::size_t>(found++)] = static_cast<int>(i);
    }
  }
  return found == 2 ? supporting : std::array<int, 2>{ -1, -1 };
}

} // namespace sl
