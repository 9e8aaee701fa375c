#include "reference/LightSampler.h"

#include "core/Error.h"

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>

namespace sl
{
namespace
{

// Hash streams: the last tuple element tells apart the different random numbers a pixel needs. Sample
// indices are < 2^31, so these never collide with one.
constexpr std::uint64_t kStreamPermutation = 0xffffffff00000001ull;
constexpr std::uint64_t kStreamRotation = 0xffffffff00000002ull;
constexpr std::uint64_t kJitterX = 0x6a09e667f3bcc909ull; // second and third hash of a sample
constexpr std::uint64_t kJitterY = 0xbb67ae8584caa73bull;

// Top 53 bits as a double in [0, 1).
double toUnit(std::uint64_t bits)
{
  return static_cast<double>(bits >> 11) * 0x1.0p-53;
}

double wrapUnit(double value)
{
  const double wrapped = value - std::floor(value);
  return wrapped < 1.0 ? wrapped : 0.0; // guards value = -tiny, where 1 - tiny rounds to 1
}

} // namespace

std::uint64_t hashTuple(std::uint64_t seed, std::uint64_t a, std::uint64_t b, std::uint64_t c)
{
  constexpr std::uint64_t kGolden = 0x9e3779b97f4a7c15ull;
  std::uint64_t h = mix64(seed + kGolden);
  h = mix64(h ^ (a + 2 * kGolden));
  h = mix64(h ^ (b + 3 * kGolden));
  return mix64(h ^ (c + 4 * kGolden));
}

std::uint32_t permuteIndex(std::uint32_t index, std::uint32_t length, std::uint32_t pattern)
{
  // Kensler 2013, Listing "permute": cycle-walking over a hash that is a bijection on the next power of two.
  SL_DCHECK(length > 0 && index < length);
  std::uint32_t mask = length - 1;
  mask |= mask >> 1;
  mask |= mask >> 2;
  mask |= mask >> 4;
  mask |= mask >> 8;
  mask |= mask >> 16;
  std::uint32_t i = index;
  const std::uint32_t p = pattern;
  do
  {
    i ^= p;
    i *= 0xe170893du;
    i ^= p >> 16;
    i ^= (i & mask) >> 4;
    i ^= p >> 8;
    i *= 0x0929eb3fu;
    i ^= p >> 23;
    i ^= (i & mask) >> 1;
    i *= 1u | p >> 27;
    i *= 0x6935fa69u;
    i ^= (i & mask) >> 11;
    i *= 0x74dcb303u;
    i ^= (i & mask) >> 2;
    i *= 0x9e501cc3u;
    i ^= (i & mask) >> 2;
    i *= 0xc860a3dfu;
    i &= mask;
    i ^= i >> 5;
  } while (i >= length);
  return (i + p) % length;
}

LightSampler::LightSampler(const Light& light, int sampleCount, LightSampling sampling, std::uint64_t seed)
  : light_(light)
  , sampleCount_(sampleCount)
  , sampling_(sampling)
  , seed_(seed)
{
  SL_CHECK(light.type == LightType::Area);
  SL_CHECK(sampleCount >= 1);
  columns_ = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(sampleCount))));
  while ((columns_ - 1) * (columns_ - 1) >= sampleCount) // guard sqrt rounding up past an exact root
  {
    --columns_;
  }
  rows_ = (sampleCount + columns_ - 1) / columns_;
}

glm::dvec2 LightSampler::unitSample(int x, int y, int index) const
{
  SL_DCHECK(index >= 0 && index < sampleCount_);
  const auto px = static_cast<std::uint64_t>(static_cast<std::uint32_t>(x));
  const auto py = static_cast<std::uint64_t>(static_cast<std::uint32_t>(y));
  if (sampling_ == LightSampling::Halton)
  {
    const std::uint64_t rotation = hashTuple(seed_, px, py, kStreamRotation);
    const glm::dvec2 shift(toUnit(rotation), toUnit(mix64(rotation ^ kJitterY)));
    const glm::dvec2 halton(radicalInverse(2, static_cast<std::uint64_t>(index)),
      radicalInverse(3, static_cast<std::uint64_t>(index)));
    return glm::dvec2(wrapUnit(halton.x + shift.x), wrapUnit(halton.y + shift.y));
  }
  const auto strata = static_cast<std::uint32_t>(columns_ * rows_);
  std::uint32_t stratum = static_cast<std::uint32_t>(index);
  if (strata != static_cast<std::uint32_t>(sampleCount_))
  {
    const auto pattern = static_cast<std::uint32_t>(hashTuple(seed_, px, py, kStreamPermutation));
    stratum = permuteIndex(stratum, strata, pattern);
  }
  const std::uint64_t h = hashTuple(seed_, px, py, static_cast<std::uint64_t>(index));
  const double jitterX = toUnit(mix64(h ^ kJitterX));
  const double jitterY = toUnit(mix64(h ^ kJitterY));
  const int column = static_cast<int>(stratum % static_cast<std::uint32_t>(columns_));
  const int row = static_cast<int>(stratum / static_cast<std::uint32_t>(columns_));
  // min(): (column + jitter) / columns can round up to 1 for the last column.
  return glm::dvec2(std::min((column + jitterX) / columns_, std::nextafter(1.0, 0.0)),
    std::min((row + jitterY) / rows_, std::nextafter(1.0, 0.0)));
}

glm::dvec3 LightSampler::lightPoint(const glm::dvec2& unit) const
{
  return pointOnAreaLight(light_, unit);
}

glm::dvec3 LightSampler::point(int x, int y, int index) const
{
  return lightPoint(unitSample(x, y, index));
}

} // namespace sl
