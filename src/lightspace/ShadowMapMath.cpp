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

double receiverTexelWorldSize(const LightView& view, const glm::dvec3& pWs, double depthLin)
{
  if (!view.warp.active())
  {
    return view.texelWorldSize(depthLin);
  }
  // J = d(texel u, v) / d(light x, y) at pWs; the texel's sides in world units are J^-1's columns.
  const glm::dmat4& m = view.clipFromWorld;
  const glm::dvec4 clip = m * glm::dvec4(pWs, 1.0);
  const glm::dvec2 ndc = glm::dvec2(clip) / clip.w;
  const glm::dvec3 rowX(m[0][0], m[1][0], m[2][0]);
  const glm::dvec3 rowY(m[0][1], m[1][1], m[2][1]);
  const glm::dvec3 rowW(m[0][3], m[1][3], m[2][3]);
  const double scale = 0.5 * view.resolution / clip.w;
  const glm::dvec3 gradU = scale * (rowX - ndc.x * rowW);
  const glm::dvec3 gradV = scale * (rowY - ndc.y * rowW);
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

double texelRatio(const CameraView& camera, const LightView& light, double pixelX, double pixelY,
  const glm::dvec3& pWs, const glm::dvec3& nWs)
{
  // Camera ray through the pixel: N + s R (affine in the pixel position, see CameraView).
  const glm::dvec3 nearPoint = camera.nearOrigin + pixelX * camera.nearStepX + pixelY * camera.nearStepY;
  const glm::dvec3 ray = camera.rayOrigin + pixelX * camera.rayStepX + pixelY * camera.rayStepY;
  const glm::dvec3& nearStepX = camera.nearStepX;
  const glm::dvec3& nearStepY = camera.nearStepY;
  const glm::dvec3& rayStepX = camera.rayStepX;
  const glm::dvec3& rayStepY = camera.rayStepY;
  const double normalDotRay = glm::dot(nWs, ray);
  if (std::abs(normalDotRay) < 1e-12 * glm::length(ray))
  {
    return 0.0; // the view ray grazes the surface: one pixel covers unboundedly many texels
  }
  const double s = glm::dot(pWs - nearPoint, ray) / glm::dot(ray, ray);
  // Moving one pixel moves the hit point along the tangent plane by dp = v - R (n.v)/(n.R), v = dN + s dR.
  const glm::dvec3 stepX = nearStepX + s * rayStepX;
  const glm::dvec3 stepY = nearStepY + s * rayStepY;
  const glm::dvec3 dpdx = stepX - ray * (glm::dot(nWs, stepX) / normalDotRay);
  const glm::dvec3 dpdy = stepY - ray * (glm::dot(nWs, stepY) / normalDotRay);

  // Texel coordinates u = N_sm (ndc.xy / 2 + 1/2), ndc = (M p).xy / (M p).w: du/dp = N_sm/2 (M_i - ndc_i M_w) / w.
  const glm::dmat4& m = light.clipFromWorld;
  const glm::dvec4 clip = m * glm::dvec4(pWs, 1.0);
  const glm::dvec2 ndc = glm::dvec2(clip) / clip.w;
  const glm::dvec3 rowX(m[0][0], m[1][0], m[2][0]);
  const glm::dvec3 rowY(m[0][1], m[1][1], m[2][1]);
  const glm::dvec3 rowW(m[0][3], m[1][3], m[2][3]);
  const double scale = 0.5 * light.resolution / clip.w;
  const glm::dvec3 gradU = scale * (rowX - ndc.x * rowW);
  const glm::dvec3 gradV = scale * (rowY - ndc.y * rowW);
  const double j00 = glm::dot(gradU, dpdx);
  const double j01 = glm::dot(gradU, dpdy);
  const double j10 = glm::dot(gradV, dpdx);
  const double j11 = glm::dot(gradV, dpdy);
  // 1 / sigma_min = sigma_max / |det| for a 2x2 matrix (stable when J is nearly singular).
  const double frobenius2 = j00 * j00 + j01 * j01 + j10 * j10 + j11 * j11;
  const double determinant = j00 * j11 - j01 * j10;
  const double sigmaMax =
    std::sqrt(0.5 * (frobenius2 + std::sqrt(std::max(0.0, frobenius2 * frobenius2 - 4.0 * determinant * determinant))));
  if (std::abs(determinant) * 1e6 <= sigmaMax)
  {
    return 1e6;
  }
  return std::min(1e6, sigmaMax / std::abs(determinant));
}

} // namespace sl
