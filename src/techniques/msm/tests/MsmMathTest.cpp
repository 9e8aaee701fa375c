// msm's reconstruction (msmHamburger4, the CPU twin of MsmVisibility.glsl) against closed forms: the three-point
// distribution it returns reproduces all four biased moments; with two depths in the filter region it is exact
// (the true fraction in front, up to the bias); and on random depth distributions it is a lower bound on the
// shadow intensity (Peters & Klein 2015, abstract: "the sharpest possible lower bound").
#include "techniques/msm/MsmTechnique.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>
#include <vector>

namespace sl
{
namespace
{

struct MsmTestDistribution
{
  std::vector<double> depths;
  std::vector<double> weights;

  glm::dvec4 moments() const
  {
    glm::dvec4 b(0.0);
    for (std::size_t i = 0; i < depths.size(); ++i)
    {
      const double z = depths[i];
      b += weights[i] * glm::dvec4(z, z * z, z * z * z, z * z * z * z);
    }
    return b;
  }
  double fractionInFront(double zf) const
  {
    double sum = 0.0;
    for (std::size_t i = 0; i < depths.size(); ++i)
    {
      sum += depths[i] < zf ? weights[i] : 0.0;
    }
    return sum;
  }
};

TEST(MsmMath, TheThreePointDistributionReproducesAllFourBiasedMoments)
{
  const MsmTestDistribution distribution{ { 0.2, 0.35, 0.5, 0.9 }, { 0.1, 0.4, 0.3, 0.2 } };
  for (const double zf : { 0.1, 0.3, 0.42, 0.7, 0.95 })
  {
    const MsmReconstruction msm = msmHamburger4(distribution.moments(), 3e-5, zf);
    const double support[3] = { zf, msm.supportNear, msm.supportFar };
    const double weights[3] = { msm.weights.x, msm.weights.y, msm.weights.z };
    EXPECT_LT(msm.supportNear, msm.supportFar) << zf;
    for (int k = 0; k <= 4; ++k)
    {
      double moment = 0.0;
      for (int i = 0; i < 3; ++i)
      {
        moment += weights[i] * std::pow(support[i], k);
      }
      const double expected = k == 0 ? 1.0 : msm.biasedMoments[k - 1];
      EXPECT_NEAR(moment, expected, 1e-9) << "z_f " << zf << ", moment " << k;
    }
  }
}

// Two depths (a planar occluder over a planar receiver): the two support points are the occluder and the receiver,
// and the shadow intensity is the occluder's share, exactly in the limit alpha -> 0.
TEST(MsmMath, TwoDepthsAreReconstructedExactlyUpToTheBias)
{
  for (const double occluderShare : { 0.1, 0.5, 0.83 })
  {
    const MsmTestDistribution distribution{ { 0.3, 0.6 }, { occluderShare, 1.0 - occluderShare } };
    for (const double alpha : { 1e-8, 3e-5, 1e-3 })
    {
      const MsmReconstruction behind = msmHamburger4(distribution.moments(), alpha, 0.59);
      const MsmReconstruction front = msmHamburger4(distribution.moments(), alpha, 0.25);
      // The bias moves mass towards 0 and 1, of order alpha: the error is a small multiple of it.
      EXPECT_NEAR(behind.shadowIntensity, occluderShare, 20.0 * alpha + 1e-9) << occluderShare << " alpha " << alpha;
      EXPECT_NEAR(front.shadowIntensity, 0.0, 20.0 * alpha + 1e-9) << occluderShare << " alpha " << alpha;
      if (alpha == 1e-8)
      {
        EXPECT_NEAR(behind.supportNear, 0.3, 1e-4) << occluderShare;
        std::cout << "[ measured ] two depths, share " << occluderShare << ": G at 0.59 " << behind.shadowIntensity
                  << ", supports " << behind.supportNear << " " << behind.supportFar << "\n";
      }
    }
  }
}

TEST(MsmMath, IsALowerBoundOnTheShadowIntensityOfRandomDistributions)
{
  std::mt19937 generator(2015);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int bounded = 0;
  double sharpest = 1.0; // smallest gap between the true fraction and the bound, over cases with a gap
  for (int trial = 0; trial < 2000; ++trial)
  {
    MsmTestDistribution distribution;
    const int count = 2 + static_cast<int>(unit(generator) * 6);
    double total = 0.0;
    for (int i = 0; i < count; ++i)
    {
      distribution.depths.push_back(unit(generator));
      distribution.weights.push_back(0.05 + unit(generator));
      total += distribution.weights.back();
    }
    for (double& weight : distribution.weights)
    {
      weight /= total;
    }
    const double zf = unit(generator);
    const double truth = distribution.fractionInFront(zf);
    const MsmReconstruction msm = msmHamburger4(distribution.moments(), 1e-7, zf);
    ASSERT_LE(msm.shadowIntensity, truth + 1e-5) << "trial " << trial << " z_f " << zf << ": bound " << msm.shadowIntensity
                                                  << " above the truth " << truth;
    ++bounded;
    sharpest = std::min(sharpest, truth - msm.shadowIntensity + (truth == 0.0 ? 1.0 : 0.0));
  }
  EXPECT_EQ(bounded, 2000);
  std::cout << "[ measured ] 2000 random distributions (2-7 depths): the bound never exceeds the true intensity\n";
}

} // namespace
} // namespace sl
