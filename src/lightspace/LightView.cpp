#include "lightspace/LightView.h"

#include "core/Error.h"
#include "lightspace/CameraView.h"
#include "lightspace/Cascades.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace sl
{
namespace
{

glm::dvec3 anyPerpendicular(const glm::dvec3& axis)
{
  const glm::dvec3 helper = std::abs(axis.y) < 0.9 ? glm::dvec3(0.0, 1.0, 0.0) : glm::dvec3(1.0, 0.0, 0.0);
  return glm::normalize(helper - axis * glm::dot(helper, axis));
}

// Linear depth and the light-space x/y coordinate used for the window (tangent or world units).
struct LightCoords
{
  double x;
  double y;
  double depthLin;
};

LightCoords toLightCoords(const glm::dmat4& viewFromWorld, LightProjection projection, const glm::dvec3& pWs)
{
  const glm::dvec4 pLs = viewFromWorld * glm::dvec4(pWs, 1.0);
  const double depthLin = -pLs.z;
  if (projection == LightProjection::Perspective)
  {
    return { pLs.x / depthLin, pLs.y / depthLin, depthLin };
  }
  return { pLs.x, pLs.y, depthLin };
}

// Sutherland-Hodgman: keeps the part of a convex polygon (light view space) where dot(plane, (p,1)) >= 0.
std::vector<glm::dvec3> clipPolygon(const std::vector<glm::dvec3>& polygon, const glm::dvec4& plane)
{
  std::vector<glm::dvec3> kept;
  for (std::size_t i = 0; i < polygon.size(); ++i)
  {
    const glm::dvec3& a = polygon[i];
    const glm::dvec3& b = polygon[(i + 1) % polygon.size()];
    const double da = glm::dot(plane, glm::dvec4(a, 1.0));
    const double db = glm::dot(plane, glm::dvec4(b, 1.0));
    if (da >= 0.0)
    {
      kept.push_back(a);
    }
    if ((da >= 0.0) != (db >= 0.0))
    {
      kept.push_back(a + (b - a) * (da / (da - db)));
    }
  }
  return kept;
}

} // namespace

void LightView::setProjectionFromWindow()
{
  if (projection == LightProjection::Perspective)
  {
    clipFromView = glm::frustum(window.x * nearDepth, window.y * nearDepth, window.z * nearDepth,
      window.w * nearDepth, nearDepth, farDepth);
  }
  else
  {
    clipFromView = glm::ortho(window.x, window.y, window.z, window.w, nearDepth, farDepth);
  }
  clipFromWorld = clipFromView * viewFromWorld;
}

double LightView::windowDepth(double depthLin) const
{
  // A depth at or behind a perspective light's centre (w <= 0: a receiver's depth less a bias larger than it) wraps
  // past 1 in z / w; like any depth before the near plane it lies in front of everything the map stores: 0.
  const glm::dvec4 clip = clipFromView * glm::dvec4(0.0, 0.0, -depthLin, 1.0);
  return clip.w > 0.0 ? std::max(0.5 * clip.z / clip.w + 0.5, 0.0) : 0.0;
}

double LightView::texelWorldSize(double depthLin) const
{
  const double extent = std::max(window.y - window.x, window.w - window.z) / resolution;
  return projection == LightProjection::Perspective ? extent * depthLin : extent;
}

glm::dvec3 directionToLight(const Light& light, const glm::dvec3& pWs)
{
  if (light.type == LightType::Directional)
  {
    return -light.direction;
  }
  return glm::normalize(light.center - pWs);
}

double lightReachMargin(const Light& light, const glm::dvec3& nWs, const glm::dvec3& toLight)
{
  double margin = std::abs(glm::dot(nWs, toLight));
  if (light.type == LightType::Area)
  {
    margin = std::min(margin, std::abs(glm::dot(light.normal, toLight)));
  }
  return margin;
}

bool lightCanReach(const Light& light, const glm::dvec3& pWs, const glm::dvec3& nWs)
{
  if (glm::dot(nWs, directionToLight(light, pWs)) <= 0.0)
  {
    return false;
  }
  switch (light.type)
  {
    case LightType::Area:
      return glm::dot(light.normal, pWs - light.center) > 0.0;
    case LightType::Spot:
      return glm::dot(light.normal, glm::normalize(pWs - light.center)) > std::cos(glm::radians(light.coneAngleDeg));
    case LightType::Point:
    case LightType::Directional:
      return true;
  }
  return true;
}

bool ReceiverSource::owns(const glm::dvec3& pWs) const
{
  for (const glm::dvec4& plane : ownerPlanes_)
  {
    if (glm::dot(plane, glm::dvec4(pWs, 1.0)) < 0.0)
    {
      return false;
    }
  }
  return true;
}

ImageReceivers::ImageReceivers(const ImageF& gbufferPosition, const ImageF& gbufferNormal)
{
  SL_CHECK(gbufferPosition.components == 4 && gbufferNormal.components == 4);
  for (std::size_t i = 0; i < gbufferPosition.pixelCount(); ++i)
  {
    const float* position = &gbufferPosition.data[i * 4];
    const float* normal = &gbufferNormal.data[i * 4];
    if (position[3] > 0.5f && normal[3] > 0.5f)
    {
      // Keep the normal's test for later: which receivers count depends on the light.
      receivers_.push_back(glm::dvec3(position[0], position[1], position[2]));
      receivers_.push_back(glm::dvec3(normal[0], normal[1], normal[2]));
    }
  }
}

ReceiverSummary ImageReceivers::summary(const Light& light)
{
  ReceiverSummary result;
  for (std::size_t i = 0; i < receivers_.size(); i += 2)
  {
    if (owns(receivers_[i]) && lightCanReach(light, receivers_[i], receivers_[i + 1]))
    {
      ++result.count;
      result.worldBounds.extend(receivers_[i]);
    }
  }
  return result;
}

ReceiverExtent ImageReceivers::extent(const Light& light, const LightView& view, const glm::dvec3& axis)
{
  ReceiverExtent result;
  result.minXY = glm::dvec2(std::numeric_limits<double>::max());
  result.maxXY = glm::dvec2(-std::numeric_limits<double>::max());
  result.minDepth = std::numeric_limits<double>::max();
  result.maxDepth = -std::numeric_limits<double>::max();
  for (std::size_t i = 0; i < receivers_.size(); i += 2)
  {
    const glm::dvec3& pWs = receivers_[i];
    if (!owns(pWs) || !lightCanReach(light, pWs, receivers_[i + 1]))
    {
      continue;
    }
    ++result.reachable;
    if (view.projection == LightProjection::Perspective)
    {
      result.minCosToAxis = std::min(result.minCosToAxis, glm::dot(axis, glm::normalize(pWs - view.eyeWs)));
    }
    const LightCoords c = toLightCoords(view.viewFromWorld, view.projection, pWs);
    if (c.depthLin <= 0.0)
    {
      continue;
    }
    ++result.inFront;
    result.minXY = glm::min(result.minXY, glm::dvec2(c.x, c.y));
    result.maxXY = glm::max(result.maxXY, glm::dvec2(c.x, c.y));
    result.minDepth = std::min(result.minDepth, c.depthLin);
    result.maxDepth = std::max(result.maxDepth, c.depthLin);
  }
  return result;
}

LightView fitLightView(const Light& light, const Scene& scene, const ImageF& gbufferPosition,
  const ImageF& gbufferNormal, const FocusSettings& settings)
{
  ImageReceivers receivers(gbufferPosition, gbufferNormal);
  return fitLightView(light, scene, receivers, settings);
}

namespace
{

// The light's frame: its eye, axis and projection (perspective from an area, spot or point light; orthographic
// for a directional light, its eye outside the scene's bounds).
void orientLightView(const Light& light, const Scene& scene, const ReceiverSummary& summary,
  const glm::dvec3& fixedAxis, LightView& view, glm::dvec3& forward)
{
  const Bounds sceneBounds = scene.bounds();
  glm::dvec3 up;
  switch (light.type)
  {
    case LightType::Area:
      view.projection = LightProjection::Perspective;
      view.eyeWs = light.center;
      forward = light.normal;
      up = light.up;
      break;
    case LightType::Spot:
      view.projection = LightProjection::Perspective;
      view.eyeWs = light.center;
      forward = light.normal;
      up = anyPerpendicular(forward);
      break;
    case LightType::Point:
    {
      // Aim at the centre of the receivers' bounding box; if the light sits at that centre (receivers all
      // around it) any axis will do: the coverage check rejects the configuration.
      view.projection = LightProjection::Perspective;
      view.eyeWs = light.center;
      const glm::dvec3 towardReceivers =
        summary.count > 0 ? summary.worldBounds.center() - light.center : sceneBounds.center() - light.center;
      forward = glm::length(towardReceivers) > 1e-9 ? glm::normalize(towardReceivers) : glm::dvec3(0.0, -1.0, 0.0);
      if (fixedAxis != glm::dvec3(0.0))
      {
        forward = glm::normalize(fixedAxis); // a cube face's
      }
      up = anyPerpendicular(forward);
      break;
    }
    case LightType::Directional:
      view.projection = LightProjection::Orthographic;
      forward = light.direction;
      up = anyPerpendicular(forward);
      view.eyeWs = sceneBounds.center() - forward * (2.0 * sceneBounds.radius() + 1.0);
      break;
  }
  view.viewFromWorld = glm::lookAt(view.eyeWs, view.eyeWs + forward, up);
}

// One perspective map covers less than a hemisphere: a point light whose visible receivers spread wider (some even
// behind it) needs a cube map.
bool beyondOneMap(const Light& light, const ReceiverExtent& extent)
{
  return light.type == LightType::Point && extent.reachable > 0 && extent.minCosToAxis < std::cos(glm::radians(80.0));
}

void refusePointLightBeyondOneMap(
  const Light& light, const Scene& scene, const ReceiverExtent& extent, const FocusSettings& settings)
{
  if (!beyondOneMap(light, extent))
  {
    return;
  }
  // Name the light as the scene file does ("<file>: lights[i]: ..."); a light that is not one of the scene's
  // (a copy made by a pass) is named by its position alone.
  std::string where;
  for (std::size_t i = 0; i < scene.lights.size(); ++i)
  {
    if (&scene.lights[i] == &light)
    {
      where = format(scene.file.empty() ? "" : scene.file.string() + ": ", "lights[", i, "]: ");
    }
  }
  throw InputError(format(settings.beyondOneMapPrefix, where, "point light at (", light.center.x, ", ",
    light.center.y, ", ", light.center.z, ") sees visible receivers more than 80 degrees off its axis; one shadow map "
    "cannot cover them", settings.beyondOneMapAdvice));
}

// The receivers' window in light x/y ({xMin, xMax, yMin, yMax}) and their depth range, never empty.
struct ReceiverWindow
{
  glm::dvec4 window{ 0.0 };
  double nearDepth = 0.0;
  double farDepth = 0.0;
};
ReceiverWindow receiverWindow(const ReceiverExtent& extent)
{
  ReceiverWindow result{ { extent.minXY.x, extent.maxXY.x, extent.minXY.y, extent.maxXY.y }, extent.minDepth,
    extent.maxDepth };
  if (extent.inFront == 0 || result.farDepth <= 0.0)
  {
    // Nothing visible can receive light: keep a valid (tiny) frustum so every stage still runs.
    result = { { -1e-3, 1e-3, -1e-3, 1e-3 }, 1.0, 2.0 };
  }
  // Degenerate extents (a single receiver point) still need a non-empty window.
  glm::dvec4& window = result.window;
  const double minExtent = 1e-6 * std::max({ 1.0, std::abs(window.y), std::abs(window.w) });
  if (window.y - window.x < minExtent)
  {
    window.x -= minExtent;
    window.y += minExtent;
  }
  if (window.w - window.z < minExtent)
  {
    window.z -= minExtent;
    window.w += minExtent;
  }
  return result;
}

// The near plane: the nearest depth of the receivers and of the casters clipped to the frustum of `window` (only
// the part inside can occlude), in front of `depthEpsilon` and before the receivers' far depth.
double nearestDepthIn(const Scene& scene, const LightView& view, const glm::dvec4& window,
  const ReceiverWindow& receivers, double depthEpsilon)
{
  double nearest = receivers.nearDepth;
  std::vector<glm::dvec4> sidePlanes; // in light view space, dot(plane, (p, 1)) >= 0 inside
  if (view.projection == LightProjection::Perspective)
  {
    // x >= xMin * depth  <=>  x + xMin * z >= 0 (z = -depth), etc.
    sidePlanes = { { 1.0, 0.0, window.x, 0.0 }, { -1.0, 0.0, -window.y, 0.0 }, { 0.0, 1.0, window.z, 0.0 },
      { 0.0, -1.0, -window.w, 0.0 } };
  }
  else
  {
    sidePlanes = { { 1.0, 0.0, 0.0, -window.x }, { -1.0, 0.0, 0.0, window.y }, { 0.0, 1.0, 0.0, -window.z },
      { 0.0, -1.0, 0.0, window.w } };
  }
  const glm::dvec4 inFrontPlane(0.0, 0.0, -1.0, -depthEpsilon);     // depth >= depthEpsilon
  const glm::dvec4 beforeFarPlane(0.0, 0.0, 1.0, receivers.farDepth); // depth <= the receivers' far depth
  std::vector<glm::dvec4> planes = sidePlanes;
  planes.push_back(beforeFarPlane);
  if (view.projection == LightProjection::Perspective)
  {
    planes.push_back(inFrontPlane);
  }
  for (const SceneObject& object : scene.objects)
  {
    if (!object.castShadows)
    {
      continue;
    }
    const TriangleMesh& mesh = object.mesh;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
    {
      std::array<glm::dvec3, 3> triangle;
      for (int k = 0; k < 3; ++k)
      {
        const glm::dvec3 pWs(mesh.positions[mesh.indices[3 * t + k]]);
        triangle[static_cast<std::size_t>(k)] = glm::dvec3(view.viewFromWorld * glm::dvec4(pWs, 1.0));
      }
      // Most triangles lie wholly inside every plane or wholly outside one (clipPolygon's own test, dot >= 0): the
      // clip would keep them unchanged or empty, so only those that straddle a plane are clipped (the fence's 63k
      // triangles, fitted twice for shadow_map_size = auto, made this loop most of the focus stage).
      bool inside = true;
      bool outside = false;
      for (const glm::dvec4& plane : planes)
      {
        int in = 0;
        for (const glm::dvec3& pLs : triangle)
        {
          in += glm::dot(plane, glm::dvec4(pLs, 1.0)) >= 0.0 ? 1 : 0;
        }
        inside = inside && in == 3;
        outside = outside || in == 0;
      }
      if (outside)
      {
        continue;
      }
      if (inside)
      {
        for (const glm::dvec3& pLs : triangle)
        {
          nearest = std::min(nearest, -pLs.z);
        }
        continue;
      }
      std::vector<glm::dvec3> polygon(triangle.begin(), triangle.end());
      if (view.projection == LightProjection::Perspective)
      {
        polygon = clipPolygon(polygon, inFrontPlane);
      }
      polygon = clipPolygon(polygon, beforeFarPlane);
      for (const glm::dvec4& plane : sidePlanes)
      {
        if (polygon.empty())
        {
          break;
        }
        polygon = clipPolygon(polygon, plane);
      }
      for (const glm::dvec3& pLs : polygon)
      {
        nearest = std::min(nearest, -pLs.z);
      }
    }
  }
  return nearest;
}

// The window grown so that `marginTexels` texels of the final map lie outside it on each side, the depth range with
// a little slack (geometry exactly at its ends is not clipped by the rasteriser), and the projection.
void setWindowAndProjection(LightView& view, const glm::dvec4& window, double nearDepth, double receiverFar,
  double depthEpsilon, const FocusSettings& settings)
{
  if (settings.snapToTexels && view.projection == LightProjection::Orthographic)
  {
    view.window = snappedWindow(window, settings.resolution, settings.marginTexels);
  }
  else
  {
    const double grow = settings.resolution / (settings.resolution - 2.0 * settings.marginTexels);
    const double xCenter = 0.5 * (window.x + window.y);
    const double yCenter = 0.5 * (window.z + window.w);
    const double xHalf = 0.5 * (window.y - window.x) * grow;
    const double yHalf = 0.5 * (window.w - window.z) * grow;
    view.window = { xCenter - xHalf, xCenter + xHalf, yCenter - yHalf, yCenter + yHalf };
  }

  view.nearDepth = std::max(depthEpsilon, nearDepth * (1.0 - 1e-3));
  view.farDepth = receiverFar * (1.0 + 1e-3) + depthEpsilon;
  if (view.projection == LightProjection::Orthographic)
  {
    view.nearDepth = nearDepth - 1e-3 * (receiverFar - nearDepth) - depthEpsilon;
  }

  view.setProjectionFromWindow();
}

glm::dmat4 matrixFromRows(const glm::dvec4& r0, const glm::dvec4& r1, const glm::dvec4& r2, const glm::dvec4& r3)
{
  return glm::transpose(glm::dmat4(r0, r1, r2, r3));
}

glm::dvec4 matrixRow(const glm::dmat4& m, int row)
{
  return { m[0][row], m[1][row], m[2][row], m[3][row] };
}

// Survey §4.2: the focused orthographic view warped by P (PerspectiveWarp.h). Three more receiver reductions: their
// eye depth range (z_n, z_f), their range along P's axis (B's length L) and their extent in the warped map.
void applyPerspectiveWarp(const Light& light, ReceiverSource& receivers, const FocusSettings& settings, LightView& view)
{
  const WarpKind kind = settings.warp.kind;
  requireWarpableLight(kind, light.type);
  SL_CHECK_MSG(settings.camera != nullptr, "a warp needs the camera");
  const CameraView& camera = *settings.camera;
  PerspectiveWarp& warp = view.warp;
  warp.kind = kind;

  // γ: the angle between the view and light directions; P's axis is the view direction on the light's image plane.
  const glm::dmat4 worldFromCamera = glm::inverse(camera.viewFromWorld);
  const glm::dvec3 eyeWs(worldFromCamera[3]);
  const glm::dvec3 viewLs = glm::dmat3(view.viewFromWorld) * -glm::normalize(glm::dvec3(worldFromCamera[2]));
  const double sinGamma = std::min(1.0, glm::length(glm::dvec2(viewLs)));
  warp.gammaDeg = glm::degrees(std::acos(std::clamp(-viewLs.z, -1.0, 1.0)));
  const glm::dvec2 axis = sinGamma > 1e-9 ? glm::dvec2(viewLs) / glm::length(glm::dvec2(viewLs)) : glm::dvec2(0.0, 1.0);
  const glm::dvec2 lateral(axis.y, -axis.x);
  const glm::dmat4 axisFromLight = matrixFromRows({ lateral, 0.0, 0.0 }, { axis, 0.0, 0.0 }, { 0.0, 0.0, 1.0, 0.0 },
    { 0.0, 0.0, 0.0, 1.0 });

  LightView probe = view;
  probe.projection = LightProjection::Orthographic;
  probe.viewFromWorld = camera.viewFromWorld; // depthLin = eye depth
  const ReceiverExtent eyeDepths = receivers.extent(light, probe, glm::dvec3(0.0, 0.0, -1.0));
  probe.viewFromWorld = axisFromLight * view.viewFromWorld; // y = the coordinate along P's axis
  const ReceiverExtent alongAxis = receivers.extent(light, probe, glm::dvec3(0.0, 0.0, -1.0));
  warp.zNear = eyeDepths.inFront > 0 ? std::max(eyeDepths.minDepth, camera.nearDepth) : camera.nearDepth;
  warp.zFar = std::max(eyeDepths.inFront > 0 ? eyeDepths.maxDepth : camera.farDepth, warp.zNear * (1.0 + 1e-9));
  const double axisNear = alongAxis.inFront > 0 ? alongAxis.minXY.y : 0.0;
  const double axisFar = alongAxis.inFront > 0 ? alongAxis.maxXY.y : 1.0;
  const double bodyLength = std::max(axisFar - axisNear, 1e-9 * std::max({ 1.0, std::abs(axisNear), std::abs(axisFar) }));
  const double eyeLateral = (axisFromLight * view.viewFromWorld * glm::dvec4(eyeWs, 1.0)).x;

  warp.nOpt = warpParameter(WarpKind::Lispsm, warp.zNear, warp.zFar, bodyLength, sinGamma);
  warp.n = settings.warp.n > 0.0 ? settings.warp.n : warpParameter(kind, warp.zNear, warp.zFar, bodyLength, sinGamma);
  warp.nearDistance = warp.n;
  warp.farDistance = warp.n + bodyLength;
  const WarpRows rows = warpRows(warp.n, bodyLength);
  // (p, u, 1) from light view coordinates: p lateral from the eye, u past B's near side along the axis.
  const glm::dvec4 pRow(lateral, 0.0, -eyeLateral);
  const glm::dvec4 uRow(axis, 0.0, -axisNear);
  const glm::dvec4 oneRow(0.0, 0.0, 0.0, 1.0);
  const auto combine = [&](const glm::dvec3& r) { return r.x * pRow + r.y * uRow + r.z * oneRow; };
  const glm::dvec4 xRow = combine(rows.x);
  const glm::dvec4 tRow = combine(rows.t);
  const glm::dvec4 wRow = combine(rows.w);

  // The receivers' extent in the warped map (x = X / W, y = T / W, depth = W), then the focus's texel margin.
  probe.projection = LightProjection::Perspective;
  probe.viewFromWorld = matrixFromRows(xRow, tRow, -wRow, oneRow) * view.viewFromWorld;
  const ReceiverExtent warped = receivers.extent(light, probe, glm::dvec3(0.0, 0.0, -1.0));
  glm::dvec4 window = warped.inFront > 0 ? glm::dvec4(warped.minXY.x, warped.maxXY.x, warped.minXY.y, warped.maxXY.y)
                                         : glm::dvec4(-1.0, 1.0, 0.0, 1.0);
  const double grow = settings.resolution / (settings.resolution - 2.0 * settings.marginTexels);
  for (int axisIndex = 0; axisIndex < 2; ++axisIndex)
  {
    const double lo = window[2 * axisIndex];
    const double hi = window[2 * axisIndex + 1];
    const double half = 0.5 * std::max(hi - lo, 1e-9 * std::max({ 1.0, std::abs(lo), std::abs(hi) })) * grow;
    window[2 * axisIndex] = 0.5 * (lo + hi) - half;
    window[2 * axisIndex + 1] = 0.5 * (lo + hi) + half;
  }

  // Clip z: the unwarped orthographic z scaled by W at the map's near edge, so |z / w| <= 1 holds for every depth in
  // [near, far] over the whole map (W grows along the axis). The depth buffer itself holds the orthographic window
  // depth (the light depth pass writes it), which orders every light ray's casters as before.
  const double strength = rows.w.y;
  const double nearEdgeU = window.z / (rows.t.y - window.z * strength);
  const double nearEdgeW = 1.0 + strength * nearEdgeU;
  SL_CHECK_MSG(nearEdgeW > 0.0 && std::isfinite(nearEdgeW), "the warp's projection centre lies inside the map");
  const glm::dvec4 clipX = (2.0 * xRow - (window.x + window.y) * wRow) / (window.y - window.x);
  const glm::dvec4 clipY = (2.0 * tRow - (window.z + window.w) * wRow) / (window.w - window.z);
  const glm::dvec4 clipZ = nearEdgeW * matrixRow(view.clipFromView, 2);
  view.clipFromWorld = matrixFromRows(clipX, clipY, clipZ, wRow) * view.viewFromWorld;
}

} // namespace

bool oneMapCovers(const Light& light, const Scene& scene, ReceiverSource& receivers)
{
  if (light.type != LightType::Point)
  {
    return true;
  }
  receivers.setOwnerPlanes({});
  LightView view;
  glm::dvec3 forward;
  orientLightView(light, scene, receivers.summary(light), glm::dvec3(0.0), view, forward);
  return !beyondOneMap(light, receivers.extent(light, view, forward));
}

// Focusing (survey §4.3): the light's frame, the receivers' window in it, the casters' near plane within that
// window (grown by the light's footprint for soft shadows), then a margin and the projection.
LightView fitLightView(const Light& light, const Scene& scene, ReceiverSource& receivers, const FocusSettings& settings)
{
  SL_CHECK(settings.resolution > 2.0 * settings.marginTexels);
  // Only the receivers this view owns (a cascade's slice); lifted however the fit ends.
  struct OwnerScope
  {
    ReceiverSource& source;
    ~OwnerScope() { source.setOwnerPlanes({}); }
  } ownerScope{ receivers };
  receivers.setOwnerPlanes(settings.ownerPlanes);
  // A fixed axis needs no bounding box to aim at.
  const bool aimed = light.type == LightType::Point && settings.perspectiveAxis == glm::dvec3(0.0);
  const ReceiverSummary summary = aimed ? receivers.summary(light) : ReceiverSummary();

  LightView view;
  view.resolution = settings.resolution;
  glm::dvec3 forward;
  orientLightView(light, scene, summary, settings.perspectiveAxis, view, forward);

  const ReceiverExtent extent = receivers.extent(light, view, forward);
  view.receiverSampleCount = extent.reachable;
  refusePointLightBeyondOneMap(light, scene, extent, settings);
  const ReceiverWindow receiverRange = receiverWindow(extent);
  glm::dvec4 window = receiverRange.window;

  // Depth range: receivers, plus casters clipped to the frustum of the window; the window may still grow.
  const double depthEpsilon = 1e-5 * receiverRange.farDepth;
  double nearDepth = nearestDepthIn(scene, view, window, receiverRange, depthEpsilon);
  if (settings.lightFootprintWidth > 0.0 && view.projection == LightProjection::Perspective)
  {
    // Soft shadows: a caster at depth z >= near hides part of a light of width w from a receiver when
    // its tangent is within (w / 2) (d - z) / (z d) < (w / 2) / near of the receiver's (similar
    // triangles), so the window must hold that much more around the receivers. One refinement: the
    // grown window's casters give the near plane (a caster nearer still, outside the first window, is
    // the approximation's limit).
    const double extra = 0.5 * settings.lightFootprintWidth / std::max(nearDepth, depthEpsilon);
    window += glm::dvec4(-extra, extra, -extra, extra);
    nearDepth = nearestDepthIn(scene, view, window, receiverRange, depthEpsilon);
  }
  setWindowAndProjection(view, window, nearDepth, receiverRange.farDepth, depthEpsilon, settings);
  if (settings.warp.kind != WarpKind::None)
  {
    applyPerspectiveWarp(light, receivers, settings, view);
  }
  return view;
}

} // namespace sl
