// Z-partitioning (survey §4.3.1): cascaded / parallel-split shadow maps (PSSM, CSM, plural sunlight buffers). The
// eye depth range [z_n, z_f] of the visible receivers is cut at split depths C_0 = z_n < C_1 < ... < C_m = z_f, and
// each slice gets its own equal-size shadow map focused on the receivers it owns (fitLightView with ownerPlanes) and
// the casters between the light and them.
//
// Split schemes (i = 0..m):
//   uniform    C_i = z_n + (z_f - z_n) i / m
//   log        C_i = z_n (z_f / z_n)^(i / m)                          (survey §4.3.1, after LTYM06: the optimal warp)
//   practical  C_i = λ log_i + (1 - λ) uniform_i                      (PSSM, ZSXL06 as the survey cites it)
//
// Selection, per visible receiver, of the cascade whose map it reads:
//   depth        the slice holding its eye depth d: C_k <= d < C_{k+1}
//   containment  the first (finest) cascade whose map holds it with the filter's margin and within its depth range
//                (its own slice's holds it by construction): the survey's remark that a point may be better served
//                by a nearer partition's map (light ∥ view)
// Blending (cascade_blend = b, a fraction of a slice): depth selection blends slice k into k + 1 over the last
// b (C_{k+1} - C_k) of slice k, weight (C_{k+1} - d) / (b (C_{k+1} - C_k)) for k; containment blends over the outer
// b of a map's half-width into the next cascade that holds the point. b = 0: a hard switch.
//
// Texel snapping (cascade_snap, orthographic cascades): each axis's texel size is rounded up to a power of 2^(1/4) and
// the window's edges to whole texels of the light's fixed frame, so a small camera move keeps every texel boundary in
// place in world space (no crawling shadow edges; ZZB09 as the survey cites it).
//
// Views that partition the pixels (PartitionViews.h): a cascade is one of m light views, each focused on the receivers
// it owns (world-space half-spaces), with a per-pixel selection (primary view, secondary view, primary's weight) that
// the multi-view loop (passes/vtkSLMultiViewPass.h) blends the technique's buffers by.
#pragma once

#include "lightspace/LightView.h"

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace sl
{

struct CameraView;
struct PartitionSet;
struct ViewSelection;

enum class SplitScheme
{
  Uniform,
  Log,
  Practical
};

enum class CascadeSelection
{
  Depth,
  Containment
};

const char* splitSchemeName(SplitScheme scheme);
const char* cascadeSelectionName(CascadeSelection selection);

struct CascadeSettings
{
  int count = 1; // cascades: 1 = one map (no partition)
  SplitScheme scheme = SplitScheme::Log;
  double lambda = 0.5; // split_lambda: practical's weight of the log split
  CascadeSelection selection = CascadeSelection::Depth;
  double blend = 0.0; // cascade_blend: band width, fraction of a slice (depth) or of a map's half-width (containment)
  bool snap = true;   // cascade_snap: whole-texel windows (orthographic cascades)
  bool active() const { return count > 1; }
};

// Throws InputError naming `--set cascades=...` unless count is 1 or the light is directional (a perspective light's
// cascades would partition by direction: cube faces, not depth slices).
void requireCascadableLight(const CascadeSettings& settings, LightType lightType);

// The m + 1 split depths C_0 = zNear .. C_m = zFar of `scheme` (closed forms above).
std::vector<double> splitDepths(SplitScheme scheme, double lambda, double zNear, double zFar, int count);

// The world-space half-spaces (dot(plane, (pWs, 1)) >= 0 inside) of the receivers view `index` is focused on: its
// eye-depth slice, extended toward the eye by the blend band of the slice before it (depth selection), whose pixels
// read this cascade too.
std::vector<glm::dvec4> cascadeOwnerPlanes(
  const CameraView& camera, const std::vector<double>& splits, int index, const CascadeSettings& settings);

// The eye depth the selection uses: -z of the camera's view space (GLSL twin in
// shaders/lightspace/PartitionSelection.glsl).
double eyeDepthOf(const CameraView& camera, const glm::dvec3& pWs);
// The CPU twin (double) of the GPU's cascade selection at a covered pixel's point (PartitionViews.h selectView for a
// set of kind Cascades).
ViewSelection selectCascade(const PartitionSet& cascades, const CameraView& camera, const glm::dvec3& pWs);

// Fits the m cascades: the receivers' eye depth range (one reduction), the splits, then one fitLightView per slice
// with its owner planes (and the texel snapping of `settings`). A PartitionSet of kind Cascades.
PartitionSet fitCascades(const Light& light, const Scene& scene, ReceiverSource& receivers, const FocusSettings& focus,
  const CascadeSettings& settings);

// Texel snapping, per axis: the texel size rounded up to 2^(k/4) world units and the window's edges to whole texels,
// the window still holding the receivers' extent {xMin, xMax, yMin, yMax} with marginTexels texels to spare on each
// side. Returns the window of resolution x resolution texels.
glm::dvec4 snappedWindow(const glm::dvec4& receiverWindow, int resolution, double marginTexels);

} // namespace sl
