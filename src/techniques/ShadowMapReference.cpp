#include "techniques/ShadowMapReference.h"

#include <algorithm>
#include <cmath>

namespace sl
{

ShadowLookup prepareShadowLookup(const ShadowMapInputs& inputs, const BiasSettings& bias, int x, int y)
{
  ShadowLookup lookup;
  ReferenceSample& sample = lookup.sample;
  if (inputs.coverage.at(x, y) <= 0.5f)
  {
    return lookup;
  }
  if (inputs.receives.at(x, y) <= 0.5f)
  {
    sample.visibility = 1.0;
    return lookup;
  }
  const glm::dvec3 pWs(inputs.position.at(x, y, 0), inputs.position.at(x, y, 1), inputs.position.at(x, y, 2));
  const glm::dvec3 nWs(inputs.normal.at(x, y, 0), inputs.normal.at(x, y, 1), inputs.normal.at(x, y, 2));
  const glm::dvec3 toLight = directionToLight(*inputs.light, pWs);
  sample.reachMargin = std::abs(glm::dot(nWs, toLight));
  if (inputs.light->type == LightType::Area)
  {
    sample.reachMargin = std::min(sample.reachMargin, std::abs(glm::dot(inputs.light->normal, toLight)));
  }
  if (!lightCanReach(*inputs.light, pWs, nWs))
  {
    return lookup;
  }
  lookup.sm = projectToShadowMap(inputs.lightView, pWs);
  sample.bias = depthBias(inputs.lightView, bias, tanAngleToLight(nWs, toLight),
    lookup.sm.depthLin);
  lookup.comparisonDepth = lookup.sm.depthLin - sample.bias;
  sample.texelRatio = texelRatio(inputs.camera, inputs.lightView, x + 0.5, y + 0.5, pWs, nWs);
  sample.evaluated = true;
  return lookup;
}

double nearestTexelTest(const ShadowMapInputs& inputs, const glm::dvec2& uvTexels, double comparisonDepth,
  ReferenceSample& sample)
{
  const int size = inputs.shadowMapLinear.width;
  const auto testTexel = [&](int i, int j) {
    const double stored = inputs.shadowMapLinear.at(std::clamp(i, 0, size - 1), std::clamp(j, 0, size - 1));
    return std::make_pair(comparisonDepth <= stored ? 1.0 : 0.0, stored);
  };
  const int i = static_cast<int>(std::floor(uvTexels.x));
  const int j = static_cast<int>(std::floor(uvTexels.y));
  const auto [result, stored] = testTexel(i, j);
  sample.depthMargin = std::min(sample.depthMargin, std::abs(comparisonDepth - stored) / std::max(1e-30, std::abs(stored)));
  // A tap this close to a texel edge could land in the neighbour on the GPU (float coordinates); that
  // only matters when the neighbour's test gives the other answer.
  const double fractionX = uvTexels.x - i;
  const double fractionY = uvTexels.y - j;
  const struct
  {
    double distance;
    int di;
    int dj;
  } edges[] = { { fractionX, -1, 0 }, { 1.0 - fractionX, 1, 0 }, { fractionY, 0, -1 }, { 1.0 - fractionY, 0, 1 } };
  for (const auto& edge : edges)
  {
    if (edge.distance < 1e-3 && testTexel(i + edge.di, j + edge.dj).first != result)
    {
      sample.texelEdgeMargin = std::min(sample.texelEdgeMargin, edge.distance);
    }
  }
  return result;
}

} // namespace sl
