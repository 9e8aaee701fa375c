#include "lightspace/MomentHamburger.h"

#include <algorithm>
#include <cmath>

namespace sl
{

namespace
{

constexpr double msmPivotFloor = 1e-12; // D22's and D33's floor, as common/MomentHamburger.glsl

} // namespace

MsmReconstruction msmHamburger4(const glm::dvec4& moments, double momentBias, double fragmentDepth)
{
  MsmReconstruction result;
  // Step 1: the moment bias.
  const glm::dvec4 b = (1.0 - momentBias) * moments + momentBias * glm::dvec4(0.5);
  result.biasedMoments = b;
  const double zf = fragmentDepth;
  // Step 2: B c = (1, z_f, z_f^2) by LDL^T (D11 = 1, L21 = b1, L31 = b2).
  // D22 >= alpha / 4 in exact arithmetic; floored as D33 only against float rounding (common/MomentHamburger.glsl).
  const double d22 = std::max(b.y - b.x * b.x, msmPivotFloor);
  const double l32d22 = b.z - b.x * b.y;
  const double l32 = l32d22 / d22;
  // B is positive definite for alpha > 0, so D33 > 0; only float rounding makes it 0 or less
  // (common/MomentHamburger.glsl).
  const double d33 = std::max((b.w - b.y * b.y) - l32d22 * l32, msmPivotFloor);
  result.pivot2 = d22;
  result.pivot3 = d33;
  glm::dvec3 c(1.0, zf, zf * zf);
  c.y -= b.x;
  c.z -= b.y + l32 * c.y;
  c.y /= d22;
  c.z /= d33;
  c.y -= l32 * c.z;
  c.x -= c.y * b.x + c.z * b.y;
  result.polynomial = c;
  // Step 3: the two other support points, the roots of c1 + c2 z + c3 z^2, by the stable form
  // common/MomentHamburger.glsl uses (equal to the authors' code's -p/2 -+ sqrt(p^2/4 - q) in exact arithmetic),
  // clamped to +-1e6 as there.
  const double root = std::sqrt(std::max(c.y * c.y - 4.0 * c.x * c.z, 0.0));
  const double large = -0.5 * (c.y + (c.y < 0.0 ? -root : root));
  const double rootA = std::clamp(large / c.z, -1e6, 1e6);
  const double rootB = std::clamp(c.x / large, -1e6, 1e6);
  const double z2 = std::min(rootA, rootB);
  const double z3 = std::max(rootA, rootB);
  result.supportNear = z2;
  result.supportFar = z3;
  // The weights of the three-point distribution on (z_f, z_2, z_3) with moments 1, b1', b2' (Lagrange: the weight
  // of z_i is E[(z - z_j)(z - z_k)] / ((z_i - z_j)(z_i - z_k))).
  const auto weight = [&](double zi, double zj, double zk) {
    return (zj * zk - b.x * (zj + zk) + b.y) / ((zi - zj) * (zi - zk));
  };
  result.weights = glm::dvec3(weight(zf, z2, z3), weight(z2, zf, z3), weight(z3, zf, z2));
  // Step 4: the weights of the support points in front of z_f, in the shader's form.
  double intensity = 0.0;
  if (zf <= z2)
  {
    intensity = 0.0;
  }
  else if (zf <= z3)
  {
    intensity = (zf * z3 - b.x * (zf + z3) + b.y) / ((z3 - z2) * (zf - z2));
  }
  else
  {
    intensity = 1.0 - (z2 * z3 - b.x * (z2 + z3) + b.y) / ((zf - z2) * (zf - z3));
  }
  result.shadowIntensity = std::clamp(intensity, 0.0, 1.0);
  return result;
}

} // namespace sl
