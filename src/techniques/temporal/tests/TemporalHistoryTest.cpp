// The CPU twin of temporal reprojection (survey §4.6; SJW07) on synthetic inputs: the confidence formula, the jitter
// sequence and the shifted light view, the history update with its disocclusion test, and the whole method on a
// synthetic straight shadow edge sampled by a jittered grid, whose misclassified fraction falls with K.
#include "techniques/temporal/TemporalTechnique.h"

#include "lightspace/ShadowMapMath.h"

#include <glm/gtc/matrix_transform.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>

namespace sl
{
namespace
{

TEST(TemporalHistory, ConfidenceIsOneAtTheTexelCentreAndZeroOnItsBorder)
{
  EXPECT_DOUBLE_EQ(shadowTestConfidence({ 3.5, 7.5 }), 1.0);
  EXPECT_DOUBLE_EQ(shadowTestConfidence({ 3.0, 7.5 }), 0.0);
  EXPECT_NEAR(shadowTestConfidence({ 3.5, 7.999999 }), 2e-6, 1e-12);
  // The larger of the two axes' distances (an L-infinity ball): 0.25 from the centre in x, 0.1 in y.
  EXPECT_NEAR(shadowTestConfidence({ 3.75, 7.4 }), 0.5, 1e-12);
  EXPECT_NEAR(shadowTestConfidence({ -0.25, -0.5 }), 0.5, 1e-12); // texel (-1, -1): centre (-0.5, -0.5)
}

TEST(TemporalHistory, JitterStartsUnshiftedAndFillsTheTexel)
{
  EXPECT_EQ(temporalJitterOffset(0), glm::dvec2(0.0));
  EXPECT_EQ(temporalJitterOffset(1), glm::dvec2(-0.5, 1.0 / 3.0));
  // The largest L-infinity distance from a point of the texel to the nearest offset (on the torus, as a whole-texel
  // shift maps the grid onto itself): it halves about every 4x more frames (a low-discrepancy set in 2D).
  double previous = 1.0;
  for (const int frames : { 1, 4, 16, 64 })
  {
    double fill = 0.0;
    for (int i = 0; i < 64; ++i)
    {
      for (int j = 0; j < 64; ++j)
      {
        const glm::dvec2 point((i + 0.5) / 64.0 - 0.5, (j + 0.5) / 64.0 - 0.5);
        double nearest = 1.0;
        for (int k = 0; k < frames; ++k)
        {
          const glm::dvec2 offset = temporalJitterOffset(k);
          EXPECT_GE(offset.x, -0.5);
          EXPECT_LT(offset.x, 0.5);
          glm::dvec2 d = glm::abs(point - offset);
          d = glm::min(d, 1.0 - d);
          nearest = std::min(nearest, std::max(d.x, d.y));
        }
        fill = std::max(fill, nearest);
      }
    }
    std::cout << "[ measured ] K = " << frames << ": every point of the texel within " << fill
              << " texel (L-inf) of a frame's offset\n";
    EXPECT_LT(fill, previous);
    previous = fill;
  }
  EXPECT_LT(previous, 0.125) << "K = 64";
}

TEST(TemporalHistory, JitteredLightViewShiftsEveryShadowMapPositionByTheOffset)
{
  for (const LightProjection projection : { LightProjection::Orthographic, LightProjection::Perspective })
  {
    LightView view;
    view.projection = projection;
    view.resolution = 256;
    view.viewFromWorld = glm::lookAt(glm::dvec3(1, 6, 2), glm::dvec3(0), glm::dvec3(0, 0, 1));
    view.clipFromView = projection == LightProjection::Perspective ? glm::perspective(0.8, 1.0, 1.0, 20.0)
                                                                   : glm::ortho(-3.0, 3.0, -3.0, 3.0, 1.0, 20.0);
    view.clipFromWorld = view.clipFromView * view.viewFromWorld;
    const glm::dvec2 offset(0.3125, -0.4);
    const LightView shifted = jitteredLightView(view, offset);
    for (const glm::dvec3 p : { glm::dvec3(0.0), glm::dvec3(1.2, -0.3, 0.7), glm::dvec3(-1.0, 0.5, -0.9) })
    {
      const ShadowMapSample before = projectToShadowMap(view, p);
      const ShadowMapSample after = projectToShadowMap(shifted, p);
      EXPECT_NEAR(after.uvTexels.x - before.uvTexels.x, offset.x, 1e-9);
      EXPECT_NEAR(after.uvTexels.y - before.uvTexels.y, offset.y, 1e-9);
      EXPECT_DOUBLE_EQ(after.depthLin, before.depthLin);
    }
  }
}

TEST(TemporalHistory, UpdateIsTheConfidenceWeightedMean)
{
  TemporalSettings settings;
  settings.confidenceExponent = 2.0;
  TemporalHistory history;
  history = updateTemporalHistory(history, { 1.0, 1.0, 10.0, 10.0 }, settings);
  history = updateTemporalHistory(history, { 0.0, 0.5, 10.0, 10.0 }, settings);
  EXPECT_DOUBLE_EQ(history.weight, 1.25);               // 1^2 + 0.5^2
  EXPECT_DOUBLE_EQ(history.visibility, 1.0 / 1.25);     // (1 x 1 + 0.25 x 0) / 1.25
  EXPECT_DOUBLE_EQ(history.frames, 2.0);
  EXPECT_DOUBLE_EQ(history.confidence, 1.0);
  EXPECT_DOUBLE_EQ(history.depth, 10.0);
  // m = 0: the plain mean, texel borders (conf 0) included.
  settings.confidenceExponent = 0.0;
  TemporalHistory plain;
  plain = updateTemporalHistory(plain, { 1.0, 0.0, 10.0, 10.0 }, settings);
  plain = updateTemporalHistory(plain, { 0.0, 0.9, 10.0, 10.0 }, settings);
  plain = updateTemporalHistory(plain, { 0.0, 0.2, 10.0, 10.0 }, settings);
  EXPECT_NEAR(plain.visibility, 1.0 / 3.0, 1e-15);
  EXPECT_DOUBLE_EQ(plain.confidence, 0.9);
  // Every frame on a texel border with m > 0: no weight; the latest sample stands.
  settings.confidenceExponent = 4.0;
  TemporalHistory border;
  border = updateTemporalHistory(border, { 1.0, 0.0, 10.0, 10.0 }, settings);
  border = updateTemporalHistory(border, { 0.0, 0.0, 10.0, 10.0 }, settings);
  EXPECT_DOUBLE_EQ(border.visibility, 0.0);
  EXPECT_DOUBLE_EQ(border.weight, 0.0);
}

TEST(TemporalHistory, DisocclusionDropsTheHistoryBeyondTheThreshold)
{
  TemporalSettings settings;
  settings.confidenceExponent = 1.0;
  settings.disocclusionThreshold = 0.01;
  TemporalHistory history;
  history = updateTemporalHistory(history, { 1.0, 0.9, 10.0, 10.0 }, settings);
  history = updateTemporalHistory(history, { 1.0, 0.8, 10.0, 10.0 }, settings);
  // The surface seen now lies 0.2 (2 %) behind the history's: another surface, the history goes.
  bool rejected = false;
  const TemporalHistory moved = updateTemporalHistory(history, { 0.0, 0.3, 10.3, 10.2 }, settings, &rejected);
  EXPECT_TRUE(rejected);
  EXPECT_DOUBLE_EQ(moved.frames, 1.0);
  EXPECT_DOUBLE_EQ(moved.visibility, 0.0);
  EXPECT_DOUBLE_EQ(moved.weight, 0.3);
  EXPECT_DOUBLE_EQ(moved.confidence, 0.3);
  EXPECT_DOUBLE_EQ(moved.depth, 10.3);
  // Within 1 %: the same surface, kept.
  const TemporalHistory kept = updateTemporalHistory(history, { 0.0, 0.3, 10.05, 10.05 }, settings, &rejected);
  EXPECT_FALSE(rejected);
  EXPECT_DOUBLE_EQ(kept.frames, 3.0);
  EXPECT_NEAR(kept.visibility, 1.7 / 2.0, 1e-15);
  // A threshold of 5 % keeps the first one too.
  settings.disocclusionThreshold = 0.05;
  updateTemporalHistory(history, { 0.0, 0.3, 10.3, 10.2 }, settings, &rejected);
  EXPECT_FALSE(rejected);
}

// The method on synthetic inputs: receivers on a 0.1-texel grid under a straight shadow edge (half-plane
// a x + b y > c shadowed, in texel units); a frame's map holds the half-plane's value at its texel centres, shifted by
// the frame's offset; each receiver accumulates its texel's value with its confidence. Misclassified: |V - truth| > 1/2.
double syntheticMisclassifiedFraction(int frames, double exponent)
{
  TemporalSettings settings;
  settings.frames = frames;
  settings.confidenceExponent = exponent;
  const glm::dvec2 normal = glm::normalize(glm::dvec2(1.0, 0.37));
  const double edge = 4.03;
  const auto shadowed = [&](const glm::dvec2& p) { return glm::dot(normal, p) > edge; };
  int misclassified = 0;
  int receivers = 0;
  for (int i = 0; i < 80; ++i)
  {
    for (int j = 0; j < 80; ++j)
    {
      const glm::dvec2 p(0.013 + 0.1 * i, 0.027 + 0.1 * j);
      TemporalHistory history;
      for (int k = 0; k < frames; ++k)
      {
        const glm::dvec2 uv = p + temporalJitterOffset(k);
        const glm::dvec2 centre = glm::floor(uv) + 0.5 - temporalJitterOffset(k); // back in unshifted texels
        history = updateTemporalHistory(
          history, { shadowed(centre) ? 0.0 : 1.0, shadowTestConfidence(uv), 1.0, 1.0 }, settings);
      }
      const double truth = shadowed(p) ? 0.0 : 1.0;
      misclassified += std::abs(history.visibility - truth) > 0.5 ? 1 : 0;
      ++receivers;
    }
  }
  return static_cast<double>(misclassified) / receivers;
}

TEST(TemporalHistory, SyntheticEdgeConvergesAsFramesAccumulate)
{
  for (const double exponent : { 1.0, 4.0 })
  {
    double previous = 1.0;
    double first = 0.0;
    for (const int frames : { 1, 4, 16, 64 })
    {
      const double fraction = syntheticMisclassifiedFraction(frames, exponent);
      std::cout << "[ measured ] synthetic edge, m = " << exponent << ", K = " << frames << ": " << 100.0 * fraction
                << " % of receivers misclassified\n";
      if (frames == 1)
      {
        first = fraction;
        EXPECT_GT(fraction, 0.01); // one map per 0.1-texel grid: a band of about a quarter texel on each side
      }
      else
      {
        EXPECT_LT(fraction, previous) << "m = " << exponent << ", K = " << frames;
      }
      previous = fraction;
    }
    EXPECT_LE(previous, 0.25 * first) << "m = " << exponent << ": K = 64 against K = 1";
  }
}

} // namespace
} // namespace sl
