#include "lightspace/PerspectiveWarp.h"

#include "core/Error.h"

#include <cmath>
#include <limits>

namespace sl
{

const char* warpName(WarpKind kind)
{
  switch (kind)
  {
    case WarpKind::None:
      return "none";
    case WarpKind::Psm:
      return "psm";
    case WarpKind::Lispsm:
      return "lispsm";
    case WarpKind::Tsm:
      return "tsm";
  }
  return "none";
}

void requireWarpableLight(WarpKind kind, LightType lightType)
{
  if (kind != WarpKind::None && lightType != LightType::Directional)
  {
    throw InputError(format("--set warp=", warpName(kind), ": a perspective warp needs a directional light (LiSPSM in ",
      "a point, spot or area light's post-perspective space is not implemented); use warp=none"));
  }
}

double lispsmOptimalN(double zNear, double zFar)
{
  return zNear + std::sqrt(zNear * zFar);
}

double warpParameter(WarpKind kind, double zNear, double zFar, double bodyLength, double sinGamma)
{
  constexpr double infinity = std::numeric_limits<double>::infinity();
  if (kind == WarpKind::None || !(sinGamma > 1e-9))
  {
    return infinity;
  }
  switch (kind)
  {
    case WarpKind::Psm:
      return zNear / sinGamma;
    case WarpKind::Lispsm:
      return lispsmOptimalN(zNear, zFar) / sinGamma;
    case WarpKind::Tsm:
      // MT04: the focus point at distance delta past the near side maps to the 80 % line, t(delta) = 0.8, which gives
      // n = 0.2 L delta / (0.8 L - delta); the focus point at B's middle (delta = L / 2): n = L / 3.
      return bodyLength / 3.0 / sinGamma;
    case WarpKind::None:
      break;
  }
  return infinity;
}

WarpRows warpRows(double n, double bodyLength)
{
  SL_CHECK(n > 0.0 && bodyLength > 0.0);
  const double strength = std::isinf(n) ? 0.0 : 1.0 / n; // 1/n: 0 is the uniform map
  return { { 1.0, 0.0, 0.0 }, { 0.0, strength + 1.0 / bodyLength, 0.0 }, { 0.0, strength, 1.0 } };
}

double closedFormWarpT(double z, double zNear, double zFar, double n)
{
  // s(z) = C (1 - n / (z - z_n + n)), C = (L + n) / L, written in 1/n so that n -> infinity is (z - z_n) / L.
  const double length = zFar - zNear;
  const double strength = std::isinf(n) ? 0.0 : 1.0 / n;
  return (1.0 + strength * length) * (z - zNear) / (length * (1.0 + strength * (z - zNear)));
}

double closedFormWarpAliasing(double z, double zNear, double zFar, double n)
{
  // dp/ds = (1/z) dz/ds = (z - z_n + n)^2 / (C n z) (survey Eq. 1 with cos α / cos β = 1).
  const double length = zFar - zNear;
  const double strength = std::isinf(n) ? 0.0 : 1.0 / n;
  const double w = 1.0 + strength * (z - zNear);
  return length * w * w / ((1.0 + strength * length) * z);
}

} // namespace sl
