// Error metrics (src/metrics): statistics on hand-built images against closed forms (exact: every value and
// error is a dyadic fraction, so float and double sums are exact), coverage masking, penumbra restriction, the
// sign convention, and the file level behind `shadowlab compare` (.vti in, error.vti / error.png / metrics.json
// out, InputError naming the file).
#include "metrics/Comparison.h"
#include "metrics/ErrorMetrics.h"

#include "core/Error.h"
#include "io/ImageIO.h"
#include "pipeline/ShadowRenderer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <limits>
#include <string>
#include <vector>

#include <unistd.h>

namespace sl
{
namespace
{

namespace fs = std::filesystem;

// A 1-component image from values in memory order: row 0 (the BOTTOM row) first, x left to right.
ImageF imageFromValues(int width, int height, std::initializer_list<float> values)
{
  ImageF image(width, height, 1);
  EXPECT_EQ(values.size(), image.data.size());
  std::size_t i = 0;
  for (float value : values)
  {
    image.data[i++] = value;
  }
  return image;
}

ImageF filled(int width, int height, float value)
{
  return ImageF(width, height, 1, value);
}

// Runs `call`, expects InputError, returns its message ("" and a failure when nothing or something else is thrown).
std::string inputErrorMessage(const std::function<void()>& call)
{
  try
  {
    call();
  }
  catch (const InputError& error)
  {
    return error.what();
  }
  catch (const std::exception& error)
  {
    ADD_FAILURE() << "expected InputError, got: " << error.what();
    return "";
  }
  ADD_FAILURE() << "expected InputError, nothing was thrown";
  return "";
}

bool contains(const std::string& text, const std::string& part)
{
  return text.find(part) != std::string::npos;
}

void expectStatisticsEqual(const ErrorStatistics& actual, const ErrorStatistics& expected, const std::string& what)
{
  EXPECT_EQ(actual.pixels, expected.pixels) << what;
  EXPECT_DOUBLE_EQ(actual.rmse, expected.rmse) << what;
  EXPECT_DOUBLE_EQ(actual.mae, expected.mae) << what;
  EXPECT_DOUBLE_EQ(actual.maxAbsError, expected.maxAbsError) << what;
  EXPECT_DOUBLE_EQ(actual.fractionAbove005, expected.fractionAbove005) << what;
}

void expectAllZero(const ErrorStatistics& statistics, const std::string& what)
{
  EXPECT_EQ(statistics.pixels, 0u) << what;
  EXPECT_EQ(statistics.rmse, 0.0) << what;
  EXPECT_EQ(statistics.mae, 0.0) << what;
  EXPECT_EQ(statistics.maxAbsError, 0.0) << what;
  EXPECT_EQ(statistics.fractionAbove005, 0.0) << what;
}

// The hand-built 4x3 pair. Reference (rows bottom to top) and error = test - reference per pixel:
//   y=0  ref 0    0.5     1    0.25      error  0.25  -0.125   0    0.03125
//   y=1  ref 1    1       0.75 0         error -0.5    0      -0.0625 0.0625
//   y=2  ref 0    0.5     1    1         error  0      0.015625 -1  0
ImageF handBuiltReference()
{
  return imageFromValues(4, 3, { 0.0f, 0.5f, 1.0f, 0.25f, 1.0f, 1.0f, 0.75f, 0.0f, 0.0f, 0.5f, 1.0f, 1.0f });
}

ImageF handBuiltTest()
{
  return imageFromValues(4, 3,
    { 0.25f, 0.375f, 1.0f, 0.28125f, 0.5f, 1.0f, 0.6875f, 0.0625f, 0.0f, 0.515625f, 0.0f, 1.0f });
}

// ---- in memory -------------------------------------------------------------------------------------------

TEST(ErrorMetrics, HandBuiltImagesMatchClosedForms)
{
  const ImageF all = filled(4, 3, 1.0f);
  const ErrorMetrics metrics = computeErrorMetrics(handBuiltTest(), handBuiltReference(), all, all);

  // All 12 pixels covered.
  //   sum |e|  = 0.25 + 0.125 + 0.03125 + 0.5 + 0.0625 + 0.0625 + 0.015625 + 1 = 2.046875
  //   sum e^2  = 0.0625 + 0.015625 + 0.0009765625 + 0.25 + 0.00390625 + 0.00390625 + 0.000244140625 + 1
  //            = 1.337158203125
  //   max |e|  = 1
  //   |e| > 0.05: 0.25, 0.125, 0.5, 0.0625, 0.0625, 1 -> 6 of 12 (0.03125 and 0.015625 are below)
  EXPECT_EQ(metrics.covered.pixels, 12u);
  EXPECT_DOUBLE_EQ(metrics.covered.rmse, std::sqrt(1.337158203125 / 12.0));
  EXPECT_DOUBLE_EQ(metrics.covered.mae, 2.046875 / 12.0);
  EXPECT_DOUBLE_EQ(metrics.covered.maxAbsError, 1.0);
  EXPECT_DOUBLE_EQ(metrics.covered.fractionAbove005, 0.5);

  // Penumbra: 0 < ref < 1 at (1,0) ref 0.5, (3,0) ref 0.25, (2,1) ref 0.75, (1,2) ref 0.5; errors
  // -0.125, 0.03125, -0.0625, 0.015625.
  //   sum |e| = 0.234375, sum e^2 = 0.015625 + 0.0009765625 + 0.00390625 + 0.000244140625 = 0.020751953125
  //   max |e| = 0.125, |e| > 0.05: 0.125, 0.0625 -> 2 of 4
  EXPECT_EQ(metrics.penumbra.pixels, 4u);
  EXPECT_DOUBLE_EQ(metrics.penumbra.rmse, std::sqrt(0.020751953125 / 4.0));
  EXPECT_DOUBLE_EQ(metrics.penumbra.mae, 0.234375 / 4.0);
  EXPECT_DOUBLE_EQ(metrics.penumbra.maxAbsError, 0.125);
  EXPECT_DOUBLE_EQ(metrics.penumbra.fractionAbove005, 0.5);
  EXPECT_EQ(metrics.array, "visibility");
}

TEST(ErrorMetrics, UncoveredPixelsDoNotCount)
{
  // Reference 0.5 everywhere; the test differs only where stated.
  const ImageF reference = filled(4, 3, 0.5f);
  ImageF test = filled(4, 3, 0.5f);
  ImageF testCoverage = filled(4, 3, 1.0f);
  ImageF referenceCoverage = filled(4, 3, 1.0f);
  test.at(0, 0) = 0.75f;  // e = 0.25, covered in both: counts
  test.at(1, 1) = 0.625f; // e = 0.125, coverage 0.75 in both (> 0.5): counts
  testCoverage.at(1, 1) = 0.75f;
  referenceCoverage.at(1, 1) = 0.75f;
  test.at(1, 0) = 1000.0f; // covered in the reference only
  testCoverage.at(1, 0) = 0.0f;
  test.at(2, 0) = -1000.0f; // covered in the test only
  referenceCoverage.at(2, 0) = 0.0f;
  test.at(3, 0) = 500.0f; // covered in neither
  testCoverage.at(3, 0) = 0.0f;
  referenceCoverage.at(3, 0) = 0.0f;
  test.at(0, 1) = 100.0f; // coverage exactly 0.5 is not covered (> 0.5)
  testCoverage.at(0, 1) = 0.5f;

  const Comparison comparison = compareImages(test, reference, testCoverage, referenceCoverage);
  // 8 pixels compared, errors 0.25, 0.125 and six 0:
  //   rmse = sqrt((0.0625 + 0.015625) / 8), mae = 0.375 / 8, max 0.25, 2 of 8 above 0.05.
  const ErrorStatistics& covered = comparison.metrics.covered;
  EXPECT_EQ(covered.pixels, 8u);
  EXPECT_DOUBLE_EQ(covered.rmse, std::sqrt(0.078125 / 8.0));
  EXPECT_DOUBLE_EQ(covered.mae, 0.375 / 8.0);
  EXPECT_DOUBLE_EQ(covered.maxAbsError, 0.25);
  EXPECT_DOUBLE_EQ(covered.fractionAbove005, 0.25);
  // All reference values are 0.5, so the penumbra is the same set.
  expectStatisticsEqual(comparison.metrics.penumbra, covered, "penumbra");

  for (const auto& [x, y] : std::vector<std::pair<int, int>>{ { 1, 0 }, { 2, 0 }, { 3, 0 }, { 0, 1 } })
  {
    EXPECT_EQ(comparison.mask.at(x, y), 0.0f) << "pixel " << x << "," << y;
    EXPECT_EQ(comparison.error.at(x, y), 0.0f) << "pixel " << x << "," << y;
  }
  EXPECT_EQ(comparison.mask.at(0, 0), 1.0f);
  EXPECT_EQ(comparison.mask.at(1, 1), 1.0f);
  EXPECT_EQ(comparison.mask.at(3, 2), 1.0f);
}

TEST(ErrorMetrics, MissingCoverageUsesTheOtherOrEveryPixel)
{
  const ImageF reference = filled(2, 1, 0.5f);
  const ImageF test = imageFromValues(2, 1, { 0.75f, 0.5625f }); // errors 0.25, 0.0625
  const ImageF onlyFirst = imageFromValues(2, 1, { 1.0f, 0.0f });
  const ImageF none;

  // Test coverage not given: the reference's decides (first pixel only).
  ErrorMetrics metrics = computeErrorMetrics(test, reference, none, onlyFirst);
  EXPECT_EQ(metrics.covered.pixels, 1u);
  EXPECT_DOUBLE_EQ(metrics.covered.maxAbsError, 0.25);
  metrics = computeErrorMetrics(test, reference, onlyFirst, none);
  EXPECT_EQ(metrics.covered.pixels, 1u);

  // Neither given: both pixels. mae = (0.25 + 0.0625) / 2, rmse = sqrt((0.0625 + 0.00390625) / 2).
  metrics = computeErrorMetrics(test, reference, none, none);
  EXPECT_EQ(metrics.covered.pixels, 2u);
  EXPECT_DOUBLE_EQ(metrics.covered.mae, 0.3125 / 2.0);
  EXPECT_DOUBLE_EQ(metrics.covered.rmse, std::sqrt(0.06640625 / 2.0));
}

TEST(ErrorMetrics, PenumbraIsStrictlyBetweenZeroAndOne)
{
  // Reference 0 and 1 (umbra, lit) carry big errors; the penumbra pixels small ones; one penumbra pixel is
  // uncovered and must not count either.
  //   x:     0     1     2      3
  //   ref    0     1     0.5    0.25      (a tiny 2^-20 at (0,1) and 1 - 2^-10 at (1,1) are penumbra too)
  const ImageF reference = imageFromValues(4, 2,
    { 0.0f, 1.0f, 0.5f, 0.25f, 0x1p-20f, 1.0f - 0x1p-10f, 0.5f, 0.0f });
  const ImageF test = imageFromValues(4, 2,
    { 1.0f, 0.0f, 0.5625f, 0.25f, 0x1p-20f + 0.03125f, 1.0f - 0x1p-10f, 0.0f, 0.0f });
  ImageF coverage = filled(4, 2, 1.0f);
  coverage.at(2, 1) = 0.0f; // ref 0.5, error -0.5: uncovered
  const ErrorMetrics metrics = computeErrorMetrics(test, reference, coverage, coverage);

  // Penumbra: (2,0) e 0.0625, (3,0) e 0, (0,1) e 0.03125, (1,1) e 0 -> 4 pixels.
  //   mae = 0.09375 / 4, rmse = sqrt((0.00390625 + 0.0009765625) / 4), max 0.0625, 1 of 4 above 0.05.
  EXPECT_EQ(metrics.penumbra.pixels, 4u);
  EXPECT_DOUBLE_EQ(metrics.penumbra.mae, 0.09375 / 4.0);
  EXPECT_DOUBLE_EQ(metrics.penumbra.rmse, std::sqrt(0.0048828125 / 4.0));
  EXPECT_DOUBLE_EQ(metrics.penumbra.maxAbsError, 0.0625);
  EXPECT_DOUBLE_EQ(metrics.penumbra.fractionAbove005, 0.25);
  // Covered: 7 pixels; the umbra/lit pixels (0,0) and (1,0) with |e| = 1 are in here, not in the penumbra.
  EXPECT_EQ(metrics.covered.pixels, 7u);
  EXPECT_DOUBLE_EQ(metrics.covered.maxAbsError, 1.0);
  EXPECT_DOUBLE_EQ(metrics.covered.mae, 2.09375 / 7.0);
}

TEST(ErrorMetrics, EmptyPenumbraAndNoCoveredPixelsGiveZeros)
{
  // Hard shadow reference (only 0 and 1): empty penumbra.
  const ImageF reference = imageFromValues(2, 1, { 0.0f, 1.0f });
  const ImageF test = imageFromValues(2, 1, { 0.5f, 0.5f });
  const ImageF all = filled(2, 1, 1.0f);
  ErrorMetrics metrics = computeErrorMetrics(test, reference, all, all);
  EXPECT_EQ(metrics.covered.pixels, 2u);
  expectAllZero(metrics.penumbra, "empty penumbra");

  // Nothing covered: everything zero, no NaN, and the JSON holds plain zeros.
  const ImageF nothing = filled(2, 1, 0.0f);
  const Comparison comparison = compareImages(test, reference, nothing, all);
  expectAllZero(comparison.metrics.covered, "no covered pixels");
  expectAllZero(comparison.metrics.penumbra, "no covered pixels, penumbra");
  for (std::size_t i = 0; i < comparison.error.data.size(); ++i)
  {
    EXPECT_EQ(comparison.error.data[i], 0.0f);
    EXPECT_EQ(comparison.mask.data[i], 0.0f);
  }
  const nlohmann::json json = metricsJson(comparison.metrics);
  EXPECT_EQ(json["covered"]["pixels"], 0);
  EXPECT_EQ(json["covered"]["rmse"].get<double>(), 0.0);
  EXPECT_EQ(json["penumbra"]["fraction_above_0.05"].get<double>(), 0.0);
}

TEST(ErrorMetrics, ErrorIsTestMinusReference)
{
  const ImageF all = filled(4, 3, 1.0f);
  const Comparison comparison = compareImages(handBuiltTest(), handBuiltReference(), all, all);
  // (0,0): test 0.25, reference 0 -> +0.25 (test too bright). (0,1): test 0.5, reference 1 -> -0.5.
  EXPECT_EQ(comparison.error.at(0, 0), 0.25f);
  EXPECT_EQ(comparison.error.at(0, 1), -0.5f);
  EXPECT_EQ(comparison.error.at(2, 2), -1.0f); // row 2 is the top row
  EXPECT_EQ(comparison.error.at(3, 0), 0.03125f);
}

TEST(ErrorMetrics, RejectsBadInputsNamingThem)
{
  const ImageF reference = handBuiltReference();
  const ImageF all = filled(4, 3, 1.0f);
  const ImageF none;
  const ComparisonInputNames names{ "t.vti", "r.vti", "visibility" };

  ImageF withNan = handBuiltTest();
  withNan.at(2, 1) = std::numeric_limits<float>::quiet_NaN();
  std::string message =
    inputErrorMessage([&] { computeErrorMetrics(withNan, reference, all, all, names); });
  EXPECT_TRUE(contains(message, "t.vti") && contains(message, "'visibility'") && contains(message, "(2, 1)"))
    << message;

  ImageF withInf = reference;
  withInf.at(3, 2) = -std::numeric_limits<float>::infinity();
  message = inputErrorMessage([&] { computeErrorMetrics(handBuiltTest(), withInf, all, all, names); });
  EXPECT_TRUE(contains(message, "r.vti") && contains(message, "(3, 2)")) << message;

  ImageF coverageWithNan = all;
  coverageWithNan.at(0, 0) = std::numeric_limits<float>::quiet_NaN();
  message = inputErrorMessage([&] { computeErrorMetrics(handBuiltTest(), reference, none, coverageWithNan, names); });
  EXPECT_TRUE(contains(message, "r.vti") && contains(message, "'coverage'") && contains(message, "(0, 0)"))
    << message;

  message = inputErrorMessage([&] { computeErrorMetrics(filled(3, 3, 0.0f), reference, none, none, names); });
  EXPECT_TRUE(contains(message, "r.vti: 4x3, but t.vti is 3x3")) << message;

  message = inputErrorMessage([&] { computeErrorMetrics(handBuiltTest(), reference, filled(4, 2, 1.0f), all, names); });
  EXPECT_TRUE(contains(message, "t.vti") && contains(message, "4x2")) << message;

  message = inputErrorMessage([&] { computeErrorMetrics(ImageF(4, 3, 3), reference, none, none, names); });
  EXPECT_TRUE(contains(message, "t.vti") && contains(message, "3 components")) << message;
}

// ---- files -----------------------------------------------------------------------------------------------

class CompareFiles : public ::testing::Test
{
protected:
  void SetUp() override
  {
    directory_ = fs::temp_directory_path() /
      format("shadowlab_metrics_test_", ::getpid(), "_",
        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(directory_);
    fs::create_directories(directory_);
  }
  void TearDown() override { fs::remove_all(directory_); }

  fs::path write(const std::string& name, const std::vector<NamedImage>& arrays) const
  {
    const fs::path path = directory_ / name;
    writeVti(path, arrays);
    return path;
  }

  // a.vti: the hand-built test with a coverage hole at (1,0) and an extra 3-component array;
  // b.vti: the hand-built reference with a coverage hole at (2,2).
  void writeHandBuiltPair()
  {
    testCoverage_ = filled(4, 3, 1.0f);
    testCoverage_.at(1, 0) = 0.0f;
    referenceCoverage_ = filled(4, 3, 1.0f);
    referenceCoverage_.at(2, 2) = 0.0f;
    testFile_ = write("a.vti",
      { { "visibility", handBuiltTest() }, { "position", ImageF(4, 3, 3, 2.0f) }, { "coverage", testCoverage_ } });
    referenceFile_ = write("b.vti", { { "visibility", handBuiltReference() }, { "coverage", referenceCoverage_ } });
  }

  fs::path directory_;
  fs::path testFile_, referenceFile_;
  ImageF testCoverage_, referenceCoverage_;
};

TEST_F(CompareFiles, SameNumbersAsInMemory)
{
  writeHandBuiltPair();
  const Comparison fromFiles = compareVtiFiles(testFile_, referenceFile_);
  const ErrorMetrics inMemory =
    computeErrorMetrics(handBuiltTest(), handBuiltReference(), testCoverage_, referenceCoverage_);
  expectStatisticsEqual(fromFiles.metrics.covered, inMemory.covered, "covered");
  expectStatisticsEqual(fromFiles.metrics.penumbra, inMemory.penumbra, "penumbra");
  // The holes at (1,0) (e -0.125) and (2,2) (e -1) are out: 10 pixels, max |e| 0.5.
  EXPECT_EQ(fromFiles.metrics.covered.pixels, 10u);
  EXPECT_DOUBLE_EQ(fromFiles.metrics.covered.maxAbsError, 0.5);
  EXPECT_EQ(fromFiles.metrics.array, "visibility");
  EXPECT_EQ(fromFiles.error.at(0, 1), -0.5f);
  EXPECT_EQ(fromFiles.mask.at(1, 0), 0.0f);
  EXPECT_EQ(fromFiles.mask.at(2, 2), 0.0f);
}

TEST_F(CompareFiles, CoverageMissingInAFileUsesTheOther)
{
  writeHandBuiltPair();
  const fs::path bare = write("bare.vti", { { "visibility", handBuiltTest() } });
  // Only the reference's hole at (2,2) (e = -1) is out: 11 pixels.
  EXPECT_EQ(compareVtiFiles(bare, referenceFile_).metrics.covered.pixels, 11u);
  const fs::path bareReference = write("bare_reference.vti", { { "visibility", handBuiltReference() } });
  EXPECT_EQ(compareVtiFiles(bare, bareReference).metrics.covered.pixels, 12u);
  EXPECT_DOUBLE_EQ(compareVtiFiles(bare, bareReference).metrics.covered.rmse, std::sqrt(1.337158203125 / 12.0));
}

TEST_F(CompareFiles, OtherArrayByName)
{
  const fs::path a = write("a.vti", { { "depth", filled(2, 2, 0.75f) }, { "visibility", filled(2, 2, 0.0f) } });
  const fs::path b = write("b.vti", { { "depth", filled(2, 2, 0.5f) }, { "visibility", filled(2, 2, 0.0f) } });
  const Comparison comparison = compareVtiFiles(a, b, "depth");
  EXPECT_EQ(comparison.metrics.array, "depth");
  EXPECT_DOUBLE_EQ(comparison.metrics.covered.mae, 0.25);
  EXPECT_EQ(compareVtiFiles(a, b).metrics.covered.mae, 0.0);
}

TEST_F(CompareFiles, ErrorsNameTheFileAndTheArrayOrSize)
{
  const fs::path big = write("big.vti", { { "visibility", filled(128, 96, 1.0f) } });
  const fs::path small = write("small.vti", { { "visibility", filled(64, 64, 1.0f) } });
  std::string message = inputErrorMessage([&] { compareVtiFiles(big, small); });
  EXPECT_TRUE(contains(message, small.string() + ": 64x64, but " + big.string() + " is 128x96")) << message;

  const fs::path noVisibility =
    write("novis.vti", { { "position", ImageF(64, 64, 3) }, { "normal", ImageF(64, 64, 3) } });
  message = inputErrorMessage([&] { compareVtiFiles(noVisibility, small); });
  EXPECT_TRUE(contains(message, noVisibility.string() + ": no array 'visibility' (arrays: position, normal)"))
    << message;
  message = inputErrorMessage([&] { compareVtiFiles(small, noVisibility); });
  EXPECT_TRUE(contains(message, noVisibility.string()) && contains(message, "'visibility'")) << message;
  message = inputErrorMessage([&] { compareVtiFiles(small, small, "shadow"); });
  EXPECT_TRUE(contains(message, small.string() + ": no array 'shadow' (arrays: visibility)")) << message;

  const fs::path missing = directory_ / "missing.vti";
  message = inputErrorMessage([&] { compareVtiFiles(small, missing); });
  EXPECT_TRUE(contains(message, missing.string())) << message;
  message = inputErrorMessage([&] { compareVtiFiles(missing, small); });
  EXPECT_TRUE(contains(message, missing.string())) << message;

  ImageF withNan = filled(64, 64, 1.0f);
  withNan.at(5, 7) = std::numeric_limits<float>::quiet_NaN();
  const fs::path nanFile = write("nan.vti", { { "visibility", withNan } });
  message = inputErrorMessage([&] { compareVtiFiles(nanFile, small); });
  EXPECT_TRUE(contains(message, nanFile.string()) && contains(message, "'visibility'") &&
    contains(message, "(5, 7)"))
    << message;
}

TEST_F(CompareFiles, WriteComparisonWritesVtiPngAndJson)
{
  writeHandBuiltPair();
  const Comparison comparison = compareVtiFiles(testFile_, referenceFile_);
  const fs::path outDir = directory_ / "out";
  writeComparison(comparison, testFile_, referenceFile_, { outDir, "compare", false, { testFile_, referenceFile_ } });

  const std::vector<NamedImage> arrays = readVti(outDir / "error.vti");
  std::vector<std::string> names;
  for (const NamedImage& named : arrays)
  {
    names.push_back(named.name);
  }
  EXPECT_EQ(names, (std::vector<std::string>{ "error", "abs_error", "reference", "test", "compared" }));
  ASSERT_EQ(arrays.size(), 5u);
  const ImageF& error = arrays[0].image;
  ASSERT_EQ(error.width, 4);
  ASSERT_EQ(error.height, 3);
  EXPECT_EQ(error.at(0, 0), 0.25f);
  EXPECT_EQ(error.at(0, 1), -0.5f);
  EXPECT_EQ(error.at(1, 0), 0.0f); // not compared (test coverage hole)
  EXPECT_EQ(error.at(2, 2), 0.0f); // not compared (reference coverage hole)
  EXPECT_EQ(arrays[1].image.at(0, 1), 0.5f);
  EXPECT_EQ(arrays[2].image.at(2, 1), 0.75f);
  EXPECT_EQ(arrays[3].image.at(2, 1), 0.6875f);
  EXPECT_EQ(arrays[4].image.at(1, 0), 0.0f);
  EXPECT_EQ(arrays[4].image.at(0, 0), 1.0f);

  const ImageU8 png = readPng(outDir / "error.png");
  EXPECT_GT(png.width, error.width); // the colour key sits right of the values
  EXPECT_GE(png.height, error.height);

  std::ifstream jsonFile(outDir / "metrics.json");
  const nlohmann::json json = nlohmann::json::parse(jsonFile);
  EXPECT_EQ(json["array"], "visibility");
  EXPECT_EQ(json["test"], testFile_.string());
  EXPECT_EQ(json["reference"], referenceFile_.string());
  for (const auto& [key, statistics] :
    { std::pair{ "covered", comparison.metrics.covered }, std::pair{ "penumbra", comparison.metrics.penumbra } })
  {
    const nlohmann::json& entry = json[key];
    EXPECT_EQ(entry["pixels"].get<std::size_t>(), statistics.pixels) << key;
    EXPECT_DOUBLE_EQ(entry["rmse"].get<double>(), statistics.rmse) << key;
    EXPECT_DOUBLE_EQ(entry["mae"].get<double>(), statistics.mae) << key;
    EXPECT_DOUBLE_EQ(entry["max_abs_error"].get<double>(), statistics.maxAbsError) << key;
    EXPECT_DOUBLE_EQ(entry["fraction_above_0.05"].get<double>(), statistics.fractionAbove005) << key;
  }
  EXPECT_EQ(json["covered"]["pixels"], 10);
}

TEST_F(CompareFiles, UnwritableOutputThrowsAndLeavesNothing)
{
  writeHandBuiltPair();
  const Comparison comparison = compareVtiFiles(testFile_, referenceFile_);
  // A regular file where the output's parent directory would be: fails for root too (chmod would not).
  const fs::path blocker = directory_ / "blocker";
  std::ofstream(blocker) << "not a directory\n";
  const fs::path outDir = blocker / "out";
  const std::string message = inputErrorMessage(
    [&] { writeComparison(comparison, testFile_, referenceFile_, { outDir, "compare", false, {} }); });
  EXPECT_TRUE(contains(message, outDir.string())) << message;
  std::vector<std::string> left;
  for (const fs::directory_entry& entry : fs::directory_iterator(directory_))
  {
    left.push_back(entry.path().filename().string());
  }
  std::sort(left.begin(), left.end());
  EXPECT_EQ(left, (std::vector<std::string>{ "a.vti", "b.vti", "blocker" }));
}

} // namespace
} // namespace sl
