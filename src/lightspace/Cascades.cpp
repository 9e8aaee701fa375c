#include "lightspace/Cascades.h"

#include "core/Error.h"
#include "lightspace/CameraView.h"
#include "lightspace/PartitionViews.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sl
{

const char* splitSchemeName(SplitScheme scheme)
{
  switch (scheme)
  {
    case SplitScheme::Uniform:
      return "uniform";
    case SplitScheme::Log:
      return "log";
    case SplitScheme::Practical:
      return "practical";
  }
  return "practical";
}

const char* cascadeSelectionName(CascadeSelection selection)
{
  return selection == CascadeSelection::Depth ? "depth" : "containment";
}

void requireCascadableLight(const CascadeSettings& settings, LightType lightType)
{
  if (settings.active() && lightType != LightType::Directional)
  {
    throw InputError(format("--set cascades=", settings.count, ": cascaded shadow maps need a directional light (a ",
      lightTypeName(lightType), " light's map is partitioned by direction, not by depth); use cascades=1"));
  }
}

std::vector<double> splitDepths(SplitScheme scheme, double lambda, double zNear, double zFar, int count)
{
  SL_CHECK(count >= 1 && zNear > 0.0 && zFar >= zNear);
  std::vector<double> splits(static_cast<std::size_t>(count) + 1);
  for (int i = 0; i <= count; ++i)
  {
    const double fraction = static_cast<double>(i) / count;
    const double uniform = zNear + (zFar - zNear) * fraction;
    const double logarithmic = zNear * std::pow(zFar / zNear, fraction);
    const double weight = scheme == SplitScheme::Uniform ? 0.0 : scheme == SplitScheme::Log ? 1.0 : lambda;
    splits[static_cast<std::size_t>(i)] = weight * logarithmic + (1.0 - weight) * uniform;
  }
  // The ends exactly, whatever the rounding of pow.
  splits.front() = zNear;
  splits.back() = zFar;
  return splits;
}

namespace
{

// The camera's eye depth as an affine function of the world point: d = dot(row, (pWs, 1)).
glm::dvec4 eyeDepthRow(const CameraView& camera)
{
  const glm::dmat4& m = camera.viewFromWorld;
  return -glm::dvec4(m[0][2], m[1][2], m[2][2], m[3][2]);
}

double sliceLength(const std::vector<double>& splits, int k)
{
  return splits[static_cast<std::size_t>(k) + 1] - splits[static_cast<std::size_t>(k)];
}

} // namespace

double eyeDepthOf(const CameraView& camera, const glm::dvec3& pWs)
{
  return glm::dot(eyeDepthRow(camera), glm::dvec4(pWs, 1.0));
}

std::vector<glm::dvec4> cascadeOwnerPlanes(
  const CameraView& camera, const std::vector<double>& splits, int index, const CascadeSettings& settings)
{
  const int count = static_cast<int>(splits.size()) - 1;
  SL_CHECK(index >= 0 && index < count);
  const glm::dvec4 depth = eyeDepthRow(camera);
  std::vector<glm::dvec4> planes;
  if (index > 0)
  {
    // Depth selection blends the previous slice's last band into this one: its receivers read this map too.
    const double band = settings.selection == CascadeSelection::Depth ? settings.blend * sliceLength(splits, index - 1) : 0.0;
    planes.push_back(depth - glm::dvec4(0.0, 0.0, 0.0, splits[static_cast<std::size_t>(index)] - band));
  }
  if (index < count - 1)
  {
    planes.push_back(glm::dvec4(0.0, 0.0, 0.0, splits[static_cast<std::size_t>(index) + 1]) - depth);
  }
  return planes;
}

ViewSelection selectCascade(const PartitionSet& cascades, const CameraView& camera, const glm::dvec3& pWs)
{
  const int count = static_cast<int>(cascades.views.size());
  SL_CHECK(cascades.kind == PartitionKind::Cascades);
  const CascadeSettings& settings = cascades.cascadeSettings;
  const double depth = eyeDepthOf(camera, pWs);
  int slice = 0;
  while (slice < count - 1 && depth >= cascades.splits[static_cast<std::size_t>(slice) + 1])
  {
    ++slice;
  }
  ViewSelection selection{ slice, slice, 1.0 };
  if (settings.selection == CascadeSelection::Depth)
  {
    const double band = settings.blend * sliceLength(cascades.splits, slice);
    const double toEnd = cascades.splits[static_cast<std::size_t>(slice) + 1] - depth;
    if (slice < count - 1 && band > 0.0 && toEnd < band)
    {
      selection.secondary = slice + 1;
      selection.primaryWeight = std::max(0.0, toEnd / band);
    }
    return selection;
  }
  // Containment: the finest map that holds the point, blended toward the next one that holds it near its edge. The
  // point's own slice's map holds it by construction (its focus owns it), so only the finer maps are tested: a
  // receiver at its own map's edge is not a decision within rounding.
  const auto holds = [&](int j, double& edge) {
    const bool held = mapHolds(cascades.views[static_cast<std::size_t>(j)], cascades.marginTexels, pWs, edge);
    return held || j == slice;
  };
  for (int j = 0; j <= slice; ++j)
  {
    double edge = 0.0;
    if (!holds(j, edge))
    {
      continue;
    }
    selection = { j, j, 1.0 };
    if (settings.blend > 0.0 && edge < settings.blend)
    {
      for (int next = j + 1; next < count; ++next)
      {
        double nextEdge = 0.0;
        if (holds(next, nextEdge))
        {
          selection.secondary = next;
          selection.primaryWeight = edge / settings.blend;
          break;
        }
      }
    }
    break;
  }
  return selection;
}

glm::dvec4 snappedWindow(const glm::dvec4& receiverWindow, int resolution, double marginTexels)
{
  const double margin = std::ceil(marginTexels);
  // A slice seen edge-on (one pixel row of ground: one eye depth) has receivers on a line; its texels along the line's
  // normal are kept at 1e-3 of the other axis's extent, so the grid stays representable and as stable as that axis.
  const double widest = std::max({ receiverWindow.y - receiverWindow.x, receiverWindow.w - receiverWindow.z, 1e-300 });
  glm::dvec4 window;
  for (int axis = 0; axis < 2; ++axis)
  {
    const double lo = receiverWindow[2 * axis];
    const double hi = receiverWindow[2 * axis + 1];
    // Two texels to spare: the floor of the low edge gives up to one.
    const double fitted = std::max(hi - lo, 1e-3 * widest) / (resolution - 2.0 * margin - 2.0);
    const double texel = std::exp2(std::ceil(4.0 * std::log2(fitted)) / 4.0);
    window[2 * axis] = (std::floor(lo / texel) - margin) * texel;
    window[2 * axis + 1] = window[2 * axis] + resolution * texel;
  }
  return window;
}

PartitionSet fitCascades(const Light& light, const Scene& scene, ReceiverSource& receivers, const FocusSettings& focus,
  const CascadeSettings& settings)
{
  requireCascadableLight(settings, light.type);
  SL_CHECK_MSG(focus.camera != nullptr, "cascades need the camera");
  const CameraView& camera = *focus.camera;
  PartitionSet cascades;
  cascades.kind = PartitionKind::Cascades;
  cascades.cascadeSettings = settings;
  cascades.marginTexels = focus.marginTexels;

  // The visible receivers' eye depth range, the eye frustum after focusing (as the warp's z_n, z_f).
  receivers.setOwnerPlanes({});
  LightView probe;
  probe.projection = LightProjection::Orthographic;
  probe.viewFromWorld = camera.viewFromWorld;
  const ReceiverExtent eyeDepths = receivers.extent(light, probe, glm::dvec3(0.0, 0.0, -1.0));
  const double zNear = eyeDepths.inFront > 0 ? std::max(eyeDepths.minDepth, camera.nearDepth) : camera.nearDepth;
  const double zFar = std::max(eyeDepths.inFront > 0 ? eyeDepths.maxDepth : camera.farDepth, zNear * (1.0 + 1e-9));
  cascades.splits = splitDepths(settings.scheme, settings.lambda, zNear, zFar, settings.count);

  for (int k = 0; k < settings.count; ++k)
  {
    FocusSettings slice = focus;
    slice.ownerPlanes = cascadeOwnerPlanes(camera, cascades.splits, k, settings);
    slice.snapToTexels = settings.snap;
    cascades.views.push_back(fitLightView(light, scene, receivers, slice));
    cascades.ownerPlanes.push_back(slice.ownerPlanes);
  }
  return cascades;
}

} // namespace sl
