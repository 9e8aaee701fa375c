// An image against its regression baseline, within a tolerance: what the regression suite
// (tests/render/RegressionTest.cpp) applies to each case's shaded image and visibility. The tolerances are data,
// next to the baselines (tests/baselines/tolerance.json).
#pragma once

#include "core/Image.h"

#include <cstddef>
#include <string>

namespace sl
{

struct RegressionTolerance
{
  double maxAbsDiff = 0.0;         // per pixel, over its components (image: 0..255 units; visibility: 0..1)
  double maxFailingFraction = 0.0; // fraction of the pixels allowed to differ by more than maxAbsDiff
};

struct RegressionComparison
{
  bool sameSize = true; // width, height and components; false: nothing else was compared
  double maxAbsDiff = 0.0;
  std::size_t failingPixels = 0;
  std::size_t pixels = 0;

  double failingFraction() const
  {
    return pixels ? static_cast<double>(failingPixels) / static_cast<double>(pixels) : 0.0;
  }
  bool passes(const RegressionTolerance& tolerance) const
  {
    return sameSize && failingFraction() <= tolerance.maxFailingFraction;
  }
};

// Per pixel: the largest absolute difference over the components. A pixel fails when that exceeds
// tolerance.maxAbsDiff; a non-finite value on either side always fails (and counts as an infinite difference).
// `perPixelDiff`, when given and the sizes agree, receives that difference per pixel (1 component, infinite
// clamped to 1e30).
RegressionComparison compareWithTolerance(const ImageU8& actual, const ImageU8& expected,
  const RegressionTolerance& tolerance, ImageF* perPixelDiff = nullptr);
RegressionComparison compareWithTolerance(const ImageF& actual, const ImageF& expected,
  const RegressionTolerance& tolerance, ImageF* perPixelDiff = nullptr);

// "<what>: max abs diff D (tolerance T), F/N pixels over it = fraction f (allowed a)", or that the size differs.
std::string describeComparison(const char* what, const RegressionComparison& comparison,
  const RegressionTolerance& tolerance);

// |actual - expected| per channel, times 8 (a difference of 32/255 or more is white); same size as the inputs.
ImageU8 amplifiedDifference(const ImageU8& actual, const ImageU8& expected);

} // namespace sl
