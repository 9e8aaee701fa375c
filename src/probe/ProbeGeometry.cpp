#include "probe/ProbeGeometry.h"

#include "core/Error.h"
#include "lightspace/ShadowMapMath.h"

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace sl
{
namespace
{

// The same helper fitLightView uses to orient a spot or point light's view (LightView.cpp).
glm::dvec3 anyPerpendicular(const glm::dvec3& axis)
{
  const glm::dvec3 helper = std::abs(axis.y) < 0.9 ? glm::dvec3(0.0, 1.0, 0.0) : glm::dvec3(1.0, 0.0, 0.0);
  return glm::normalize(helper - axis * glm::dot(helper, axis));
}

glm::dvec3 vectorOf(const ProbeQuantity* quantity, const glm::dvec3& fallback)
{
  if (quantity == nullptr || quantity->value.size() != 3)
  {
    return fallback;
  }
  return { quantity->value[0], quantity->value[1], quantity->value[2] };
}

glm::dvec3 gbufferVector(const FrameResult& frame, const char* buffer, glm::ivec2 pixel, const glm::dvec3& fallback)
{
  const NamedImage* named = frame.find(buffer);
  if (named == nullptr || named->image.components < 3 || pixel.x < 0 || pixel.y < 0 ||
    pixel.x >= named->image.width || pixel.y >= named->image.height)
  {
    return fallback;
  }
  return { named->image.at(pixel.x, pixel.y, 0), named->image.at(pixel.x, pixel.y, 1),
    named->image.at(pixel.x, pixel.y, 2) };
}

// The distinct values of `label` over `items`, in order of first appearance.
template <typename Item>
std::vector<std::string> labelsInOrder(const std::vector<Item>& items, std::string Item::*label)
{
  std::vector<std::string> labels;
  for (const Item& item : items)
  {
    if (std::find(labels.begin(), labels.end(), item.*label) == labels.end())
    {
      labels.push_back(item.*label);
    }
  }
  return labels;
}

} // namespace

glm::dvec3 ProbeLightFrame::worldFromLight(const glm::dvec2& lightXY) const
{
  return glm::dvec3(worldFromView * glm::dvec4(lightXY, 0.0, 1.0));
}

glm::dvec2 ProbeLightFrame::lightFromWorld(const glm::dvec3& pWs) const
{
  return glm::dvec2(viewFromWorld * glm::dvec4(pWs, 1.0));
}

std::vector<PartitionView> partitionViewsOf(const FrameResult& frame)
{
  std::vector<PartitionView> views;
  if (frame.partitions)
  {
    const PartitionSet& partitions = *frame.partitions;
    for (int k = 0; k < partitions.viewCount(); ++k)
    {
      const std::string label = partitionViewLabel(partitions, k);
      if (partitions.kind == PartitionKind::Cascades)
      {
        const glm::dvec2 range(partitions.splits.at(static_cast<std::size_t>(k)),
          partitions.splits.at(static_cast<std::size_t>(k) + 1));
        views.push_back({ &partitions.views[static_cast<std::size_t>(k)], partitionViewSuffix(partitions, k),
          format(label, " of ", partitions.viewCount(), ", eye depth ", range.x, " .. ", range.y), range });
      }
      else
      {
        views.push_back({ &partitions.views[static_cast<std::size_t>(k)], partitionViewSuffix(partitions, k),
          format(label, " of ", partitions.viewCount()), glm::dvec2(0.0) });
      }
    }
  }
  else if (frame.lightView)
  {
    views.push_back({ &*frame.lightView, "", "", glm::dvec2(0.0) });
  }
  return views;
}

ViewSelection partitionSelectionAt(const FrameResult& frame, glm::ivec2 pixel)
{
  const NamedImage* position = frame.find("position");
  if (!frame.partitions || position == nullptr)
  {
    return {};
  }
  const ImageF& p = position->image;
  return selectView(
    *frame.partitions, frame.camera, glm::dvec3(p.at(pixel.x, pixel.y, 0), p.at(pixel.x, pixel.y, 1), p.at(pixel.x, pixel.y, 2)));
}

ProbeMap probeMapOf(const FrameResult& frame, glm::ivec2 pixel)
{
  const std::vector<PartitionView> views = partitionViewsOf(frame);
  if (views.empty())
  {
    return {};
  }
  const PartitionView& partition =
    views.size() == 1 ? views.front() : views.at(static_cast<std::size_t>(partitionSelectionAt(frame, pixel).primary));
  ProbeMap map;
  map.view = partition.view;
  map.exportName = "shadow_map_depth" + partition.exportSuffix;
  map.label = partition.label;
  const NamedImage* named = findNamed(frame.lightSpace, map.exportName);
  map.depth = named != nullptr && !named->image.empty() ? &named->image : nullptr;
  return map;
}

ProbeLightFrame probeLightFrame(const LightView* view, const Scene& scene, const Light& light,
  const glm::dvec3& receiverWs)
{
  ProbeLightFrame result;
  if (view != nullptr)
  {
    result.viewFromWorld = view->viewFromWorld;
    result.orthographic = view->projection == LightProjection::Orthographic;
  }
  else
  {
    // No shadow map (an object-space technique): the frame fitLightView would have chosen.
    glm::dvec3 eye = light.center;
    glm::dvec3 forward = light.normal;
    glm::dvec3 up = light.up;
    switch (light.type)
    {
      case LightType::Area:
        break;
      case LightType::Spot:
        up = anyPerpendicular(forward);
        break;
      case LightType::Point:
      {
        const glm::dvec3 toward = receiverWs - light.center;
        forward = glm::length(toward) > 1e-12 ? glm::normalize(toward) : glm::dvec3(0.0, -1.0, 0.0);
        up = anyPerpendicular(forward);
        break;
      }
      case LightType::Directional:
        forward = light.direction;
        up = anyPerpendicular(forward);
        eye = receiverWs - forward * (2.0 * scene.bounds().radius() + 1.0);
        result.orthographic = true;
        break;
    }
    result.viewFromWorld = glm::lookAt(eye, eye + forward, up);
  }
  result.worldFromView = glm::inverse(result.viewFromWorld);
  result.eyeWs = glm::dvec3(result.worldFromView * glm::dvec4(0.0, 0.0, 0.0, 1.0));
  result.axisWs = glm::normalize(glm::dvec3(result.worldFromView * glm::dvec4(0.0, 0.0, -1.0, 0.0)));
  return result;
}

std::vector<glm::dvec3> lightOutline(const Light& light, int diskSegments)
{
  if (light.type != LightType::Area)
  {
    return {};
  }
  const glm::dvec3 right = light.right();
  const double half = 0.5 * light.size;
  std::vector<glm::dvec3> outline;
  if (light.shape == LightShape::Square)
  {
    for (const glm::dvec2& corner : { glm::dvec2(-1, -1), glm::dvec2(1, -1), glm::dvec2(1, 1), glm::dvec2(-1, 1) })
    {
      outline.push_back(light.center + half * (corner.x * right + corner.y * light.up));
    }
    return outline;
  }
  SL_CHECK(diskSegments >= 3);
  for (int i = 0; i < diskSegments; ++i)
  {
    const double angle = glm::two_pi<double>() * i / diskSegments;
    outline.push_back(light.center + half * (std::cos(angle) * right + std::sin(angle) * light.up));
  }
  return outline;
}

glm::dvec3 worldFromTexel(const LightView& view, const glm::dvec2& uvTexels, double depthLin)
{
  const glm::dvec2 ndc = uvTexels / static_cast<double>(view.resolution) * 2.0 - 1.0;
  if (view.warp.active())
  {
    // A warped map (survey §4.2, directional lights): the light-view point (x, y, -depthLin) whose clip.xy equals
    // ndc clip.w, two linear equations in x and y.
    const glm::dmat4 clipFromLight = view.clipFromWorld * glm::inverse(view.viewFromWorld);
    const auto row = [&](int r) {
      return glm::dvec4(clipFromLight[0][r], clipFromLight[1][r], clipFromLight[2][r], clipFromLight[3][r]);
    };
    const glm::dvec4 rowU = row(0) - ndc.x * row(3);
    const glm::dvec4 rowV = row(1) - ndc.y * row(3);
    const double rhsU = rowU.z * depthLin - rowU.w;
    const double rhsV = rowV.z * depthLin - rowV.w;
    const double determinant = rowU.x * rowV.y - rowU.y * rowV.x;
    const glm::dvec4 pLs((rhsU * rowV.y - rhsV * rowU.y) / determinant, (rowU.x * rhsV - rowV.x * rhsU) / determinant,
      -depthLin, 1.0);
    return glm::dvec3(glm::inverse(view.viewFromWorld) * pLs);
  }
  glm::dvec4 pLs = glm::inverse(view.clipFromView) * glm::dvec4(ndc, 0.0, 1.0);
  pLs /= pLs.w;
  if (view.projection == LightProjection::Perspective)
  {
    // A point on the texel's ray; scale it along the ray (through the eye) to the asked depth.
    const double scale = depthLin / -pLs.z;
    pLs = glm::dvec4(glm::dvec3(pLs) * scale, 1.0);
  }
  else
  {
    pLs.z = -depthLin;
  }
  return glm::dvec3(glm::inverse(view.viewFromWorld) * pLs);
}

const ProbeQuantity* findQuantity(const ProbeRecord& record, const std::string& group, const std::string& name)
{
  for (const ProbeQuantity& quantity : record.quantities)
  {
    if (quantity.group == group && quantity.name == name)
    {
      return &quantity;
    }
  }
  return nullptr;
}

ProbeReceiver probeReceiver(const ProbeResult& probe, const FrameResult& frame, const ProbeMap& map,
  const ProbeLightFrame& lightFrame)
{
  const ProbeRecord& record = probe.record;
  ProbeReceiver receiver;
  receiver.position = vectorOf(findQuantity(record, "receiver", "position"),
    gbufferVector(frame, "position", probe.pixel, glm::dvec3(0.0)));
  receiver.normal = vectorOf(findQuantity(record, "receiver", "normal"),
    gbufferVector(frame, "normal", probe.pixel, glm::dvec3(0.0, 0.0, 1.0)));
  const glm::dvec4 pLs = lightFrame.viewFromWorld * glm::dvec4(receiver.position, 1.0);
  receiver.depthLin = -pLs.z;
  if (const ProbeQuantity* depth = findQuantity(record, "receiver", "receiver_depth"); depth && depth->value.size() == 1)
  {
    receiver.depthLin = depth->value[0];
  }
  if (const ProbeQuantity* uv = findQuantity(record, "receiver", "shadow_map_position"); uv && uv->value.size() == 2)
  {
    receiver.uvTexels = glm::dvec2(uv->value[0], uv->value[1]);
  }
  else if (map.view != nullptr)
  {
    receiver.uvTexels = projectToShadowMap(*map.view, receiver.position).uvTexels;
  }
  if (const ProbeQuantity* bias = findQuantity(record, "receiver", "depth_bias"); bias && bias->value.size() == 1)
  {
    receiver.bias = bias->value[0];
  }
  return receiver;
}

ProbeSetting probeSetting(const ProbeResult& probe, const FrameResult& frame, const Scene& scene)
{
  ProbeSetting setting;
  setting.light = &scene.lights.at(static_cast<std::size_t>(probe.lightIndex));
  // The receiver's position does not depend on the light frame; a light without a view needs it for its frame.
  const glm::dvec3 position = vectorOf(findQuantity(probe.record, "receiver", "position"),
    gbufferVector(frame, "position", probe.pixel, glm::dvec3(0.0)));
  setting.map = probeMapOf(frame, probe.pixel);
  setting.lightFrame = probeLightFrame(setting.map.view, scene, *setting.light, position);
  setting.receiver = probeReceiver(probe, frame, setting.map, setting.lightFrame);
  return setting;
}

bool isEmptyShadowMapTexel(const LightView& view, double storedDepth)
{
  return !(storedDepth <= 1.5 * view.farDepth);
}

TexelRect probeShadowMapCrop(const ProbeRecord& record, const std::optional<glm::dvec2>& receiverTexel, int mapSize)
{
  glm::ivec2 lo(std::numeric_limits<int>::max());
  glm::ivec2 hi(std::numeric_limits<int>::min());
  const auto include = [&](glm::ivec2 first, glm::ivec2 last) {
    lo = glm::min(lo, first);
    hi = glm::max(hi, last);
  };
  // Texel coordinates are clamped to +-2 map sides first so that a wild kernel cannot overflow an int.
  const auto texelOf = [&](double coordinate) {
    return static_cast<int>(std::floor(std::clamp(coordinate, -2.0 * mapSize, 3.0 * mapSize)));
  };
  for (const ProbeTexel& texel : record.texels)
  {
    include(texel.texel, texel.texel);
  }
  for (const ProbeKernel& kernel : record.kernels)
  {
    const glm::ivec2 first(texelOf(kernel.lo.x), texelOf(kernel.lo.y));
    // hi is the rectangle's far edge: the last texel it covers ends there.
    const glm::ivec2 last(texelOf(std::ceil(kernel.hi.x) - 1.0), texelOf(std::ceil(kernel.hi.y) - 1.0));
    include(first, glm::max(first, last));
  }
  if (receiverTexel)
  {
    const glm::ivec2 texel(texelOf(receiverTexel->x), texelOf(receiverTexel->y));
    include(texel, texel);
    // The pixel's footprint, up to 32 texels around the receiver (an oversampled pixel's covers many; past that
    // the crop would shrink the texel it reads out of sight, and the polygon is clipped instead).
    for (const ProbeMapPolygon& polygon : record.mapPolygons)
    {
      for (const glm::dvec2& point : polygon.points)
      {
        const glm::dvec2 near = glm::clamp(point, *receiverTexel - 32.0, *receiverTexel + 32.0);
        const glm::ivec2 corner(texelOf(near.x), texelOf(near.y));
        include(corner, corner);
      }
    }
  }
  if (lo.x > hi.x || mapSize <= 0)
  {
    return {};
  }
  const int margin = std::max(4, std::max(hi.x - lo.x + 1, hi.y - lo.y + 1) / 8);
  lo = glm::max(lo - margin, glm::ivec2(0));
  hi = glm::min(hi + margin, glm::ivec2(mapSize - 1));
  if (lo.x > hi.x || lo.y > hi.y)
  {
    return {};
  }
  TexelRect crop{ lo, hi - lo + 1 };
  for (int axis = 0; axis < 2; ++axis)
  {
    if (crop.size[axis] > kMaxProbeCropSide)
    {
      const int centre = receiverTexel ? texelOf((*receiverTexel)[axis]) : (lo[axis] + hi[axis]) / 2;
      crop.lo[axis] = std::clamp(centre - kMaxProbeCropSide / 2, lo[axis], hi[axis] + 1 - kMaxProbeCropSide);
      crop.size[axis] = kMaxProbeCropSide;
    }
  }
  return crop;
}

ProbeCropArrays probeCropArrays(const ProbeRecord& record, const ImageF& shadowMapDepth, const TexelRect& crop)
{
  SL_CHECK(!crop.empty() && crop.lo.x >= 0 && crop.lo.y >= 0 && crop.lo.x + crop.size.x <= shadowMapDepth.width &&
    crop.lo.y + crop.size.y <= shadowMapDepth.height);
  ProbeCropArrays arrays;
  arrays.crop = crop;
  const int width = crop.size.x;
  const int height = crop.size.y;
  arrays.depth = shadowMapDepth.channels(0, 1).crop(crop.lo.x, crop.lo.y, width, height);
  arrays.read = Image<std::uint8_t>(width, height, 1, 0);
  arrays.compared = Image<std::uint8_t>(width, height, 1, 0);
  arrays.occluding = Image<std::uint8_t>(width, height, 1, 0);
  arrays.weight = ImageF(width, height, 1, 0.0f);
  arrays.visitedLevel = Image<int>(width, height, 1, -1);
  for (const ProbeTexel& texel : record.texels)
  {
    if (!crop.contains(texel.texel))
    {
      continue;
    }
    const glm::ivec2 local = texel.texel - crop.lo;
    arrays.read.at(local.x, local.y) = 1;
    if (!std::isnan(texel.comparedDepth))
    {
      arrays.compared.at(local.x, local.y) = 1;
    }
    if (texel.occluding)
    {
      arrays.occluding.at(local.x, local.y) = 1;
    }
    arrays.weight.at(local.x, local.y) += static_cast<float>(texel.weight);
  }
  // The smallest visited node over each texel: the deepest the traversal went there, whichever way a structure
  // numbers its levels.
  Image<double> smallestArea(width, height, 1, std::numeric_limits<double>::infinity());
  for (const ProbeNode& node : record.nodes)
  {
    const glm::ivec2 first = glm::max(node.lo, crop.lo);
    const glm::ivec2 last = glm::min(node.hi, crop.lo + crop.size - 1);
    const double area = (static_cast<double>(node.hi.x) - node.lo.x + 1.0) * (static_cast<double>(node.hi.y) - node.lo.y + 1.0);
    for (int y = first.y; y <= last.y; ++y)
    {
      for (int x = first.x; x <= last.x; ++x)
      {
        const glm::ivec2 local = glm::ivec2(x, y) - crop.lo;
        if (area < smallestArea.at(local.x, local.y))
        {
          smallestArea.at(local.x, local.y) = area;
          arrays.visitedLevel.at(local.x, local.y) = node.level;
        }
      }
    }
  }
  return arrays;
}

std::vector<std::string> nodeDecisionLabels(const ProbeRecord& record)
{
  return labelsInOrder(record.nodes, &ProbeNode::decision);
}

std::vector<std::string> kernelRoleLabels(const ProbeRecord& record)
{
  return labelsInOrder(record.kernels, &ProbeKernel::role);
}

std::vector<std::string> polygonRoleLabels(const ProbeRecord& record)
{
  return labelsInOrder(record.lightPolygons, &ProbeLightPolygon::role);
}

int labelCode(const std::vector<std::string>& labels, const std::string& label)
{
  const auto found = std::find(labels.begin(), labels.end(), label);
  return found == labels.end() ? -1 : static_cast<int>(found - labels.begin());
}

glm::dvec2 ProbeSection::toSection(const glm::dvec3& pWs) const
{
  const glm::dvec3 offset = pWs - origin;
  return { glm::dot(offset, across), glm::dot(offset, towardLight) };
}

glm::dvec3 ProbeSection::toWorld(const glm::dvec2& section) const
{
  return origin + section.x * across + section.y * towardLight;
}

ProbeSection probeSection(const glm::dvec3& lightCentre, const glm::dvec3& lightAxis, const glm::dvec3& receiver,
  const glm::dvec3& receiverNormal)
{
  ProbeSection section;
  section.origin = lightCentre;
  const glm::dvec3 axis = glm::normalize(lightAxis);
  const glm::dvec3 toReceiver = receiver - lightCentre;
  const double distance = glm::length(toReceiver);
  glm::dvec3 normal = glm::cross(toReceiver, axis);
  if (glm::length(normal) <= 1e-9 * distance || distance == 0.0)
  {
    // The receiver lies on the axis: every plane through the axis holds both; take the one holding the normal.
    section.usesReceiverNormal = true;
    normal = glm::cross(axis, receiverNormal);
    if (glm::length(normal) <= 1e-9)
    {
      normal = anyPerpendicular(axis);
    }
  }
  section.normal = glm::normalize(normal);
  section.towardLight = glm::normalize(-axis + section.normal * glm::dot(axis, section.normal));
  section.across = glm::normalize(glm::cross(section.towardLight, section.normal));
  if (glm::dot(toReceiver, section.across) < 0.0)
  {
    section.across = -section.across;
    section.normal = -section.normal;
  }
  return section;
}

std::vector<SectionSegment> sceneSection(const Scene& scene, const ProbeSection& section)
{
  std::vector<SectionSegment> segments;
  for (std::size_t o = 0; o < scene.objects.size(); ++o)
  {
    const SceneObject& object = scene.objects[o];
    const TriangleMesh& mesh = object.mesh;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
    {
      glm::dvec3 corners[3];
      double side[3];
      for (int k = 0; k < 3; ++k)
      {
        corners[k] = glm::dvec3(mesh.positions[mesh.indices[3 * t + k]]);
        side[k] = glm::dot(corners[k] - section.origin, section.normal);
      }
      glm::dvec3 cut[2];
      int cuts = 0;
      for (int k = 0; k < 3 && cuts < 2; ++k)
      {
        const int next = (k + 1) % 3;
        if ((side[k] > 0.0) != (side[next] > 0.0))
        {
          cut[cuts++] = corners[k] + (corners[next] - corners[k]) * (side[k] / (side[k] - side[next]));
        }
      }
      if (cuts == 2)
      {
        segments.push_back({ section.toSection(cut[0]), section.toSection(cut[1]), o, object.castShadows });
      }
    }
  }
  return segments;
}

double lightHalfExtentInSection(const Light& light, const ProbeSection& section)
{
  if (light.type != LightType::Area)
  {
    return 0.0;
  }
  const double half = 0.5 * light.size;
  if (light.shape == LightShape::Disk)
  {
    return half;
  }
  // The chord through a square's centre along a unit direction w of its plane leaves it where the larger of
  // |w . right|, |w . up| reaches the half side.
  const double reach = std::max(std::abs(glm::dot(section.across, light.right())), std::abs(glm::dot(section.across, light.up)));
  return reach > 0.0 ? half / reach : half;
}

std::vector<SectionTexelColumn> sectionShadowMapColumns(
  const LightView& view, const ImageF& shadowMapDepth, const ProbeSection& section, const glm::dvec3& receiverWs)
{
  std::vector<SectionTexelColumn> columns;
  const int size = shadowMapDepth.width;
  if (size <= 0 || shadowMapDepth.height != size)
  {
    return columns;
  }
  // The section plane holds the light's eye (perspective) or its direction (orthographic), so its image in the
  // map is a line: the one through the receiver's texel position and that of a point beside it in the plane.
  const ShadowMapSample receiverSample = projectToShadowMap(view, receiverWs);
  const double step = 16.0 * view.texelWorldSize(std::max(receiverSample.depthLin, 1e-12));
  const glm::dvec2 start = receiverSample.uvTexels;
  const glm::dvec2 beside = projectToShadowMap(view, receiverWs + step * section.across).uvTexels;
  if (!(glm::length(beside - start) > 1e-9))
  {
    return columns;
  }
  const glm::dvec2 direction = glm::normalize(beside - start);
  // Liang-Barsky: the line's parameter range inside [0, size]^2.
  double tMin = -std::numeric_limits<double>::infinity();
  double tMax = std::numeric_limits<double>::infinity();
  for (int axis = 0; axis < 2; ++axis)
  {
    if (std::abs(direction[axis]) < 1e-15)
    {
      if (start[axis] < 0.0 || start[axis] > size)
      {
        return columns;
      }
      continue;
    }
    double t0 = (0.0 - start[axis]) / direction[axis];
    double t1 = (size - start[axis]) / direction[axis];
    if (t0 > t1)
    {
      std::swap(t0, t1);
    }
    tMin = std::max(tMin, t0);
    tMax = std::min(tMax, t1);
  }
  if (!(tMin < tMax))
  {
    return columns;
  }
  // Every parameter where the line crosses a texel edge, in order.
  std::vector<double> crossings{ tMin, tMax };
  for (int axis = 0; axis < 2; ++axis)
  {
    if (std::abs(direction[axis]) < 1e-15)
    {
      continue;
    }
    const double a = start[axis] + tMin * direction[axis];
    const double b = start[axis] + tMax * direction[axis];
    for (double edge = std::ceil(std::min(a, b)); edge <= std::max(a, b); edge += 1.0)
    {
      crossings.push_back((edge - start[axis]) / direction[axis]);
    }
  }
  std::sort(crossings.begin(), crossings.end());
  bool previousKept = false;
  for (std::size_t i = 0; i + 1 < crossings.size(); ++i)
  {
    const double t0 = crossings[i];
    const double t1 = crossings[i + 1];
    if (t1 - t0 < 1e-9)
    {
      continue;
    }
    const glm::dvec2 middle = start + 0.5 * (t0 + t1) * direction;
    const glm::ivec2 texel = glm::clamp(glm::ivec2(glm::floor(middle)), glm::ivec2(0), glm::ivec2(size - 1));
    const double stored = shadowMapDepth.at(texel.x, texel.y);
    if (isEmptyShadowMapTexel(view, stored))
    {
      previousKept = false;
      continue;
    }
    SectionTexelColumn column;
    column.texel = texel;
    column.storedDepth = stored;
    column.enter = section.toSection(worldFromTexel(view, start + t0 * direction, stored));
    column.exit = section.toSection(worldFromTexel(view, start + t1 * direction, stored));
    column.joinsPrevious = previousKept;
    columns.push_back(column);
    previousKept = true;
  }
  return columns;
}

} // namespace sl
