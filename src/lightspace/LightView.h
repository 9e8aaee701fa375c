// The light's view for shadow mapping, focused on what matters (survey §4.1, "Focusing").
//
// The frustum is fitted to the *visible receivers* (the G-buffer's covered points that the light can
// reach and that receive shadows) and its depth range to the *shadow casters* clipped to that frustum,
// instead of a fixed frustum around the whole scene. This is the intersection body B of the survey's
// Fig. 7, computed exactly from the visible samples rather than from the view frustum's convex hull.
//
// Conventions: light view space is right-handed, looking down -z; "linear depth" (depthLin) is the
// distance along the light axis, -z_view, positive in front of the light. The shadow map is
// resolution x resolution texels; texel (i, j) covers uvSm in [i/N, (i+1)/N) x [j/N, (j+1)/N), row 0 at
// the bottom; its centre is at ((i + 0.5)/N, (j + 0.5)/N).
#pragma once

#include "core/Image.h"
#include "lightspace/PerspectiveWarp.h"
#include "scene/Scene.h"

#include <glm/glm.hpp>

#include <string>
#include <utility>
#include <vector>

namespace sl
{

enum class LightProjection
{
  Perspective, // area (from its centre), point, spot
  Orthographic // directional
};

struct LightView
{
  LightProjection projection = LightProjection::Perspective;
  glm::dvec3 eyeWs{ 0.0 };        // the light centre (perspective) or a point behind the scene (orthographic)
  glm::dmat4 viewFromWorld{ 1.0 };
  glm::dmat4 clipFromView{ 1.0 };
  glm::dmat4 clipFromWorld{ 1.0 };
  // Extent of the frustum in the light's x/y: tangents (x/depthLin) for perspective, world units for
  // orthographic. (xMin, xMax, yMin, yMax), already including the kernel margin.
  glm::dvec4 window{ -1.0, 1.0, -1.0, 1.0 };
  double nearDepth = 0.1; // linear depth range covered by the map
  double farDepth = 10.0;
  int resolution = 1024;
  int receiverSampleCount = 0; // visible receiver points the frustum was fitted to
  // A perspective warp (survey §4.2, PerspectiveWarp.h) is part of clipFromWorld; clipFromView stays the unwarped
  // orthographic projection, whose window depth the warped map's depth buffer still holds (windowDepth is valid).
  PerspectiveWarp warp;

  // Sets clipFromView from projection, window and [nearDepth, farDepth], and clipFromWorld from it and viewFromWorld
  // (unwarped: a warp is applied after, applyPerspectiveWarp).
  void setProjectionFromWindow();
  // World-space size of one shadow-map texel at linear depth `depthLin` (the larger of its two sides).
  double texelWorldSize(double depthLin) const;
  // The depth the map's depth buffer stores for linear depth `depthLin`: window z in [0, 1] (hyperbolic for a
  // perspective light); 0 for any depth before the near plane, the light's centre and behind it included.
  // GLSL twin: windowDepth (common/ShadowMapCommon.glsl).
  double windowDepth(double depthLin) const;
};

struct CameraView;

struct FocusSettings
{
  int resolution = 1024;
  double marginTexels = 1.0; // extra texels on each side, for filter kernels reaching past the receivers
  // Soft-shadow techniques: width (world units) of the area light whose occluders the map must also hold.
  // A perspective window then grows by (width / 2) / near on each side (see fitLightView). 0: hard shadows.
  double lightFootprintWidth = 0.0;
  // A perspective warp of the focused map (survey §4.2): needs the camera and a directional light.
  WarpSettings warp;
  const CameraView* camera = nullptr;
  // A view that owns only part of the visible receivers (a cascade's slice, Cascades.h): world-space half-spaces,
  // dot(plane, (pWs, 1)) >= 0 inside; the fit sees only the receivers inside all of them. Empty: every receiver.
  std::vector<glm::dvec4> ownerPlanes;
  // Texel snapping (Cascades.h snappedWindow) of an orthographic window: whole texels of the light's fixed frame.
  bool snapToTexels = false;
  // A point light's axis, fixed (a cube face's, CubeFaces.h); zero: aimed at the receivers' bounding box.
  glm::dvec3 perspectiveAxis{ 0.0 };
  // The refusal of a point light whose receivers one map cannot cover (fitLightView) is beyondOneMapPrefix, then
  // "<file>: lights[i]: point light at (...) sees ...; one shadow map cannot cover them", then beyondOneMapAdvice:
  // the renderer names the techniques that can (cube maps) or the setting that turned them off.
  std::string beyondOneMapPrefix;
  std::string beyondOneMapAdvice = ": use a spot or area light";
};

// Can the light illuminate a point at all, ignoring occluders? False behind an area light's plane,
// outside a spot cone, or when the surface faces away from the light (the light is below its horizon).
bool lightCanReach(const Light& light, const glm::dvec3& pWs, const glm::dvec3& nWs);
// Direction from pWs toward the light's centre (or against a directional light's direction), unit.
glm::dvec3 directionToLight(const Light& light, const glm::dvec3& pWs);
// How near lightCanReach's decisions are to their boundary, as the twins and probes measure it: the smaller of
// |nWs . toLight| (the facing test) and, for an area light, |light.normal . toLight| (its plane); toLight as
// directionToLight gives it. The tests count a margin under 1e-5 as one float rounding may decide either way.
double lightReachMargin(const Light& light, const glm::dvec3& nWs, const glm::dvec3& toLight);

// What the fit needs to know about the visible receivers (covered pixels that receive shadows and that
// the light can reach), in two questions. A ReceiverSource answers them: on the CPU from read-back
// G-buffer images (ImageReceivers, the reference), or on the GPU by a compute-shader reduction
// (passes/GpuReceivers.h) that reads back a few numbers instead of the whole G-buffer.
struct ReceiverSummary
{
  int count = 0;
  Bounds worldBounds;
};

struct ReceiverExtent
{
  int reachable = 0;          // all visible receivers the light can reach
  int inFront = 0;            // of those, the ones with depthLin > 0 (the others cannot be in the map)
  glm::dvec2 minXY{ 0.0 };    // light x/y over those: tangents (perspective) or world units (orthographic)
  glm::dvec2 maxXY{ 0.0 };
  double minDepth = 0.0;      // linear depth range over those
  double maxDepth = 0.0;
  double minCosToAxis = 1.0;  // perspective: min over all receivers of dot(axis, unit(p - eye))
};

class ReceiverSource
{
public:
  virtual ~ReceiverSource() = default;
  // Restricts the next questions to the receivers inside every plane (FocusSettings::ownerPlanes); {} lifts it.
  void setOwnerPlanes(std::vector<glm::dvec4> planes) { ownerPlanes_ = std::move(planes); }
  const std::vector<glm::dvec4>& ownerPlanes() const { return ownerPlanes_; }
  // Only asked for point lights (their axis aims at the receivers' bounding box).
  virtual ReceiverSummary summary(const Light& light) = 0;
  virtual ReceiverExtent extent(const Light& light, const LightView& view, const glm::dvec3& axis) = 0;

protected:
  bool owns(const glm::dvec3& pWs) const;

private:
  std::vector<glm::dvec4> ownerPlanes_;
};

// The CPU reference: gbufferPosition RGBA (xyz = pWs, w = coverage), gbufferNormal RGBA (xyz = nWs,
// w = receives shadows).
class ImageReceivers : public ReceiverSource
{
public:
  ImageReceivers(const ImageF& gbufferPosition, const ImageF& gbufferNormal);
  ReceiverSummary summary(const Light& light) override;
  ReceiverExtent extent(const Light& light, const LightView& view, const glm::dvec3& axis) override;

private:
  std::vector<glm::dvec3> receivers_;
};

// Whether one shadow map covers the light's visible receivers: false only for a point light that sees some more than
// 80 degrees off the axis fitLightView would give it (surrounded by them: cube faces can, CubeFaces.h). Two receiver
// reductions.
bool oneMapCovers(const Light& light, const Scene& scene, ReceiverSource& receivers);

// Fits the light view. Throws InputError when one shadow map cannot cover the receivers (oneMapCovers; its message
// as FocusSettings::beyondOneMapPrefix/Advice complete it), or when a warp is asked of a light that is not
// directional.
LightView fitLightView(const Light& light, const Scene& scene, ReceiverSource& receivers, const FocusSettings& settings);
// Convenience: the CPU reference on G-buffer images.
LightView fitLightView(const Light& light, const Scene& scene, const ImageF& gbufferPosition,
  const ImageF& gbufferNormal, const FocusSettings& settings);

} // namespace sl
