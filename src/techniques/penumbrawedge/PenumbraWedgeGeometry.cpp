#include "techniques/penumbrawedge/PenumbraWedgeGeometry.h"

#include "core/Error.h"
#include "objectspace/ShadowVolumeGeometry.h"
#include "objectspace/ShadowVolumeReference.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace sl
{
namespace
{

// A linear function k + dot(slope, x) of light coordinates x = (right, up) offsets from the centre.
struct LightLinear
{
  double constant = 0.0;
  glm::dvec2 slope{ 0.0 };
  double at(const glm::dvec2& x) const { return constant + glm::dot(slope, x); }
  LightLinear negated() const { return { -constant, -slope }; }
};

// Sutherland-Hodgman: the part of the convex polygon where f >= 0.
std::vector<glm::dvec2> clipPolygon(const std::vector<glm::dvec2>& polygon, const LightLinear& f)
{
  std::vector<glm::dvec2> clipped;
  for (std::size_t i = 0; i < polygon.size(); ++i)
  {
    const glm::dvec2& a = polygon[i];
    const glm::dvec2& b = polygon[(i + 1) % polygon.size()];
    const double fa = f.at(a);
    const double fb = f.at(b);
    if (fa >= 0.0)
    {
      clipped.push_back(a);
    }
    if ((fa >= 0.0) != (fb >= 0.0))
    {
      clipped.push_back(a + (fa / (fa - fb)) * (b - a));
    }
  }
  return clipped;
}

double polygonArea(const std::vector<glm::dvec2>& polygon)
{
  double twice = 0.0;
  for (std::size_t i = 0; i < polygon.size(); ++i)
  {
    const glm::dvec2& a = polygon[i];
    const glm::dvec2& b = polygon[(i + 1) % polygon.size()];
    twice += a.x * b.y - a.y * b.x;
  }
  return 0.5 * std::abs(twice);
}

int signOf(double value)
{
  return (value > 0.0) - (value < 0.0);
}

} // namespace

PenumbraWedgeArea penumbraWedgeArea(const DcsWedgeEdge& wedge, const glm::dvec3& pWs, const Light& light)
{
  SL_CHECK_MSG(light.type == LightType::Area && light.shape == LightShape::Square, "penumbra wedges need a square area light");
  PenumbraWedgeArea result;
  result.multiplicity = wedgeMultiplicity(wedge, pWs);
  if (result.multiplicity == 0)
  {
    return result;
  }
  // Relative to v0, as the shader (float differences of nearby points, not of large coordinates).
  const glm::dvec3 right = light.right();
  const glm::dvec3 up = light.up;
  const glm::dvec3 p = pWs - wedge.v0;
  const glm::dvec3 edge = wedge.v1 - wedge.v0;
  const glm::dvec3 c = light.center - wedge.v0;
  const auto onLight = [&](const glm::dvec3& normal, double constant) {
    return LightLinear{ constant, glm::dvec2(glm::dot(right, normal), glm::dot(up, normal)) };
  };
  // g(s) = orient(v0, v1, p, s) = dot(s - v0, (v1 - v0) x (p - v0)): s on the far side of e's projection when
  // g(s) g(c) < 0.
  const glm::dvec3 planeNormal = glm::cross(edge, p);
  const double gCentre = glm::dot(c, planeNormal);
  if (gCentre == 0.0)
  {
    return result; // c lies on the plane of p and e: no segment from c crosses the projection
  }
  const double side = signOf(gCentre);
  const LightLinear beyondEdge = onLight(planeNormal, gCentre).negated(); // -g(s): > 0 beyond e when g(c) > 0
  const LightLinear centrePlane = onLight(glm::cross(edge, c), 0.0); // orient(v0, v1, c, s), 0 at s = c
  // orient(p, c, s, v_i) = dot(s - p, (v_i - p) x (c - p)): the planes through p, c and each end of e, which bound
  // the sector. Like orient(v0, v1, c, s) they vanish at s = c: no constant term on the light (as in the shader).
  const LightLinear sector0 = onLight(glm::cross(-p, c - p), 0.0);
  const LightLinear sector1 = onLight(glm::cross(edge - p, c - p), 0.0);
  const auto scaled = [](const LightLinear& f, double by) { return LightLinear{ by * f.constant, by * f.slope }; };
  const double half = 0.5 * light.size;
  const std::vector<glm::dvec2> square = { { -half, -half }, { half, -half }, { half, half }, { -half, half } };
  double area = 0.0;
  for (const double sectorSide : { 1.0, -1.0 })
  {
    std::vector<glm::dvec2> region = square;
    for (const LightLinear& f : { scaled(beyondEdge, side), scaled(centrePlane, side), scaled(sector0, sectorSide),
           scaled(sector1, -sectorSide) })
    {
      region = clipPolygon(region, f);
      if (region.size() < 3)
      {
        break;
      }
    }
    if (region.size() >= 3)
    {
      const double part = polygonArea(region);
      if (part > 0.0)
      {
        area += part;
        result.farRegion.insert(result.farRegion.end(), region.begin(), region.end());
      }
    }
  }
  result.change = -static_cast<int>(side) * result.multiplicity;
  result.areaFraction = std::min(1.0, area / (light.size * light.size));
  result.occlusionDelta = result.areaFraction > 0.0 ? signOf(result.change) * result.areaFraction : 0.0;
  return result;
}

std::vector<DcsWedgeEdge> centreSilhouetteWedges(const DcsEdgeSet& wedges)
{
  std::vector<DcsWedgeEdge> centre;
  std::copy_if(wedges.wedges.begin(), wedges.wedges.end(), std::back_inserter(centre),
    [](const DcsWedgeEdge& wedge) { return wedge.silhouetteFromCentre; });
  return centre;
}

PenumbraWedgeScene penumbraWedgeScene(const Scene& scene, const Light& light)
{
  PenumbraWedgeScene prepared;
  prepared.wedges = centreSilhouetteWedges(potentialSilhouetteWedges(weldCasters(scene, true), light));
  prepared.stsvs = buildStsvSet(scene, light);
  return prepared;
}

PenumbraWedgePixel penumbraWedgePixel(const PenumbraWedgeScene& prepared, const Scene& scene, const Light& light,
  const glm::dvec3& pWs, double receiverOffset, const std::vector<glm::dvec3>& samples, StsvOcclusionTest test,
  ProbeRecorder* recorder)
{
  PenumbraWedgePixel pixel;
  pixel.countedPoint = shadowVolumeReceiverPoint(scene, receiverOffset, pWs);
  const glm::dvec3& p = pixel.countedPoint;
  if (recorder)
  {
    recorder->beginGroup("centre (hard shadow volume)");
  }
  pixel.centreCount = casterCrossings(scene, VolumeLight::from(light), p, recorder, true);
  pixel.occlusionRaw = pixel.centreCount > 0 ? 1.0 : 0.0;
  const std::vector<glm::dvec3> outline = lightOutline(light);
  if (recorder)
  {
    recorder->beginGroup("wedges containing the point");
  }
  for (const DcsWedgeEdge& wedge : prepared.wedges)
  {
    if (!wedgeContains(wedge, p, outline, light.normal))
    {
      continue;
    }
    ++pixel.wedgesCovering;
    const PenumbraWedgeArea area = penumbraWedgeArea(wedge, p, light);
    pixel.occlusionRaw += area.occlusionDelta;
    if (recorder && !area.farRegion.empty())
    {
      recorder->lightPolygon({ "far region of a wedge of caster " + std::to_string(wedge.objectIndex) + ": M_e = " +
          std::to_string(area.multiplicity) + ", count change " + std::to_string(area.change),
        area.farRegion, area.occlusionDelta * light.size * light.size });
    }
  }
  // STSVs (Forest et al. 2009 Alg. 1): OR the samples each STSV holding p hides.
  const StsvPointOcclusion stsv = stsvPointOcclusion(prepared.stsvs, scene, p, samples, test);
  pixel.stsvCovering = stsv.covering;
  pixel.stsvEmptyHits = stsv.emptyHits;
  pixel.stsvHidden.assign(samples.size(), false);
  for (std::size_t i = 0; i < samples.size(); ++i)
  {
    pixel.stsvHidden[i] = stsv.hiddenBy[i] > 0;
  }
  if (recorder && stsv.covering > 0)
  {
    recorder->beginGroup("STSVs containing the point");
    recorder->quantity("stsv_covering", stsv.covering, "STSVs", "Forest et al. 2009 §2.3");
    recorder->quantity("stsv_empty_hits", stsv.emptyHits, "STSVs", "STSVs holding the point that hide none of its samples");
  }
  pixel.stsvOccludedSamples = static_cast<int>(std::count(pixel.stsvHidden.begin(), pixel.stsvHidden.end(), true));
  if (!samples.empty())
  {
    pixel.occlusionRaw += static_cast<double>(pixel.stsvOccludedSamples) / static_cast<double>(samples.size());
  }
  pixel.visibility = 1.0 - std::clamp(pixel.occlusionRaw, 0.0, 1.0);
  return pixel;
}

} // namespace sl
