// The sampling-error datasets (issue 29: deep-view, deep-view-behind; datasets/generator) measured on the frames the
// renderer makes: the depth range the camera and the visible receivers span, and the perspective aliasing a uniform
// map leaves on them (survey §3). The CLI side (renders, wall-ring's refusal) is tests/cli/SamplingDatasetsCliTest.cpp.
#include "support/TestSupport.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

namespace sl
{
namespace
{

// (view depth, texel_ratio) of the covered pixels on the ground (normal +y), sorted by depth.
std::vector<std::pair<double, double>> groundSamples(const FrameResult& frame)
{
  const ImageF& depth = frame.find("depth")->image;
  const ImageF& coverage = frame.find("coverage")->image;
  const ImageF& normal = frame.find("normal")->image;
  const ImageF& texelRatio = frame.find("texel_ratio")->image;
  std::vector<std::pair<double, double>> samples;
  for (int y = 0; y < depth.height; ++y)
  {
    for (int x = 0; x < depth.width; ++x)
    {
      if (coverage.at(x, y) > 0.5f && normal.at(x, y, 1) > 0.999f)
      {
        samples.emplace_back(depth.at(x, y), texelRatio.at(x, y));
      }
    }
  }
  std::sort(samples.begin(), samples.end());
  return samples;
}

double medianTexelRatio(std::vector<std::pair<double, double>>::const_iterator first,
  std::vector<std::pair<double, double>>::const_iterator last)
{
  std::vector<double> ratios;
  for (auto it = first; it != last; ++it)
  {
    ratios.push_back(it->second);
  }
  std::nth_element(ratios.begin(), ratios.begin() + ratios.size() / 2, ratios.end());
  return ratios[ratios.size() / 2];
}

// The camera's clipping range as the frame used it (makeCameraView from the scene's bounds) spans more than 100:1, the
// deep view the survey's Fig. 12 plots (z from 1 to 100). The visible ground's range depends on the pixel rows next
// to the horizon (the camera looks horizontally): at 128 rows the first row below it meets the ground at 311, past
// its far edge (302), and the second at 103.6, so 42:1 here; at the scene's 512 rows 102:1 (2.43 .. 249).
TEST(SamplingDatasets, DeepViewsSpanAHundredfoldDepthRange)
{
  for (const std::string name : { "deep-view", "deep-view-behind" })
  {
    const FrameResult frame = test::renderDataset(test::loadDataset(name), "hard", 128, 128);
    const double clipRatio = frame.camera.farDepth / frame.camera.nearDepth;
    const std::vector<std::pair<double, double>> ground = groundSamples(frame);
    ASSERT_GT(ground.size(), 2000u) << name;
    const double visibleRatio = ground.back().first / ground.front().first;
    std::cout << "[ measured ] " << name << ": camera near " << frame.camera.nearDepth << ", far "
              << frame.camera.farDepth << " (far/near " << clipRatio << "); visible ground depth "
              << ground.front().first << " .. " << ground.back().first << " (" << visibleRatio << ")\n";
    EXPECT_GE(clipRatio, 100.0) << name;
    EXPECT_GE(visibleRatio, 40.0) << name;
    // The near plane is the scene's own (the ground starts 2 ahead), not the renderer's 1e-4 floor.
    EXPECT_NEAR(frame.camera.nearDepth, 1.98, 1e-9) << name;
  }
}

// What deep-view is for: under a uniform (focused, unwarped) map the nearest ground is undersampled far more than the
// farthest, by about the depth ratio (survey §3, Eq. 1: dp/ds ~ 1/z with the light perpendicular to the view).
TEST(SamplingDatasets, UniformMapUndersamplesTheNearGround)
{
  const FrameResult frame = test::renderDataset(test::loadDataset("deep-view"), "hard", 128, 128);
  const std::vector<std::pair<double, double>> ground = groundSamples(frame);
  ASSERT_GT(ground.size(), 2000u);
  const std::size_t bin = ground.size() / 20; // the nearest and farthest 5 % of the ground pixels
  const double nearMedian = medianTexelRatio(ground.begin(), ground.begin() + bin);
  const double farMedian = medianTexelRatio(ground.end() - bin, ground.end());
  std::cout << "[ measured ] deep-view hard 128x128: median texel_ratio " << nearMedian << " at depths "
            << ground.front().first << " .. " << ground[bin].first << ", " << farMedian << " at "
            << ground[ground.size() - bin].first << " .. " << ground.back().first << "\n";
  EXPECT_GT(nearMedian, 1.0) << "the nearest ground should be undersampled (more than a pixel per texel)";
  EXPECT_GT(nearMedian, 10.0 * farMedian);
}

} // namespace
} // namespace sl
