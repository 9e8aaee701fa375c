// Views that partition the pixels (survey §4.3, "Partitioning"): several light views, each focused on the visible
// receivers it owns (fitLightView with FocusSettings::ownerPlanes), and a per-pixel selection of the view (or the two
// views blended) whose map the pixel reads. The multi-view loop (passes/vtkSLMultiViewPass.h) runs the light-space
// stages and the technique once per view and blends the technique's buffers by the selection.
//
// A view's owner region: the world-space half-spaces ownerPlanes[k] (dot(plane, (pWs, 1)) >= 0 inside); a view owns
// the receivers inside all of them. The kinds differ in how the regions are cut and how a pixel picks its view:
//   cascades    eye-depth slices (survey §4.3.1, Cascades.h); by the slice of the eye depth, or by containment in the
//               finer maps, blended across the borders
//   cube faces  the six 90-degree pyramids around a point light (survey §2, CubeFaces.h); by the dominant axis of
//               p - light centre
//   fvsm tiles  the leaves of a quadtree over the focused window (survey §4.3.3, FittedVirtualShadowMap.h): four
//               half-spaces per tile (parallel to a directional light, through a perspective light's centre); by the
//               tile whose rectangle holds the point's light x/y
#pragma once

#include "lightspace/Cascades.h"
#include "lightspace/CubeFaces.h"
#include "lightspace/LightView.h"

#include <glm/glm.hpp>

#include <memory>
#include <string>
#include <vector>

namespace sl
{

struct CameraView;
struct FittedVirtualShadowMap;

enum class PartitionKind
{
  Cascades,
  CubeFaces,
  FvsmTiles
};

// "cascades" | "cube_faces" | "fvsm_tiles"
const char* partitionKindName(PartitionKind kind);

// One pixel's selection: the technique's buffers are primaryWeight x the primary view's + (1 - primaryWeight) x the
// secondary's (secondary = primary when there is nothing to blend).
struct ViewSelection
{
  int primary = 0;
  int secondary = 0;
  double primaryWeight = 1.0;
};

struct PartitionSet
{
  PartitionKind kind = PartitionKind::Cascades;
  std::vector<LightView> views;
  std::vector<std::vector<glm::dvec4>> ownerPlanes; // per view: its owner region (above)
  // The focus's margin: a map holds a point "with its filter" when it lies this many texels inside the map's edge.
  double marginTexels = 1.0;
  // Cascades: the settings that chose them and the m + 1 split depths (eye depth).
  CascadeSettings cascadeSettings;
  std::vector<double> splits;
  // fvsm tiles: the pre-pass, the quadtree and its root view (views[k] is tile k's).
  std::shared_ptr<const FittedVirtualShadowMap> fvsm;
  // Cube faces: the light's centre and each view's face (0 +x .. 5 -z; faces without receivers have no view).
  glm::dvec3 lightCenterWs{ 0.0 };
  std::vector<int> viewFaces;

  int viewCount() const { return static_cast<int>(views.size()); }
};

// Whether pWs lies inside every plane (an empty list holds every point).
bool ownerRegionHolds(const std::vector<glm::dvec4>& planes, const glm::dvec3& pWs);

// The CPU twin (double) of the GPU's selection (shaders/lightspace/PartitionSelection.glsl) at a covered pixel's
// point, for any kind.
ViewSelection selectView(const PartitionSet& partitions, const CameraView& camera, const glm::dvec3& pWs);

// Containment's test: the map's window position of pWs (NDC) and its linear depth lie inside view's inner window
// (marginTexels in from its edge) and depth range; `edgeFraction` receives the distance to the inner window's nearest
// edge as a fraction of its half-width (0 at the edge, 1 at the centre).
bool mapHolds(const LightView& view, double marginTexels, const glm::dvec3& pWs, double& edgeFraction);

// Names of view k: the suffix of its maps in light_space.vti ("_c0" for cascade 0, "_px" for cube face +x, "_t0" for
// fvsm tile 0) and its label in the categorical buffer and the probe ("cascade 0", "cube face +x", "tile 0 (level 2)").
std::string partitionViewSuffix(const PartitionSet& partitions, int view);
std::string partitionViewLabel(const PartitionSet& partitions, int view);

} // namespace sl
