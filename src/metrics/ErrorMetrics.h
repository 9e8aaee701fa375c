// Per-pixel error of a real-time technique against the ray-traced reference, in memory (no files; see
// Comparison.h for `shadowlab compare`).
//
// Conventions:
//  - error = test - reference, per pixel (positive: the technique is too bright / lets too much light through).
//  - A pixel is compared when it is covered in BOTH images: coverage > 0.5. An empty coverage image (0x0) means
//    "not given": the other image's coverage decides; neither given: every pixel is compared.
//  - Penumbra pixels: compared pixels whose reference is strictly inside (0, 1).
//  - Statistics over an empty set are pixels = 0 and all zeros (never NaN).
#pragma once

#include "core/Image.h"

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>

namespace sl
{

// |error| above this counts in ErrorStatistics::fractionAbove005 (5% of the light: a visible step).
inline constexpr double kVisibleErrorThreshold = 0.05;

struct ErrorStatistics
{
  std::size_t pixels = 0;        // pixels the statistics run over
  double rmse = 0.0;             // sqrt(mean(error^2))
  double mae = 0.0;              // mean(|error|)
  double maxAbsError = 0.0;      // max(|error|)
  double fractionAbove005 = 0.0; // fraction of the pixels with |error| > kVisibleErrorThreshold
};

struct ErrorMetrics
{
  ErrorStatistics covered;  // over the pixels covered in both images
  ErrorStatistics penumbra; // the same restricted to penumbra pixels: 0 < reference < 1 (strictly)
  std::string array = "visibility";
};

// The metrics plus the images behind them (the outputs of `shadowlab compare`).
struct Comparison
{
  ErrorMetrics metrics;
  ImageF error; // test - reference where compared, 0 elsewhere; 1 component
  ImageF mask;  // 1 where compared, 0 elsewhere; 1 component
  ImageF test;      // the inputs as compared (error.vti shows them next to the error)
  ImageF reference;
};

// Where the inputs came from, for error messages: "<test>: ...", "<reference>: ... array '<array>' ...".
struct ComparisonInputNames
{
  std::string test = "test";
  std::string reference = "reference";
  std::string array = "visibility"; // also goes to ErrorMetrics::array
};

// Throws InputError when an image is not 1 component, the sizes differ (values or a given coverage), or a value
// is NaN/inf (any pixel, covered or not), naming the input, the array and the first such pixel (x, y).
Comparison compareImages(const ImageF& test, const ImageF& reference, const ImageF& testCoverage,
  const ImageF& referenceCoverage, const ComparisonInputNames& names = {});

// compareImages(...).metrics.
ErrorMetrics computeErrorMetrics(const ImageF& test, const ImageF& reference, const ImageF& testCoverage,
  const ImageF& referenceCoverage, const ComparisonInputNames& names = {});

// {"array", "covered": {...}, "penumbra": {...}}, each with pixels, rmse, mae, max_abs_error, fraction_above_0.05.
nlohmann::json metricsJson(const ErrorMetrics& metrics);

} // namespace sl
