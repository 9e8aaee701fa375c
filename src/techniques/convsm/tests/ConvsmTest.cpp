// convsm (Annen et al. 2007): the twin against closed forms of the truncated Fourier series of the step (with
// depth_range and reconstruction_scale), the GLSL against the twin pixel by pixel (datasets, M = 4, 8, 16, random
// scenes; at the defaults and at depth_range=1 reconstruction_scale=1), lit receivers, umbrae and the stacked
// occluders against PCF, the contact leak and the error against PCF away from contact as M grows, the probe, and
// the bad-input messages of `terms` and `depth_range`.
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

// depth_range s and reconstruction_scale a against closed forms. Normalised depths enter the series as s z_n, so a
// gap g = z_n - d_n reads S_M(s g); visibility is clamp(a S_M(s g), 0, 1). At s = 1/2 the widest gap, g = -1 (an
// occluder at the light's near end over a receiver at its far end), reads S_M(-1/2) = 1 - S_M(1/2), i.e.
// 1/2 - (2/pi) L_M with L_M the Leibniz partial sum, and a = 2 makes it 1 - (4/pi) L_M; at s = 1 the same gap sits
// on the series' jump, S_M(-1) = 1/2 (the defect depth_range removes). At g = 0, S = 1/2 and a = 2 reads exactly 1.
TEST(Convsm, TwinDepthRangeAndReconstructionScaleEqualClosedForms)
{
  const struct
  {
    int terms;
    double leibniz;
  } partialSums[] = { { 4, 76.0 / 105.0 }, { 8, 33976.0 / 45045.0 }, { 16, 3473755390832.0 / 4512611027925.0 } };
  for (const auto& row : partialSums)
  {
    const int M = row.terms;
    // The widest gap at the defaults (s = 1/2, a = 2).
    const double widest = convsmStepSeries(0.5 * 1.0, 0.5 * 0.0, M, 0.0);
    EXPECT_NEAR(widest, 0.5 - 2.0 / M_PI * row.leibniz, 1e-13) << "M " << M;
    EXPECT_NEAR(convsmVisibility(widest, 2.0), 1.0 - 4.0 / M_PI * row.leibniz, 1e-13) << "M " << M;
    // The same gap at s = 1: the jump, 1/2 whatever the scale's clamp does to it.
    EXPECT_NEAR(convsmStepSeries(1.0, 0.0, M, 0.0), 0.5, 1e-13) << "M " << M;
    EXPECT_NEAR(convsmVisibility(convsmStepSeries(1.0, 0.0, M, 0.0), 1.0), 0.5, 1e-13) << "M " << M;
    // d = z: 1/2, scaled by 2 to exactly lit; by 1 it stays 1/2; by 4 it clamps to 1.
    for (const double d : { 0.0, 0.2, 0.5 })
    {
      EXPECT_EQ(convsmVisibility(convsmStepSeries(d, d, M, 0.0), 2.0), 1.0) << "M " << M << " d " << d;
      EXPECT_NEAR(convsmVisibility(convsmStepSeries(d, d, M, 0.0), 1.0), 0.5, 1e-15) << "M " << M << " d " << d;
      EXPECT_EQ(convsmVisibility(convsmStepSeries(d, d, M, 0.0), 4.0), 1.0) << "M " << M << " d " << d;
    }
    // A gap of -1/2 at s = 1/2: S_M(-1/4) = 1/2 - (sqrt 2 / pi) Q_M, Q_M = 1 + 1/3 - 1/5 - 1/7 + ... (+ + - -).
    double quarter = 0.0;
    for (int k = 1; k <= M; ++k)
    {
      quarter += ((k - 1) % 4 < 2 ? 1.0 : -1.0) / (2 * k - 1);
    }
    const double halfGap = convsmStepSeries(0.5 * 0.8, 0.5 * 0.3, M, 0.0);
    EXPECT_NEAR(halfGap, 0.5 - std::sqrt(2.0) / M_PI * quarter, 1e-13) << "M " << M;
    EXPECT_NEAR(convsmVisibility(halfGap, 2.0), std::clamp(1.0 - 2.0 * std::sqrt(2.0) / M_PI * quarter, 0.0, 1.0), 1e-13) << "M " << M;
    std::cout << "[ measured ] M " << M << ", depth_range 1/2, scale 2: gap -1 reads " << convsmVisibility(widest, 2.0)
              << ", gap -1/2 reads " << convsmVisibility(halfGap, 2.0) << "\n";
  }
  // The scale is a plain clamp(a f, 0, 1).
  EXPECT_NEAR(convsmVisibility(0.3, 3.0), 0.9, 1e-15);
  EXPECT_EQ(convsmVisibility(-0.02, 2.0), 0.0);
  EXPECT_EQ(convsmVisibility(0.7, 2.0), 1.0);
  EXPECT_NEAR(convsmVisibility(0.3, 2.0), 0.6, 1e-15);
}

TEST(Convsm, DepthRangeZeroIsRefusedNamingIt)
{
  ParameterValues values("convsm", findTechnique("convsm").parameters);
  values.set("depth_range=0");
  try
  {
    ConvsmSettings::from(values);
    FAIL() << "depth_range=0 accepted";
  }
  catch (const InputError& error)
  {
    EXPECT_NE(std::string(error.what()).find("depth_range=0"), std::string::npos) << error.what();
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

// The twin on a rendered frame, with depth_range: its reconstruction is the box mean of the pointwise series
// S_M(s z_n - s d_n) over the box's texels (the depth mapping applied to both depths), and its visibility
// clamp(a f, 0, 1). Computed here from the shadow map's texels, independently of convsmBasisAverage.
TEST(Convsm, TwinIsTheBoxMeanOfTheScaledStep)
{
  const Scene scene = test::loadDataset("stacked-occluders");
  for (const std::string range : { "0.5", "0.3", "1" })
  {
    const std::vector<std::string> settings{ "shadow_map_size=128", "prefilter_texels=3", "terms=8", "depth_range=" + range, "reconstruction_scale=1.5" };
    const FrameResult frame = test::renderDataset(scene, "convsm", 48, 40, settings);
    const ShadowMapInputs inputs = test::shadowMapInputs(frame, scene);
    const ConvsmSettings parsed = ConvsmSettings::from(frame.parameters);
    ASSERT_EQ(parsed.depthRange, std::stod(range));
    ASSERT_EQ(parsed.reconstructionScale, 1.5);
    const int size = inputs.shadowMapLinear.width;
    int checked = 0;
    for (int y = 0; y < 40; ++y)
    {
      for (int x = 0; x < 48; ++x)
      {
        const ConvsmSample cpu = convsmReference(inputs, parsed, x, y);
        if (!cpu.sample.evaluated)
        {
          continue;
        }
        const ShadowLookup lookup = prepareShadowLookup(inputs, parsed.bias, x, y);
        const int cx = std::clamp(static_cast<int>(std::floor(lookup.sm.uvTexels.x)), 0, size - 1);
        const int cy = std::clamp(static_cast<int>(std::floor(lookup.sm.uvTexels.y)), 0, size - 1);
        const double dNormalized = convsmNormalizedDepth(inputs, lookup.comparisonDepth);
        double boxMean = 0.0;
        for (int j = -1; j <= 1; ++j)
        {
          for (int i = -1; i <= 1; ++i)
          {
            const double z = inputs.shadowMapLinear.at(std::clamp(cx + i, 0, size - 1), std::clamp(cy + j, 0, size - 1));
            boxMean += convsmStepSeries(parsed.depthRange * dNormalized, parsed.depthRange * convsmNormalizedDepth(inputs, z), 8, 0.0) / 9.0;
          }
        }
        ++checked;
        EXPECT_NEAR(cpu.reconstruction, boxMean, 1e-12) << "depth_range " << range << " pixel " << x << "," << y;
        EXPECT_EQ(cpu.sample.visibility, std::clamp(1.5 * cpu.reconstruction, 0.0, 1.0)) << "depth_range " << range << " pixel " << x << "," << y;
        EXPECT_NEAR(cpu.dSeries, parsed.depthRange * dNormalized, 1e-15);
      }
    }
    EXPECT_GT(checked, 500) << range;
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
  int lit = 0;          // visibility >= 0.45 (at reconstruction_scale 1 the series reads about 1/2 on lit receivers)
  int umbra = 0;        // visibility < 0.1 (at the defaults, M = 4 reads 0.078 at the widest gap)
  int transition = 0;   // in between
  int overshooting = 0;
  int edgeResolved = 0; // matched the box across the nearest texel edge (below)
  double maxDifference = 0.0;
};

// The twin's reconstruction with the receiver's texel moved across its nearest texel edge, when it lies within
// 1e-2 texel of one; NaN otherwise. The GPU projects the receiver in float: one very near the light (random seed 1:
// 0.004 of the light's range from it) moves by up to a few 1e-3 texel, and its box is the neighbouring texel's.
double convsmAcrossTexelEdge(const ShadowMapInputs& inputs, const ConvsmSettings& settings, const glm::dvec2& uvTexels, double dSeries)
{
  glm::dvec2 moved = uvTexels;
  bool near = false;
  for (int axis = 0; axis < 2; ++axis)
  {
    const double fraction = uvTexels[axis] - std::floor(uvTexels[axis]);
    if (fraction < 1e-2 || fraction > 1.0 - 1e-2)
    {
      moved[axis] += fraction < 0.5 ? -2e-2 : 2e-2;
      near = true;
    }
  }
  if (!near)
  {
    return std::nan("");
  }
  const FourierCoefficients coefficients = convsmBasisAverage(inputs, moved, settings.prefilter.texels, settings.terms, settings.depthRange);
  return convsmReconstruct(dSeries, coefficients, settings.terms, settings.ringingAlpha);
}

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
      (v >= 0.45 ? agreement.lit : v < 0.1 ? agreement.umbra : agreement.transition) += 1;
      agreement.overshooting += cpu.reconstruction < 0.0 || cpu.reconstruction > 1.0 ? 1 : 0;
      const double difference = std::abs(reconstruction.at(x, y) - cpu.reconstruction);
      if (difference > tolerance)
      {
        const double across = convsmAcrossTexelEdge(inputs, settings, lookup.sm.uvTexels, cpu.dSeries);
        if (std::abs(reconstruction.at(x, y) - across) <= tolerance)
        {
          ++agreement.edgeResolved;
          EXPECT_NEAR(visibility.at(x, y), convsmVisibility(across, settings.reconstructionScale), tolerance) << label << " visibility at " << x << "," << y;
          continue;
        }
      }
      agreement.maxDifference = std::max(agreement.maxDifference, difference);
      EXPECT_LE(difference, tolerance) << label << " reconstruction at " << x << "," << y << ": GPU " << reconstruction.at(x, y)
                                       << " twin " << cpu.reconstruction;
      EXPECT_NEAR(visibility.at(x, y), cpu.sample.visibility, tolerance) << label << " visibility at " << x << "," << y;
      EXPECT_NEAR(overshoot.at(x, y), cpu.reconstruction - std::clamp(cpu.reconstruction, 0.0, 1.0), tolerance) << label << " overshoot at " << x << "," << y;
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

// The two configurations every GPU-against-twin case runs: the defaults (depth_range 1/2, reconstruction_scale 2)
// and the raw series over the whole period without bias (depth_range 1, reconstruction_scale 1, bias 0: the
// technique before them).
const std::vector<std::vector<std::string>>& convsmTestConfigurations()
{
  static const std::vector<std::vector<std::string>> configurations{ {},
    { "depth_range=1", "reconstruction_scale=1", "bias_constant_texels=0", "bias_slope_texels=0" } };
  return configurations;
}

// Tolerance 5e-5: the GPU evaluates sin(c_k z_s) in float with c_k up to 31 pi, averages the box in float and sums
// M terms of weight 2 / c_k; the twin does all of it in double (measured at most 6e-6). The scale 2 doubles the
// difference of visibility where it is not clamped.
TEST(Convsm, GpuMatchesTheTwinOnDatasets)
{
  for (const std::string dataset : { "stacked-occluders", "bunny", "contact" })
  {
    const Scene scene = test::loadDataset(dataset);
    for (const std::vector<std::string>& configuration : convsmTestConfigurations())
    for (const std::string terms : { "4", "8", "16" })
    {
      std::vector<std::string> settings{ "shadow_map_size=256", "prefilter_texels=5", "terms=" + terms };
      settings.insert(settings.end(), configuration.begin(), configuration.end());
      const FrameResult frame = test::renderDataset(scene, "convsm", 96, 80, settings);
      const std::string label = test::caseLabel(dataset, settings);
      const ConvsmAgreement agreement = convsmCompare(frame, scene, label, 5e-5);
      std::cout << "[ measured ] " << label << ": compared " << agreement.compared << " (lit " << agreement.lit << ", umbra "
                << agreement.umbra << ", transition " << agreement.transition << ", overshooting " << agreement.overshooting << "), skipped " << agreement.skipped << ", max |gpu - twin| "
                << agreement.maxDifference << "\n";
      EXPECT_GT(agreement.compared, 300) << label;
      EXPECT_GT(agreement.lit, 20) << label;
      EXPECT_GT(agreement.umbra, 20) << label;
      EXPECT_GT(agreement.transition, 20) << label << ": the series must soften the shadow edges";
    }
  }
  // The damping, a wider box, and depth_range and reconstruction_scale off both configurations.
  const Scene scene = test::loadDataset("contact");
  const std::vector<std::string> settings{ "shadow_map_size=256", "prefilter_texels=7", "terms=8", "ringing_alpha=3", "depth_range=0.7", "reconstruction_scale=3" };
  const ConvsmAgreement agreement = convsmCompare(test::renderDataset(scene, "convsm", 96, 80, settings), scene, test::caseLabel("contact", settings), 5e-5);
  std::cout << "[ measured ] " << test::caseLabel("contact", settings) << ": compared " << agreement.compared << ", max |gpu - twin| " << agreement.maxDifference << "\n";
  EXPECT_GT(agreement.compared, 300);
}

// Random generated configurations (scene/RandomScenes.h) against the twin, M drawn from the seed.
TEST(Convsm, GpuMatchesTheTwinOnRandomScenes)
{
  const char* termChoices[] = { "4", "8", "16" };
  int compared = 0;
  for (std::uint64_t seed = 1; seed <= 6; ++seed)
  for (const std::vector<std::string>& configuration : convsmTestConfigurations())
  {
    const RandomScene random = randomScene(seed, 64);
    const Scene scene = parseScene(random.json, "convsm seed " + std::to_string(seed), ".");
    std::vector<std::string> settings{ "shadow_map_size=128", "prefilter_texels=" + std::to_string(1 + 2 * (seed % 3)),
      std::string("terms=") + termChoices[seed % 3] };
    settings.insert(settings.end(), configuration.begin(), configuration.end());
    const FrameResult frame = test::renderDataset(scene, "convsm", 64, 64, settings);
    const std::string label = "seed " + std::to_string(seed) + " (" + random.summary + ") " + test::caseLabel("", settings);
    const ConvsmAgreement agreement = convsmCompare(frame, scene, label, 5e-5);
    std::cout << "[ measured ] " << label << ": compared " << agreement.compared << " (" << agreement.edgeResolved
              << " matching the box across the nearest texel edge), max |gpu - twin| " << agreement.maxDifference << "\n";
    compared += agreement.compared;
    EXPECT_LE(agreement.edgeResolved, 5) << label;
  }
  EXPECT_GT(compared, 2000);
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

// Contact at the defaults: where an occluder nearly touches its receiver the step's transition (about 1 / (M s)
// of the depth range wide) straddles both, and the series reads neither 0 nor 1 over what PCF finds shadowed: it
// leaks light there (CSM's known leak at contact); away from contact the error is the series' tail, which falls
// as M grows. Lit receivers (box PCF 1) read lit: the scale maps the series' 1/2 at d = z to 1.
TEST(Convsm, LeakAtContactAndErrorAwayFromContact)
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
    EXPECT_GT(figures.contactMeanLeak, 0.1) << terms << ": the transition straddling the contact leaks light";
    EXPECT_GT(figures.contactMaxLeak, 2.0 * figures.awayMaxError) << terms << ": contact must be the worst";
    EXPECT_EQ(figures.litMeanLeak, 0.0) << terms << ": lit receivers read lit";
    EXPECT_LT(figures.awayMaxError, 0.8 * previousAway) << terms << ": more terms, less error away from contact";
    previousAway = figures.awayMaxError;
  }
}

struct ConvsmRegionFigures
{
  int pixels = 0;
  double meanVisibility = 0.0;
  double maxVisibility = 0.0;
  double meanPcf = 0.0;
  double meanGap = 0.0; // d_n - z_n of the box's nearest texel to the light
  int flagged = 0;      // |light_leak| > 1e-3
};

// The twin's and the GPU's figures over the pixels whose box (`margin` texels wider than the prefilter's on each
// side) `selects`: each box texel's linear depth z and the receiver's compared depth (pcf's default bias) given.
template <typename Select>
ConvsmRegionFigures convsmRegionFigures(const FrameResult& frame, const Scene& scene, int margin, Select selects)
{
  const ShadowMapInputs inputs = test::shadowMapInputs(frame, scene);
  const ConvsmSettings settings = ConvsmSettings::from(frame.parameters);
  const ImageF& visibility = frame.find("visibility")->image;
  const ImageF& lightLeak = frame.find("light_leak")->image;
  const int size = inputs.shadowMapLinear.width;
  const int half = (settings.prefilter.texels - 1) / 2 + margin;
  ConvsmRegionFigures figures;
  for (int y = 0; y < visibility.height; ++y)
  {
    for (int x = 0; x < visibility.width; ++x)
    {
      const ConvsmSample cpu = convsmReference(inputs, settings, x, y);
      if (!cpu.sample.evaluated)
      {
        continue;
      }
      const ShadowLookup lookup = prepareShadowLookup(inputs, settings.bias, x, y);
      const double leakDepth = prepareShadowLookup(inputs, defaultBiasSettings(), x, y).comparisonDepth;
      const int cx = std::clamp(static_cast<int>(std::floor(lookup.sm.uvTexels.x)), 0, size - 1);
      const int cy = std::clamp(static_cast<int>(std::floor(lookup.sm.uvTexels.y)), 0, size - 1);
      bool all = true;
      double nearestZ = 1e300;
      for (int j = -half; j <= half && all; ++j)
      {
        for (int i = -half; i <= half && all; ++i)
        {
          const double z = inputs.shadowMapLinear.at(std::clamp(cx + i, 0, size - 1), std::clamp(cy + j, 0, size - 1));
          all = selects(z, leakDepth);
          nearestZ = std::min(nearestZ, z);
        }
      }
      if (!all)
      {
        continue;
      }
      ++figures.pixels;
      figures.meanVisibility += visibility.at(x, y);
      figures.maxVisibility = std::max(figures.maxVisibility, static_cast<double>(visibility.at(x, y)));
      figures.meanPcf += cpu.boxPcf;
      figures.meanGap += cpu.dNormalized - convsmNormalizedDepth(inputs, nearestZ);
      figures.flagged += std::abs(lightLeak.at(x, y)) > 1e-3f ? 1 : 0;
    }
  }
  const int count = std::max(figures.pixels, 1);
  figures.meanVisibility /= count;
  figures.meanPcf /= count;
  figures.meanGap /= count;
  return figures;
}

std::ostream& operator<<(std::ostream& out, const ConvsmRegionFigures& figures)
{
  return out << figures.pixels << " px, visibility mean " << figures.meanVisibility << " max " << figures.maxVisibility << ", box PCF mean "
             << figures.meanPcf << ", d_n - z_n mean " << figures.meanGap << ", flagged by light_leak " << figures.flagged;
}

// Lit receivers (every texel of the box passes pcf's comparison) read lit at the defaults on three datasets; with
// reconstruction_scale 1 they read the series' 1/2 (d = z), the defect the scale removes.
TEST(Convsm, LitReceiversReadLitAtTheDefaults)
{
  for (const std::string dataset : { "stacked-occluders", "planar-occluder", "contact" })
  {
    const Scene scene = test::loadDataset(dataset);
    for (const std::vector<std::string>& configuration : convsmTestConfigurations())
    {
      std::vector<std::string> settings{ "shadow_map_size=256", "prefilter_texels=5" };
      settings.insert(settings.end(), configuration.begin(), configuration.end());
      const FrameResult frame = test::renderDataset(scene, "convsm", 96, 80, settings);
      const ImageF& visibility = frame.find("visibility")->image;
      const ShadowMapInputs inputs = test::shadowMapInputs(frame, scene);
      const ConvsmSettings parsed = ConvsmSettings::from(frame.parameters);
      int lit = 0;
      int readLit = 0;
      double minimum = 1.0;
      double mean = 0.0;
      for (int y = 0; y < visibility.height; ++y)
      {
        for (int x = 0; x < visibility.width; ++x)
        {
          const ConvsmSample cpu = convsmReference(inputs, parsed, x, y);
          if (!cpu.sample.evaluated || cpu.boxPcf < 1.0)
          {
            continue;
          }
          ++lit;
          readLit += visibility.at(x, y) >= 0.99f ? 1 : 0;
          minimum = std::min(minimum, static_cast<double>(visibility.at(x, y)));
          mean += visibility.at(x, y);
        }
      }
      mean /= std::max(lit, 1);
      const std::string label = test::caseLabel(dataset, settings);
      std::cout << "[ measured ] " << label << ": lit (box PCF 1) " << lit << " px, reading >= 0.99 " << readLit << ", min " << minimum
                << ", mean " << mean << "\n";
      ASSERT_GT(lit, 1000) << label;
      if (configuration.empty())
      {
        EXPECT_EQ(readLit, lit) << label << ": min " << minimum;
      }
      else
      {
        EXPECT_NEAR(mean, 0.5, 0.05) << label << ": the raw series reads 1/2 at d = z";
      }
    }
  }
}

// The series represents H(z - d) on (-1, 1) only: it is the square wave of period 2, which jumps back at z - d = -1
// and 1 and reads 1/2 there. Over the whole period (depth_range 1) an occluder near the light (z_n ~ 0) over a
// receiver at the far end (d_n ~ 1) sits on that jump: on planar-occluder the umbra reads about 1/2 (scale 1),
// every pixel flagged by light_leak. At the defaults (depth_range 1/2) the gap reads S_M(-1/2) and the umbra
// (every texel of the box widened by two texels occluding) is dark.
TEST(Convsm, PlanarOccluderUmbraIsDarkAtTheDefaults)
{
  const Scene scene = test::loadDataset("planar-occluder");
  for (const std::vector<std::string>& configuration : convsmTestConfigurations())
  {
    std::vector<std::string> settings{ "shadow_map_size=256", "prefilter_texels=5", "terms=16" };
    settings.insert(settings.end(), configuration.begin(), configuration.end());
    const FrameResult frame = test::renderDataset(scene, "convsm", 96, 80, settings);
    const ConvsmRegionFigures umbra = convsmRegionFigures(frame, scene, 2, [](double z, double leakDepth) { return !(leakDepth <= z); });
    const std::string label = test::caseLabel("planar-occluder", settings);
    std::cout << "[ measured ] " << label << ": umbra " << umbra << "\n";
    ASSERT_GT(umbra.pixels, 100) << label;
    EXPECT_GT(umbra.meanGap, 0.8) << label << ": the occluder must lie near the light and the receiver near the far end";
    EXPECT_EQ(umbra.meanPcf, 0.0) << label;
    if (configuration.empty())
    {
      EXPECT_LE(umbra.maxVisibility, 0.05) << label;
    }
    else
    {
      EXPECT_GT(umbra.meanVisibility, 0.3) << label << ": the series' jump at z - d = -1 reads about 1/2";
      EXPECT_EQ(umbra.flagged, umbra.pixels) << label << ": every such pixel must be flagged";
    }
  }
}

// stacked-occluders: the upper occluder (linear depth 1.7 from the light, the lower one 2.6, the floor 3.2) sits
// near the light's near end. Its umbra (every texel of the box widened by two texels is the upper occluder's)
// against PCF (0 there): dark at the defaults, about 1/2 over the whole period at scale 1.
TEST(Convsm, StackedOccludersUpperOccluderShadows)
{
  const Scene scene = test::loadDataset("stacked-occluders");
  for (const std::vector<std::string>& configuration : convsmTestConfigurations())
  {
    std::vector<std::string> settings{ "shadow_map_size=256", "prefilter_texels=5" };
    settings.insert(settings.end(), configuration.begin(), configuration.end());
    const FrameResult frame = test::renderDataset(scene, "convsm", 96, 80, settings);
    const ConvsmRegionFigures upper = convsmRegionFigures(frame, scene, 2, [](double z, double leakDepth) { return z < 2.15 && !(leakDepth <= z); });
    const ConvsmRegionFigures lower = convsmRegionFigures(frame, scene, 2, [](double z, double leakDepth) { return z > 2.15 && !(leakDepth <= z); });
    const std::string label = test::caseLabel("stacked-occluders", settings);
    std::cout << "[ measured ] " << label << ": upper occluder's umbra " << upper << "; lower occluder's umbra " << lower << "\n";
    ASSERT_GT(upper.pixels, 50) << label;
    ASSERT_GT(lower.pixels, 50) << label;
    if (configuration.empty())
    {
      EXPECT_LE(upper.meanVisibility, upper.meanPcf + 0.05) << label;
      EXPECT_LE(lower.meanVisibility, lower.meanPcf + 0.05) << label;
    }
    else
    {
      EXPECT_GT(upper.meanVisibility, 0.3) << label << ": the series' jump reads about 1/2";
    }
  }
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
          // The default depth_range 1/2: z_s = z_n / 2.
          const double zs = 0.5 * convsmNormalizedDepth(inputs, texel.storedDepth);
          meanSin1 += texel.weight * std::sin(M_PI * zs);
          meanCos8 += texel.weight * std::cos(15.0 * M_PI * zs);
          ++boxTexels;
        }
      }
      EXPECT_EQ(boxTexels, 25) << label;
      EXPECT_NEAR(quantity("filtered_sin_1"), meanSin1, 1e-12) << label;
      EXPECT_NEAR(quantity("filtered_cos_8"), meanCos8, 1e-12) << label;
      // The reconstructed step's middle sample is the reconstruction at the receiver's own depth.
      const ProbeQuantity* middle = record.find("reconstructed_step_4");
      ASSERT_NE(middle, nullptr) << label;
      EXPECT_EQ(middle->value.at(0), quantity("d_series")) << label;
      EXPECT_EQ(quantity("d_series"), 0.5 * quantity("d_normalized")) << label;
      EXPECT_EQ(quantity("visibility"), std::clamp(quantity("reconstruction_scale") * quantity("reconstruction"), 0.0, 1.0)) << label;
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
        EXPECT_LE(step->value.at(0), 0.5) << label << " step " << j << ": d' in [0, depth_range]";
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
