#include "metrics/RegressionComparison.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <sstream>

namespace sl
{
namespace
{

template <typename T>
RegressionComparison compareComponents(const Image<T>& actual, const Image<T>& expected,
  const RegressionTolerance& tolerance, ImageF* perPixelDiff)
{
  RegressionComparison result;
  if (actual.width != expected.width || actual.height != expected.height || actual.components != expected.components)
  {
    result.sameSize = false;
    return result;
  }
  result.pixels = actual.pixelCount();
  if (perPixelDiff)
  {
    *perPixelDiff = ImageF(actual.width, actual.height, 1);
  }
  for (std::size_t i = 0; i < result.pixels; ++i)
  {
    double pixelDiff = 0.0;
    for (int c = 0; c < actual.components; ++c)
    {
      const std::size_t k = i * static_cast<std::size_t>(actual.components) + static_cast<std::size_t>(c);
      const double a = static_cast<double>(actual.data[k]);
      const double e = static_cast<double>(expected.data[k]);
      const double diff = (std::isfinite(a) && std::isfinite(e)) ? std::abs(a - e) : HUGE_VAL;
      pixelDiff = std::max(pixelDiff, diff);
    }
    result.maxAbsDiff = std::max(result.maxAbsDiff, pixelDiff);
    if (pixelDiff > tolerance.maxAbsDiff)
    {
      ++result.failingPixels;
    }
    if (perPixelDiff)
    {
      perPixelDiff->data[i] = static_cast<float>(std::min(pixelDiff, 1e30));
    }
  }
  return result;
}

} // namespace

RegressionComparison compareWithTolerance(const ImageU8& actual, const ImageU8& expected,
  const RegressionTolerance& tolerance, ImageF* perPixelDiff)
{
  return compareComponents(actual, expected, tolerance, perPixelDiff);
}

RegressionComparison compareWithTolerance(const ImageF& actual, const ImageF& expected,
  const RegressionTolerance& tolerance, ImageF* perPixelDiff)
{
  return compareComponents(actual, expected, tolerance, perPixelDiff);
}

std::string describeComparison(const char* what, const RegressionComparison& comparison,
  const RegressionTolerance& tolerance)
{
  std::ostringstream text;
  text << what << ": ";
  if (!comparison.sameSize)
  {
    text << "size differs from the baseline";
    return text.str();
  }
  text << "max abs diff " << comparison.maxAbsDiff << " (tolerance " << tolerance.maxAbsDiff << "), "
       << comparison.failingPixels << "/" << comparison.pixels << " pixels over it = fraction "
       << comparison.failingFraction() << " (allowed " << tolerance.maxFailingFraction << ")";
  return text.str();
}

ImageU8 amplifiedDifference(const ImageU8& actual, const ImageU8& expected)
{
  ImageU8 diff(actual.width, actual.height, actual.components);
  for (std::size_t k = 0; k < diff.data.size(); ++k)
  {
    const int d = std::abs(static_cast<int>(actual.data[k]) - static_cast<int>(expected.data[k]));
    diff.data[k] = static_cast<std::uint8_t>(std::min(255, 8 * d));
  }
  return diff;
}

} // namespace sl
