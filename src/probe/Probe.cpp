#include "probe/Probe.h"

#include "core/Error.h"
#include "lightspace/ShadowMapMath.h"
#include "output/OutputWriter.h"
#include "probe/ProbeGeometry.h"

#include <cmath>
#include <limits>

namespace sl
{

double ProbeResult::difference() const
{
  return std::abs(gpuVisibility - outcome.visibility);
}

bool ProbeResult::agrees() const
{
  return difference() <= outcome.tolerance + 1e-6 || !outcome.ambiguity.empty();
}

namespace
{

// The map's sampling error at the pixel (survey §3, Eq. 1-2 per axis, as the frame's texel_ratio_s/_t buffers) and
// the pixel's footprint in the map: the pixel's corners' camera rays met on the receiver's tangent plane and
// projected through the light matrix, so a warped map (§4.2) shows the footprint its warp gives. The map is the one
// the pixel's test reads: with views that partition the pixels (cascades, §4.3.1) the pixel's own view, named with
// the pixels it serves. Frames whose views publish the sampling-error buffers only (a technique with sub-lights has
// one view each).
void recordSamplingError(const FrameResult& frame, const Scene& scene, int lightIndex, glm::ivec2 pixel,
  ProbeRecorder& recorder)
{
  const std::vector<PartitionView> views = partitionViewsOf(frame);
  if (views.empty() || frame.find("texel_ratio_t") == nullptr)
  {
    return;
  }
  const ImageF& position = frame.find("position")->image;
  const ImageF& normal = frame.find("normal")->image;
  const ImageF& receives = frame.find("receives_shadows")->image;
  const glm::dvec3 pWs(position.at(pixel.x, pixel.y, 0), position.at(pixel.x, pixel.y, 1), position.at(pixel.x, pixel.y, 2));
  const glm::dvec3 nWs(normal.at(pixel.x, pixel.y, 0), normal.at(pixel.x, pixel.y, 1), normal.at(pixel.x, pixel.y, 2));
  const Light& light = scene.lights.at(static_cast<std::size_t>(lightIndex));
  if (receives.at(pixel.x, pixel.y) <= 0.5f || !lightCanReach(light, pWs, nWs))
  {
    return;
  }
  const CameraView& camera = frame.camera;
  const int viewIndex = partitionSelectionAt(frame, pixel).primary;
  const PartitionView& partition = views.at(static_cast<std::size_t>(viewIndex));
  const LightView& view = *partition.view;
  recorder.beginGroup("sampling error");
  if (views.size() > 1)
  {
    recorder.category("shadow_map", viewIndex, "shadow_map_depth" + partition.exportSuffix,
      "the map the pixel's test reads: " + partition.label + " (survey §4.3)");
    if (partition.eyeDepthRange.y > 0.0) // a cascade's slice; FVSM tiles and cube faces own parts of the light's view instead
    {
      recorder.quantity("view_eye_depth_range", partition.eyeDepthRange, "world units",
        "survey §4.3.1, the split depths C_k, C_k+1 of the pixel's slice");
    }
  }
  const SamplingError error = samplingError(camera, view, pixel.x + 0.5, pixel.y + 0.5, pWs, nWs);
  recorder.quantity("texel_ratio_s", error.texelRatioS, "pixels per texel", "survey Eq. 2, along the map's s axis");
  recorder.quantity("texel_ratio_t", error.texelRatioT, "pixels per texel",
    "survey Eq. 2, along the map's t axis (the axis a warp acts on)");
  recorder.quantity("perspective_factor", error.perspectiveFactor, "pixels per texel", "survey Eq. 1, (1/z)(dz/ds)");
  recorder.quantity("projection_factor", error.projectionFactor, "", "survey Eq. 1, cos(alpha)/cos(beta)");
  if (view.warp.active())
  {
    recorder.quantity("warp_n", view.warp.n, "world units", "survey §4.2 (P's free parameter n)");
  }
  ProbeMapPolygon footprint{ "pixel footprint", {}, "survey Eq. 2 (the pixel on the receiver's plane, in the map)" };
  for (const glm::dvec2& corner : { glm::dvec2(0, 0), glm::dvec2(1, 0), glm::dvec2(1, 1), glm::dvec2(0, 1) })
  {
    const double x = pixel.x + corner.x;
    const double y = pixel.y + corner.y;
    const glm::dvec3 origin = camera.nearOrigin + x * camera.nearStepX + y * camera.nearStepY;
    const glm::dvec3 ray = camera.rayOrigin + x * camera.rayStepX + y * camera.rayStepY;
    const double along = glm::dot(ray, nWs);
    const double distance = std::abs(along) < 1e-12 * glm::length(ray) ? -1.0 : glm::dot(pWs - origin, nWs) / along;
    if (distance <= 0.0)
    {
      return; // the corner's ray runs along the plane or meets it behind the eye: no bounded footprint
    }
    const glm::dvec3 onPlane = origin + distance * ray;
    footprint.points.push_back(projectToShadowMap(view, onPlane).uvTexels);
  }
  recorder.mapPolygon(std::move(footprint));
}

} // namespace

ProbeResult probePixel(const FrameResult& frame, const Scene& scene, int lightIndex, glm::ivec2 pixel)
{
  SL_CHECK_MSG(frame.descriptor != nullptr, "frame of ", frame.technique, " has no descriptor");
  if (!frame.descriptor->probe)
  {
    throw InputError("--technique " + frame.technique + ": this technique has no probe recorder");
  }
  const std::string pixelText = std::to_string(pixel.x) + "," + std::to_string(pixel.y);
  if (pixel.x < 0 || pixel.y < 0 || pixel.x >= frame.resolution.x || pixel.y >= frame.resolution.y)
  {
    throw InputError("--pixel " + pixelText + ": outside the " + std::to_string(frame.resolution.x) + "x" +
      std::to_string(frame.resolution.y) + " image (x in 0.." + std::to_string(frame.resolution.x - 1) + ", y in 0.." +
      std::to_string(frame.resolution.y - 1) + ", row 0 at the bottom)");
  }
  const NamedImage* coverage = frame.find("coverage");
  SL_CHECK(coverage != nullptr);
  if (coverage->image.at(pixel.x, pixel.y) <= 0.5f)
  {
    throw InputError("--pixel " + pixelText + ": a background pixel (no surface there to probe)");
  }
  ProbeResult result;
  result.technique = frame.technique;
  result.pixel = pixel;
  result.lightIndex = lightIndex;
  // Multisampled frames: the technique ran once per pixel, from the first sample (SS08 §7); its value before the
  // resolve is what the twin replays.
  const NamedImage* pixelVisibility = frame.find("msaa_pixel_visibility");
  const NamedImage* visibility = pixelVisibility ? pixelVisibility : frame.find("visibility");
  SL_CHECK(visibility != nullptr);
  result.gpuVisibility = visibility->image.at(pixel.x, pixel.y);
  ProbeRecorder recorder;
  const ProbeContext context{ &frame, &scene, lightIndex };
  result.outcome = frame.descriptor->probe(context, pixel, recorder);
  if (pixelVisibility)
  {
    // The resolve that followed (passes/vtkSLMsaaResolvePass.h): each sample's depth and the visibility it took.
    recorder.beginGroup("msaa resolve");
    const ImageF& depths = frame.find("msaa_sample_depth")->image;
    const ImageF& sampleVisibility = frame.find("msaa_sample_visibility")->image;
    for (int s = 0; s < depths.components; ++s)
    {
      const std::string sample = "sample " + std::to_string(s);
      recorder.quantity(sample + " depth", depths.at(pixel.x, pixel.y, s), "world units",
        "SS08 §7 (0: the sample is uncovered)");
      recorder.quantity(sample + " visibility", sampleVisibility.at(pixel.x, pixel.y, s), "",
        "SS08 §7 (the pixel's within tau of the first sample's depth, else the closest-depth 4-neighbour's)");
    }
    recorder.quantity("interpolated samples", frame.find("msaa_interpolated_samples")->image.at(pixel.x, pixel.y),
      "samples", "SS08 §7");
    recorder.quantity("resolved visibility", frame.find("visibility")->image.at(pixel.x, pixel.y), "",
      "the mean of the covered samples' visibilities");
  }
  recordSamplingError(frame, scene, lightIndex, pixel, recorder);
  result.record = std::move(recorder.record());
  return result;
}

glm::ivec2 pickPixel(const FrameResult& frame, const glm::dvec3& world, double tolerance)
{
  const std::string pointText = format(world.x, ",", world.y, ",", world.z);
  const glm::dvec4 clip = frame.camera.clipFromWorld * glm::dvec4(world, 1.0);
  if (clip.w <= 0.0)
  {
    throw InputError("--pick world " + pointText + ": behind the camera");
  }
  const glm::dvec3 ndc = glm::dvec3(clip) / clip.w;
  const glm::ivec2 pixel(static_cast<int>(std::floor((ndc.x * 0.5 + 0.5) * frame.resolution.x)),
    static_cast<int>(std::floor((ndc.y * 0.5 + 0.5) * frame.resolution.y)));
  if (pixel.x < 0 || pixel.y < 0 || pixel.x >= frame.resolution.x || pixel.y >= frame.resolution.y)
  {
    throw InputError("--pick world " + pointText + ": outside the camera's view");
  }
  // The point projects into `pixel`; it is what the pixel shows when the G-buffer's surface point of that pixel
  // (or of a neighbour, the point may sit on a pixel edge) lies on it.
  const ImageF& coverage = frame.find("coverage")->image;
  const ImageF& position = frame.find("position")->image;
  double nearest = std::numeric_limits<double>::infinity();
  glm::ivec2 best = pixel;
  for (int dy = -1; dy <= 1; ++dy)
  {
    for (int dx = -1; dx <= 1; ++dx)
    {
      const glm::ivec2 candidate = pixel + glm::ivec2(dx, dy);
      if (candidate.x < 0 || candidate.y < 0 || candidate.x >= frame.resolution.x ||
        candidate.y >= frame.resolution.y || coverage.at(candidate.x, candidate.y) <= 0.5f)
      {
        continue;
      }
      const glm::dvec3 surface(position.at(candidate.x, candidate.y, 0), position.at(candidate.x, candidate.y, 1),
        position.at(candidate.x, candidate.y, 2));
      const double distance = glm::length(surface - world);
      if (distance < nearest)
      {
        nearest = distance;
        best = candidate;
      }
    }
  }
  if (!(nearest <= tolerance))
  {
    throw InputError("--pick world " + pointText + ": not a visible surface point (the nearest surface shown around pixel " +
      std::to_string(pixel.x) + "," + std::to_string(pixel.y) + " is " +
      (std::isfinite(nearest) ? format(nearest, " away, more than ", tolerance) : std::string("none: background")) + ")");
  }
  return best;
}

namespace
{

nlohmann::json vec(const glm::dvec2& v)
{
  return { v.x, v.y };
}

nlohmann::json vec(const glm::ivec2& v)
{
  return { v.x, v.y };
}

// NaN is not JSON: a missing value is null.
nlohmann::json jsonNumber(double value)
{
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json();
}

} // namespace

nlohmann::json probeJson(const ProbeResult& probe, const FrameResult& frame, const Scene& scene)
{
  const ProbeRecord& record = probe.record;
  nlohmann::json quantities = nlohmann::json::array();
  for (const ProbeQuantity& quantity : record.quantities)
  {
    nlohmann::json item = { { "group", quantity.group }, { "name", quantity.name }, { "unit", quantity.unit },
      { "source", quantity.source } };
    if (!quantity.text.empty())
    {
      // A categorical value: its label, and its code where the buffer that publishes it stores one.
      item["label"] = quantity.text;
    }
    if (quantity.value.empty())
    {
      item["value"] = quantity.text;
    }
    else if (quantity.value.size() == 1)
    {
      item["value"] = jsonNumber(quantity.value[0]);
    }
    else
    {
      nlohmann::json components = nlohmann::json::array();
      for (const double component : quantity.value)
      {
        components.push_back(jsonNumber(component));
      }
      item["value"] = components;
    }
    quantities.push_back(item);
  }
  nlohmann::json texels = nlohmann::json::array();
  for (const ProbeTexel& texel : record.texels)
  {
    texels.push_back({ { "texel", vec(texel.texel) }, { "role", texel.role }, { "stored_depth", jsonNumber(texel.storedDepth) },
      { "compared_depth", jsonNumber(texel.comparedDepth) }, { "occluding", texel.occluding }, { "weight", jsonNumber(texel.weight) } });
  }
  nlohmann::json nodes = nlohmann::json::array();
  for (const ProbeNode& node : record.nodes)
  {
    nodes.push_back({ { "structure", node.structure }, { "level", node.level }, { "lo", vec(node.lo) }, { "hi", vec(node.hi) },
      { "min_depth", jsonNumber(node.minDepth) }, { "max_depth", jsonNumber(node.maxDepth) }, { "decision", node.decision } });
  }
  nlohmann::json kernels = nlohmann::json::array();
  for (const ProbeKernel& kernel : record.kernels)
  {
    kernels.push_back({ { "role", kernel.role }, { "lo", vec(kernel.lo) }, { "hi", vec(kernel.hi) }, { "label", kernel.label },
      { "source", kernel.source } });
  }
  nlohmann::json polygons = nlohmann::json::array();
  for (const ProbeLightPolygon& polygon : record.lightPolygons)
  {
    nlohmann::json points = nlohmann::json::array();
    for (const glm::dvec2& point : polygon.points)
    {
      points.push_back(vec(point));
    }
    polygons.push_back({ { "role", polygon.role }, { "points", points }, { "signed_area", jsonNumber(polygon.signedArea) } });
  }
  nlohmann::json edges = nlohmann::json::array();
  for (const ProbeContourEdge& edge : record.contourEdges)
  {
    edges.push_back({ { "a", vec(edge.a) }, { "b", vec(edge.b) }, { "light_a", vec(edge.lightA) },
      { "light_b", vec(edge.lightB) }, { "signed_area", jsonNumber(edge.signedArea) } });
  }
  nlohmann::json mapPolygons = nlohmann::json::array();
  for (const ProbeMapPolygon& polygon : record.mapPolygons)
  {
    nlohmann::json points = nlohmann::json::array();
    for (const glm::dvec2& point : polygon.points)
    {
      points.push_back(vec(point));
    }
    mapPolygons.push_back({ { "role", polygon.role }, { "points", points }, { "source", polygon.source } });
  }
  nlohmann::json samples = nlohmann::json::array();
  for (const ProbeLightSample& sample : record.lightSamples)
  {
    samples.push_back({ { "position", vec(sample.position) }, { "blocked", sample.blocked },
      { "depth_complexity", sample.depthComplexity } });
  }
  const Light& light = scene.lights.at(static_cast<std::size_t>(probe.lightIndex));
  OutputContext context;
  context.lightIndex = probe.lightIndex;
  return {
    { "technique", probe.technique },
    { "pixel", vec(probe.pixel) },
    { "pixel_convention", "image coordinates, row 0 at the bottom (as buffers.vti)" },
    { "gpu_visibility", probe.gpuVisibility },
    { "twin_visibility", jsonNumber(probe.outcome.visibility) },
    { "twin_evaluated", probe.outcome.evaluated },
    { "difference", jsonNumber(probe.difference()) },
    { "tolerance", probe.outcome.tolerance },
    { "ambiguity", probe.outcome.ambiguity },
    { "agrees", probe.agrees() },
    { "twin", probe.outcome.twin },
    { "light_coordinates", "the light view's x and y on the light plane, world units from the light's centre" },
    { "light", { { "center", { light.center.x, light.center.y, light.center.z } }, { "size", light.size },
                 { "normal", { light.normal.x, light.normal.y, light.normal.z } } } },
    { "frame", frameStats(frame, context) },
    { "quantities", quantities },
    { "texels", texels },
    { "nodes", nodes },
    { "kernels", kernels },
    { "map_polygons", mapPolygons },
    { "light_polygons", polygons },
    { "contour_edges", edges },
    { "light_samples", samples },
    { "dropped", { { "texels", record.droppedTexels }, { "nodes", record.droppedNodes },
                   { "light_polygons", record.droppedPolygons }, { "contour_edges", record.droppedEdges } } },
  };
}

} // namespace sl
