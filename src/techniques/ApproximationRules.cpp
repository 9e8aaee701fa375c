#include "techniques/ApproximationRules.h"

#include "core/Error.h"
#include "frame/FrameResult.h"
#include "lightspace/LightView.h"
#include "lightspace/ShadowMapMath.h"
#include "scene/RayTriangle.h"
#include "techniques/ProbeSupport.h"

#include <algorithm>
#include <cmath>

namespace sl
{

ShadowMapFootprint::ShadowMapFootprint(const ApproximationContext& context, int view)
  : inputs_(shadowMapInputsOf(*context.frame, *context.scene, context.lightIndex, false, view))
{
  SL_CHECK_MSG(!inputs_.shadowMapLinear.data.empty(), context.frame->technique, ": no shadow_map_depth export");
  const Light& light = *inputs_.light;
  lightSize_ = light.type == LightType::Area ? light.size : 0.0;
  // Level 0 is the map itself (read through minLevel/maxLevel): no copy of a map that is 16 MiB at the default size.
  // The min-max pyramid is built by the first question that reads it (casterRange, hiddenByMargin): hard's and pcf's
  // rules ask only depthTestMixed, which reads the map itself (at the default 2048^2 map the pyramid is ~0.1 s).
}

void ShadowMapFootprint::buildPyramid() const
{
  std::call_once(pyramidBuilt_, [this] {
    while (minLevel(levelCount() - 1).width > 1 && minLevel(levelCount() - 1).height > 1)
    {
      const ImageF& fineMin = minLevel(levelCount() - 1);
      const ImageF& fineMax = maxLevel(levelCount() - 1);
      ImageF coarseMin((fineMin.width + 1) / 2, (fineMin.height + 1) / 2, 1, 0.0f);
      ImageF coarseMax = coarseMin;
      for (int y = 0; y < coarseMin.height; ++y)
      {
        for (int x = 0; x < coarseMin.width; ++x)
        {
          float lo = 1e30f;
          float hi = -1e30f;
          for (int dy = 0; dy < 2; ++dy)
          {
            for (int dx = 0; dx < 2; ++dx)
            {
              const int fx = std::min(2 * x + dx, fineMin.width - 1);
              const int fy = std::min(2 * y + dy, fineMin.height - 1);
              lo = std::min(lo, fineMin.at(fx, fy));
              hi = std::max(hi, fineMax.at(fx, fy));
            }
          }
          coarseMin.at(x, y) = lo;
          coarseMax.at(x, y) = hi;
        }
      }
      coarseMinLevels_.push_back(std::move(coarseMin));
      coarseMaxLevels_.push_back(std::move(coarseMax));
    }
  });
}

std::optional<ShadowMapFootprint::Receiver> ShadowMapFootprint::receiver(int x, int y) const
{
  if (inputs_.coverage.at(x, y) <= 0.5f || inputs_.receives.at(x, y) <= 0.5f)
  {
    return std::nullopt;
  }
  const glm::dvec3 pWs(inputs_.position.at(x, y, 0), inputs_.position.at(x, y, 1), inputs_.position.at(x, y, 2));
  const glm::dvec3 nWs(inputs_.normal.at(x, y, 0), inputs_.normal.at(x, y, 1), inputs_.normal.at(x, y, 2));
  if (!lightCanReach(*inputs_.light, pWs, nWs))
  {
    return std::nullopt;
  }
  Receiver receiver;
  receiver.sample = projectToShadowMap(inputs_.lightView, pWs);
  if (!(receiver.sample.depthLin > 0.0))
  {
    return std::nullopt;
  }
  // The receiver's own surface, sampled up to a texel away on a slope (the default bias's rule, ShadowMapMath.h).
  const double tanTheta = tanAngleToLight(nWs, directionToLight(*inputs_.light, pWs));
  receiver.margin =
    receiverTexelWorldSize(inputs_.lightView, pWs, receiver.sample.depthLin) * (1.0 + 2.0 * std::min(tanTheta, 10.0));
  return receiver;
}

ShadowMapFootprint::CasterRange ShadowMapFootprint::casterRange(int x, int y) const
{
  buildPyramid();
  CasterRange range;
  const std::optional<Receiver> point = receiver(x, y);
  if (!point)
  {
    return range;
  }
  const LightView& view = inputs_.lightView;
  const double d = point->sample.depthLin;
  const double threshold = d - point->margin;
  const int resolution = inputs_.shadowMapLinear.width;
  // Texels per unit of light-space x/y (tangents for a perspective light).
  const glm::dvec2 texelsPerUnit(resolution / (view.window.y - view.window.x), resolution / (view.window.w - view.window.z));
  const bool perspective = view.projection == LightProjection::Perspective;
  const auto halfWidth = [&](double z) {
    // Orthographic (directional) lights have no area: only the point's own texel.
    return perspective ? 0.5 * lightSize_ * std::max(0.0, d - z) / (d * std::max(z, 1e-12)) : 0.0;
  };
  const double largest = halfWidth(std::max(view.nearDepth, 1e-6));
  const glm::dvec2 radius = glm::dvec2(largest) * texelsPerUnit + glm::dvec2(1.0);
  int level = 0;
  while (level + 1 < levelCount() && std::max(radius.x, radius.y) / double(1 << level) > 16.0)
  {
    ++level;
  }
  const ImageF& mins = minLevel(level);
  const ImageF& maxs = maxLevel(level);
  const double scale = 1.0 / double(1 << level);
  const glm::dvec2 centre = point->sample.uvTexels;
  const int x0 = std::max(0, static_cast<int>(std::floor((centre.x - radius.x) * scale)));
  const int x1 = std::min(mins.width - 1, static_cast<int>(std::floor((centre.x + radius.x) * scale)));
  const int y0 = std::max(0, static_cast<int>(std::floor((centre.y - radius.y) * scale)));
  const int y1 = std::min(mins.height - 1, static_cast<int>(std::floor((centre.y + radius.y) * scale)));
  const double nodeHalf = 0.5 * double(1 << level);
  double lo = 1e300;
  double hi = -1e300;
  for (int ny = y0; ny <= y1; ++ny)
  {
    for (int nx = x0; nx <= x1; ++nx)
    {
      const double nodeMin = mins.at(nx, ny);
      if (!(nodeMin < threshold))
      {
        range.receiverSeen = true;
        continue;
      }
      // The node's nearest point to the receiver's texel position, against the region of its nearest caster depth.
      const glm::dvec2 nodeCentre = (glm::dvec2(nx, ny) + 0.5) * double(1 << level);
      const glm::dvec2 offset = glm::max(glm::abs(nodeCentre - centre) - glm::dvec2(nodeHalf), glm::dvec2(0.0));
      const glm::dvec2 reach = glm::dvec2(halfWidth(nodeMin)) * texelsPerUnit + glm::dvec2(0.5);
      if (offset.x > reach.x || offset.y > reach.y)
      {
        continue;
      }
      lo = std::min(lo, nodeMin);
      hi = std::max(hi, nodeMin);
      const double nodeMax = maxs.at(nx, ny);
      if (nodeMax < threshold)
      {
        hi = std::max(hi, nodeMax);
      }
      else
      {
        range.receiverSeen = true;
      }
      if (lightSize_ > 0.0 && nodeMin < d)
      {
        range.texelOnLight = std::max(range.texelOnLight, view.texelWorldSize(nodeMin) * d / (d - nodeMin) / lightSize_);
      }
    }
  }
  if (lo <= hi)
  {
    range.found = true;
    range.minDepth = lo;
    range.maxDepth = hi;
  }
  return range;
}

bool ShadowMapFootprint::depthTestMixed(int x, int y, double radius, double bias, bool nearBias) const
{
  const std::optional<Receiver> point = receiver(x, y);
  if (!point)
  {
    return false;
  }
  const ImageF& map = inputs_.shadowMapLinear;
  const double d = point->sample.depthLin;
  const int cx = static_cast<int>(std::floor(point->sample.uvTexels.x));
  const int cy = static_cast<int>(std::floor(point->sample.uvTexels.y));
  const int r = static_cast<int>(std::ceil(radius));
  bool occluded = false;
  bool lit = false;
  for (int dy = -r; dy <= r; ++dy)
  {
    for (int dx = -r; dx <= r; ++dx)
    {
      const double stored = map.at(std::clamp(cx + dx, 0, map.width - 1), std::clamp(cy + dy, 0, map.height - 1));
      const bool occludes = stored < d - bias;
      occluded |= occludes;
      lit |= !occludes;
      if (nearBias && !occludes && stored < d - 1e-6 * d && stored >= d - 2.0 * bias - point->margin)
      {
        return true;
      }
    }
  }
  return occluded && lit;
}

double ShadowMapFootprint::hiddenByMargin(int x, int y, double limit) const
{
  buildPyramid();
  const std::optional<Receiver> point = receiver(x, y);
  const LightView& view = inputs_.lightView;
  if (!point || !(lightSize_ > 0.0) || view.projection != LightProjection::Perspective)
  {
    return 0.0;
  }
  const double d = point->sample.depthLin;
  const double hiddenFrom = std::max(d - point->margin, 0.0);
  const glm::dvec3 pWs(inputs_.position.at(x, y, 0), inputs_.position.at(x, y, 1), inputs_.position.at(x, y, 2));
  const glm::dvec3 nWs(inputs_.normal.at(x, y, 0), inputs_.normal.at(x, y, 1), inputs_.normal.at(x, y, 2));
  const glm::dvec3 pLs(view.viewFromWorld * glm::dvec4(pWs, 1.0));
  const glm::dvec3 nLs = glm::dmat3(view.viewFromWorld) * nWs;
  const int resolution = inputs_.shadowMapLinear.width;
  const glm::dvec2 unitsPerTexel(
    (view.window.y - view.window.x) / resolution, (view.window.w - view.window.z) / resolution);
  const glm::dvec2 pointTangent = glm::dvec2(view.window.x, view.window.z) + point->sample.uvTexels * unitsPerTexel;
  const double halfLight = 0.5 * lightSize_;
  const double lightArea = inputs_.light->shape == LightShape::Disk ? 0.25 * M_PI * lightSize_ * lightSize_
                                                                   : lightSize_ * lightSize_;
  // The receiver's plane at tangent (u, v): depth z where n . (z (u, v, -1) - p) = 0; +inf where the ray misses it.
  const auto planeDepth = [&](glm::dvec2 tangent) {
    const double denominator = glm::dot(nLs, glm::dvec3(tangent, -1.0));
    const double depth = glm::dot(nLs, pLs) / denominator;
    return denominator != 0.0 && depth > 0.0 ? depth : 1e300;
  };
  double hidden = 0.0;
  // Texels [t0, t1) of a node, stored depths [lo, hi]: 0 outside the light, else its clipped back-projection.
  const auto area = [&](glm::dvec2 t0, glm::dvec2 t1, double lo, double hi) {
    const glm::dvec2 a0 = t0 * unitsPerTexel + glm::dvec2(view.window.x, view.window.z) - pointTangent;
    const glm::dvec2 a1 = t1 * unitsPerTexel + glm::dvec2(view.window.x, view.window.z) - pointTangent;
    const double sLo = lo * d / (d - lo);
    const double sHi = hi * d / (d - hi);
    const glm::dvec2 from = glm::min(a0 * sLo, a0 * sHi);
    const glm::dvec2 to = glm::max(a1 * sLo, a1 * sHi);
    const glm::dvec2 overlap = glm::max(glm::min(to, glm::dvec2(halfLight)) - glm::max(from, glm::dvec2(-halfLight)),
      glm::dvec2(0.0));
    return overlap.x * overlap.y / lightArea;
  };
  const std::function<void(int, int, int)> visit = [&](int level, int nx, int ny) {
    if (hidden > limit)
    {
      return;
    }
    const ImageF& mins = minLevel(level);
    const ImageF& maxs = maxLevel(level);
    const double nodeMin = mins.at(nx, ny);
    const double nodeMax = maxs.at(nx, ny);
    const glm::dvec2 t0 = glm::dvec2(nx, ny) * double(1 << level);
    const glm::dvec2 t1 = glm::min(t0 + double(1 << level), glm::dvec2(resolution));
    // Deeper than the receiver's plane anywhere in the node, or not hidden, or outside the light: nothing.
    double plane = 1e300;
    for (const glm::dvec2 corner : { t0, t1, glm::dvec2(t0.x, t1.y), glm::dvec2(t1.x, t0.y) })
    {
      plane = std::min(plane, planeDepth(glm::dvec2(view.window.x, view.window.z) + corner * unitsPerTexel));
    }
    const double hiddenTo = std::min(plane, d) - 1e-3 * d;
    const double lo = std::max(nodeMin, hiddenFrom);
    const double hi = std::min(nodeMax, hiddenTo);
    if (lo > hi || area(t0, t1, lo, hi) <= 0.0)
    {
      return;
    }
    if (nodeMin >= hiddenFrom && nodeMax <= hiddenTo)
    {
      hidden += area(t0, t1, nodeMin, nodeMax);
      return;
    }
    if (level == 0)
    {
      return; // one texel: its depth lies outside the band
    }
    const ImageF& finer = minLevel(level - 1);
    for (int cy = 2 * ny; cy <= std::min(2 * ny + 1, finer.height - 1); ++cy)
    {
      for (int cx = 2 * nx; cx <= std::min(2 * nx + 1, finer.width - 1); ++cx)
      {
        visit(level - 1, cx, cy);
      }
    }
  };
  const int top = levelCount() - 1;
  for (int ny = 0; ny < minLevel(top).height; ++ny)
  {
    for (int nx = 0; nx < minLevel(top).width; ++nx)
    {
      visit(top, nx, ny);
    }
  }
  return std::min(hidden, 1.0);
}

double blockerDepthRatio(double minDepth, double maxDepth, double receiverDepth)
{
  const double d = receiverDepth;
  return maxDepth * (d - minDepth) / (minDepth * (d - maxDepth));
}

void markMultipleBlockerDepths(const ShadowMapFootprint& footprint, ImageF& codes, float code, double tolerance)
{
  for (int y = 0; y < codes.height; ++y)
  {
    for (int x = 0; x < codes.width; ++x)
    {
      if (codes.at(x, y) != 0.0f)
      {
        continue;
      }
      const ShadowMapFootprint::CasterRange range = footprint.casterRange(x, y);
      if (!range.found)
      {
        continue;
      }
      const std::optional<ShadowMapFootprint::Receiver> point = footprint.receiver(x, y);
      if (blockerDepthRatio(range.minDepth, range.maxDepth, point->sample.depthLin) - 1.0 > tolerance)
      {
        codes.at(x, y) = code;
      }
    }
  }
}

void markShadowMapSampling(const ShadowMapFootprint& footprint, const FrameResult& frame, ImageF& codes, float code,
  const ImageF* kernelTexels)
{
  const NamedImage* bias = frame.find("depth_bias");
  SL_CHECK_MSG(bias, frame.technique, ": no depth_bias buffer");
  for (int y = 0; y < codes.height; ++y)
  {
    for (int x = 0; x < codes.width; ++x)
    {
      const double radius = kernelTexels ? 0.5 * kernelTexels->at(x, y) + 1.0 : 1.0;
      if (codes.at(x, y) == 0.0f && footprint.depthTestMixed(x, y, radius, bias->image.at(x, y), true))
      {
        codes.at(x, y) = code;
      }
    }
  }
}

void markShadowMapSampling(const ApproximationContext& context, ImageF& codes, float code, const ImageF* kernelTexels)
{
  const FrameResult& frame = *context.frame;
  if (!frame.partitions)
  {
    markShadowMapSampling(ShadowMapFootprint(context), frame, codes, code, kernelTexels);
    return;
  }
  const ImageF& position = frame.find("position")->image;
  const ImageF& coverage = frame.find("coverage")->image;
  std::vector<ViewSelection> selections(codes.pixelCount());
  for (int y = 0; y < codes.height; ++y)
  {
    for (int x = 0; x < codes.width; ++x)
    {
      const glm::dvec3 pWs(position.at(x, y, 0), position.at(x, y, 1), position.at(x, y, 2));
      selections[static_cast<std::size_t>(y) * codes.width + x] =
        coverage.at(x, y) > 0.5f ? selectView(*frame.partitions, frame.camera, pWs) : ViewSelection{};
    }
  }
  constexpr float notRead = -1.0f; // markShadowMapSampling marks only pixels whose code is 0
  for (int k = 0; k < frame.partitions->viewCount(); ++k)
  {
    ImageF viewCodes(codes.width, codes.height, 1, notRead);
    for (std::size_t i = 0; i < codes.pixelCount(); ++i)
    {
      const ViewSelection& s = selections[i];
      if (s.primary == k || (s.primaryWeight < 1.0 && s.secondary == k))
      {
        viewCodes.data[i] = codes.data[i];
      }
    }
    markShadowMapSampling(ShadowMapFootprint(context, k), frame, viewCodes, code, kernelTexels);
    for (std::size_t i = 0; i < codes.pixelCount(); ++i)
    {
      codes.data[i] = viewCodes.data[i] == code ? code : codes.data[i];
    }
  }
}

namespace
{

void markRaysThroughPerforatedCaster(const ApproximationContext& context, ImageF& codes, float code, bool wholeLight);

} // namespace

void markCentreRayThroughPerforatedCaster(const ApproximationContext& context, ImageF& codes, float code)
{
  markRaysThroughPerforatedCaster(context, codes, code, false);
}

void markLightRaysThroughPerforatedCaster(const ApproximationContext& context, ImageF& codes, float code)
{
  markRaysThroughPerforatedCaster(context, codes, code, true);
}

Approximation perforatedCasterInMapApproximation()
{
  return { "perforated caster in the map",
    "a segment from the point to the light's centre or to a corner of it crosses a caster with an alpha texture: "
    "the shadow map samples its holes at texel centres" };
}

namespace
{

// Marks with `code` every covered, unmarked pixel whose segment from its point to one of the targets `targetsOf`
// gives crosses a caster with an alpha texture (double precision, RayTriangle.h).
void markSegmentsThroughPerforatedCaster(const ApproximationContext& context, ImageF& codes, float code,
  const std::function<void(const glm::dvec3& point, std::vector<glm::dvec3>& targets)>& targetsOf)
{
  std::vector<const SceneObject*> perforated;
  for (const SceneObject& object : context.scene->objects)
  {
    if (object.castShadows && object.hasAlphaTexture)
    {
      perforated.push_back(&object);
    }
  }
  const NamedImage* position = context.frame->find("position");
  const NamedImage* coverage = context.frame->find("coverage");
  if (perforated.empty() || !position || !coverage)
  {
    return;
  }
  std::vector<glm::dvec3> targets;
  for (int y = 0; y < codes.height; ++y)
  {
    for (int x = 0; x < codes.width; ++x)
    {
      if (codes.at(x, y) != 0.0f || coverage->image.at(x, y) <= 0.5f)
      {
        continue;
      }
      const glm::dvec3 p(position->image.at(x, y, 0), position->image.at(x, y, 1), position->image.at(x, y, 2));
      targets.clear();
      targetsOf(p, targets);
      bool crossed = false;
      for (std::size_t k = 0; k < targets.size() && !crossed; ++k)
      {
        for (const SceneObject* object : perforated)
        {
          const TriangleMesh& mesh = object->mesh;
          for (std::size_t t = 0; t < mesh.triangleCount() && !crossed; ++t)
          {
            const glm::dvec3 a = mesh.positions[mesh.indices[3 * t]];
            const glm::dvec3 b = mesh.positions[mesh.indices[3 * t + 1]];
            const glm::dvec3 c = mesh.positions[mesh.indices[3 * t + 2]];
            const std::optional<RayTriangleHit> hit = intersectRayTriangle(p, targets[k] - p, a, b - a, c - a);
            crossed = hit && hit->t > 1e-6 && hit->t < 1.0;
          }
        }
      }
      if (crossed)
      {
        codes.at(x, y) = code;
      }
    }
  }
}

void markRaysThroughPerforatedCaster(const ApproximationContext& context, ImageF& codes, float code, bool wholeLight)
{
  const Light& light = context.scene->lights.at(static_cast<std::size_t>(context.lightIndex));
  markSegmentsThroughPerforatedCaster(context, codes, code, [&](const glm::dvec3& p, std::vector<glm::dvec3>& targets) {
    // To the centre (and the light's extreme points), or 1e6 along a directional light's reverse direction.
    if (light.type == LightType::Directional)
    {
      targets.push_back(p - 1e6 * light.direction);
      return;
    }
    targets.push_back(light.center);
    if (wholeLight && light.type == LightType::Area)
    {
      const glm::dvec3 right = 0.5 * light.size * light.right();
      const glm::dvec3 up = 0.5 * light.size * light.up;
      const bool square = light.shape == LightShape::Square;
      for (const glm::dvec2 corner : { glm::dvec2(1, 1), glm::dvec2(1, -1), glm::dvec2(-1, 1), glm::dvec2(-1, -1) })
      {
        targets.push_back(square ? light.center + corner.x * right + corner.y * up
                                 : light.center + (corner.x > 0 ? 1.0 : -1.0) * (corner.y > 0 ? right : up));
      }
    }
  });
}

} // namespace

void markCoarseShadowMap(const ShadowMapFootprint& footprint, ImageF& codes, float code, double tolerance)
{
  for (int y = 0; y < codes.height; ++y)
  {
    for (int x = 0; x < codes.width; ++x)
    {
      if (codes.at(x, y) != 0.0f)
      {
        continue;
      }
      const std::optional<ShadowMapFootprint::Receiver> point = footprint.receiver(x, y);
      if (!point)
      {
        continue;
      }
      // A texel so wide at the receiver that its own surface's margin (about the depth bias) spans more than 5% of
      // the distance to the light: casters within that margin are invisible to the technique, and a caster the map
      // holds stands, in its one layer, for everything behind it down to the margin. Without a caster in the
      // footprint the value changes by at most the part of the light the invisible ones hide.
      const bool wideReceiverTexel = point->margin > 0.05 * point->sample.depthLin;
      const ShadowMapFootprint::CasterRange range = footprint.casterRange(x, y);
      if (wideReceiverTexel && (range.found || footprint.hiddenByMargin(x, y, tolerance) > tolerance))
      {
        codes.at(x, y) = code;
        continue;
      }
      // An edge placed to within one texel moves the shadow's boundary on the light by texelOnLight of its size:
      // along an edge that crosses the light, about texelOnLight of the light is seen or hidden.
      if (range.found && range.receiverSeen && range.texelOnLight > tolerance)
      {
        codes.at(x, y) = code;
      }
    }
  }
}

Approximation coarseShadowMapApproximation()
{
  return { "coarse shadow map",
    "the map's resolution decides the visible fraction by more than the tolerance: the receiver's texel is so wide "
    "that its margin (about the depth bias) exceeds 5% of the distance to the light and either the texels that can "
    "hide part of the light hold casters or the casters within the margin hide more than the tolerance of the "
    "light, or a shadow edge runs through the texels that can hide part of the light "
    "and one of their caster texels back-projects onto more than the tolerance of the light's size" };
}

Approximation averageBlockerDepthApproximation()
{
  return { "average blocker depth",
    "the shadow-map texels that can hide part of the light from the point (PCSS's blocker-search region, at each "
    "texel's own depth) hold casters at depths whose penumbra estimates (d - z) / z differ by a factor of more than "
    "1 + the tolerance" };
}

Approximation occluderFusionApproximation()
{
  return { "occluder fusion",
    "the shadow-map texels that can hide part of the light from the point hold casters at depths whose "
    "back-projection scales (d - z) / z differ by a factor of more than 1 + the tolerance: their back-projections "
    "overlap or leave gaps, and casters hidden from the light's centre are not in the map" };
}

AccuracyContract oneLayerSoftShadowContract(BlockerDepthModel model, double tolerance)
{
  AccuracyContract contract;
  contract.reference = ReferenceModel::AreaLight;
  contract.tolerance = tolerance;
  contract.approximations = { model == BlockerDepthModel::Average ? averageBlockerDepthApproximation()
                                                                  : occluderFusionApproximation(),
    coarseShadowMapApproximation(), perforatedCasterInMapApproximation() };
  // PCSS's blocker search is sized at the near plane (Fernando 2005, step 1), so its average also takes casters that
  // cannot hide the light; back-projection keeps each micro-occluder's own footprint on the light.
  const bool averagesTheSearch = model == BlockerDepthModel::Average;
  if (averagesTheSearch)
  {
    contract.approximations.push_back(blockerSearchBeyondTheLightApproximation());
  }
  contract.markApproximations = [tolerance, averagesTheSearch](const ApproximationContext& context, ImageF& codes) {
    const ShadowMapFootprint footprint(context);
    markMultipleBlockerDepths(footprint, codes, 1.0f, tolerance);
    markCoarseShadowMap(footprint, codes, 2.0f, tolerance);
    markLightRaysThroughPerforatedCaster(context, codes, 3.0f);
    if (averagesTheSearch)
    {
      markBlockerSearchBeyondTheLight(footprint, *context.frame, codes, 4.0f);
    }
  };
  return contract;
}

AccuracyContract momentBoundSoftShadowContract(Approximation bound, double tolerance)
{
  AccuracyContract contract;
  contract.reference = ReferenceModel::AreaLight;
  contract.tolerance = tolerance;
  contract.approximations = { averageBlockerDepthApproximation(), std::move(bound), coarseShadowMapApproximation(),
    perforatedCasterInMapApproximation(), blockerSearchBeyondTheLightApproximation() };
  contract.markApproximations = [tolerance](const ApproximationContext& context, ImageF& codes) {
    const ShadowMapFootprint footprint(context);
    markMultipleBlockerDepths(footprint, codes, 1.0f, tolerance);
    markWhere(*context.frame, "light_leak", [](float leak) { return std::abs(leak) > 0.01f; }, codes, 2.0f);
    markCoarseShadowMap(footprint, codes, 3.0f, tolerance);
    markLightRaysThroughPerforatedCaster(context, codes, 4.0f);
    markBlockerSearchBeyondTheLight(footprint, *context.frame, codes, 5.0f);
  };
  return contract;
}

void markPartialVisibility(const FrameResult& frame, ImageF& codes, float code, double epsilon)
{
  markWhere(frame, "visibility", [&](float value) { return value > epsilon && value < 1.0 - epsilon; }, codes, code);
}

void markWhere(const FrameResult& frame, const std::string& buffer, const std::function<bool(float)>& predicate,
  ImageF& codes, float code)
{
  const NamedImage* named = frame.find(buffer);
  if (!named)
  {
    return;
  }
  for (int y = 0; y < codes.height; ++y)
  {
    for (int x = 0; x < codes.width; ++x)
    {
      if (codes.at(x, y) == 0.0f && predicate(named->image.at(x, y, 0)))
      {
        codes.at(x, y) = code;
      }
    }
  }
}

} // namespace sl

namespace sl
{

void markBlockerSearchBeyondTheLight(const ShadowMapFootprint& footprint, const FrameResult& frame, ImageF& codes,
  float code, double visibilityChange)
{
  const ImageF& visibility = frame.find("visibility")->image;
  const ShadowMapInputs& inputs = footprint.inputs();
  const LightView& view = inputs.lightView;
  if (inputs.light->type != LightType::Area || view.projection != LightProjection::Perspective)
  {
    return;
  }
  const double lightSize = inputs.light->size;
  const ImageF& map = inputs.shadowMapLinear;
  const glm::dvec2 texelsPerUnit(map.width / (view.window.y - view.window.x), map.height / (view.window.w - view.window.z));
  constexpr int kTapsPerAxis = 32; // pcss's default max_grid_taps: a regular sub-grid beyond it
  for (int y = 0; y < codes.height; ++y)
  {
    for (int x = 0; x < codes.width; ++x)
    {
      if (codes.at(x, y) != 0.0f)
      {
        continue;
      }
      const std::optional<ShadowMapFootprint::Receiver> point = footprint.receiver(x, y);
      if (!point)
      {
        continue;
      }
      const double d = point->sample.depthLin;
      const double threshold = d - point->margin;
      const glm::dvec2 centre = point->sample.uvTexels;
      double searchLo = 1e300;
      double searchHi = -1e300;
      // The casters of a square of half-width `half` (texels) about the point, read on at most kTapsPerAxis^2 taps.
      const auto casters = [&](const glm::dvec2& half, double& depthSum, double nearest = -1e300, double farthest = 1e300) {
        int count = 0;
        depthSum = 0.0;
        const glm::ivec2 taps = glm::min(glm::ivec2(glm::ceil(2.0 * half)) + 1, glm::ivec2(kTapsPerAxis));
        for (int j = 0; j < taps.y; ++j)
        {
          for (int i = 0; i < taps.x; ++i)
          {
            const glm::dvec2 offset = (glm::dvec2(i, j) + 0.5) / glm::dvec2(taps) * 2.0 - 1.0;
            const glm::dvec2 uv = centre + offset * half;
            const double z = map.at(std::clamp(static_cast<int>(std::floor(uv.x)), 0, map.width - 1),
              std::clamp(static_cast<int>(std::floor(uv.y)), 0, map.height - 1));
            if (z < threshold && z >= nearest && z <= farthest)
            {
              searchLo = std::min(searchLo, z);
              searchHi = std::max(searchHi, z);
              depthSum += z;
              ++count;
            }
          }
        }
        return count;
      };
      const auto kernelHalf = [&](double z) {
        return glm::dvec2(0.5 * lightSize * std::max(0.0, d - z) / (d * z)) * texelsPerUnit;
      };
      // The search region of PCSS step 1 / VSSM Alg. 1 L7: w_i at the near plane, and its average blocker depth.
      double searchSum = 0.0;
      const int found = casters(kernelHalf(view.nearDepth), searchSum);
      if (found == 0)
      {
        continue;
      }
      const double searchNearest = searchLo;
      const double searchFarthest = searchHi;
      const double slack = 0.01 * d;
      // The PCF step's value with the penumbra kernel at blocker depth z, counting the casters of depths in
      // [nearest, farthest].
      const auto filtered = [&](double z, double nearest, double farthest) {
        const glm::dvec2 half = kernelHalf(z);
        const glm::ivec2 taps = glm::min(glm::ivec2(glm::ceil(2.0 * half)) + 1, glm::ivec2(kTapsPerAxis));
        double sum = 0.0;
        return 1.0 - static_cast<double>(casters(half, sum, nearest, farthest)) / (taps.x * taps.y);
      };
      // What the kernel gives from the casters that can hide the light only, at their depths (exact for one depth;
      // a spread of them is "average blocker depth"), or 1 where none can.
      const ShadowMapFootprint::CasterRange reached = footprint.casterRange(x, y);
      double lowest = 1.0;
      double highest = 1.0;
      if (reached.found)
      {
        const double nearer = filtered(reached.minDepth, reached.minDepth - slack, reached.maxDepth + slack);
        const double farther = filtered(reached.maxDepth, reached.minDepth - slack, reached.maxDepth + slack);
        lowest = std::min(nearer, farther);
        highest = std::max(nearer, farther);
      }
      // Casters beyond the light's reach at other depths than those within it, and a value that strays from the
      // latter's kernel.
      const bool beyond = !reached.found || searchNearest < reached.minDepth - slack ||
        searchFarthest > reached.maxDepth + slack;
      const double value = visibility.at(x, y);
      const bool misplaced = beyond && (value < lowest - visibilityChange || value > highest + visibilityChange);
      if (misplaced)
      {
        codes.at(x, y) = code;
      }
    }
  }
}

Approximation blockerSearchBeyondTheLightApproximation()
{
  return { "blocker search beyond the light",
    "the blocker search region, sized at the near plane (Fernando 2005 step 1; VSSM Alg. 1 L7), holds caster texels "
    "that cannot hide any of the light from the point, at depths more than 1% of the receiver's outside those of the "
    "casters that can, and the value differs by more than 0.1 from what the penumbra kernel gives at those casters' "
    "depths counting only them (1 where none can)" };
}

} // namespace sl

namespace sl
{

void markSampleRaysThroughPerforatedCaster(const ApproximationContext& context, const std::vector<glm::dvec3>& samples,
  ImageF& codes, float code)
{
  markSegmentsThroughPerforatedCaster(
    context, codes, code, [&](const glm::dvec3&, std::vector<glm::dvec3>& targets) { targets = samples; });
}

void markSeveralPolygonIds(const ApproximationContext& context, ImageF& codes, float code)
{
  const FrameResult& frame = *context.frame;
  SL_CHECK_MSG(frame.lightView.has_value() && !frame.partitions, frame.technique, ": polygon ids need one map");
  const ImageF* ids = nullptr;
  for (const NamedImage& named : frame.lightSpace)
  {
    ids = named.name == "shadow_map_polygon_id" ? &named.image : ids;
  }
  SL_CHECK_MSG(ids, frame.technique, ": no shadow_map_polygon_id");
  const ShadowMapFootprint footprint(context);
  const ImageF& ownIds = frame.find("polygon_id")->image; // 0: casts no shadow, compared by depth
  const int size = ids->width;
  for (int y = 0; y < codes.height; ++y)
  {
    for (int x = 0; x < codes.width; ++x)
    {
      if (codes.at(x, y) != 0.0f || ownIds.at(x, y) == 0.0f)
      {
        continue;
      }
      const std::optional<ShadowMapFootprint::Receiver> receiver = footprint.receiver(x, y);
      if (!receiver)
      {
        continue;
      }
      const glm::dvec2 uv = receiver->sample.uvTexels;
      const int tx = static_cast<int>(std::floor(uv.x));
      const int ty = static_cast<int>(std::floor(uv.y));
      const float centre = ids->at(std::clamp(tx, 0, size - 1), std::clamp(ty, 0, size - 1));
      bool several = false;
      for (int dy = -1; dy <= 1 && !several; ++dy)
      {
        for (int dx = -1; dx <= 1; ++dx)
        {
          if (ids->at(std::clamp(tx + dx, 0, size - 1), std::clamp(ty + dy, 0, size - 1)) != centre)
          {
            several = true;
            break;
          }
        }
      }
      codes.at(x, y) = several ? code : 0.0f;
    }
  }
}

void markDepthLayerGap(const ApproximationContext& context, ImageF& codes, float code, const ImageF* kernelTexels)
{
  const FrameResult& frame = *context.frame;
  const ImageF* first = nullptr;
  const ImageF* compared = nullptr;
  for (const NamedImage& named : frame.lightSpace)
  {
    first = named.name == "shadow_map_first_depth" ? &named.image : first;
    compared = named.name == "shadow_map_depth" ? &named.image : compared;
  }
  if (!first || !compared || frame.partitions)
  {
    return; // no layered map (depth_layer = first), or views that partition the pixels (their layers are per view)
  }
  const ShadowMapFootprint footprint(context);
  const ImageF& bias = frame.find("depth_bias")->image;
  const int size = first->width;
  for (int y = 0; y < codes.height; ++y)
  {
    for (int x = 0; x < codes.width; ++x)
    {
      if (codes.at(x, y) != 0.0f)
      {
        continue;
      }
      const std::optional<ShadowMapFootprint::Receiver> receiver = footprint.receiver(x, y);
      if (!receiver)
      {
        continue;
      }
      const ShadowMapSample& sm = receiver->sample;
      const double depth = sm.depthLin - bias.at(x, y);
      const int radius = static_cast<int>(std::ceil(kernelTexels ? 0.5 * kernelTexels->at(x, y) + 1.0 : 1.0));
      const int tx = static_cast<int>(std::floor(sm.uvTexels.x));
      const int ty = static_cast<int>(std::floor(sm.uvTexels.y));
      bool gap = false;
      for (int dy = -radius; dy <= radius && !gap; ++dy)
      {
        for (int dx = -radius; dx <= radius && !gap; ++dx)
        {
          const int sx = std::clamp(tx + dx, 0, size - 1);
          const int sy = std::clamp(ty + dy, 0, size - 1);
          gap = depth > first->at(sx, sy) && depth <= compared->at(sx, sy);
        }
      }
      codes.at(x, y) = gap ? code : 0.0f;
    }
  }
}

} // namespace sl
