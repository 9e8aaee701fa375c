#include "techniques/dcs/DcsReference.h"

#include "objectspace/ShadowVolumeGeometry.h"
#include "objectspace/ShadowVolumeReference.h"

#include <algorithm>
#include <string>

namespace sl
{

DcsPixelTwin dcsPixelTwin(const Scene& scene, const Light& light, const DcsEdgeSet& wedges,
  const LightSampleSet& samples, glm::ivec2 pixel, const glm::dvec3& pWs, const glm::dvec3& nWs,
  double receiverOffset, ProbeRecorder* recorder, StsvOcclusionTest test)
{
  DcsPixelTwin twin;
  twin.countedPoint = shadowVolumeReceiverPoint(scene, receiverOffset, pWs);
  const glm::dvec3& p = twin.countedPoint;
  if (recorder)
  {
    recorder->beginGroup("centre (reference sample)");
  }
  twin.centreCount = casterCrossings(scene, VolumeLight::from(light), p, recorder, true);
  const std::vector<glm::dvec3> points = dcsSamplePoints(light, samples, pixel);
  twin.sampleCounts.assign(points.size(), twin.centreCount);
  const std::vector<glm::dvec3> outline = lightOutline(light);
  if (recorder)
  {
    recorder->beginGroup("wedges containing the point");
  }
  for (const DcsWedgeEdge& wedge : wedges.wedges)
  {
    if (!wedgeContains(wedge, p, outline, light.normal))
    {
      continue;
    }
    ++twin.wedgesCovering;
    const int multiplicity = wedgeMultiplicity(wedge, p);
    int changed = 0;
    for (std::size_t index = 0; index < points.size() && multiplicity != 0; ++index)
    {
      const int change = sampleCountChange(wedge, p, light.center, points[index]);
      twin.sampleCounts[index] += change;
      changed += change != 0;
    }
    if (recorder)
    {
      // The edge's projection from p onto the light plane, in light coordinates (right, up) from the centre.
      const auto onLight = [&](const glm::dvec3& q) {
        const double heightP = glm::dot(light.normal, p - light.center);
        const double heightQ = glm::dot(light.normal, q - light.center);
        const glm::dvec3 hit = heightP - heightQ > 1e-300 ? p + (heightP / (heightP - heightQ)) * (q - p) : q;
        return glm::dvec2(glm::dot(hit - light.center, light.right()), glm::dot(hit - light.center, light.up));
      };
      recorder->lightPolygon({ "wedge of caster " + std::to_string(wedge.objectIndex) + ": M_e = " +
          std::to_string(multiplicity) + ", " + std::to_string(changed) + " samples changed",
        { onLight(wedge.v0), onLight(wedge.v1) }, 0.0 }); // a segment, no area: M_e is in its role
    }
  }
  // Perforated casters: +1 for every sample an STSV holding p hides (STSV_DCS).
  const StsvPointOcclusion stsv = stsvPointOcclusion(buildStsvSet(scene, light), scene, p, points, test);
  for (std::size_t index = 0; index < points.size(); ++index)
  {
    twin.sampleCounts[index] += stsv.hiddenBy[index];
  }
  if (recorder && stsv.covering > 0)
  {
    recorder->beginGroup("STSVs containing the point");
    recorder->quantity("stsv_covering", stsv.covering, "STSVs", "Forest et al. 2009 §2.3");
  }
  twin.dcMin = *std::min_element(twin.sampleCounts.begin(), twin.sampleCounts.end());
  twin.dcMax = *std::max_element(twin.sampleCounts.begin(), twin.sampleCounts.end());
  int hiddenCount = 0;
  for (std::size_t index = 0; index < points.size(); ++index)
  {
    const bool blocked = twin.sampleCounts[index] > 0;
    const bool belowHorizon = glm::dot(nWs, points[index] - pWs) <= 0.0;
    twin.hidden.push_back(blocked || belowHorizon);
    twin.occludedSamples += blocked;
    hiddenCount += blocked || belowHorizon;
    if (recorder)
    {
      const glm::dvec3 offset = points[index] - light.center;
      recorder->lightSample({ glm::dvec2(glm::dot(offset, light.right()), glm::dot(offset, light.up)),
        blocked || belowHorizon, twin.sampleCounts[index] });
    }
  }
  twin.visibility = static_cast<double>(samples.count() - hiddenCount) / samples.count();
  return twin;
}

} // namespace sl
