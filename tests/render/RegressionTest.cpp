// Offscreen regression: every dataset x every registered technique that supports the dataset's light,
// rendered at 128x128 with default parameters (plus the technique's sweepTestSettings) and compared with the committed baselines in
//   tests/baselines/<dataset>/<technique>/image.png        shaded RGB, 8 bit
//   tests/baselines/<dataset>/<technique>/visibility.exr   visibility, 32-bit float
// Tolerances are data, next to the baselines: tests/baselines/tolerance.json ("default" plus optional
// per-case entries "<dataset>/<technique>"; each gives, for "image" and "visibility", max_abs_diff and
// max_failing_fraction = fraction of pixels allowed to differ by more than max_abs_diff). Its _comment says
// why the numbers are what they are. The comparison itself is src/metrics/RegressionComparison.h.
//
// On a failure the actual outputs and the differences are written to
//   <build>/test-output/regression/<dataset>/<technique>/{actual.png, actual_visibility.exr, diff.png,
//   diff_visibility.png}
// and their paths and the numbers are in the failure message. A missing baseline is a failure (a newly
// registered technique or dataset needs blessing before the suite passes).
//
// Re-blessing (after an intended change; look at the new images before committing them). Either
//   SHADOWLAB_BLESS=1 ctest --test-dir build -R Regression
// or
//   SHADOWLAB_BLESS=1 ./build/tests/gpu_tests --gtest_filter='*Regression*'
// writes the current outputs as the new baselines (creating the directories) and passes. The gtest names are
// "Baselines/RegressionTest.Matches/<dataset>_<technique>" with '-' in dataset names turned into '_', e.g.
// Baselines/RegressionTest.Matches/planar_occluder_pcf, and the ctest names are the same (label `regression`),
// so -R Regression selects them all; to re-bless one case:
//   SHADOWLAB_BLESS=1 ctest --test-dir build -R 'Regression.*planar_occluder_pcf'.
#include "core/Error.h"
#include "io/ImageIO.h"
#include "metrics/RegressionComparison.h"
#include "support/TestSupport.h"
#include "techniques/Registry.h"
#include "vis/HeatMap.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace sl
{
namespace
{

namespace fs = std::filesystem;
using Json = nlohmann::json;

constexpr int kBaselineWidth = 128;
constexpr int kBaselineHeight = 128;
const char* const kBlessCommand = "SHADOWLAB_BLESS=1 ctest --test-dir build -R Regression";

fs::path baselineRoot()
{
  return test::sourceDir() / "tests" / "baselines";
}

bool blessRequested()
{
  const char* value = std::getenv("SHADOWLAB_BLESS");
  return value != nullptr && std::string(value) == "1";
}

// ---- tolerance (data: tests/baselines/tolerance.json) ----------------------------------------------------

struct CaseTolerance
{
  RegressionTolerance image;      // max_abs_diff in 0..255 units, per channel
  RegressionTolerance visibility; // max_abs_diff in visibility units (0..1)
};

RegressionTolerance parseTolerance(const Json& entry, const std::string& where, RegressionTolerance base)
{
  for (const auto& [key, value] : entry.items())
  {
    if (key == "max_abs_diff")
    {
      base.maxAbsDiff = value.get<double>();
    }
    else if (key == "max_failing_fraction")
    {
      base.maxFailingFraction = value.get<double>();
    }
    else
    {
      throw InputError("tolerance.json: " + where + ": unknown key '" + key + "'");
    }
  }
  if (!(base.maxAbsDiff >= 0.0) || !(base.maxFailingFraction >= 0.0) || !(base.maxFailingFraction <= 1.0))
  {
    throw InputError("tolerance.json: " + where + ": needs max_abs_diff >= 0 and max_failing_fraction in [0, 1]");
  }
  return base;
}

CaseTolerance parseCaseTolerance(const Json& entry, const std::string& where, CaseTolerance base)
{
  for (const auto& [key, value] : entry.items())
  {
    if (key == "image")
    {
      base.image = parseTolerance(value, where + ".image", base.image);
    }
    else if (key == "visibility")
    {
      base.visibility = parseTolerance(value, where + ".visibility", base.visibility);
    }
    else if (key != "_comment")
    {
      throw InputError("tolerance.json: " + where + ": unknown key '" + key + "'");
    }
  }
  return base;
}

Json loadToleranceFile()
{
  const fs::path path = baselineRoot() / "tolerance.json";
  std::ifstream stream(path);
  if (!stream)
  {
    throw InputError(path.string() + ": cannot read the regression tolerances");
  }
  return Json::parse(stream);
}

// The default entry, overridden field by field by the "<dataset>/<technique>" entry when there is one.
CaseTolerance toleranceFor(const std::string& dataset, const std::string& technique)
{
  const Json file = loadToleranceFile();
  if (!file.contains("default"))
  {
    throw InputError("tolerance.json: no \"default\" entry");
  }
  CaseTolerance tolerance = parseCaseTolerance(file.at("default"), "default", CaseTolerance{});
  const std::string key = dataset + "/" + technique;
  if (file.contains(key))
  {
    tolerance = parseCaseTolerance(file.at(key), key, tolerance);
  }
  return tolerance;
}

// ---- one regression case -----------------------------------------------------------------------------------

struct CaseOutcome
{
  bool passed = false;
  std::string message;
};

// Compares (or, with bless, writes) the baseline of one case. Failure artefacts go to `outputDir`, which is
// emptied first so nothing stale is left from an earlier run.
CaseOutcome checkAgainstBaseline(const ImageU8& image, const ImageF& visibility, const fs::path& baselineDir,
  const fs::path& outputDir, const CaseTolerance& tolerance, bool bless)
{
  const fs::path imagePath = baselineDir / "image.png";
  const fs::path visibilityPath = baselineDir / "visibility.exr";
  std::error_code ignored;
  fs::remove_all(outputDir, ignored);

  CaseOutcome outcome;
  if (bless)
  {
    fs::create_directories(baselineDir);
    writePng(imagePath, image);
    writeExr(visibilityPath, visibility);
    outcome.passed = true;
    outcome.message = "blessed: wrote " + imagePath.string() + " and " + visibilityPath.string();
    return outcome;
  }

  const auto writeActual = [&](std::ostringstream& message) {
    fs::create_directories(outputDir);
    writePng(outputDir / "actual.png", image);
    writeExr(outputDir / "actual_visibility.exr", visibility);
    message << "\n  actual image:      " << (outputDir / "actual.png").string()
            << "\n  actual visibility: " << (outputDir / "actual_visibility.exr").string();
  };

  std::ostringstream message;
  if (!fs::is_regular_file(imagePath) || !fs::is_regular_file(visibilityPath))
  {
    message << "missing baseline " << (fs::is_regular_file(imagePath) ? visibilityPath : imagePath).string()
            << "\n  to create it run: " << kBlessCommand
            << "\n  (or SHADOWLAB_BLESS=1 ./build/tests/gpu_tests --gtest_filter='*Regression*'), then review and commit "
            << baselineDir.string();
    writeActual(message);
    outcome.message = message.str();
    return outcome;
  }

  const ImageU8 expectedImage = readPng(imagePath);
  const ImageF expectedVisibility = readExr(visibilityPath);
  ImageF visibilityDiff;
  const RegressionComparison imageResult = compareWithTolerance(image, expectedImage, tolerance.image);
  const RegressionComparison visibilityResult =
    compareWithTolerance(visibility, expectedVisibility, tolerance.visibility, &visibilityDiff);
  outcome.passed = imageResult.passes(tolerance.image) && visibilityResult.passes(tolerance.visibility);

  message << describeComparison("image", imageResult, tolerance.image) << "\n"
          << describeComparison("visibility", visibilityResult, tolerance.visibility);
  if (!imageResult.sameSize)
  {
    message << "\n  image size " << image.width << "x" << image.height << "x" << image.components << ", baseline "
            << expectedImage.width << "x" << expectedImage.height << "x" << expectedImage.components;
  }
  if (!visibilityResult.sameSize)
  {
    message << "\n  visibility size " << visibility.width << "x" << visibility.height << ", baseline "
            << expectedVisibility.width << "x" << expectedVisibility.height;
  }
  if (!outcome.passed)
  {
    message << "\n  baseline: " << baselineDir.string();
    writeActual(message);
    if (imageResult.sameSize)
    {
      writePng(outputDir / "diff.png", amplifiedDifference(image, expectedImage));
      message << "\n  |image diff| x8:   " << (outputDir / "diff.png").string();
    }
    if (visibilityResult.sameSize)
    {
      HeatMapOptions options;
      options.title = "|visibility - baseline|";
      options.rangeMin = 0.0;
      options.rangeMax = std::max(tolerance.visibility.maxAbsDiff * 4.0, 1e-6);
      writeHeatMapPng(visibilityDiff, nullptr, options, outputDir / "diff_visibility.png");
      message << "\n  |visibility diff|: " << (outputDir / "diff_visibility.png").string();
    }
    message << "\n  if the change is intended, re-bless: " << kBlessCommand;
  }
  outcome.message = message.str();
  return outcome;
}

// ---- the parameterised suite -------------------------------------------------------------------------------

// The cases: every dataset x every registered technique that supports the dataset's shadow-casting light
// (test::datasetTechniquePairs, shared with the NaN/inf sweep).
using RegressionCase = test::DatasetTechnique;

class RegressionTest : public testing::TestWithParam<RegressionCase>
{
};

TEST_P(RegressionTest, Matches)
{
  const RegressionCase& param = GetParam();
  const Scene scene = test::loadDataset(param.dataset);
  const FrameResult frame =
    test::renderDataset(scene, param.technique, kBaselineWidth, kBaselineHeight, findTechnique(param.technique).sweepTestSettings);
  const NamedImage* visibility = frame.find("visibility");
  ASSERT_NE(visibility, nullptr) << param.dataset << "/" << param.technique << ": no visibility buffer";
  ASSERT_EQ(frame.image.width, kBaselineWidth);
  ASSERT_EQ(frame.image.height, kBaselineHeight);
  ASSERT_EQ(frame.image.components, 3);
  // The NaN/inf sweep's check on the defaults (HardCasesTest.cpp checks the variants).
  test::expectFiniteBuffersAndVisibilityInRange(frame, param.dataset + " " + param.technique);

  const CaseTolerance tolerance = toleranceFor(param.dataset, param.technique);
  const bool bless = blessRequested();
  const CaseOutcome outcome = checkAgainstBaseline(frame.image, visibility->image,
    baselineRoot() / param.dataset / param.technique,
    test::testOutputDir() / "regression" / param.dataset / param.technique, tolerance, bless);
  if (bless)
  {
    std::cout << "[ BLESS    ] " << param.dataset << "/" << param.technique << ": " << outcome.message << "\n";
  }
  EXPECT_TRUE(outcome.passed) << param.dataset << "/" << param.technique << " on " << frame.glRenderer << ":\n"
                              << outcome.message;
}

INSTANTIATE_TEST_SUITE_P(
  Baselines, RegressionTest, testing::ValuesIn(test::datasetTechniquePairs()), test::datasetTechniqueName);

// ---- the comparator and the tolerance data themselves --------------------------------------------------------

// The reference visibility for the comparator tests: the committed baseline when there is one (the point is
// a realistic image with shadow edges), else a fresh render so this test does not depend on blessing order.
ImageF referenceVisibility(const std::string& dataset, const std::string& technique)
{
  const fs::path path = baselineRoot() / dataset / technique / "visibility.exr";
  if (fs::is_regular_file(path))
  {
    return readExr(path);
  }
  const FrameResult frame = test::renderDataset(test::loadDataset(dataset), technique, kBaselineWidth, kBaselineHeight);
  return frame.find("visibility")->image;
}

TEST(RegressionComparator, FlagsAnInvertedBlockAndAcceptsChangesWithinTolerance)
{
  const ImageF baseline = referenceVisibility("planar-occluder", "pcf");
  ASSERT_EQ(baseline.width, kBaselineWidth);
  ASSERT_EQ(baseline.height, kBaselineHeight);
  const RegressionTolerance tolerance = toleranceFor("planar-occluder", "pcf").visibility;
  ASSERT_GT(tolerance.maxAbsDiff, 0.0);
  const std::size_t allowedPixels =
    static_cast<std::size_t>(std::floor(tolerance.maxFailingFraction * static_cast<double>(baseline.pixelCount())));
  ASSERT_LT(allowedPixels, 100u) << "tolerance.json allows " << allowedPixels
                                 << " failing pixels: a 10x10 block could hide in it";

  const RegressionComparison identical = compareWithTolerance(baseline, baseline, tolerance);
  EXPECT_TRUE(identical.passes(tolerance)) << describeComparison("identical", identical, tolerance);
  EXPECT_EQ(identical.maxAbsDiff, 0.0);

  // A 10x10 block set to 1 - v. Pick a block whose visibility is far from 0.5 so that every pixel changes by
  // much more than the tolerance (in a fully lit or fully shadowed area, by 1).
  ImageF inverted = baseline;
  int blockX = -1;
  int blockY = -1;
  for (int y = 0; y + 10 <= baseline.height && blockX < 0; y += 5)
  {
    for (int x = 0; x + 10 <= baseline.width && blockX < 0; x += 5)
    {
      bool allFar = true;
      for (int j = 0; j < 10 && allFar; ++j)
      {
        for (int i = 0; i < 10 && allFar; ++i)
        {
          allFar = std::abs(1.0 - 2.0 * baseline.at(x + i, y + j)) > 4.0 * tolerance.maxAbsDiff;
        }
      }
      if (allFar)
      {
        blockX = x;
        blockY = y;
      }
    }
  }
  ASSERT_GE(blockX, 0) << "no 10x10 block with visibility away from 0.5 in the reference";
  for (int j = 0; j < 10; ++j)
  {
    for (int i = 0; i < 10; ++i)
    {
      inverted.at(blockX + i, blockY + j) = 1.0f - inverted.at(blockX + i, blockY + j);
    }
  }
  const RegressionComparison invertedResult = compareWithTolerance(inverted, baseline, tolerance);
  EXPECT_FALSE(invertedResult.passes(tolerance))
    << "block at " << blockX << "," << blockY << ": " << describeComparison("inverted", invertedResult, tolerance);
  EXPECT_EQ(invertedResult.failingPixels, 100u);
  EXPECT_GT(invertedResult.maxAbsDiff, 4.0 * tolerance.maxAbsDiff);

  // Within tolerance: every pixel moved by 3/4 of max_abs_diff, plus `allowedPixels` pixels moved by a lot.
  ImageF nudged = baseline;
  for (float& value : nudged.data)
  {
    value += static_cast<float>(0.75 * tolerance.maxAbsDiff);
  }
  for (std::size_t k = 0; k < allowedPixels; ++k)
  {
    nudged.data[k * 97 % nudged.data.size()] += 0.5f;
  }
  const RegressionComparison nudgedResult = compareWithTolerance(nudged, baseline, tolerance);
  EXPECT_TRUE(nudgedResult.passes(tolerance)) << describeComparison("nudged", nudgedResult, tolerance);
  EXPECT_EQ(nudgedResult.failingPixels, allowedPixels);

  // One failing pixel more than allowed fails; a NaN counts as failing; a size change fails.
  nudged.data[nudged.data.size() - 1] += 0.5f;
  const RegressionComparison overResult = compareWithTolerance(nudged, baseline, tolerance);
  EXPECT_FALSE(overResult.passes(tolerance)) << describeComparison("one over", overResult, tolerance);
  ImageF withNan = baseline;
  withNan.data[0] = std::nanf("");
  EXPECT_EQ(compareWithTolerance(withNan, baseline, tolerance).failingPixels, 1u);
  const ImageF smaller(kBaselineWidth - 1, kBaselineHeight, 1, 1.0f);
  EXPECT_FALSE(compareWithTolerance(smaller, baseline, tolerance).passes(tolerance));

  // The RGB comparator counts a pixel once, by its worst channel.
  ImageU8 rgb(4, 4, 3, 100);
  ImageU8 rgbChanged = rgb;
  rgbChanged.at(1, 2, 2) = 100 + 5;
  rgbChanged.at(3, 3, 0) = 100 - 3;
  const RegressionTolerance rgbTolerance{ 4.0, 0.0 };
  const RegressionComparison rgbResult = compareWithTolerance(rgbChanged, rgb, rgbTolerance);
  EXPECT_EQ(rgbResult.failingPixels, 1u);
  EXPECT_EQ(rgbResult.maxAbsDiff, 5.0);
  EXPECT_FALSE(rgbResult.passes(rgbTolerance));
}

// The missing-baseline, failure-artefact and bless paths, on a scratch baseline directory (never the real one).
TEST(RegressionComparator, MissingBaselineFailsAndBlessCreatesIt)
{
  const fs::path scratch = test::testOutputDir() / "regression-selftest";
  std::error_code ignored;
  fs::remove_all(scratch, ignored);
  const fs::path baselineDir = scratch / "baselines" / "case" / "tech";
  const fs::path outputDir = scratch / "output";

  ImageU8 image(16, 8, 3, 0);
  ImageF visibility(16, 8, 1, 0.0f);
  for (int y = 0; y < 8; ++y)
  {
    for (int x = 0; x < 16; ++x)
    {
      visibility.at(x, y) = x < 8 ? 1.0f : 0.25f;
      image.at(x, y, 0) = static_cast<std::uint8_t>(16 * x);
      image.at(x, y, 1) = static_cast<std::uint8_t>(32 * y);
    }
  }
  const CaseTolerance tolerance{ { 4.0, 0.0 }, { 0.02, 0.0 } };

  const CaseOutcome missing = checkAgainstBaseline(image, visibility, baselineDir, outputDir, tolerance, false);
  EXPECT_FALSE(missing.passed);
  EXPECT_NE(missing.message.find("missing baseline"), std::string::npos) << missing.message;
  EXPECT_NE(missing.message.find(kBlessCommand), std::string::npos) << missing.message;
  EXPECT_TRUE(fs::is_regular_file(outputDir / "actual.png")) << missing.message;
  EXPECT_TRUE(fs::is_regular_file(outputDir / "actual_visibility.exr")) << missing.message;
  EXPECT_FALSE(fs::exists(baselineDir)) << "a failing comparison must not create a baseline";

  const CaseOutcome blessed = checkAgainstBaseline(image, visibility, baselineDir, outputDir, tolerance, true);
  EXPECT_TRUE(blessed.passed) << blessed.message;
  ASSERT_TRUE(fs::is_regular_file(baselineDir / "image.png"));
  ASSERT_TRUE(fs::is_regular_file(baselineDir / "visibility.exr"));
  EXPECT_FALSE(fs::exists(outputDir)) << "stale failure artefacts must be cleared";

  // The written baseline round-trips exactly (row order included), so the same frame passes.
  const CaseOutcome same = checkAgainstBaseline(image, visibility, baselineDir, outputDir, tolerance, false);
  EXPECT_TRUE(same.passed) << same.message;
  EXPECT_FALSE(fs::exists(outputDir));

  // A changed frame fails, names the numbers and writes every artefact it names.
  ImageF changedVisibility = visibility;
  changedVisibility.at(15, 7) = 1.0f;
  ImageU8 changedImage = image;
  changedImage.at(0, 0, 2) = 200;
  const CaseOutcome changed =
    checkAgainstBaseline(changedImage, changedVisibility, baselineDir, outputDir, tolerance, false);
  EXPECT_FALSE(changed.passed);
  EXPECT_NE(changed.message.find("max abs diff 0.75"), std::string::npos) << changed.message;
  EXPECT_NE(changed.message.find("max abs diff 200"), std::string::npos) << changed.message;
  for (const char* file : { "actual.png", "actual_visibility.exr", "diff.png", "diff_visibility.png" })
  {
    EXPECT_TRUE(fs::is_regular_file(outputDir / file)) << file;
    EXPECT_NE(changed.message.find((outputDir / file).string()), std::string::npos) << file << "\n" << changed.message;
  }
  const ImageU8 diff = readPng(outputDir / "diff.png");
  ASSERT_EQ(diff.width, 16);
  ASSERT_EQ(diff.height, 8);
  EXPECT_EQ(diff.at(0, 0, 2), 255) << "200 levels x8 saturates";
  EXPECT_EQ(diff.at(1, 0, 2), 0);
  fs::remove_all(scratch, ignored);
}

// The tolerances must tell the techniques apart: at 128x128 with default parameters a 3x3 PCF kernel in a
// 2048-texel map is narrower than a pixel, so hard and pcf differ in only a few pixels on some datasets
// (near-light: 8 of 16384). If the failing-pixel allowance swallowed that, swapping the techniques (or PCF
// silently degrading to one tap) would pass the regression. Fresh renders, so blessing order does not matter.
TEST(RegressionComparator, TellsHardFromPcfOnEveryDataset)
{
  for (const std::string& dataset : test::datasetNames())
  {
    if (!test::rendersDataset("hard", dataset))
    {
      continue;
    }
    const Scene scene = test::loadDataset(dataset);
    const FrameResult hard = test::renderDataset(scene, "hard", kBaselineWidth, kBaselineHeight);
    const FrameResult pcf = test::renderDataset(scene, "pcf", kBaselineWidth, kBaselineHeight);
    const CaseTolerance tolerance = toleranceFor(dataset, "pcf");
    const RegressionComparison image = compareWithTolerance(hard.image, pcf.image, tolerance.image);
    const RegressionComparison visibility =
      compareWithTolerance(hard.find("visibility")->image, pcf.find("visibility")->image, tolerance.visibility);
    EXPECT_FALSE(image.passes(tolerance.image) && visibility.passes(tolerance.visibility))
      << dataset << ": the hard render passes as the pcf baseline\n"
      << describeComparison("image", image, tolerance.image) << "\n"
      << describeComparison("visibility", visibility, tolerance.visibility);
  }
}

// Every per-case entry of tolerance.json names a case that exists, so a renamed dataset cannot leave a stale,
// loosened tolerance behind; and the default is tight enough to catch a real change.
TEST(RegressionComparator, ToleranceFileIsConsistent)
{
  const Json file = loadToleranceFile();
  ASSERT_TRUE(file.contains("default"));
  ASSERT_TRUE(file.contains("_comment")) << "tolerance.json must say why its numbers are what they are";
  const CaseTolerance defaults = parseCaseTolerance(file.at("default"), "default", CaseTolerance{});
  // Below one PCF tap step (1/9) and one visibility step in the shading; a handful of pixels.
  EXPECT_LE(defaults.visibility.maxAbsDiff, 0.05);
  EXPECT_LE(defaults.visibility.maxFailingFraction, 0.001);
  EXPECT_LE(defaults.image.maxAbsDiff, 8.0);
  EXPECT_LE(defaults.image.maxFailingFraction, 0.001);
  std::vector<std::string> known;
  for (const RegressionCase& c : test::datasetTechniquePairs())
  {
    known.push_back(c.dataset + "/" + c.technique);
  }
  for (const auto& [key, value] : file.items())
  {
    if (key == "default" || key == "_comment")
    {
      continue;
    }
    EXPECT_NE(std::find(known.begin(), known.end(), key), known.end())
      << "tolerance.json entry '" << key << "' is not a regression case";
    EXPECT_NO_THROW(parseCaseTolerance(value, key, defaults)) << key;
  }
}

} // namespace
} // namespace sl
