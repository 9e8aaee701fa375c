#include "techniques/izb/IzbTwin.h"

#include "core/Error.h"
#include "lightspace/LightView.h"

#include <algorithm>
#include <cmath>

namespace sl
{

IzbLight IzbLight::from(const Light& light)
{
  IzbLight result;
  result.directional = light.type == LightType::Directional;
  result.position = light.center;
  result.direction = glm::normalize(light.direction);
  return result;
}

IzbGrid IzbGrid::fit(const Light& light, const Bounds& sceneBounds, int size)
{
  IzbGrid grid;
  grid.size = size;
  grid.directional = light.type == LightType::Directional;
  grid.faces = grid.directional ? 1 : 6;
  grid.lightPosition = light.center;
  grid.lightDirection = glm::normalize(light.direction);
  if (!grid.directional)
  {
    return grid;
  }
  const glm::dvec3 helper =
    std::abs(grid.lightDirection.y) < 0.9 ? glm::dvec3(0.0, 1.0, 0.0) : glm::dvec3(1.0, 0.0, 0.0);
  grid.axisU = glm::normalize(glm::cross(helper, grid.lightDirection));
  grid.axisV = glm::cross(grid.lightDirection, grid.axisU);
  // The window: the scene's bounding box seen along the light, so every sample and caster projects into it (a
  // sample outside it by rounding is clamped to the border texels, which stand for everything beyond).
  glm::dvec2 low(1e300), high(-1e300);
  for (int corner = 0; corner < 8; ++corner)
  {
    const glm::dvec3 point((corner & 1) ? sceneBounds.max.x : sceneBounds.min.x,
      (corner & 2) ? sceneBounds.max.y : sceneBounds.min.y, (corner & 4) ? sceneBounds.max.z : sceneBounds.min.z);
    const glm::dvec2 projected(glm::dot(point, grid.axisU), glm::dot(point, grid.axisV));
    low = glm::min(low, projected);
    high = glm::max(high, projected);
  }
  const double pad = 1e-3 * std::max(high.x - low.x, high.y - low.y) + 1e-9;
  grid.windowMin = low - pad;
  grid.texelsPerUnit = glm::dvec2(size) / (high - low + 2.0 * pad);
  return grid;
}

namespace
{

// The cube face's axes: the major axis `axis` (0 x, 1 y, 2 z) and the two after it, cyclically.
struct IzbFaceAxes
{
  int major, u, v;
  double sign;
};

IzbFaceAxes izbFaceAxes(int face)
{
  const int major = face / 2;
  return { major, (major + 1) % 3, (major + 2) % 3, (face % 2) ? -1.0 : 1.0 };
}

// The major axis of d, ties to the lower axis (as izb/IzbCommon.glsl picks it).
int izbMajorAxis(const glm::dvec3& d)
{
  const glm::dvec3 m = glm::abs(d);
  if (m.x >= m.y && m.x >= m.z)
  {
    return 0;
  }
  return m.y >= m.z ? 1 : 2;
}

double izbDet(const glm::dvec3& x, const glm::dvec3& y, const glm::dvec3& z)
{
  return glm::dot(glm::cross(x, y), z);
}

// The bound on the float evaluation of det(x, y, z) = cross(x, y) . z from operands carrying componentwise absolute
// errors ex, ey, ez: first-order propagation (ex . |y x z| + ey . |z x x| + ez . |x y|) plus the rounding of the cross
// product (2u per component of |x_j y_k| + |x_k y_j|) and of the dot product (3u), times 2 for safety (README.md,
// "Ambiguity"). Componentwise, so a triangle in an axis plane keeps the exact zeros float keeps too.
glm::dvec3 izbAbsCross(const glm::dvec3& x, const glm::dvec3& y)
{
  return glm::abs(glm::dvec3(x.y * y.z, x.z * y.x, x.x * y.y)) + glm::abs(glm::dvec3(x.z * y.y, x.x * y.z, x.y * y.x));
}

double izbDetBound(const glm::dvec3& x, const glm::dvec3& ex, const glm::dvec3& y, const glm::dvec3& ey,
  const glm::dvec3& z, const glm::dvec3& ez)
{
  return 2.0 * (glm::dot(ex, glm::abs(glm::cross(y, z))) + glm::dot(ey, glm::abs(glm::cross(z, x))) +
    glm::dot(ez, glm::abs(glm::cross(x, y))) + 5.0 * izbFloatRoundoff * glm::dot(izbAbsCross(x, y), glm::abs(z)));
}

// -1 / +1 when the value's sign is certain beyond its bound, 0 when float rounding may flip it.
int izbCertainSign(double value, double bound)
{
  return value > bound ? 1 : (value < -bound ? -1 : 0);
}

} // namespace

IzbGrid::Place IzbGrid::place(const glm::dvec3& point) const
{
  Place result;
  if (directional)
  {
    result.texels = (glm::dvec2(glm::dot(point, axisU), glm::dot(point, axisV)) - windowMin) * texelsPerUnit;
  }
  else
  {
    const glm::dvec3 d = point - lightPosition;
    const int major = izbMajorAxis(d);
    result.face = 2 * major + (d[major] < 0.0 ? 1 : 0);
    const IzbFaceAxes axes = izbFaceAxes(result.face);
    const double m = std::abs(d[major]);
    const glm::dvec2 st = m > 0.0 ? glm::dvec2(d[axes.u], d[axes.v]) / m : glm::dvec2(0.0);
    result.texels = (st + 1.0) * (0.5 * size);
  }
  result.texels = glm::clamp(result.texels, glm::dvec2(0.0), glm::dvec2(size));
  const int x = std::min(static_cast<int>(result.texels.x), size - 1);
  const int y = std::min(static_cast<int>(result.texels.y), size - 1);
  result.texel = result.face * size * size + y * size + x;
  return result;
}

double IzbGrid::placementErrorTexels(const glm::dvec3& point) const
{
  const double u = izbFloatRoundoff;
  if (directional)
  {
    const double error = 8.0 * u * (glm::length(point) + glm::length(windowMin));
    return error * std::max(texelsPerUnit.x, texelsPerUnit.y);
  }
  const glm::dvec3 d = point - lightPosition;
  const double m = std::max(std::abs(d.x), std::max(std::abs(d.y), std::abs(d.z)));
  const double error = 8.0 * u * (glm::length(point) + glm::length(lightPosition));
  return m > 0.0 ? 2.0 * error / m * size : 1e300;
}

std::vector<glm::dvec2> IzbGrid::facePolygon(
  const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, int face, bool& wholeFace) const
{
  wholeFace = false;
  if (directional)
  {
    std::vector<glm::dvec2> polygon;
    for (const glm::dvec3& vertex : { a, b, c })
    {
      polygon.push_back((glm::dvec2(glm::dot(vertex, axisU), glm::dot(vertex, axisV)) - windowMin) * texelsPerUnit);
    }
    return polygon;
  }
  // The triangle in the face's frame (m along the major axis, then u, v), clipped to the face's pyramid
  // |u|, |v| <= k m, k slightly above 1 so a sample whose float direction picked this face by a rounding is inside.
  const IzbFaceAxes axes = izbFaceAxes(face);
  constexpr double widen = 1.0 + 1e-4;
  std::vector<glm::dvec3> polygon;
  double scale = 0.0;
  for (const glm::dvec3& vertex : { a, b, c })
  {
    const glm::dvec3 d = vertex - lightPosition;
    polygon.emplace_back(axes.sign * d[axes.major], d[axes.u], d[axes.v]);
    scale = std::max(scale, glm::length(d));
  }
  for (int plane = 0; plane < 4; ++plane)
  {
    const int component = 1 + plane / 2;
    const double side = (plane % 2) ? -1.0 : 1.0;
    const auto inside = [&](const glm::dvec3& p) { return widen * p.x - side * p[component]; };
    std::vector<glm::dvec3> clipped;
    for (std::size_t i = 0; i < polygon.size(); ++i)
    {
      const glm::dvec3& from = polygon[i];
      const glm::dvec3& to = polygon[(i + 1) % polygon.size()];
      const double fromValue = inside(from), toValue = inside(to);
      if (fromValue >= 0.0)
      {
        clipped.push_back(from);
      }
      if ((fromValue >= 0.0) != (toValue >= 0.0))
      {
        clipped.push_back(from + (fromValue / (fromValue - toValue)) * (to - from));
      }
    }
    polygon.swap(clipped);
    if (polygon.empty())
    {
      return {};
    }
  }
  std::vector<glm::dvec2> projected;
  for (const glm::dvec3& p : polygon)
  {
    if (p.x <= 1e-9 * scale)
    {
      // The triangle passes (within rounding) through the light itself: its projection is unbounded.
      wholeFace = true;
      return {};
    }
    projected.push_back((glm::dvec2(p.y, p.z) / p.x + 1.0) * (0.5 * size));
  }
  return projected;
}

bool IzbGrid::texelMeetsPolygon(int x, int y, const std::vector<glm::dvec2>& polygon) const
{
  // Separating axes of a convex polygon and a square: the square's axes are the bounding box already tested; the
  // polygon's edges remain. A border texel reaches to infinity beyond the border.
  const double margin = 1.0 / izbCoverageMarginInverse;
  constexpr double far = 1e12;
  const glm::dvec2 low(x == 0 ? -far : x, y == 0 ? -far : y);
  const glm::dvec2 high(x == size - 1 ? far : x + 1.0, y == size - 1 ? far : y + 1.0);
  double twiceArea = 0.0;
  double extent = 0.0;
  for (std::size_t i = 0; i < polygon.size(); ++i)
  {
    const glm::dvec2& p = polygon[i];
    const glm::dvec2& q = polygon[(i + 1) % polygon.size()];
    twiceArea += p.x * q.y - p.y * q.x;
    extent = std::max(extent, glm::length(q - p));
  }
  if (std::abs(twiceArea) <= 1e-12 * (extent * extent + 1.0))
  {
    return true; // edge-on to the light: no orientation to separate with, the box decides
  }
  const double orientation = twiceArea > 0.0 ? 1.0 : -1.0;
  for (std::size_t i = 0; i < polygon.size(); ++i)
  {
    const glm::dvec2& p = polygon[i];
    const glm::dvec2 edge = polygon[(i + 1) % polygon.size()] - p;
    const double length = glm::length(edge);
    if (length <= 1e-12 * extent)
    {
      continue;
    }
    // The inside of edge p -> q is where orientation * cross(edge, x - p) >= 0: its largest value over the square.
    double largest = -1e300;
    for (const glm::dvec2& corner : { low, high, glm::dvec2(low.x, high.y), glm::dvec2(high.x, low.y) })
    {
      largest = std::max(largest, orientation * (edge.x * (corner.y - p.y) - edge.y * (corner.x - p.x)));
    }
    if (largest < -margin * length)
    {
      return false;
    }
  }
  return true;
}

IzbSampleTest izbSampleTest(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& q,
  const IzbLight& light, double offsetWorld)
{
  const double u = izbFloatRoundoff;
  // Componentwise error bounds of the float operands (README.md, "Ambiguity"): q = p + offset n rounds by
  // u (|q| + offset) at most (p and n are exact floats, |n_i| <= 1); the vertices are exact floats; each difference
  // rounds by u of its own magnitude; the light's position is a float uniform.
  const glm::dvec3 eq = 2.0 * u * (glm::abs(q) + offsetWorld);
  const glm::dvec3 qa = a - q, qb = b - q, qc = c - q;
  const glm::dvec3 ea = eq + u * glm::abs(qa), eb = eq + u * glm::abs(qb), ec = eq + u * glm::abs(qc);
  const glm::dvec3 d = light.directional ? light.direction : q - light.position;
  const glm::dvec3 ed = light.directional ? 2.0 * u * glm::abs(d)
                                          : eq + u * glm::abs(light.position) + u * glm::abs(d);

  // Johnson et al. 2005: q is inside the triangle in light space when the edge functions share a sign.
  const double edges[3] = { izbDet(qa, qb, d), izbDet(qb, qc, d), izbDet(qc, qa, d) };
  const double edgeBounds[3] = { izbDetBound(qa, ea, qb, eb, d, ed), izbDetBound(qb, eb, qc, ec, d, ed),
    izbDetBound(qc, ec, qa, ea, d, ed) };
  // The plane test: f(x) = det(b - a, c - a, x - a), at q and at the light (directional: the slope along d).
  const glm::dvec3 e1 = b - a, e2 = c - a, aq = q - a;
  const glm::dvec3 ee1 = u * glm::abs(e1), ee2 = u * glm::abs(e2);
  const double fq = izbDet(e1, e2, aq);
  const double fqBound = izbDetBound(e1, ee1, e2, ee2, aq, eq + u * glm::abs(aq));
  const glm::dvec3 al = light.directional ? d : light.position - a;
  const double fl = izbDet(e1, e2, al);
  const double flBound = izbDetBound(e1, ee1, e2, ee2, al,
    light.directional ? ed : u * glm::abs(light.position) + u * glm::abs(al));

  IzbSampleTest result;
  const bool inside = (edges[0] > 0.0 && edges[1] > 0.0 && edges[2] > 0.0) ||
    (edges[0] < 0.0 && edges[1] < 0.0 && edges[2] < 0.0);
  // Between q and the light: a point light's plane value changes sign from q to the light; a directional light's
  // crossing q - t d lies at t = f(q) / f'(d) > 0.
  const bool between = light.directional ? ((fq > 0.0 && fl > 0.0) || (fq < 0.0 && fl < 0.0))
                                         : ((fq > 0.0 && fl < 0.0) || (fq < 0.0 && fl > 0.0));
  result.shadows = inside && between;

  int positive = 0, negative = 0, unsure = -1;
  for (int i = 0; i < 3; ++i)
  {
    const int sign = izbCertainSign(edges[i], edgeBounds[i]);
    positive += sign > 0 ? 1 : 0;
    negative += sign < 0 ? 1 : 0;
    unsure = sign == 0 ? i : unsure;
  }
  const int planeAtQ = izbCertainSign(fq, fqBound);
  const int planeAtLight = izbCertainSign(fl, flBound);
  const int wanted = light.directional ? 1 : -1; // the product of the two plane signs that means "between"
  const bool insideCertain = positive == 3 || negative == 3;
  const bool insidePossible = positive == 0 || negative == 0;
  const bool betweenCertain = planeAtQ * planeAtLight == wanted;
  const bool betweenPossible = planeAtQ * planeAtLight != -wanted;
  result.definite = insideCertain && betweenCertain;
  result.uncertain = insidePossible && betweenPossible && !result.definite;
  // Uncertain through one edge alone (README.md, "Shared edges"): the other two edges and the plane are certain.
  if (result.uncertain && betweenCertain && (positive == 2 || negative == 2))
  {
    result.loneEdge = unsure;
    result.orientation = positive == 2 ? 1 : -1;
  }
  return result;
}

IzbEdgeEvent izbEdgeEvent(std::uint32_t fromVertex, std::uint32_t toVertex, int orientation)
{
  const std::uint32_t low = std::min(fromVertex, toVertex);
  const std::uint32_t high = std::max(fromVertex, toVertex);
  const std::uint32_t reversed = fromVertex > toVertex ? izbEdgeTopBit : 0u;
  return { low | reversed, high | (orientation > 0 ? izbEdgeTopBit : 0u) };
}

bool izbEdgePairCovers(std::uint32_t events, std::uint32_t xorFirst, std::uint32_t xorSecond)
{
  // Two events only: their words XOR to these values exactly when they name the same edge with the same
  // orientation, listed in opposite directions (never by hashing: the words are the vertex ids themselves).
  return events == 2 && xorFirst == izbEdgeTopBit && xorSecond == 0u;
}

std::vector<glm::dvec3> izbCasterTriangles(const Scene& scene)
{
  std::vector<glm::dvec3> vertices;
  for (const SceneObject& object : scene.objects)
  {
    if (!object.castShadows)
    {
      continue;
    }
    for (const std::uint32_t index : object.mesh.indices)
    {
      vertices.emplace_back(object.mesh.positions[index]);
    }
  }
  return vertices;
}

std::vector<std::uint32_t> izbCasterVertexIds(const Scene& scene)
{
  std::vector<std::uint32_t> ids;
  std::uint32_t offset = 0;
  for (const SceneObject& object : scene.objects)
  {
    if (!object.castShadows)
    {
      continue;
    }
    for (const std::uint32_t index : object.mesh.indices)
    {
      ids.push_back(offset + index);
    }
    offset += static_cast<std::uint32_t>(object.mesh.positions.size());
  }
  SL_CHECK_MSG(offset < izbEdgeTopBit, "izb: more than 2^31 caster vertices");
  return ids;
}

IzbTwinFrame izbTwin(const FrameResult& frame, const Scene& scene, const Light& light, int gridSize, double offsetWorld)
{
  const ImageF& position = frame.find("position")->image;
  const ImageF& normal = frame.find("normal")->image;
  const ImageF& coverage = frame.find("coverage")->image;
  const ImageF& receives = frame.find("receives_shadows")->image;
  const IzbGrid grid = IzbGrid::fit(light, scene.bounds(), gridSize);
  const IzbLight izbLight = IzbLight::from(light);
  // The offset as the pass's float uniform holds it.
  const double offset = static_cast<float>(offsetWorld);

  IzbTwinFrame twin;
  twin.width = position.width;
  twin.height = position.height;
  twin.pixels.resize(static_cast<std::size_t>(twin.width) * twin.height);
  twin.listLength.assign(grid.texelCount(), 0);
  std::vector<glm::dvec3> samples(twin.pixels.size());
  std::vector<int> definite(twin.pixels.size(), 0), uncertain(twin.pixels.size(), 0), shadowed(twin.pixels.size(), 0);
  std::vector<std::uint32_t> edgeEvents(twin.pixels.size(), 0), xorFirst(twin.pixels.size(), 0),
    xorSecond(twin.pixels.size(), 0);
  for (int y = 0; y < twin.height; ++y)
  {
    for (int x = 0; x < twin.width; ++x)
    {
      IzbTwinPixel& pixel = twin.pixels[static_cast<std::size_t>(y) * twin.width + x];
      const glm::dvec3 pWs(position.at(x, y, 0), position.at(x, y, 1), position.at(x, y, 2));
      const glm::dvec3 nWs(normal.at(x, y, 0), normal.at(x, y, 1), normal.at(x, y, 2));
      if (coverage.at(x, y) <= 0.5f)
      {
        continue;
      }
      if (receives.at(x, y) <= 0.5f)
      {
        pixel.visibility = 1.0;
        continue;
      }
      pixel.reachAmbiguous = izbReachMargin(light, pWs, nWs) < izbReachAmbiguity;
      if (!lightCanReach(light, pWs, nWs))
      {
        continue;
      }
      pixel.tested = true;
      const glm::dvec3 q = izbSamplePoint(pWs, nWs, offset);
      const IzbGrid::Place place = grid.place(q);
      pixel.texel = place.texel;
      pixel.ambiguous = pixel.ambiguous || grid.placementErrorTexels(q) > 0.5 / izbCoverageMarginInverse;
      const glm::dvec2 fraction = place.texels - glm::floor(place.texels);
      pixel.texelMargin = std::min(std::min(fraction.x, 1.0 - fraction.x), std::min(fraction.y, 1.0 - fraction.y));
      if (!grid.directional)
      {
        // Near a cube edge the float direction may pick the other face.
        glm::dvec3 m = glm::abs(q - grid.lightPosition);
        std::sort(&m.x, &m.x + 3);
        pixel.texelMargin = std::min(pixel.texelMargin, (m.z - m.y) / m.z * grid.size);
      }
      samples[&pixel - twin.pixels.data()] = q;
      ++twin.listLength[static_cast<std::size_t>(place.texel)];
    }
  }
  // The samples of each texel, contiguous (counts, prefix sum, fill).
  std::vector<int> start(grid.texelCount() + 1, 0);
  for (std::size_t texel = 0; texel < grid.texelCount(); ++texel)
  {
    start[texel + 1] = start[texel] + twin.listLength[texel];
  }
  std::vector<int> fill(start.begin(), start.end() - 1);
  std::vector<int> listed(static_cast<std::size_t>(start.back()));
  for (std::size_t index = 0; index < twin.pixels.size(); ++index)
  {
    if (twin.pixels[index].tested)
    {
      listed[static_cast<std::size_t>(fill[static_cast<std::size_t>(twin.pixels[index].texel)]++)] =
        static_cast<int>(index);
    }
  }
  const std::vector<glm::dvec3> triangles = izbCasterTriangles(scene);
  const std::vector<std::uint32_t> vertexIds = izbCasterVertexIds(scene);
  std::vector<std::uint32_t> texels;
  for (std::size_t t = 0; t + 2 < triangles.size(); t += 3)
  {
    texels.clear();
    grid.triangleTexels(triangles[t], triangles[t + 1], triangles[t + 2],
      [&](std::uint32_t texel) { return twin.listLength[texel] > 0; }, texels);
    for (const std::uint32_t texel : texels)
    {
      for (int k = start[texel]; k < start[texel + 1]; ++k)
      {
        const std::size_t index = static_cast<std::size_t>(listed[static_cast<std::size_t>(k)]);
        const IzbSampleTest test =
          izbSampleTest(triangles[t], triangles[t + 1], triangles[t + 2], samples[index], izbLight, offset);
        ++twin.pixels[index].triangleTests;
        shadowed[index] |= test.shadows ? 1 : 0;
        definite[index] |= test.definite ? 1 : 0;
        uncertain[index] |= test.uncertain ? 1 : 0;
        if (test.loneEdge >= 0)
        {
          const IzbEdgeEvent event = izbEdgeEvent(vertexIds[t + static_cast<std::size_t>(test.loneEdge)],
            vertexIds[t + static_cast<std::size_t>((test.loneEdge + 1) % 3)], test.orientation);
          ++edgeEvents[index];
          xorFirst[index] ^= event.first;
          xorSecond[index] ^= event.second;
        }
      }
    }
  }
  for (std::size_t index = 0; index < twin.pixels.size(); ++index)
  {
    IzbTwinPixel& pixel = twin.pixels[index];
    if (pixel.tested)
    {
      const bool paired = izbEdgePairCovers(edgeEvents[index], xorFirst[index], xorSecond[index]);
      pixel.visibility = (shadowed[index] || paired) ? 0.0 : 1.0;
      pixel.ambiguous = pixel.ambiguous || (uncertain[index] && !definite[index] && !paired);
    }
  }
  return twin;
}

double izbReachMargin(const Light& light, const glm::dvec3& pWs, const glm::dvec3& nWs)
{
  double margin = lightReachMargin(light, nWs, directionToLight(light, pWs));
  if (light.type == LightType::Spot)
  {
    const double coneCosine = glm::dot(light.normal, glm::normalize(pWs - light.center));
    margin = std::min(margin, std::abs(coneCosine - std::cos(glm::radians(light.coneAngleDeg))));
  }
  return margin;
}

} // namespace sl
