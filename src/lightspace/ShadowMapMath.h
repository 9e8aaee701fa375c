// The shadow-map math shared by every shadow-map technique, in double precision. It mirrors, line for
// line, shaders/common/ShadowMapCommon.glsl; tests check the GLSL against it on read-back buffers.
#pragma once

#include "lightspace/CameraView.h"
#include "lightspace/LightView.h"

#include <glm/glm.hpp>

namespace sl
{

// Where a receiver falls in the shadow map: continuous texel coordinates (texel (i, j) spans
// [i, i+1) x [j, j+1)) and its linear depth along the light axis.
struct ShadowMapSample
{
  glm::dvec2 uvTexels;
  double depthLin;
};

ShadowMapSample projectToShadowMap(const LightView& view, const glm::dvec3& pWs);

// Depth bias (survey §5): constant plus slope-scaled, both in units of the world-space size of one
// shadow-map texel at the receiver, so one setting works at any scene scale and map resolution.
//   bias = texelWorldSize(depthLin) * (constantTexels + slopeTexels * min(tan(theta), maxSlope))
// theta is the angle between the receiver normal and the direction to the light: a receiver tilted by
// theta changes depth by tan(theta) per unit of lateral distance, and the stored depth is sampled up
// to half a texel diagonal (~0.71 texel) away, so slopeTexels >= 0.71 removes acne.
struct BiasSettings
{
  double constantTexels = 0.5;
  double slopeTexels = 1.0;
  double maxSlope = 10.0;
};

double depthBias(const LightView& view, const BiasSettings& bias, double tanTheta, double depthLin);
// The world size of one texel at the receiver pWs: texelWorldSize(depthLin) for an unwarped map; under a perspective
// warp (survey §4.2) the larger side of the warped texel's footprint on the plane through pWs facing the light,
// from the local Jacobian of texel coordinates over the light's x and y (LiSPSM keeps normal slope-scale biasing,
// survey §5, once the bias follows the texel it compares against).
double receiverTexelWorldSize(const LightView& view, const glm::dvec3& pWs, double depthLin);
// depthBias with receiverTexelWorldSize: what every shadow-map lookup applies (equal to depthBias unwarped).
double depthBiasAt(const LightView& view, const BiasSettings& bias, double tanTheta, const glm::dvec3& pWs,
  double depthLin);
double tanAngleToLight(const glm::dvec3& nWs, const glm::dvec3& toLight);

// The survey's aliasing error m (Eq. 2), evaluated exactly for the pixel: the Jacobian J of
// shadow-map texel coordinates with respect to screen pixel coordinates, following the surface's tangent
// plane, gives texel_ratio = 1 / sigma_min(J): how many screen pixels one shadow-map texel spans along
// its most stretched direction. m > 1 means undersampling (jagged shadow edges). Clamped to [0, 1e6].
double texelRatio(const CameraView& camera, const LightView& light, double pixelX, double pixelY,
  const glm::dvec3& pWs, const glm::dvec3& nWs);

// The sampling error of the map at a visible receiver (survey §3), in screen pixels per shadow-map texel, for any
// light matrix (a warp or a cascade included: it reads light.clipFromWorld). Per axis, as Eq. 2 is stated: one
// texel step along the map's s (or t) axis, followed on the surface's tangent plane, moves the pixel by
// texelRatioS (texelRatioT) pixels; texelRatio, the most stretched direction, is never below either. Eq. 1 splits
// the t axis's error into perspectiveFactor, (1/z)(dz/ds): one t-texel's width across the light ray, in pixels
// across the eye ray at the receiver's distance, and projectionFactor, cos(alpha)/cos(beta): the surface's cosines
// to the eye and to the light. Their product is texelRatioT where the t axis, the normal, the light and the eye ray
// lie in one plane (the survey's Fig. 3). All 0 where the eye or the light grazes the surface; clamped to 1e6.
struct SamplingError
{
  double texelRatio = 0.0;
  double texelRatioS = 0.0;
  double texelRatioT = 0.0;
  double perspectiveFactor = 0.0;
  double projectionFactor = 0.0;
};
SamplingError samplingError(const CameraView& camera, const LightView& light, double pixelX, double pixelY,
  const glm::dvec3& pWs, const glm::dvec3& nWs);
// Unit direction from pWs toward the light view's centre of projection (perspective) or along its axis
// (orthographic): the direction its texels are cast along.
glm::dvec3 directionToLightView(const LightView& light, const glm::dvec3& pWs);

} // namespace sl
