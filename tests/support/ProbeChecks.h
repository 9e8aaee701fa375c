// What the probe tests of the back-projection techniques (gbp06, gbp07, yfgl09; issue 15) check alike: which
// pixels to probe, the recorded quantities, and that the recorded areas add up to the pixel's occluded area.
#pragma once

#include "frame/FrameResult.h"
#include "frame/ProbeRecord.h"
#include "frame/TechniqueDescriptor.h"
#include "scene/Scene.h"
#include "techniques/ContourBackprojection.h"
#include "techniques/ContourReceiver.h"

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace sl::test
{

// The first component of the recorded quantity `name`; a quantity not recorded fails the test and reads NaN.
inline double recordedValue(const ProbeRecord& record, const std::string& name, const std::string& label)
{
  const ProbeQuantity* quantity = record.find(name);
  EXPECT_NE(quantity, nullptr) << label << ": no " << name;
  return quantity && !quantity->value.empty() ? quantity->value[0] : std::nan("");
}

// At most `count` of `pixels`, evenly spaced in their order (the midpoints of `count` equal runs), so that the
// pixels probed come from all over the frame when `pixels` are in scan order.
inline std::vector<glm::ivec2> evenlySpaced(const std::vector<glm::ivec2>& pixels, std::size_t count)
{
  const std::size_t picks = std::min(pixels.size(), count);
  std::vector<glm::ivec2> spaced;
  for (std::size_t k = 0; k < picks; ++k)
  {
    spaced.push_back(pixels[(2 * k + 1) * pixels.size() / (2 * picks)]);
  }
  return spaced;
}

// gbp06 and gbp07: the pixels of each class in the frame's `classification` buffer, in scan order; not the
// untested nor the ones cut short, and penumbra pixels only with partial visibility (|V - 0.5| < 0.48).
inline std::map<BackprojectionClass, std::vector<glm::ivec2>> backprojectionProbeCandidates(const FrameResult& frame)
{
  const ImageF& classes = frame.find("classification")->image;
  const ImageF& visibility = frame.find("visibility")->image;
  std::map<BackprojectionClass, std::vector<glm::ivec2>> candidates;
  for (int y = 0; y < classes.height; ++y)
  {
    for (int x = 0; x < classes.width; ++x)
    {
      const auto gpuClass = static_cast<BackprojectionClass>(std::lround(classes.at(x, y)));
      if (gpuClass != BackprojectionClass::NotTested && gpuClass != BackprojectionClass::OverLoopBudget &&
        (gpuClass != BackprojectionClass::Penumbra || std::abs(visibility.at(x, y) - 0.5f) < 0.48f))
      {
        candidates[gpuClass].emplace_back(x, y);
      }
    }
  }
  return candidates;
}

// gbp06 and gbp07: probes the candidates of each class (backprojectionProbeCandidates), 24 evenly spaced ones at
// most, until 2 lit, 2 umbra and 6 penumbra pixels replayed unambiguous (ProbeOutcome::ambiguity empty), and calls
// check(pixel, gpuClass, outcome, record) on each of those. Stops at the first fatal failure. Returns how many
// pixels of each class were checked.
template <typename Check>
std::map<BackprojectionClass, int> probeBackprojectionPixels(const TechniqueDescriptor& technique,
  const FrameResult& frame, const Scene& scene, Check&& check)
{
  std::map<BackprojectionClass, int> probed;
  for (const auto& entry : backprojectionProbeCandidates(frame))
  {
    const BackprojectionClass gpuClass = entry.first;
    for (const glm::ivec2 pixel : evenlySpaced(entry.second, 24)) // ambiguous ones skipped
    {
      if (probed[gpuClass] >= (gpuClass == BackprojectionClass::Penumbra ? 6 : 2))
      {
        break;
      }
      ProbeRecorder recorder;
      const ProbeOutcome outcome = technique.probe({ &frame, &scene, 0 }, pixel, recorder);
      if (!outcome.ambiguity.empty())
      {
        continue;
      }
      ++probed[gpuClass];
      check(pixel, gpuClass, outcome, recorder.record());
      if (testing::Test::HasFatalFailure())
      {
        return probed;
      }
    }
  }
  return probed;
}

// Recorded contour edges whose signed area is 0: checked against the radial area of their back-projection, or
// skipped (yfgl09's packets record edges outside the pixel's own kernel, which integrate nothing).
enum class ZeroAreaEdges
{
  Checked,
  Skipped
};

// GBP07's radial integration as recorded: f(O) A (the light polygons' signed areas) plus each contour edge's
// signed area, every edge's (but as `zeroAreaEdges` says) the radial area of its back-projection onto the square
// light of half-size `halfSize` within 1e-15 of the light's area.
inline double contourCoveredArea(const ProbeRecord& record, double halfSize, ZeroAreaEdges zeroAreaEdges,
  const std::string& label)
{
  const double lightArea = 4.0 * halfSize * halfSize;
  double covered = 0.0;
  for (const ProbeLightPolygon& polygon : record.lightPolygons)
  {
    covered += polygon.signedArea; // f(O) A
  }
  for (const ProbeContourEdge& edge : record.contourEdges)
  {
    if (zeroAreaEdges == ZeroAreaEdges::Checked || edge.signedArea != 0.0)
    {
      EXPECT_NEAR(edge.signedArea, radialEdgeArea(edge.lightA, edge.lightB, halfSize), 1e-15 * lightArea) << label;
    }
    covered += edge.signedArea;
  }
  return covered;
}

// The area the record says is covered equals the recorded occluded_area and, for a partial pixel (0 < V < 1),
// (1 - V) A, both within 1e-9 of the light's area A. Returns whether the pixel is partial.
inline bool expectCoveredAreaIsOccludedArea(const ProbeRecord& record, double covered, double visibility,
  double lightArea, const std::string& label)
{
  EXPECT_NEAR(covered, recordedValue(record, "occluded_area", label), 1e-9 * lightArea) << label;
  if (visibility > 0.0 && visibility < 1.0)
  {
    EXPECT_NEAR(covered, (1.0 - visibility) * lightArea, 1e-9 * lightArea) << label;
    return true;
  }
  return false;
}

} // namespace sl::test
