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
#include "scene/Scene.h"

#include <glm/glm.hpp>

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

  // World-space size of one shadow-map texel at linear depth `depthLin` (the larger of its two sides).
  double texelWorldSize(double depthLin) const;
};

struct FocusSettings
{
  int resolution = 1024;
  double marginTexels = 1.0; // extra texels on each side, for filter kernels reaching past the receivers
};

// Can the light illuminate a point at all, ignoring occluders? False behind an area light's plane,
// outside a spot cone, or when the surface faces away from the light (the light is below its horizon).
bool lightCanReach(const Light& light, const glm::dvec3& pWs, const glm::dvec3& nWs);
// Direction from pWs toward the light's centre (or against a directional light's direction), unit.
glm::dvec3 directionToLight(const Light& light, const glm::dvec3& pWs);

// Fits the light view. `gbufferPosition` is RGBA (xyz = pWs, w = coverage), `gbufferNormal` RGBA
// (xyz = nWs, w = receives shadows). Throws InputError when the light cannot be handled by one
// shadow map (a point light surrounded by the visible receivers).
LightView fitLightView(const Light& light, const Scene& scene, const ImageF& gbufferPosition,
  const ImageF& gbufferNormal, const FocusSettings& settings);

} // namespace sl
