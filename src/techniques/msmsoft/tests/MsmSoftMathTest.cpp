// msmsoft's blocker estimate (msmSoftBlockers, the CPU twin of MsmSoftVisibility.glsl's estimateBlockers) against
// closed forms: the weights it derives (Lagrange on the support {z_f, z_1, z_2}) reproduce the biased moments of
// order 0-2 and, with the canonical representation's support, of order 3-4 too; with two depths in the search region
// G_b is the occluder's fraction and z_avg the eps-weighted occluder depth; without blockers z_avg is z_f.
#include "techniques/msmsoft/MsmSoftTechnique.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace sl
{
namespace
{

glm::dvec4 msmSoftTestMoments(const std::vector<double>& depths, const std::vector<double>& weights)
{
  glm::dvec4 b(0.0);
  for (std::size_t i = 0; i < depths.size(); ++i)
  {
    const double z = depths[i];
    b += weights[i] * glm::dvec4(z, z * z, z * z * z, z * z * z * z);
  }
  return b;
}

TEST(MsmSoftMath, TheBlockerWeightsReproduceTheBiasedMoments)
{
  const glm::dvec4 moments = msmSoftTestMoments({ 0.15, 0.3, 0.55, 0.8 }, { 0.2, 0.3, 0.1, 0.4 });
  for (const double zf : { 0.2, 0.4, 0.6, 0.79 })
  {
    const MsmSoftBlockers blockers = msmSoftBlockers(moments, 3e-5, 1e-3, zf);
    const MsmReconstruction& canonical = blockers.canonical;
    const double z1 = canonical.supportNear;
    const double z2 = canonical.supportFar;
    const double w1 = blockers.weights.x;
    const double w2 = blockers.weights.y;
    const double wf = 1.0 - w1 - w2;
    for (int k = 1; k <= 4; ++k)
    {
      const double moment = wf * std::pow(zf, k) + w1 * std::pow(z1, k) + w2 * std::pow(z2, k);
      EXPECT_NEAR(moment, canonical.biasedMoments[k - 1], 1e-9) << "z_f " << zf << ", moment " << k;
    }
    // The same weights msmHamburger4 derives for its support.
    EXPECT_NEAR(w1, canonical.weights.y, 1e-12) << zf;
    EXPECT_NEAR(w2, canonical.weights.z, 1e-12) << zf;
    EXPECT_GE(wf, 0.0) << zf;
    // G_b: the weights of the support in front of z_f; z_avg between them.
    const double expected = (z1 < zf ? w1 : 0.0) + (z2 < zf ? w2 : 0.0);
    EXPECT_NEAR(blockers.intensity, expected, 1e-15) << zf;
    EXPECT_GE(blockers.averageDepth, 0.0) << zf;
    EXPECT_LE(blockers.averageDepth, zf) << zf;
  }
}

TEST(MsmSoftMath, TwoDepthsGiveTheOccluderFractionAndDepth)
{
  for (const double p : { 0.05, 0.3, 0.7 })
  {
    const double zo = 0.25;
    const double zr = 0.6;
    const double zf = zr - 1e-4; // the receiver's depth minus the bias
    const double alpha = 1e-6;
    const double epsilon = 1e-3;
    const MsmSoftBlockers blockers =
      msmSoftBlockers(msmSoftTestMoments({ zo, zr }, { p, 1.0 - p }), alpha, epsilon, zf);
    EXPECT_NEAR(blockers.intensity, p, 1e-3) << p;
    EXPECT_NEAR(blockers.averageDepth, (epsilon * zf + p * zo) / (epsilon + p), 1e-3) << p;
  }
}

TEST(MsmSoftMath, WithoutBlockersTheAverageDepthIsTheReceivers)
{
  const double zf = 0.4;
  const MsmSoftBlockers blockers = msmSoftBlockers(msmSoftTestMoments({ 0.45, 0.7 }, { 0.5, 0.5 }), 3e-5, 1e-3, zf);
  EXPECT_LT(blockers.intensity, 1e-3);
  EXPECT_NEAR(blockers.averageDepth, zf, 0.05 * zf);
  const MsmSoftBlockers single = msmSoftBlockers(msmSoftTestMoments({ 0.7 }, { 1.0 }), 3e-5, 1e-3, zf);
  EXPECT_TRUE(std::isfinite(single.averageDepth));
  EXPECT_NEAR(single.averageDepth, zf, 0.05 * zf);
}

} // namespace
} // namespace sl
