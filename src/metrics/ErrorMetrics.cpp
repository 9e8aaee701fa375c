#include "metrics/ErrorMetrics.h"

#include "core/Error.h"

#include <algorithm>
#include <cmath>

namespace sl
{
namespace
{

// Sums in double; the statistics come out of them in finish().
struct ErrorAccumulator
{
  std::size_t pixels = 0;
  std::size_t aboveThreshold = 0;
  double sumSquared = 0.0;
  double sumAbs = 0.0;
  double maxAbs = 0.0;

  void add(double error)
  {
    const double absError = std::abs(error);
    ++pixels;
    sumSquared += error * error;
    sumAbs += absError;
    maxAbs = std::max(maxAbs, absError);
    if (absError > kVisibleErrorThreshold)
    {
      ++aboveThreshold;
    }
  }

  ErrorStatistics finish() const
  {
    ErrorStatistics statistics;
    if (pixels == 0)
    {
      return statistics; // all zeros, not 0/0
    }
    const double count = static_cast<double>(pixels);
    statistics.pixels = pixels;
    statistics.rmse = std::sqrt(sumSquared / count);
    statistics.mae = sumAbs / count;
    statistics.maxAbsError = maxAbs;
    statistics.fractionAbove005 = static_cast<double>(aboveThreshold) / count;
    return statistics;
  }
};

std::string sizeText(const ImageF& image)
{
  return format(image.width, "x", image.height);
}

void checkScalar(const ImageF& image, const std::string& input, const std::string& array)
{
  if (image.components != 1)
  {
    throw InputError(format(input, ": array '", array, "' has ", image.components,
      " components; only 1-component arrays can be compared"));
  }
}

// First non-finite value in row order from the bottom row (row 0 = bottom, as in Image and the .vti).
void checkFinite(const ImageF& image, const std::string& input, const std::string& array)
{
  for (int y = 0; y < image.height; ++y)
  {
    for (int x = 0; x < image.width; ++x)
    {
      const float value = image.at(x, y);
      if (!std::isfinite(value))
      {
        throw InputError(format(input, ": array '", array, "' is ", value, " at pixel (", x, ", ", y,
          ") (row 0 = bottom); inputs must be finite"));
      }
    }
  }
}

void checkCoverage(const ImageF& coverage, const ImageF& values, const std::string& input,
  const std::string& array)
{
  if (coverage.empty())
  {
    return; // not given
  }
  checkScalar(coverage, input, "coverage");
  if (coverage.width != values.width || coverage.height != values.height)
  {
    throw InputError(format(input, ": array 'coverage' is ", sizeText(coverage), ", but '", array, "' is ",
      sizeText(values)));
  }
  checkFinite(coverage, input, "coverage");
}

bool covered(const ImageF& coverage, std::size_t pixel)
{
  return coverage.empty() || coverage.data[pixel] > 0.5f;
}

} // namespace

Comparison compareImages(const ImageF& test, const ImageF& reference, const ImageF& testCoverage,
  const ImageF& referenceCoverage, const ComparisonInputNames& names)
{
  checkScalar(test, names.test, names.array);
  checkScalar(reference, names.reference, names.array);
  if (test.width != reference.width || test.height != reference.height)
  {
    throw InputError(format(names.reference, ": ", sizeText(reference), ", but ", names.test, " is ",
      sizeText(test), " (array '", names.array, "')"));
  }
  checkFinite(test, names.test, names.array);
  checkFinite(reference, names.reference, names.array);
  checkCoverage(testCoverage, test, names.test, names.array);
  checkCoverage(referenceCoverage, reference, names.reference, names.array);

  Comparison comparison;
  comparison.metrics.array = names.array;
  comparison.error = ImageF(test.width, test.height, 1, 0.0f);
  comparison.mask = ImageF(test.width, test.height, 1, 0.0f);
  ErrorAccumulator coveredErrors;
  ErrorAccumulator penumbraErrors;
  for (std::size_t i = 0; i < test.pixelCount(); ++i)
  {
    if (!covered(testCoverage, i) || !covered(referenceCoverage, i))
    {
      continue;
    }
    const double referenceValue = reference.data[i];
    const double error = static_cast<double>(test.data[i]) - referenceValue;
    comparison.error.data[i] = static_cast<float>(error);
    comparison.mask.data[i] = 1.0f;
    coveredErrors.add(error);
    if (referenceValue > 0.0 && referenceValue < 1.0)
    {
      penumbraErrors.add(error);
    }
  }
  comparison.metrics.covered = coveredErrors.finish();
  comparison.metrics.penumbra = penumbraErrors.finish();
  comparison.test = test;
  comparison.reference = reference;
  return comparison;
}

ErrorMetrics computeErrorMetrics(const ImageF& test, const ImageF& reference, const ImageF& testCoverage,
  const ImageF& referenceCoverage, const ComparisonInputNames& names)
{
  return compareImages(test, reference, testCoverage, referenceCoverage, names).metrics;
}

nlohmann::json metricsJson(const ErrorMetrics& metrics)
{
  auto statisticsJson = [](const ErrorStatistics& statistics) {
    return nlohmann::json{ { "pixels", statistics.pixels }, { "rmse", statistics.rmse }, { "mae", statistics.mae },
      { "max_abs_error", statistics.maxAbsError }, { "fraction_above_0.05", statistics.fractionAbove005 } };
  };
  return { { "array", metrics.array }, { "covered", statisticsJson(metrics.covered) },
    { "penumbra", statisticsJson(metrics.penumbra) } };
}

} // namespace sl
