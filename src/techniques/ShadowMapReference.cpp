#include "techniques/ShadowMapReference.h"

#include <algorithm>
#include <cmath>

namespace sl
{

ShadowLookup prepareShadowLookup(const ShadowMapInputs& inputs, const BiasSettings& bias, int x, int y,
  ProbeRecorder* recorder)
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
  if (recorder)
  {
    recorder->beginGroup("receiver");
    recorder->quantity("position", pWs, "world units", "G-buffer (pWs)");
    recorder->quantity("normal", nWs, "", "G-buffer (nWs)");
    recorder->quantity("direction_to_light", toLight, "", "ShadowLab: toward the light's centre");
  }
  sample.reachMargin = lightReachMargin(*inputs.light, nWs, toLight);
  if (!lightCanReach(*inputs.light, pWs, nWs))
  {
    if (recorder)
    {
      recorder->category("light_reach", "faces away / outside the light's reach: unlit, no shadow test",
        "ShadowLab (lightCanReach, LightView.h)");
    }
    return lookup;
  }
  lookup.sm = projectToShadowMap(inputs.lightView, pWs);
  sample.bias = depthBiasAt(inputs.lightView, bias, tanAngleToLight(nWs, toLight), pWs, lookup.sm.depthLin);
  lookup.comparisonDepth = lookup.sm.depthLin - sample.bias;
  sample.texelRatio = texelRatio(inputs.camera, inputs.lightView, x + 0.5, y + 0.5, pWs, nWs);
  sample.evaluated = true;
  if (recorder)
  {
    recorder->quantity("shadow_map_position", lookup.sm.uvTexels, "texels", "survey §2 (light-space projection)");
    recorder->quantity("receiver_depth", lookup.sm.depthLin, "linear depth", "survey §2 (d, distance along the light axis)");
    recorder->quantity("tan_angle_to_light", tanAngleToLight(nWs, toLight), "", "survey §5 (tan theta)");
    recorder->quantity("texel_world_size", receiverTexelWorldSize(inputs.lightView, pWs, lookup.sm.depthLin), "world units",
      "survey §2 (one texel at the receiver's depth)");
    recorder->quantity("depth_bias", sample.bias, "linear depth", "survey §5 (constant + slope-scaled bias)");
    recorder->quantity("comparison_depth", lookup.comparisonDepth, "linear depth", "survey §5 (d - bias)");
    recorder->quantity("texel_ratio", sample.texelRatio, "pixels per texel", "survey Eq. 2 (aliasing error m)");
  }
  return lookup;
}

TexelWithEdges texelWithEdges(const glm::dvec2& uvTexels)
{
  TexelWithEdges cell;
  cell.texel = glm::ivec2(static_cast<int>(std::floor(uvTexels.x)), static_cast<int>(std::floor(uvTexels.y)));
  const glm::dvec2 fraction = uvTexels - glm::dvec2(cell.texel);
  cell.edges = { { { fraction.x, cell.texel + glm::ivec2(-1, 0) }, { 1.0 - fraction.x, cell.texel + glm::ivec2(1, 0) },
    { fraction.y, cell.texel + glm::ivec2(0, -1) }, { 1.0 - fraction.y, cell.texel + glm::ivec2(0, 1) } } };
  return cell;
}

double nearestTexelTest(const ShadowMapInputs& inputs, const glm::dvec2& uvTexels, double comparisonDepth,
  ReferenceSample& sample, ProbeRecorder* recorder, const char* role, double weight)
{
  const int size = inputs.shadowMapLinear.width;
  const auto testTexel = [&](const glm::ivec2& texel) {
    const double stored =
      inputs.shadowMapLinear.at(std::clamp(texel.x, 0, size - 1), std::clamp(texel.y, 0, size - 1));
    return std::make_pair(comparisonDepth <= stored ? 1.0 : 0.0, stored);
  };
  const TexelWithEdges cell = texelWithEdges(uvTexels);
  const auto [result, stored] = testTexel(cell.texel);
  sample.noteDepthComparison(comparisonDepth, stored);
  if (recorder)
  {
    recorder->texel({ glm::clamp(cell.texel, glm::ivec2(0), glm::ivec2(size - 1)), role, stored, comparisonDepth,
      result == 0.0, weight });
  }
  // A tap this close to a texel edge could land in the neighbour on the GPU (float coordinates); that
  // only matters when the neighbour's test gives the other answer.
  for (const TexelEdge& edge : cell.edges)
  {
    if (edge.distance < 1e-3 && testTexel(edge.neighbour).first != result)
    {
      sample.texelEdgeMargin = std::min(sample.texelEdgeMargin, edge.distance);
    }
  }
  return result;
}

double polygonIdTest(const ShadowMapInputs& inputs, const glm::dvec2& uvTexels, int x, int y, ProbeRecorder* recorder)
{
  const int size = inputs.shadowMapPolygonId.width;
  const glm::ivec2 texel = glm::clamp(glm::ivec2(static_cast<int>(std::floor(uvTexels.x)),
    static_cast<int>(std::floor(uvTexels.y))), glm::ivec2(0), glm::ivec2(size - 1));
  const double stored = inputs.shadowMapPolygonId.at(texel.x, texel.y);
  const double own = inputs.receiverPolygonId.at(x, y);
  const double result = stored == own ? 1.0 : 0.0;
  if (recorder)
  {
    recorder->quantity("receiver_polygon_id", own, "", "survey §5 (Hourcade & Nicolas 1985: the receiver's polygon id)");
    recorder->quantity("stored_polygon_id", stored, "", "survey §5 (the nearest caster triangle's id at the texel)");
  }
  return result;
}

double layerComparisonDepth(
  ShadowMapDepthLayer layer, double first, double second, double texelWorldSizeAtFirst, double dualMaxOffsetTexels)
{
  const double midpoint = 0.5 * (first + second);
  switch (layer)
  {
    case ShadowMapDepthLayer::First:
    case ShadowMapDepthLayer::PolygonId:
      return first;
    case ShadowMapDepthLayer::Midpoint:
      return midpoint;
    case ShadowMapDepthLayer::Dual:
      return std::min(midpoint, first + dualMaxOffsetTexels * texelWorldSizeAtFirst);
  }
  return first;
}

ImageF layerComparisonMap(ShadowMapDepthLayer layer, const ImageF& first, const ImageF& second, const LightView& view,
  double dualMaxOffsetTexels)
{
  ImageF compared(first.width, first.height, 1);
  for (int y = 0; y < first.height; ++y)
  {
    for (int x = 0; x < first.width; ++x)
    {
      const double z1 = first.at(x, y);
      compared.at(x, y) = static_cast<float>(
        layerComparisonDepth(layer, z1, second.at(x, y), view.texelWorldSize(z1), dualMaxOffsetTexels));
    }
  }
  return compared;
}

} // namespace sl
