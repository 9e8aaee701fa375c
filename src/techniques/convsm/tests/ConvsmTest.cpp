// convsm (Annen et al. 2007): the twin against closed forms of the truncated Fourier series of the step, the GLSL
// against the twin pixel by pixel (datasets, M = 4, 8, 16, random scenes), the ringing at contact and the error
// against PCF away from contact as M grows, the probe, and the bad-input message of `terms`.
#include "support/TestSupport.h"
#include "core/Error.h"
#include "frame/ProbeRecord.h"
#include "scene/RandomScenes.h"
#include "scene/Scene.h"
#include "techniques/ProbeSupport.h"
#include "techniques/Registry.h"
#include "techniques/ShadowMapParameters.h"
#include "techniques/convsm/ConvsmTechnique.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>

namespace sl
{
namespace
{

// The basis of one depth (every texel of a box at z_n): the coefficients a box of it averages to.
FourierCoefficients convsmTestBasisOf(double zNormalized, int terms)
{
  FourierCoefficients basis;
  for (int k = 1; k <= terms; ++k)
  {
    basis.sine.push_back(std::sin(M_PI * (2 * k - 1) * zNormalized));
    basis.cosine.push_back(std::cos(M_PI * (2 * k - 1) * zNormalized));
  }
  return basis;
}

// The twin's series at z_n - d_n = 1/2, 0, -1/2 and 1/4 against their closed forms: sin(c_k / 2) = (-1)^(k+1), so
// S_M(1/2) = 1/2 + (2/pi) (1 - 1/3 + 1/5 - ...), the Leibniz partial sums (exact rationals below); S_M(0) = 1/2;
// S_M(-t) = 1 - S_M(t); sin(c_k / 4) = +-sqrt(2)/2 in the pattern + + - -.
TEST(Convsm, TwinSeriesEqualsClosedForms)
{
  const struct
  {
    int terms;
    double leibniz;
  } partialSums[] = { { 4, 76.0 / 105.0 }, { 8, 33976.0 / 45045.0 }, { 16, 3473755390832.0 / 4512611027925.0 } };
  for (const auto& row : partialSums)
  {
    const int M = row.terms;
    const double half = 0.5 + 2.0 / M_PI * row.leibniz;
    // The series depends on z - d only: the same difference at several depths.
    for (const double d : { 0.1, 0.25, 0.4 })
    {
      EXPECT_NEAR(convsmStepSeries(d, d + 0.5, M, 0.0), half, 1e-13) << "M " << M << " d " << d;
      EXPECT_NEAR(convsmStepSeries(d + 0.5, d, M, 0.0), 1.0 - half, 1e-13) << "M " << M << " d " << d;
      EXPECT_NEAR(convsmStepSeries(d, d, M, 0.0), 0.5, 1e-15) << "M " << M << " d " << d;
    }
    double quarter = 0.0;
    for (int k = 1; k <= M; ++k)
    {
      quarter += ((k - 1) % 4 < 2 ? 1.0 : -1.0) / (2 * k - 1);
    }
    EXPECT_NEAR(convsmStepSeries(0.3, 0.55, M, 0.0), 0.5 + std::sqrt(2.0) / M_PI * quarter, 1e-13) << "M " << M;
    std::cout << "[ measured ] S_" << M << "(1/2) = " << half << ", S_" << M << "(1/4) = " << convsmStepSeries(0.3, 0.55, M, 0.0) << "\n";
  }
  // Damping at M = 4, alpha = 1: sigma_k = exp(-(k/4)^2) on each Leibniz term.
  const double damped = 0.5 + 2.0 / M_PI * (std::exp(-1.0 / 16.0) - std::exp(-4.0 / 16.0) / 3.0 + std::exp(-9.0 / 16.0) / 5.0 - std::exp(-1.0) / 7.0);
  EXPECT_NEAR(convsmStepSeries(0.2, 0.7, 4, 1.0), damped, 1e-13);
  // Away from the step the truncated series converges to H: the worst error over |z - d| in [1/4, 3/4] halves
  // roughly with each doubling of M.
  double previous = 1.0;
  for (const int M : { 4, 8, 16 })
  {
    double worst = 0.0;
    for (int i = 0; i <= 200; ++i)
    {
      const double t = 0.25 + 0.5 * i / 200.0;
      worst = std::max({ worst, std::abs(convsmStepSeries(0.0, t, M, 0.0) - 1.0), std::abs(convsmStepSeries(t, 0.0, M, 0.0)) });
    }
    std::cout << "[ measured ] M " << M << ": max |S_M(t) - H(t)| over |t| in [1/4, 3/4] = " << worst << "\n";
    EXPECT_LT(worst, 0.75 * previous) << "M " << M;
    previous = worst;
  }
}

// Reconstruction from prefiltered coefficients is linear in the box: a box holding two depths in fractions f and
// 1 - f reconstructs f S(d, z1) + (1 - f) S(d, z2), the filtered step (the paper's point). This pins the signs of
// cos(c_k d) E[sin] - sin(c_k d) E[cos].
TEST(Convsm, TwinReconstructionIsTheFilteredSeries)
{
  for (const int M : { 4, 8, 16 })
  {
    for (const double alpha : { 0.0, 2.0 })
    {
      const double z1 = 0.31;
      const double z2 = 0.77;
      const double f = 9.0 / 25.0;
      const FourierCoefficients a = convsmTestBasisOf(z1, M);
      const FourierCoefficients b = convsmTestBasisOf(z2, M);
      FourierCoefficients mixed;
      for (int k = 0; k < M; ++k)
      {
        mixed.sine.push_back(f * a.sine[k] + (1.0 - f) * b.sine[k]);
        mixed.cosine.push_back(f * a.cosine[k] + (1.0 - f) * b.cosine[k]);
      }
      for (const double d : { 0.05, 0.3, 0.5, 0.76, 0.95 })
      {
        EXPECT_NEAR(convsmReconstruct(d, mixed, M, alpha), f * convsmStepSeries(d, z1, M, alpha) + (1.0 - f) * convsmStepSeries(d, z2, M, alpha), 1e-13)
          << "M " << M << " alpha " << alpha << " d " << d;
      }
    }
  }
}

TEST(Convsm, TermsNotAMultipleOfFourIsRefusedNamingIt)
{
  ParameterValues values("convsm", findTechnique("convsm").parameters);
  values.set("terms=6");
  try
  {
    ConvsmSettings::from(values);
    FAIL() << "terms=6 accepted";
  }
  catch (const InputError& error)
  {
    EXPECT_NE(std::string(error.what()).find("terms=6"), std::string::npos) << error.what();
  }
}

struct ConvsmAgreement
{
  int compared = 0;
  int skipped = 0;
  int halfLit = 0;      // visibility >= 0.45: lit receivers, where the series reads about 1/2 (d = z)
  int umbra = 0;        // visibility < 0.02
  int transition = 0;   // in between
  int overshooting = 0;
  double maxDifference = 0.0;
};

// The GPU's reconstruction, visibility, overshoot and light_leak against the twin at every pixel; pixels within
// float rounding of a texel edge or a light-reach test are counted, not compared (a neighbouring texel's box),
// and light_leak only where no PCF comparison ties.
ConvsmAgreement convsmCompare(const FrameResult& frame, const Scene& scene, const std::string& label, double tolerance)
{
  const ShadowMapInputs inputs = test::shadowMapInputs(frame, scene);
  const ConvsmSettings settings = ConvsmSettings::from(frame.parameters);
  const ImageF& visibility = frame.find("visibility")->image;
  const ImageF& reconstruction = frame.find("reconstruction")->image;
  const ImageF& overshoot = frame.find("overshoot")->image;
  const ImageF& lightLeak = frame.find("light_leak")->image;
  ConvsmAgreement agreement;
  for (int y = 0; y < visibility.height; ++y)
  {
    for (int x = 0; x < visibility.width; ++x)
    {
      const ConvsmSample cpu = convsmReference(inputs, settings, x, y);
      if (!cpu.sample.evaluated)
      {
        EXPECT_EQ(visibility.at(x, y), cpu.sample.visibility) << label << " pixel " << x << "," << y;
        continue;
      }
      const ShadowLookup lookup = prepareShadowLookup(inputs, settings.bias, x, y);
      std::string ambiguity;
      noteMomentTexelEdge(ambiguity, lookup.sm.uvTexels);
      if (!ambiguity.empty() || cpu.sample.reachMargin < probeReachAmbiguity)
      {
        ++agreement.skipped;
        continue;
      }
      ++agreement.compared;
      const double v = cpu.sample.visibility;
      (v >= 0.45 ? agreement.halfLit : v < 0.02 ? agreement.umbra : agreement.transition) += 1;
      agreement.overshooting += cpu.reconstruction < 0.0 || cpu.reconstruction > 1.0 ? 1 : 0;
      const double difference = std::abs(reconstruction.at(x, y) - cpu.reconstruction);
      agreement.maxDifference = std::max(agreement.maxDifference, difference);
      EXPECT_LE(difference, tolerance) << label << " reconstruction at " << x << "," << y << ": GPU " << reconstruction.at(x, y)
                                       << " twin " << cpu.reconstruction;
      EXPECT_NEAR(visibility.at(x, y), cpu.sample.visibility, tolerance) << label << " visibility at " << x << "," << y;
      EXPECT_NEAR(overshoot.at(x, y), cpu.reconstruction - cpu.sample.visibility, tolerance) << label << " overshoot at " << x << "," << y;
      const double leakDepth = prepareShadowLookup(inputs, defaultBiasSettings(), x, y).comparisonDepth;
      const PcfRange range = boxPcfRange(inputs, lookup.sm.uvTexels, leakDepth, settings.prefilter.texels, probeDepthAmbiguity);
      if (range.ties == 0)
      {
        EXPECT_NEAR(lightLeak.at(x, y), cpu.lightLeak, tolerance) << label << " light_leak at " << x << "," << y;
      }
    }
  }
  return agreement;
}

// Tolerance 5e-5: the GPU evaluates sin(c_k z_n) in float with c_k up to 31 pi, averages the box in float and sums
// M terms of weight 2 / c_k; the twin does all of it in double (measured at most 6e-6).
TEST(Convsm, GpuMatchesTheTwinOnDatasets)
{
  for (const std::string dataset : { "stacked-occluders", "bunny", "contact" })
  {
    const Scene scene = test::loadDataset(dataset);
    for (const std::string terms : { "4", "8", "16" })
    {
      const std::vector<std::string> settings{ "shadow_map_size=256", "prefilter_texels=5", "terms=" + terms };
      const FrameResult frame = test::renderDataset(scene, "convsm", 96, 80, settings);
      const std::string label = test::caseLabel(dataset, settings);
      const ConvsmAgreement agreement = convsmCompare(frame, scene, label, 5e-5);
      std::cout << "[ measured ] " << label << ": compared " << agreement.compared << " (lit " << agreement.halfLit << ", umbra "
                << agreement.umbra << ", transition " << agreement.transition << ", overshooting " << agreement.overshooting << "), skipped " << agreement.skipped << ", max |gpu - twin| "
                << agreement.maxDifference << "\n";
      EXPECT_GT(agreement.compared, 300) << label;
      EXPECT_GT(agreement.halfLit, 20) << label;
      EXPECT_GT(agreement.umbra, 20) << label;
      EXPECT_GT(agreement.transition, 20) << label << ": the series must soften the shadow edges";
    }
  }
  // The damping and a wider box.
  const Scene scene = test::loadDataset("contact");
  const std::vector<std::string> settings{ "shadow_map_size=256", "prefilter_texels=7", "terms=8", "ringing_alpha=3" };
  const ConvsmAgreement agreement = convsmCompare(test::renderDataset(scene, "convsm", 96, 80, settings), scene, test::caseLabel("contact", settings), 5e-5);
  std::cout << "[ measured ] contact, ringing_alpha=3: compared " << agreement.compared << ", max |gpu - twin| " << agreement.maxDifference << "\n";
  EXPECT_GT(agreement.compared, 300);
}

// Random generated configurations (scene/RandomScenes.h) against the twin, M drawn from the seed.
TEST(Convsm, GpuMatchesTheTwinOnRandomScenes)
{
  const char* termChoices[] = { "4", "8", "16" };
  int compared = 0;
  for (std::uint64_t seed = 1; seed <= 6; ++seed)
  {
    const RandomScene random = randomScene(seed, 64);
    const Scene scene = parseScene(random.json, "convsm seed " + std::to_string(seed), ".");
    const std::vector<std::string> settings{ "shadow_map_size=128", "prefilter_texels=" + std::to_string(1 + 2 * (seed % 3)),
      std::string("terms=") + termChoices[seed % 3] };
    const FrameResult frame = test::renderDataset(scene, "convsm", 64, 64, settings);
    const std::string label = "seed " + std::to_string(seed) + " (" + random.summary + ") " + test::caseLabel("", settings);
    const ConvsmAgreement agreement = convsmCompare(frame, scene, label, 5e-5);
    std::cout << "[ measured ] " << label << ": compared " << agreement.compared << ", max |gpu - twin| " << agreement.maxDifference << "\n";
    compared += agreement.compared;
  }
  EXPECT_GT(compared, 1000);
}

struct ConvsmLeakFigures
{
  int contactPixels = 0;
  double contactMaxLeak = -1.0;  // most light leaked (visibility - pcf) near contact
  double contactMinLeak = 1.0;   // most darkening there
  double contactMeanLeak = 0.0;
  int awayPixels = 0;
  double awayMeanError = 0.0;    // mean |visibility - pcf| away from contact
  double awayMaxError = 0.0;
  double maxOvershoot = 0.0;     // max |reconstruction - clamp| over the frame
  int litPixels = 0;             // box PCF 1
  double litMeanLeak = 0.0;
};

// Classifies each pixel with an occluding texel in its box (the box PCF's failing comparisons, pcf's default
// bias) by the gap, in normalised depth, between the receiver and its nearest occluding texel: "near contact"
// below 1/32 of the light's depth range (inside the step's transition for every M <= 16), "away" when every
// texel of the box, occluding or not, is at least 1/4 from the receiver's depth (where the series converges).
ConvsmLeakFigures convsmLeakFigures(const FrameResult& frame, const Scene& scene)
{
  const ShadowMapInputs inputs = test::shadowMapInputs(frame, scene);
  const ConvsmSettings settings = ConvsmSettings::from(frame.parameters);
  const int width = settings.prefilter.texels;
  const int size = inputs.shadowMapLinear.width;
  const ImageF& overshoot = frame.find("overshoot")->image;
  const ImageF& lightLeak = frame.find("light_leak")->image;
  ConvsmLeakFigures figures;
  for (int y = 0; y < overshoot.height; ++y)
  {
    for (int x = 0; x < overshoot.width; ++x)
    {
      figures.maxOvershoot = std::max(figures.maxOvershoot, std::abs(static_cast<double>(overshoot.at(x, y))));
      const ConvsmSample cpu = convsmReference(inputs, settings, x, y);
      if (cpu.sample.evaluated && cpu.boxPcf >= 1.0)
      {
        ++figures.litPixels;
        figures.litMeanLeak += lightLeak.at(x, y);
      }
      if (!cpu.sample.evaluated || cpu.boxPcf >= 1.0)
      {
        continue;
      }
      const ShadowLookup lookup = prepareShadowLookup(inputs, settings.bias, x, y);
      const double leakDepth = prepareShadowLookup(inputs, defaultBiasSettings(), x, y).comparisonDepth;
      const int cx = std::clamp(static_cast<int>(std::floor(lookup.sm.uvTexels.x)), 0, size - 1);
      const int cy = std::clamp(static_cast<int>(std::floor(lookup.sm.uvTexels.y)), 0, size - 1);
      double nearestOccluderGap = 1e300;
      double nearestGap = 1e300;
      for (int j = -(width - 1) / 2; j <= width / 2; ++j)
      {
        for (int i = -(width - 1) / 2; i <= width / 2; ++i)
        {
          const double z = inputs.shadowMapLinear.at(std::clamp(cx + i, 0, size - 1), std::clamp(cy + j, 0, size - 1));
          const double gap = cpu.dNormalized - convsmNormalizedDepth(inputs, z);
          nearestGap = std::min(nearestGap, std::abs(gap));
          if (!(leakDepth <= z))
          {
            nearestOccluderGap = std::min(nearestOccluderGap, gap);
          }
        }
      }
      const double leak = lightLeak.at(x, y);
      if (nearestOccluderGap < 1.0 / 32.0)
      {
        ++figures.contactPixels;
        figures.contactMaxLeak = std::max(figures.contactMaxLeak, leak);
        figures.contactMinLeak = std::min(figures.contactMinLeak, leak);
        figures.contactMeanLeak += leak;
      }
      else if (nearestGap >= 0.25)
      {
        ++figures.awayPixels;
        figures.awayMeanError += std::abs(leak);
        figures.awayMaxError = std::max(figures.awayMaxError, std::abs(leak));
      }
    }
  }
  figures.contactMeanLeak /= std::max(figures.contactPixels, 1);
  figures.awayMeanError /= std::max(figures.awayPixels, 1);
  figures.litMeanLeak /= std::max(figures.litPixels, 1);
  return figures;
}

// Ringing at contact: where an occluder nearly touches its receiver the step's transition (about 1/M of the depth
// range wide) straddles both, and the series reads neither 0 nor 1 over what PCF finds shadowed; away from
// contact the error is the series' tail, whose worst value halves with each doubling of M.
TEST(Convsm, RingingAtContactAndErrorAwayFromContact)
{
  const Scene scene = test::loadDataset("contact");
  double previousAway = 1.0;
  for (const std::string terms : { "4", "8", "16" })
  {
    const std::vector<std::string> settings{ "shadow_map_size=256", "prefilter_texels=5", "terms=" + terms };
    const FrameResult frame = test::renderDataset(scene, "convsm", 128, 128, settings);
    const ConvsmLeakFigures figures = convsmLeakFigures(frame, scene);
    std::cout << "[ measured ] contact terms=" << terms << ": near contact " << figures.contactPixels << " px, light_leak max "
              << figures.contactMaxLeak << " min " << figures.contactMinLeak << " mean " << figures.contactMeanLeak << "; away "
              << figures.awayPixels << " px, |visibility - pcf| mean " << figures.awayMeanError << " max " << figures.awayMaxError
              << "; max |overshoot| " << figures.maxOvershoot << "; lit (box PCF 1) " << figures.litPixels
              << " px, light_leak mean " << figures.litMeanLeak << "\n";
    ASSERT_GT(figures.contactPixels, 20) << terms;
    ASSERT_GT(figures.awayPixels, 20) << terms;
    EXPECT_GT(std::max(figures.contactMaxLeak, -figures.contactMinLeak), 4.0 * figures.awayMaxError) << terms << ": contact must be the worst";
    // Lit receivers compare with their own texels, d = z: the series' 1/2 (its box averages the texels on both
    // sides of the receiver's depth), so light_leak is about -1/2 there.
    EXPECT_NEAR(figures.litMeanLeak, -0.5, 0.1) << terms;
    EXPECT_LT(figures.awayMaxError, 0.8 * previousAway) << terms << ": more terms, less error away from contact";
    previousAway = figures.awayMaxError;
  }
}

// The series represents H(z - d) on (-1, 1) only: it is the square wave of period 2, which jumps back at z - d = -1
// and 1 and reads 1/2 there (sin(c_k) = 0 for every k). With depths normalised to the light's whole range an
// occluder near the light (z_n ~ 0) over a receiver at the far end (d_n ~ 1) sits on that jump: on
// planar-occluder the umbra reads about 1/2, i.e. as bright as the lit floor, which also reads 1/2 (d = z). Both
// are flagged per pixel by light_leak (|light_leak| > 1e-3: "light bleeding").
TEST(Convsm, UmbraReadsOneHalfWhereOccluderAndReceiverSpanTheDepthRange)
{
  for (const int M : { 4, 8, 16 })
  {
    EXPECT_NEAR(convsmStepSeries(1.0, 0.0, M, 0.0), 0.5, 1e-13) << "M " << M;
    EXPECT_NEAR(convsmStepSeries(0.0, 1.0, M, 0.0), 0.5, 1e-13) << "M " << M;
  }
  const Scene scene = test::loadDataset("planar-occluder");
  const FrameResult frame = test::renderDataset(scene, "convsm", 96, 80, { "shadow_map_size=256", "prefilter_texels=5", "terms=16" });
  const ShadowMapInputs inputs = test::shadowMapInputs(frame, scene);
  const ConvsmSettings settings = ConvsmSettings::from(frame.parameters);
  const ImageF& visibility = frame.find("visibility")->image;
  const ImageF& lightLeak = frame.find("light_leak")->image;
  int umbra = 0;
  int flagged = 0;
  double meanVisibility = 0.0;
  double meanGap = 0.0;
  for (int y = 0; y < visibility.height; ++y)
  {
    for (int x = 0; x < visibility.width; ++x)
    {
      const ConvsmSample cpu = convsmReference(inputs, settings, x, y);
      if (!cpu.sample.evaluated || cpu.boxPcf > 0.0)
      {
        continue;
      }
      ++umbra;
      meanVisibility += visibility.at(x, y);
      flagged += std::abs(lightLeak.at(x, y)) > 1e-3f ? 1 : 0;
      const ShadowLookup lookup = prepareShadowLookup(inputs, settings.bias, x, y);
      const glm::ivec2 texel = glm::clamp(glm::ivec2(glm::floor(lookup.sm.uvTexels)), glm::ivec2(0), glm::ivec2(inputs.shadowMapLinear.width - 1));
      meanGap += cpu.dNormalized - convsmNormalizedDepth(inputs, inputs.shadowMapLinear.at(texel.x, texel.y));
    }
  }
  ASSERT_GT(umbra, 100);
  meanVisibility /= umbra;
  meanGap /= umbra;
  std::cout << "[ measured ] planar-occluder terms=16: " << umbra << " umbra px (box PCF 0), d_n - z_n mean " << meanGap
            << ", visibility mean " << meanVisibility << ", flagged by light_leak " << flagged << "\n";
  EXPECT_GT(meanGap, 0.8) << "the occluder must lie near the light and the receiver near the far end";
  EXPECT_GT(meanVisibility, 0.3) << "the series' jump at z - d = -1 reads about 1/2";
  EXPECT_EQ(flagged, umbra) << "every such pixel must be flagged";
}

// The probe records the box the blur averaged, each term's coefficients and the reconstructed step; its replay
// agrees with the GPU's buffers on a lit, a penumbra and an umbra pixel.
TEST(Convsm, ProbeRecordsTheCoefficientsAndTheReconstructedStep)
{
  const Scene scene = test::loadDataset("stacked-occluders");
  const FrameResult frame = test::renderDataset(scene, "convsm", 96, 80, { "shadow_map_size=256", "prefilter_texels=5", "terms=8" });
  const ShadowMapInputs inputs = test::shadowMapInputs(frame, scene);
  int probed[3] = { 0, 0, 0 };
  for (int y = 0; y < 80; y += 3)
  {
    for (int x = 0; x < 96; x += 3)
    {
      ProbeRecorder recorder;
      const ProbeOutcome outcome = findTechnique("convsm").probe({ &frame, &scene, 0 }, { x, y }, recorder);
      if (!outcome.evaluated || !outcome.ambiguity.empty())
      {
        continue;
      }
      const int kind = outcome.visibility >= 0.45 ? 0 : outcome.visibility <= 0.02 ? 2 : 1;
      if (probed[kind] >= 2)
      {
        continue;
      }
      ++probed[kind];
      const ProbeRecord& record = recorder.record();
      const std::string label = format("pixel ", x, ",", y);
      const auto quantity = [&](const std::string& name) {
        const ProbeQuantity* found = record.find(name);
        EXPECT_NE(found, nullptr) << label << ": " << name << " not recorded";
        return found != nullptr ? found->value.at(0) : -99.0;
      };
      const auto gpu = [&](const char* buffer) { return static_cast<double>(frame.find(buffer)->image.at(x, y)); };
      EXPECT_NEAR(quantity("reconstruction"), gpu("reconstruction"), outcome.tolerance) << label;
      EXPECT_NEAR(outcome.visibility, gpu("visibility"), outcome.tolerance) << label;
      // The recorded coefficients are the box's mean basis.
      double meanSin1 = 0.0;
      double meanCos8 = 0.0;
      int boxTexels = 0;
      for (const ProbeTexel& texel : record.texels)
      {
        if (texel.role == "fourier box")
        {
          const double zn = convsmNormalizedDepth(inputs, texel.storedDepth);
          meanSin1 += texel.weight * std::sin(M_PI * zn);
          meanCos8 += texel.weight * std::cos(15.0 * M_PI * zn);
          ++boxTexels;
        }
      }
      EXPECT_EQ(boxTexels, 25) << label;
      EXPECT_NEAR(quantity("filtered_sin_1"), meanSin1, 1e-12) << label;
      EXPECT_NEAR(quantity("filtered_cos_8"), meanCos8, 1e-12) << label;
      // The reconstructed step's middle sample is the reconstruction at the receiver's own depth.
      const ProbeQuantity* middle = record.find("reconstructed_step_4");
      ASSERT_NE(middle, nullptr) << label;
      EXPECT_EQ(middle->value.at(0), quantity("d_normalized")) << label;
      EXPECT_NEAR(middle->value.at(1), quantity("reconstruction"), 1e-15) << label;
      // Nine samples of d' in [0, 1], in order, each the reconstruction from the recorded coefficients.
      FourierCoefficients recorded;
      for (int k = 1; k <= 8; ++k)
      {
        recorded.sine.push_back(quantity(format("filtered_sin_", k)));
        recorded.cosine.push_back(quantity(format("filtered_cos_", k)));
      }
      double previousD = 0.0;
      for (int j = 0; j < 9; ++j)
      {
        const ProbeQuantity* step = record.find(format("reconstructed_step_", j));
        ASSERT_NE(step, nullptr) << label << " step " << j;
        EXPECT_GE(step->value.at(0), previousD) << label << " step " << j;
        EXPECT_LE(step->value.at(0), 1.0) << label << " step " << j;
        EXPECT_NEAR(step->value.at(1), convsmReconstruct(step->value.at(0), recorded, 8, 0.0), 1e-12) << label << " step " << j;
        previousD = step->value.at(0);
      }
      if (const ProbeQuantity* leak = record.find("light_leak"))
      {
        EXPECT_NEAR(leak->value.at(0), gpu("light_leak"), outcome.tolerance) << label;
      }
    }
  }
  EXPECT_EQ(probed[0], 2) << "lit-ish pixels probed";
  EXPECT_EQ(probed[1], 2) << "penumbra pixels probed";
  EXPECT_EQ(probed[2], 2) << "umbra pixels probed";
}

} // namespace
} // namespace sl
