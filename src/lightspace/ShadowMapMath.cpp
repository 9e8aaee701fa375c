#include "lightspace/ShadowMapMath.h"

#include <algorithm>
#include <cmath>

namespace sl
{

ShadowMapSample projectToShadowMap(const LightView& view, const glm::dvec3& pWs)
{
  const glm::dvec4 clip = view.clipFromWorld * glm::dvec4(pWs, 1.0);
  const glm::dvec2 ndc = glm::dvec2(clip) / clip.w;
  const glm::dvec4 pLs = view.viewFromWorld * glm::dvec4(pWs, 1.0);
  return { (ndc * 0.5 + 0.5) * static_cast<double>(view.resolution), -pLs.z };
}

double tanAngleToLight(const glm::dvec3& nWs, const glm::dvec3& toLight)
{
  const double cosTheta = std::clamp(glm::dot(nWs, toLight), 1e-4, 1.0);
  return std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta)) / cosTheta;
}

double depthBias(const LightView& view, const BiasSettings& bias, double tanTheta, double depthLin)
{
  return view.texelWorldSize(depthLin) * (bias.constantTexels + bias.slopeTexels * std::min(tanTheta, bias.maxSlope));
}

namespace
{

// Texel coordinates u = N_sm (ndc.xy / 2 + 1/2), ndc = (M p).xy / (M p).w: du/dp = N_sm/2 (M_i - ndc_i M_w) / w.
struct TexelGradients
{
  glm::dvec3 u;
  glm::dvec3 v;
};

TexelGradients texelGradients(const LightView& light, const glm::dvec3& pWs)
{
  const glm::dmat4& m = light.clipFromWorld;
  const glm::dvec4 clip = m * glm::dvec4(pWs, 1.0);
  const glm::dvec2 ndc = glm::dvec2(clip) / clip.w;
  const glm::dvec3 rowX(m[0][0], m[1][0], m[2][0]);
  const glm::dvec3 rowY(m[0][1], m[1][1], m[2][1]);
  const glm::dvec3 rowW(m[0][3], m[1][3], m[2][3]);
  const double scale = 0.5 * light.resolution / clip.w;
  return { scale * (rowX - ndc.x * rowW), scale * (rowY - ndc.y * rowW) };
}

} // namespace

double receiverTexelWorldSize(const LightView& view, const glm::dvec3& pWs, double depthLin)
{
  if (!view.warp.active())
  {
    return view.texelWorldSize(depthLin);
  }
  // J = d(texel u, v) / d(light x, y) at pWs; the texel's sides in world units are J^-1's columns.
  const TexelGradients gradient = texelGradients(view, pWs);
  const glm::dvec3& gradU = gradient.u;
  const glm::dvec3& gradV = gradient.v;
  const glm::dvec3 lightX(view.viewFromWorld[0][0], view.viewFromWorld[1][0], view.viewFromWorld[2][0]);
  const glm::dvec3 lightY(view.viewFromWorld[0][1], view.viewFromWorld[1][1], view.viewFromWorld[2][1]);
  const double j00 = glm::dot(gradU, lightX);
  const double j01 = glm::dot(gradU, lightY);
  const double j10 = glm::dot(gradV, lightX);
  const double j11 = glm::dot(gradV, lightY);
  const double determinant = std::max(std::abs(j00 * j11 - j01 * j10), 1e-300);
  return std::max(std::sqrt(j11 * j11 + j10 * j10), std::sqrt(j01 * j01 + j00 * j00)) / determinant;
}

double depthBiasAt(const LightView& view, const BiasSettings& bias, double tanTheta, const glm::dvec3& pWs,
  double depthLin)
{
  return receiverTexelWorldSize(view, pWs, depthLin) *
    (bias.constantTexels + bias.slopeTexels * std::min(tanTheta, bias.maxSlope));
}

namespace
{

constexpr double kMaxSamplingError = 1e6;

// The camera ray through a pixel at the receiver: N + s R (affine in the pixel position, see CameraView), with s the
// receiver's parameter along it. Formed once per pixel; every plane's pixel steps below read it.
struct RayAtReceiver
{
  glm::dvec3 ray;
  double s;
};

RayAtReceiver rayAtReceiver(const CameraView& camera, double pixelX, double pixelY, const glm::dvec3& pWs)
{
  const glm::dvec3 nearPoint = camera.nearOrigin + pixelX * camera.nearStepX + pixelY * camera.nearStepY;
  const glm::dvec3 ray = camera.rayOrigin + pixelX * camera.rayStepX + pixelY * camera.rayStepY;
  return { ray, glm::dot(pWs - nearPoint, ray) / glm::dot(ray, ray) };
}

// The world steps on the plane through the receiver with normal `planeNormal` that one pixel step in x and in y moves
// the camera ray's hit point by: dp = v - R (n.v)/(n.R), v = dN + s dR. False where the ray grazes the plane.
bool pixelStepsOnPlane(const CameraView& camera, const RayAtReceiver& at, const glm::dvec3& planeNormal,
  glm::dvec3& dpdx, glm::dvec3& dpdy)
{
  const double normalDotRay = glm::dot(planeNormal, at.ray);
  if (std::abs(normalDotRay) < 1e-12 * glm::length(at.ray) * glm::length(planeNormal))
  {
    return false; // the view ray grazes the plane: one pixel covers unboundedly many texels
  }
  const glm::dvec3 stepX = camera.nearStepX + at.s * camera.rayStepX;
  const glm::dvec3 stepY = camera.nearStepY + at.s * camera.rayStepY;
  dpdx = stepX - at.ray * (glm::dot(planeNormal, stepX) / normalDotRay);
  dpdy = stepY - at.ray * (glm::dot(planeNormal, stepY) / normalDotRay);
  return true;
}

// |column k of A^-1| for the 2x2 A = [a00 a01; a10 a11], clamped as every sampling error is.
double inverseColumnLength(double a00, double a01, double a10, double a11, int column)
{
  const double determinant = a00 * a11 - a01 * a10;
  const double length = column == 0 ? std::hypot(a11, a10) : std::hypot(a01, a00);
  if (std::abs(determinant) * kMaxSamplingError <= length)
  {
    return kMaxSamplingError;
  }
  return std::min(kMaxSamplingError, length / std::abs(determinant));
}

// 1 / sigma_min of J = [j00 j01; j10 j11], the most stretched direction of J^-1, as sigma_max / |det| (stable when J
// is nearly singular), clamped as every sampling error is.
double largestStretch(double j00, double j01, double j10, double j11)
{
  const double frobenius2 = j00 * j00 + j01 * j01 + j10 * j10 + j11 * j11;
  const double determinant = j00 * j11 - j01 * j10;
  const double sigmaMax =
    std::sqrt(0.5 * (frobenius2 + std::sqrt(std::max(0.0, frobenius2 * frobenius2 - 4.0 * determinant * determinant))));
  if (std::abs(determinant) * kMaxSamplingError <= sigmaMax)
  {
    return kMaxSamplingError;
  }
  return std::min(kMaxSamplingError, sigmaMax / std::abs(determinant));
}

// Two unit vectors spanning the plane normal to unit `normal`.
void planeBasis(const glm::dvec3& normal, glm::dvec3& e1, glm::dvec3& e2)
{
  const glm::dvec3 helper = std::abs(normal.x) < 0.9 ? glm::dvec3(1.0, 0.0, 0.0) : glm::dvec3(0.0, 1.0, 0.0);
  e1 = glm::normalize(glm::cross(normal, helper));
  e2 = glm::cross(normal, e1);
}

} // namespace

double texelRatio(const CameraView& camera, const LightView& light, double pixelX, double pixelY,
  const glm::dvec3& pWs, const glm::dvec3& nWs)
{
  glm::dvec3 dpdx, dpdy;
  if (!pixelStepsOnPlane(camera, rayAtReceiver(camera, pixelX, pixelY, pWs), nWs, dpdx, dpdy))
  {
    return 0.0;
  }
  const TexelGradients gradient = texelGradients(light, pWs);
  return largestStretch(glm::dot(gradient.u, dpdx), glm::dot(gradient.u, dpdy), glm::dot(gradient.v, dpdx),
    glm::dot(gradient.v, dpdy));
}

glm::dvec3 directionToLightView(const LightView& light, const glm::dvec3& pWs)
{
  if (light.projection == LightProjection::Perspective)
  {
    return glm::normalize(light.eyeWs - pWs);
  }
  // The light view looks down its -z: toward the light is its +z axis, the third row of viewFromWorld.
  const glm::dmat4& m = light.viewFromWorld;
  return glm::normalize(glm::dvec3(m[0][2], m[1][2], m[2][2]));
}

SamplingError samplingError(const CameraView& camera, const LightView& light, double pixelX, double pixelY,
  const glm::dvec3& pWs, const glm::dvec3& nWs)
{
  SamplingError error;
  const glm::dvec3 toLight = directionToLightView(light, pWs);
  const RayAtReceiver at = rayAtReceiver(camera, pixelX, pixelY, pWs);
  const glm::dvec3 toEye = -glm::normalize(at.ray);
  const double cosToLight = std::abs(glm::dot(nWs, toLight));
  glm::dvec3 dpdx, dpdy;
  if (cosToLight < 1e-12 || !pixelStepsOnPlane(camera, at, nWs, dpdx, dpdy))
  {
    return error;
  }
  const TexelGradients gradient = texelGradients(light, pWs);
  // J = d(texel)/d(pixel) on the tangent plane; its inverse's columns are one s and one t texel step, in pixels.
  const double j00 = glm::dot(gradient.u, dpdx);
  const double j01 = glm::dot(gradient.u, dpdy);
  const double j10 = glm::dot(gradient.v, dpdx);
  const double j11 = glm::dot(gradient.v, dpdy);
  error.texelRatio = largestStretch(j00, j01, j10, j11);
  error.texelRatioS = inverseColumnLength(j00, j01, j10, j11, 0);
  error.texelRatioT = inverseColumnLength(j00, j01, j10, j11, 1);

  // Eq. 1, dz/ds: one t-texel step on the plane across the light ray, in world units.
  glm::dvec3 acrossLight1, acrossLight2;
  planeBasis(toLight, acrossLight1, acrossLight2);
  const double texelWidthT = inverseColumnLength(glm::dot(gradient.u, acrossLight1), glm::dot(gradient.u, acrossLight2),
    glm::dot(gradient.v, acrossLight1), glm::dot(gradient.v, acrossLight2), 1);
  // 1/z: the pixel's footprint on the plane across the eye ray at the receiver (z times the pixel's angle).
  glm::dvec3 eyeStepX, eyeStepY;
  pixelStepsOnPlane(camera, at, toEye, eyeStepX, eyeStepY);
  const double pixelWidth = std::sqrt(glm::length(glm::cross(eyeStepX, eyeStepY)));
  error.perspectiveFactor = std::min(kMaxSamplingError, texelWidthT / pixelWidth);
  error.projectionFactor = std::min(kMaxSamplingError, std::abs(glm::dot(nWs, toEye)) / cosToLight);
  return error;
}

} // namespace sl
