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
  const int i = std::clamp(static_cast<int>(std::floor(uvTexels.x)), 0, size - 1);
  const int j = std::clamp(static_cast<int>(std::floor(uvTexels.y)), 0, size - 1);
  const double stored = inputs.shadowMapLinear.at(i, j);
  const double fractionX = uvTexels.x - std::floor(uvTexels.x);
  const double fractionY = uvTexels.y - std::floor(uvTexels.y);
  sample.texelEdgeMargin = std::min({ sample.texelEdgeMargin, fractionX, 1.0 - fractionX, fractionY, 1.0 - fractionY });
  sample.depthMargin = std::min(sample.depthMargin, std::abs(comparisonDepth - stored) / std::max(1e-30, std::abs(stored)));
  return comparisonDepth <= stored ? 1.0 : 0.0;
}

} // namespace sl
