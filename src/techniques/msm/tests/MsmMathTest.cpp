// msm's reconstruction (msmHamburger4, the CPU twin of MsmVisibility.glsl) against closed forms: the three-point
// distribution it returns reproduces all four biased moments; with two depths in the filter region it is exact
// (the true fraction in front, up to the bias); and on random depth distributions it is the sharpest lower bound on
// the shadow intensity (Peters & Klein 2015, abstract: "the sharpest possible lower bound"): never above the true
// fraction, and attained by a distribution with the same moments.
#include "structures/powermoments/PowerMomentMapStructure.h"
#include "techniques/Registry.h"
#include "techniques/msm/MsmTechnique.h"

#include <gtest/gtest.h>

#include <algorithm>
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

// 2 to 7 depths in [0, 1) with positive weights summing to 1.
MsmTestDistribution randomMsmTestDistribution(std::mt19937& generator, std::uniform_real_distribution<double>& unit)
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
  return distribution;
}

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
    const MsmTestDistribution distribution = randomMsmTestDistribution(generator, unit);
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

// Steps 2-4 are the four-moment case (m = 4) of the general solution of the moment problem that Peters et al. 2017
// (JCGT) print as their Algorithm 1 (read in a third-party translation of §2, see README.md, Sources): set the
// Hankel matrix B(b), solve B q = (1, z_f, z_f^2), take the roots z_1, z_2 of q_0 + q_1 z + q_2 z^2, set z_0 = z_f,
// solve the Vandermonde system A w = (b_0, b_1, b_2) and return sum_l w_l delta_{z_l}; the shadow intensity is
// that distribution's mass strictly in front of z_f (their Eq. 1). This reference follows those steps literally,
// with generic Gaussian elimination (no LDL^T, no Lagrange closed forms, no case split), in long double. A wrong
// pivot, weight formula or case in msmHamburger4 would break the agreement.
struct MsmAlgorithmOneResult
{
  long double support[3];
  long double weights[3];
  long double intensity;
};

void msmAlgorithmOneSolve3(long double matrix[3][3], long double rhs[3], long double out[3])
{
  for (int column = 0; column < 3; ++column)
  {
    int pivot = column;
    for (int row = column + 1; row < 3; ++row)
    {
      pivot = std::fabs(matrix[row][column]) > std::fabs(matrix[pivot][column]) ? row : pivot;
    }
    std::swap(matrix[column], matrix[pivot]);
    std::swap(rhs[column], rhs[pivot]);
    for (int row = column + 1; row < 3; ++row)
    {
      const long double factor = matrix[row][column] / matrix[column][column];
      for (int k = column; k < 3; ++k)
      {
        matrix[row][k] -= factor * matrix[column][k];
      }
      rhs[row] -= factor * rhs[column];
    }
  }
  for (int row = 2; row >= 0; --row)
  {
    long double sum = rhs[row];
    for (int k = row + 1; k < 3; ++k)
    {
      sum -= matrix[row][k] * out[k];
    }
    out[row] = sum / matrix[row][row];
  }
}

MsmAlgorithmOneResult msmAlgorithmOneReference(const glm::dvec4& biased, double zf)
{
  const long double b[5] = { 1.0L, biased.x, biased.y, biased.z, biased.w };
  long double hankel[3][3];
  for (int j = 0; j < 3; ++j)
  {
    for (int k = 0; k < 3; ++k)
    {
      hankel[j][k] = b[j + k];
    }
  }
  long double rhs[3] = { 1.0L, zf, static_cast<long double>(zf) * zf };
  long double q[3];
  msmAlgorithmOneSolve3(hankel, rhs, q);
  const long double root = std::sqrt(q[1] * q[1] - 4.0L * q[0] * q[2]);
  MsmAlgorithmOneResult result{};
  result.support[0] = zf;
  result.support[1] = (-q[1] - root) / (2.0L * q[2]);
  result.support[2] = (-q[1] + root) / (2.0L * q[2]);
  if (result.support[1] > result.support[2])
  {
    std::swap(result.support[1], result.support[2]);
  }
  long double vandermonde[3][3];
  for (int j = 0; j < 3; ++j)
  {
    for (int l = 0; l < 3; ++l)
    {
      vandermonde[j][l] = std::pow(result.support[l], static_cast<long double>(j));
    }
  }
  long double lowMoments[3] = { b[0], b[1], b[2] };
  msmAlgorithmOneSolve3(vandermonde, lowMoments, result.weights);
  result.intensity = 0.0L;
  for (int l = 1; l < 3; ++l)
  {
    result.intensity += result.support[l] < zf ? result.weights[l] : 0.0L;
  }
  return result;
}

TEST(MsmMath, StepsTwoToFourAreTheGeneralAlgorithmForFourMoments)
{
  constexpr double alpha = 3e-5;
  std::mt19937 generator(2017);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double largestSupportError = 0.0;
  double largestWeightError = 0.0;
  double largestIntensityError = 0.0;
  int compared = 0;
  int positive = 0;
  for (int trial = 0; trial < 2000; ++trial)
  {
    const MsmTestDistribution distribution = randomMsmTestDistribution(generator, unit);
    const double zf = unit(generator);
    const MsmReconstruction msm = msmHamburger4(distribution.moments(), alpha, zf);
    const MsmAlgorithmOneResult reference = msmAlgorithmOneReference(msm.biasedMoments, zf);
    // Where B is near singular both solves amplify rounding; compare where the last pivot keeps them well posed.
    if (msm.pivot3 < 1e-9)
    {
      continue;
    }
    ++compared;
    const double supportError = std::max(std::abs(msm.supportNear - static_cast<double>(reference.support[1])),
      std::abs(msm.supportFar - static_cast<double>(reference.support[2])));
    const double weightError = std::max({ std::abs(msm.weights.x - static_cast<double>(reference.weights[0])),
      std::abs(msm.weights.y - static_cast<double>(reference.weights[1])),
      std::abs(msm.weights.z - static_cast<double>(reference.weights[2])) });
    const double referenceIntensity = std::clamp(static_cast<double>(reference.intensity), 0.0, 1.0);
    const double intensityError = std::abs(msm.shadowIntensity - referenceIntensity);
    EXPECT_LT(supportError, 1e-6 * (1.0 + std::abs(msm.supportFar)))
      << "trial " << trial << " z_f " << zf << ": supports " << msm.supportNear << " " << msm.supportFar
      << " against " << static_cast<double>(reference.support[1]) << " " << static_cast<double>(reference.support[2]);
    EXPECT_LT(weightError, 1e-7) << "trial " << trial << " z_f " << zf;
    EXPECT_LT(intensityError, 1e-7) << "trial " << trial << " z_f " << zf << ": G " << msm.shadowIntensity
                                    << " against Algorithm 1's " << referenceIntensity;
    largestSupportError = std::max(largestSupportError, supportError);
    largestWeightError = std::max(largestWeightError, weightError);
    largestIntensityError = std::max(largestIntensityError, intensityError);
    positive += msm.shadowIntensity > 0.05 ? 1 : 0;
  }
  EXPECT_GT(compared, 1000) << "too few well-posed cases";
  EXPECT_GT(positive, compared / 4) << "the cases must exercise a positive bound";
  std::cout << "[ measured ] msmHamburger4 against the general algorithm (m = 4), " << compared
            << " well-posed random distributions of 2000, alpha " << alpha << ": max |support error| "
            << largestSupportError << ", max |weight error| " << largestWeightError << ", max |G error| "
            << largestIntensityError << ", G > 0.05 in " << positive << "\n";
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
