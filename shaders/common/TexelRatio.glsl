// The survey's aliasing error m (Eq. 2), exact per pixel: screen pixels spanned by one shadow-map texel
// along its most stretched direction, 1 / sigma_min of d(texel)/d(pixel) on the surface's tangent plane.
// Mirrors sl::texelRatio (src/lightspace/ShadowMapMath.cpp), which documents the derivation.
#include "common/CameraRay.glsl"
#include "common/ShadowMapCommon.glsl"

float texelRatio(vec2 pixel, vec3 pWs, vec3 nWs)
{
  vec3 nearPoint = cameraNearPoint(pixel);
  vec3 ray = cameraRayDirection(pixel);
  float normalDotRay = dot(nWs, ray);
  if (abs(normalDotRay) < 1e-12 * length(ray))
  {
    return 0.0;
  }
  float s = dot(pWs - nearPoint, ray) / dot(ray, ray);
  vec3 stepX = cameraNearStepX + s * cameraRayStepX;
  vec3 stepY = cameraNearStepY + s * cameraRayStepY;
  vec3 dpdx = stepX - ray * (dot(nWs, stepX) / normalDotRay);
  vec3 dpdy = stepY - ray * (dot(nWs, stepY) / normalDotRay);

  vec3 gradU;
  vec3 gradV;
  texelGradients(pWs, gradU, gradV);
  float j00 = dot(gradU, dpdx);
  float j01 = dot(gradU, dpdy);
  float j10 = dot(gradV, dpdx);
  float j11 = dot(gradV, dpdy);
  float frobenius2 = j00 * j00 + j01 * j01 + j10 * j10 + j11 * j11;
  float determinant = j00 * j11 - j01 * j10;
  float sigmaMax = sqrt(0.5 * (frobenius2 + sqrt(max(0.0, frobenius2 * frobenius2 - 4.0 * determinant * determinant))));
  if (abs(determinant) * 1e6 <= sigmaMax)
  {
    return 1e6;
  }
  return min(1e6, sigmaMax / abs(determinant));
}
