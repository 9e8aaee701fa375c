// Where the items a probe recorded lie (probe.vtm and probe.png share it, probe/ProbeDataSet.cxx and
// probe/ProbeFigure.cxx): light coordinates and shadow-map texels mapped to world space, the light's outline, the
// receiver, the crop of the shadow map around what the twin read, and the cross-section through the light's
// centre and the receiver. Everything in double precision; nothing here draws or knows VTK.
#pragma once

#include "core/Image.h"
#include "frame/FrameResult.h"
#include "frame/ProbeRecord.h"
#include "probe/Probe.h"
#include "scene/Scene.h"

#include <glm/glm.hpp>

#include <optional>
#include <string>
#include <vector>

namespace sl
{

// The light views of a frame whose views partition its pixels (survey §4.3: cascades, FrameResult::cascades), each
// with the suffix of its light-space exports (shadow_map_depth<suffix>) and a label naming it and the pixels it
// serves; one view, suffix "", for a frame with one shadow map; none without one. The probe draws and measures the
// map of the pixel's own view through these two functions, whatever kind of partition the frame has.
struct PartitionView
{
  const LightView* view = nullptr;
  std::string exportSuffix;        // "" or "_c<k>"
  std::string label;               // "" or "cascade 2 of 4, eye depth 8.1 .. 21.4"
  glm::dvec2 eyeDepthRange{ 0.0 }; // the slice [C_k, C_k+1] a cascade serves; 0, 0 for a single view
};
std::vector<PartitionView> partitionViewsOf(const FrameResult& frame);
// The view a covered pixel's shadow test reads (the CPU twin of the GPU's selection, selectView: primary and,
// where it blends, secondary); {0, 0, 1} for a frame with one view.
ViewSelection partitionSelectionAt(const FrameResult& frame, glm::ivec2 pixel);

// The shadow map the probed pixel's test read (partitionViewsOf): the frame's one map or,
// where its light views partition the pixels (cascades), the map of the pixel's own view; none without a map.
struct ProbeMap
{
  const LightView* view = nullptr;
  const ImageF* depth = nullptr; // its linear-depth export (empty texels 2 x far), or nullptr
  std::string exportName;        // "shadow_map_depth", "shadow_map_depth_c2"
  std::string label;             // which view and the pixels it serves; "" for a frame with one view
};
ProbeMap probeMapOf(const FrameResult& frame, glm::ivec2 pixel);

// The light's view frame, in which the record's light coordinates are given (ProbeLightPolygon): the view of the
// map the pixel read when the frame rendered a shadow map (`view`), else the frame fitLightView would give the light (eye at its centre
// looking along its normal, `up` in its plane; a point light looks at the receiver, a directional light's eye is
// behind the receiver).
struct ProbeLightFrame
{
  glm::dmat4 viewFromWorld{ 1.0 };
  glm::dmat4 worldFromView{ 1.0 };
  glm::dvec3 eyeWs{ 0.0 };  // the light's centre (the view's origin)
  glm::dvec3 axisWs{ 0.0, 0.0, -1.0 }; // unit, the view's -z: the direction the light shines along
  bool orthographic = false;

  // A point of the light plane (view z = 0) given in light coordinates (view x, y; world units from the centre).
  glm::dvec3 worldFromLight(const glm::dvec2& lightXY) const;
  glm::dvec2 lightFromWorld(const glm::dvec3& pWs) const;
};
ProbeLightFrame probeLightFrame(const LightView* view, const Scene& scene, const Light& light,
  const glm::dvec3& receiverWs);

// An area light's outline in world space: a square's 4 corners or a disk as `diskSegments` points, in order
// around the light; empty for point, spot and directional lights.
std::vector<glm::dvec3> lightOutline(const Light& light, int diskSegments = 64);

// The world-space point at linear depth `depthLin` whose shadow-map position is `uvTexels` (continuous texel
// coordinates: texel i spans [i, i + 1]); the inverse of projectToShadowMap (lightspace/ShadowMapMath.h).
glm::dvec3 worldFromTexel(const LightView& view, const glm::dvec2& uvTexels, double depthLin);

// The probed receiver: what the twin recorded in its "receiver" group (position, normal, shadow_map_position,
// receiver_depth, depth_bias), completed from the frame's G-buffer and the map's view where the record has none.
struct ProbeReceiver
{
  glm::dvec3 position{ 0.0 };
  glm::dvec3 normal{ 0.0, 0.0, 1.0 };
  std::optional<glm::dvec2> uvTexels; // in the shadow map; none without a light view
  double depthLin = 0.0;              // along the light's axis
  std::optional<double> bias;
};
ProbeReceiver probeReceiver(const ProbeResult& probe, const FrameResult& frame, const ProbeMap& map,
  const ProbeLightFrame& lightFrame);

// The light, the map the pixel read, its view frame and the receiver of a probe, as probe.vtm and probe.png use them.
struct ProbeSetting
{
  const Light* light = nullptr; // scene.lights[probe.lightIndex]
  ProbeMap map;
  ProbeLightFrame lightFrame;
  ProbeReceiver receiver;
};
ProbeSetting probeSetting(const ProbeResult& probe, const FrameResult& frame, const Scene& scene);

// The first quantity `name` of group `group`, or nullptr.
const ProbeQuantity* findQuantity(const ProbeRecord& record, const std::string& group, const std::string& name);

// Empty texels hold 2 x far (ShadowMapStructure.cpp): anything beyond 1.5 x far is "no caster".
bool isEmptyShadowMapTexel(const LightView& view, double storedDepth);

// A rectangle of whole texels: lo .. lo + size - 1.
struct TexelRect
{
  glm::ivec2 lo{ 0 };
  glm::ivec2 size{ 0 };
  bool empty() const { return size.x <= 0 || size.y <= 0; }
  bool contains(const glm::ivec2& texel) const
  {
    return texel.x >= lo.x && texel.y >= lo.y && texel.x < lo.x + size.x && texel.y < lo.y + size.y;
  }
};

// The crop of a `mapSize` x `mapSize` shadow map that probe.vtm and probe.png show: every recorded texel and
// kernel and the receiver's texel, grown on each side by a margin of max(4, 1/8 of the larger side) texels,
// then clamped to the map and to kMaxProbeCropSide texels per side (centred on the receiver's texel when cut).
// Hierarchy nodes are not included: an HSM's root covers the whole map; they are drawn clipped to the crop.
inline constexpr int kMaxProbeCropSide = 512;
TexelRect probeShadowMapCrop(const ProbeRecord& record, const std::optional<glm::dvec2>& receiverTexel, int mapSize);

// Per-texel arrays over a crop (row 0 at the bottom, crop-relative): the stored depth and what the record says
// about each texel.
struct ProbeCropArrays
{
  TexelRect crop;
  ImageF depth;                 // the map's linear depth
  Image<std::uint8_t> read;     // 1: the twin read the texel
  Image<std::uint8_t> compared; // 1: read and compared against the receiver's depth
  Image<std::uint8_t> occluding; // 1: a comparison found it in front of the receiver
  ImageF weight;                // sum of the recorded taps' weights (0 where none)
  Image<int> visitedLevel;      // the finest (lowest) level of a visited hierarchy node covering it, -1 if none
};
ProbeCropArrays probeCropArrays(const ProbeRecord& record, const ImageF& shadowMapDepth, const TexelRect& crop);

// Labels in order of first appearance; an item's code is its label's index (categorical colours, cell arrays).
std::vector<std::string> nodeDecisionLabels(const ProbeRecord& record);
std::vector<std::string> kernelRoleLabels(const ProbeRecord& record);
std::vector<std::string> polygonRoleLabels(const ProbeRecord& record);
int labelCode(const std::vector<std::string>& labels, const std::string& label);

// The cross-section of probe.png: the plane through the light's centre and the receiver that contains the
// light's axis (or, when the receiver lies on the axis, the receiver's normal). 2-D section coordinates:
// origin at the light's centre, x `across` (parallel to the light plane, the receiver at x >= 0), y
// `towardLight` (minus the light's axis), in world units.
struct ProbeSection
{
  glm::dvec3 origin{ 0.0 };
  glm::dvec3 across{ 1.0, 0.0, 0.0 };
  glm::dvec3 towardLight{ 0.0, 1.0, 0.0 };
  glm::dvec3 normal{ 0.0, 0.0, 1.0 };
  bool usesReceiverNormal = false; // the receiver lies on the light's axis

  glm::dvec2 toSection(const glm::dvec3& pWs) const;
  glm::dvec3 toWorld(const glm::dvec2& section) const;
};
ProbeSection probeSection(const glm::dvec3& lightCentre, const glm::dvec3& lightAxis, const glm::dvec3& receiver,
  const glm::dvec3& receiverNormal);

// A scene triangle cut by the section plane.
struct SectionSegment
{
  glm::dvec2 a{ 0.0 };
  glm::dvec2 b{ 0.0 };
  std::size_t object = 0;
  bool castsShadows = true;
};
// Every triangle of the scene intersected with the section's plane, in double (triangles lying in the plane
// are left out: they have no cut).
std::vector<SectionSegment> sceneSection(const Scene& scene, const ProbeSection& section);

// Half the light's extent along the section's `across` axis (the light plane cut by the section): a square's
// half-chord through its centre, a disk's radius; 0 for point, spot and directional lights.
double lightHalfExtentInSection(const Light& light, const ProbeSection& section);

// A shadow-map texel the section's plane passes through, with its stored depth drawn as a step: the texel's
// footprint on the section at that depth runs from `enter` to `exit` (section coordinates), in the order the
// walk crossed the map.
struct SectionTexelColumn
{
  glm::ivec2 texel{ 0 };
  double storedDepth = 0.0;
  glm::dvec2 enter{ 0.0 };
  glm::dvec2 exit{ 0.0 };
  bool joinsPrevious = false; // the previous column ends where this one starts (same boundary ray): a riser
};
// The texels along the section plane's image in the map (a line through the receiver's shadow-map position),
// every one the line crosses, in order; empty texels are left out.
std::vector<SectionTexelColumn> sectionShadowMapColumns(
  const LightView& view, const ImageF& shadowMapDepth, const ProbeSection& section, const glm::dvec3& receiverWs);

} // namespace sl
