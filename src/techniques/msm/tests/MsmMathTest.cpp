// msm's reconstruction (msmHamburger4, the CPU twin of MsmVisibility.glsl) against closed forms: the three-point
// distribution it returns reproduces all four biased moments; with two depths in the filter region it is exact
// (the true fraction in front, up to the bias); and on random depth distributions it is the sharpest lower bound on
// the shadow intensity (Peters & Klein 2015, abstract: "the sharpest possible lower bound"): never above the true
// fraction, and attained by a distribution with the same moments.
#include "structures/powermoments/PowerMomentMapStructure.h"
#include "techniques/Registry.h"
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

// The bound and its sharpness on random distributions of 2-7 depths. A lower bound: G never exceeds the fraction
// of the biased distribution ((1 - alpha) mu + alpha (delta_0 + delta_1) / 2, whose moments are b') in front of z_f.
// The sharpest one: the three-point distribution msmHamburger4 returns (z_f, z_2, z_3 with their weights) is a
// distribution, has the same moments 1, b1'..b4' and puts exactly G in front of z_f, so no lower bound can exceed
// G. A function returning G = 0 (or any value below the bound) fails the
// second check wherever the bound is positive, and many cases must have G well above 0.
TEST(MsmMath, IsTheSharpestLowerBoundOnRandomDistributions)
{
  constexpr double alpha = 3e-5;
  std::mt19937 generator(2015);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int positive = 0; // cases with G > 0.05
  double largestExcess = -1.0;       // max of G - the biased true fraction (<= 0 for a lower bound)
  double largestAttainedError = 0.0; // max |G - the three-point distribution's mass in front of z_f|
  double sumGap = 0.0;               // the biased true fraction - G, summed (the bound's looseness, for the record)
  double largestMomentError = 0.0;   // of the three-point distribution's moments 0..4 against 1, b'
  constexpr int trials = 2000;
  for (int trial = 0; trial < trials; ++trial)
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
    const double biasedTruth = (1.0 - alpha) * distribution.fractionInFront(zf) + 0.5 * alpha; // z_f in (0, 1)
    const MsmReconstruction msm = msmHamburger4(distribution.moments(), alpha, zf);
    const double intensity = msm.shadowIntensity;
    EXPECT_LE(intensity, biasedTruth + 1e-9) << "trial " << trial << " z_f " << zf << ": bound " << intensity
                                             << " above the biased true fraction " << biasedTruth;
    // The three-point distribution that attains the bound: non-negative weights summing to 1, mass before z_f = G.
    const double support[3] = { zf, msm.supportNear, msm.supportFar };
    const double weights[3] = { msm.weights.x, msm.weights.y, msm.weights.z };
    double inFront = 0.0;
    for (int i = 0; i < 3; ++i)
    {
      EXPECT_GE(weights[i], -1e-9) << "trial " << trial << " z_f " << zf << ": weight " << i;
      inFront += support[i] < zf ? weights[i] : 0.0;
    }
    for (int k = 0; k <= 4; ++k)
    {
      double moment = 0.0;
      for (int i = 0; i < 3; ++i)
      {
        moment += weights[i] * std::pow(support[i], k);
      }
      const double expected = k == 0 ? 1.0 : msm.biasedMoments[k - 1];
      largestMomentError = std::max(largestMomentError, std::abs(moment - expected));
      EXPECT_NEAR(moment, expected, 1e-9) << "trial " << trial << " z_f " << zf << ", moment " << k;
    }
    EXPECT_NEAR(intensity, inFront, 1e-9) << "trial " << trial << " z_f " << zf << ": G is not attained";
    largestExcess = std::max(largestExcess, intensity - biasedTruth);
    largestAttainedError = std::max(largestAttainedError, std::abs(intensity - inFront));
    sumGap += biasedTruth - intensity;
    positive += intensity > 0.05 ? 1 : 0;
  }
  EXPECT_GT(positive, trials / 4) << "the cases must exercise a positive bound";
  std::cout << "[ measured ] " << trials << " random distributions (2-7 depths), alpha " << alpha
            << ": max (G - biased true fraction) " << largestExcess << ", max |G - mass of the three-point distribution in "
            << "front of z_f| " << largestAttainedError << ", max moment error " << largestMomentError
            << ", mean looseness " << sumGap / trials << ", G > 0.05 in " << positive << "\n";
}

// A sloped receiver's own texels in the filter box: depths spread evenly over a slab around its own. Compared at its
// exact depth (the slab's centre, no depth bias), half the slab lies in front, and the four-moment bound of the
// uniform distribution there tends to 5/18 = 0.278 as alpha -> 0 (a closed form: the moments of the uniform
// distribution on [c - h, c + h], (hi^(k+1) - lo^(k+1)) / ((k + 1)(hi - lo))). The figure on README.md (Parameters).
TEST(MsmMath, AUniformSlabAtItsCentreGivesFiveEighteenthsAsTheBiasVanishes)
{
  const auto uniformSlabMoments = [](double centre, double halfWidth) {
    const double lo = centre - halfWidth;
    const double hi = centre + halfWidth;
    glm::dvec4 moments(0.0);
    for (int k = 1; k <= 4; ++k)
    {
      moments[k - 1] = (std::pow(hi, k + 1) - std::pow(lo, k + 1)) / ((k + 1) * (hi - lo));
    }
    return moments;
  };
  const double limit = msmHamburger4(uniformSlabMoments(0.5, 0.2), 1e-8, 0.5).shadowIntensity;
  EXPECT_NEAR(limit, 5.0 / 18.0, 1e-4);
  std::cout << "[ measured ] uniform slab [0.3, 0.7] at its centre, alpha 1e-8: G " << limit << " (5/18 = " << 5.0 / 18.0
            << "); at alpha 3e-5 (default), slab centred at 0.5 of half width";
  double previous = 0.0;
  for (const double halfWidth : { 0.01, 0.05, 0.1, 0.2 })
  {
    const double intensity = msmHamburger4(uniformSlabMoments(0.5, halfWidth), 3e-5, 0.5).shadowIntensity;
    std::cout << " " << halfWidth << ": G " << intensity;
    // The bias pulls the thin slabs' bound towards 0: it grows with the slab, below the limit.
    EXPECT_GT(intensity, previous) << halfWidth;
    EXPECT_LT(intensity, 5.0 / 18.0) << halfWidth;
    previous = intensity;
  }
  std::cout << "\n";
}

// power_moment_map declares no parameters: it reads the moment map's prefilter from msm's values, and a table
// without them is an internal error, not a silent box of 1.
TEST(MsmMath, ThePowerMomentMapReadsMsmsPrefilter)
{
  ParameterValues values = findTechnique("msm").defaultParameters();
  EXPECT_TRUE(powerMomentMapStructure().parameters.empty());
  values.set("prefilter_texels", 7);
  EXPECT_FALSE(PowerMomentMapSettings::from(values).mipmap);
  EXPECT_EQ(PowerMomentMapSettings::from(values).blurTexels, 7);
  values.set("prefilter=mipmap");
  EXPECT_TRUE(PowerMomentMapSettings::from(values).mipmap);
  EXPECT_EQ(PowerMomentMapSettings::from(values).blurTexels, 1);
  const ParameterValues withoutPrefilter("power_moment_map", powerMomentMapStructure().parameters);
  EXPECT_DEATH(PowerMomentMapSettings::from(withoutPrefilter), "must declare the moment map's prefilter parameters");
}

} // namespace
} // namespace sl
