#include "techniques/MomentReference.h"

#include <algorithm>
#include <cmath>

namespace sl
{
namespace
{

template <typename Visit>
void visitBox(const ShadowMapInputs& inputs, const glm::dvec2& uvTexels, int width, Visit visit)
{
  const int size = inputs.shadowMapLinear.width;
  const int centerX = std::clamp(static_cast<int>(std::floor(uvTexels.x)), 0, size - 1);
  const int centerY = std::clamp(static_cast<int>(std::floor(uvTexels.y)), 0, size - 1);
  const int first = -(width - 1) / 2;
  for (int j = 0; j < width; ++j)
  {
    for (int i = 0; i < width; ++i)
    {
      visit(static_cast<double>(inputs.shadowMapLinear.at(
        std::clamp(centerX + first + i, 0, size - 1), std::clamp(centerY + first + j, 0, size - 1))));
    }
  }
}

} // namespace

FilteredMoments boxMoments(const ShadowMapInputs& inputs, const glm::dvec2& uvTexels, int width, double exponent)
{
  FilteredMoments moments;
  const double nearDepth = inputs.lightView.nearDepth;
  const double farDepth = inputs.lightView.farDepth;
  visitBox(inputs, uvTexels, width, [&](double z) {
    moments.mean += z;
    moments.second += z * z;
    moments.exponential += std::exp(exponent * std::clamp((z - nearDepth) / (farDepth - nearDepth), 0.0, 1.0));
  });
  const double count = static_cast<double>(width) * width;
  moments.mean /= count;
  moments.second /= count;
  moments.exponential /= count;
  return moments;
}

double boxPcf(const ShadowMapInputs& inputs, const glm::dvec2& uvTexels, double comparisonDepth, int width)
{
  double lit = 0.0;
  visitBox(inputs, uvTexels, width, [&](double z) { lit += comparisonDepth <= z ? 1.0 : 0.0; });
  return lit / (static_cast<double>(width) * width);
}

} // namespace sl
