// Named light-sample sets (LightSampleSet.h; Forest et al. 2009 §4.1). Every coordinate is a 16-bit fixed-point
// number (k 2^-16, k in 0..65535), so what the CPU computes in double the GPU computes in float without rounding,
// and the GLSL twin, shaders/common/LightSampleSet.glsl, mirrors the integer steps below one for one.
#include "lightspace/LightSampleSet.h"

#include "core/Error.h"
#include "lightspace/LightSamples.h"

#include <algorithm>
#include <cmath>

namespace sl
{
namespace
{

constexpr double kFixedPointUnit = 1.0 / 65536.0; // 2^-16: the grain of every coordinate and shift

// Chris Wellons' "lowbias32" integer hash (a bijection of 32-bit words, bias ~0.17 of a random permutation's):
// uint arithmetic only, so GLSL's `uint` (which wraps modulo 2^32 like std::uint32_t) repeats it bit for bit.
std::uint32_t hash32(std::uint32_t value)
{
  value ^= value >> 16;
  value *= 0x7FEB352Du;
  value ^= value >> 15;
  value *= 0x846CA68Bu;
  value ^= value >> 16;
  return value;
}

// Two 16-bit fixed-point coordinates from one 32-bit word: (high half, low half).
glm::uvec2 fixedPointPair(std::uint32_t bits)
{
  return glm::uvec2(bits >> 16, bits & 0xFFFFu);
}

glm::dvec2 toUnit(const glm::uvec2& fixedPoint)
{
  return glm::dvec2(fixedPoint) * kFixedPointUnit;
}

// splitmix64 (Steele, Lea & Flood 2014): the construction's random bits, one stream per (pattern, seed), the same
// on every platform (std's distributions are not).
class BitStream
{
public:
  BitStream(std::uint32_t seed, std::uint64_t salt)
    : state_((static_cast<std::uint64_t>(seed) << 32) ^ salt)
  {
  }
  std::uint64_t next()
  {
    state_ += 0x9E3779B97F4A7C15ull;
    return mix64(state_);
  }

private:
  std::uint64_t state_;
};

int gridSide(int count)
{
  const int side = static_cast<int>(std::lround(std::sqrt(static_cast<double>(count))));
  SL_CHECK(side * side == count);
  return side;
}

// The sqrt(N) x sqrt(N) cell centres, row by row from (0, 0): (2 i + 1) / (2 sqrt N), a multiple of 2^-16 since
// 2 sqrt(N) <= 32.
std::vector<glm::dvec2> gridPoints(int count)
{
  const int side = gridSide(count);
  std::vector<glm::dvec2> points;
  for (int j = 0; j < side; ++j)
  {
    for (int i = 0; i < side; ++i)
    {
      points.emplace_back((i + 0.5) / side, (j + 0.5) / side);
    }
  }
  return points;
}

// One point per cell of the same grid, uniform on the cell's 2^-16 lattice (Forest et al. 2009 Fig. 5 b).
std::vector<glm::dvec2> stratifiedPoints(int count, std::uint32_t seed)
{
  const int side = gridSide(count);
  const std::uint32_t cellUnits = 65536u / static_cast<std::uint32_t>(side); // 2^-16 steps per cell side
  BitStream bits(seed, 0x5354524154494649ull); // "STRATIFI"
  std::vector<glm::dvec2> points;
  for (int j = 0; j < side; ++j)
  {
    for (int i = 0; i < side; ++i)
    {
      const glm::uvec2 jitter = fixedPointPair(static_cast<std::uint32_t>(bits.next() >> 32)) % cellUnits;
      points.push_back(toUnit(glm::uvec2(i, j) * cellUnits + jitter));
    }
  }
  return points;
}

// Dart throwing (Cook 1986, Forest et al. 2009's [Coo86]) on the 2^-16 lattice of the unit square: a candidate is kept when it is
// at least the minimum distance from every point kept so far; after kMaxMisses candidates in a row are rejected
// the set is jammed and starts again from empty (the stream goes on, so the restart draws other darts). At the
// paper's distances this finishes in a few restarts (N = 16: a mean of ~3, N = 64 and 256: < 1; each well under a
// few milliseconds, LightSampleSetTest measures). N <= 256, so testing every kept point is cheaper than a grid.
std::vector<glm::dvec2> poissonPoints(int count, std::uint32_t seed)
{
  constexpr int kMaxMisses = 5000;
  constexpr int kMaxRestarts = 100000; // never reached at the paper's densities (an invariant, not an input error)
  const double minDistance = lightSamplePoissonDistance(count);
  const double minDistanceSquared = minDistance * minDistance;
  BitStream bits(seed, 0x504F4953534F4E44ull); // "POISSOND"
  std::vector<glm::dvec2> points;
  points.reserve(static_cast<std::size_t>(count));
  for (int restart = 0; restart < kMaxRestarts; ++restart)
  {
    points.clear();
    int misses = 0;
    while (static_cast<int>(points.size()) < count && misses < kMaxMisses)
    {
      const glm::dvec2 candidate = toUnit(fixedPointPair(static_cast<std::uint32_t>(bits.next() >> 32)));
      bool farEnough = true;
      for (const glm::dvec2& point : points)
      {
        const glm::dvec2 difference = candidate - point;
        if (glm::dot(difference, difference) < minDistanceSquared)
        {
          farEnough = false;
          break;
        }
      }
      if (farEnough)
      {
        points.push_back(candidate);
        misses = 0;
      }
      else
      {
        ++misses;
      }
    }
    if (static_cast<int>(points.size()) == count)
    {
      return points;
    }
  }
  SL_CHECK_MSG(false, "no Poisson-disk set of ", count, " points at distance ", minDistance, " for seed ", seed);
  return points;
}

// Bits reversed: the radical inverse in base 2 (van der Corput) as a 32-bit fraction.
std::uint32_t reverseBits(std::uint32_t value)
{
  value = (value << 16) | (value >> 16);
  value = ((value & 0x00FF00FFu) << 8) | ((value & 0xFF00FF00u) >> 8);
  value = ((value & 0x0F0F0F0Fu) << 4) | ((value & 0xF0F0F0F0u) >> 4);
  value = ((value & 0x33333333u) << 2) | ((value & 0xCCCCCCCCu) >> 2);
  value = ((value & 0x55555555u) << 1) | ((value & 0xAAAAAAAAu) >> 1);
  return value;
}

// Sobol's second dimension as a 32-bit fraction: primitive polynomial x + 1, m_1 = 1, so the direction numbers
// are V_1 = 2^31 and V_k = V_{k-1} ^ (V_{k-1} >> 1) (Bratley & Fox 1988), XOR-ed for the set bits of `index`.
std::uint32_t sobolSecondDimension(std::uint32_t index)
{
  std::uint32_t result = 0;
  for (std::uint32_t direction = 1u << 31; index != 0; index >>= 1, direction ^= direction >> 1)
  {
    if (index & 1u)
    {
      result ^= direction;
    }
  }
  return result;
}

// The first N points of the Sobol (0,2)-sequence (Forest et al. 2009 §4.1): van der Corput base 2 and Sobol's second
// dimension. For N = 2^m they are a (0, m, 2)-net; cutting them to 16 bits keeps that (an elementary interval of
// area 2^-m, m <= 8, is decided by the top 8 bits of each coordinate).
std::vector<glm::dvec2> zeroTwoPoints(int count)
{
  std::vector<glm::dvec2> points;
  for (std::uint32_t index = 0; index < static_cast<std::uint32_t>(count); ++index)
  {
    points.push_back(toUnit(glm::uvec2(reverseBits(index) >> 16, sobolSecondDimension(index) >> 16)));
  }
  return points;
}

const char* const kPatternNames[] = { "grid", "stratified", "poisson", "zero_two" };

} // namespace

const std::vector<int>& lightSampleCounts()
{
  static const std::vector<int> counts = { 16, 64, 256 };
  return counts;
}

const std::vector<std::string>& lightSamplePatternNames()
{
  static const std::vector<std::string> names = [] {
    std::vector<std::string> all;
    for (const char* name : kPatternNames)
    {
      all.emplace_back(name);
    }
    for (const char* name : kPatternNames)
    {
      all.push_back(std::string(name) + "_4x4");
    }
    return all;
  }();
  return names;
}

LightSampleSetSettings lightSampleSetSettings(const std::string& patternName, int count, std::uint32_t seed)
{
  const std::vector<std::string>& names = lightSamplePatternNames();
  std::size_t index = 0;
  while (index < names.size() && names[index] != patternName)
  {
    ++index;
  }
  if (index == names.size())
  {
    std::string valid;
    for (const std::string& name : names)
    {
      valid += (valid.empty() ? "" : ", ") + name;
    }
    throw InputError(format("--light-samples ", printable(patternName), ": unknown light-sample pattern (", valid, ")"));
  }
  const std::vector<int>& counts = lightSampleCounts();
  if (std::find(counts.begin(), counts.end(), count) == counts.end())
  {
    throw InputError(format("--samples ", count, ": must be 16, 64 or 256 with --light-samples"));
  }
  LightSampleSetSettings settings;
  settings.pattern = static_cast<LightSamplePattern>(index % 4);
  settings.interleaved = index >= 4;
  settings.count = count;
  settings.seed = seed;
  return settings;
}

std::string lightSamplePatternName(const LightSampleSetSettings& settings)
{
  return lightSamplePatternNames().at(static_cast<std::size_t>(settings.pattern) + (settings.interleaved ? 4 : 0));
}

// Forest et al. 2009 fixes the distance "experimentally" for 16 and 64 samples (§4.1) without saying in which domain. It is
// the plain unit square: N disks of diameter d around points of the square lie in the square grown by d / 2, so
// the packing density is eta = N pi d^2 / 4 / (1 + d)^2, 0.4886 for (16, 0.2456139) and 0.4749 for
// (64, 0.1076681), both below the jamming density of random sequential addition (~0.547), where dart throwing
// still finishes. On the torus the density would be N pi d^2 / 4 = 0.758 (N = 16), far above that limit: dart
// throwing jams every time (measured: 0 of 20 seeds after 2000 restarts), and 0.2456 is within 2 % of the 4 x 4
// grid's toroidal distance 1/4. For N = 256 the distance with N = 64's density eta: sqrt(N pi / 4) d =
// sqrt(eta) (1 + d), d = sqrt(eta) / (sqrt(N pi / 4) - sqrt(eta)) = 0.0510840.
double lightSamplePoissonDistance(int count)
{
  switch (count)
  {
    case 16: return 0.2456139;
    case 64: return 0.1076681;
    case 256:
    {
      const double pi = 3.14159265358979323846;
      const double d64 = 0.1076681;
      const double density64 = 64.0 * pi * d64 * d64 / 4.0 / ((1.0 + d64) * (1.0 + d64));
      return std::sqrt(density64) / (std::sqrt(256.0 * pi / 4.0) - std::sqrt(density64));
    }
    default: break;
  }
  SL_CHECK_MSG(false, "no Poisson-disk distance for ", count, " light samples");
  return 0.0;
}

LightSampleSet::LightSampleSet(const LightSampleSetSettings& settings)
  : settings_(settings)
{
  const std::vector<int>& counts = lightSampleCounts();
  SL_CHECK_MSG(std::find(counts.begin(), counts.end(), settings.count) != counts.end(), "light-sample count ",
    settings.count, " is not 16, 64 or 256");
  switch (settings.pattern)
  {
    case LightSamplePattern::Grid: basePoints_ = gridPoints(settings.count); break;
    case LightSamplePattern::Stratified: basePoints_ = stratifiedPoints(settings.count, settings.seed); break;
    case LightSamplePattern::Poisson: basePoints_ = poissonPoints(settings.count, settings.seed); break;
    case LightSamplePattern::ZeroTwo: basePoints_ = zeroTwoPoints(settings.count); break;
  }
}

glm::dvec2 LightSampleSet::pixelShift(int x, int y) const
{
  const std::uint32_t seed = settings_.seed;
  if (!settings_.interleaved)
  {
    const std::uint32_t h0 = hash32(seed + 0x9E3779B9u);
    return toUnit(fixedPointPair(hash32(hash32(h0 ^ static_cast<std::uint32_t>(x)) + static_cast<std::uint32_t>(y))));
  }
  // fract(frameShift + ((x mod 4 + 1/2) / 4, (y mod 4 + 1/2) / 4) / sqrt N) in 2^-16 units: (2 a + 1) 2^16 /
  // (8 sqrt N) = (2 a + 1) (8192 / sqrt N), an integer for sqrt N in {4, 8, 16}; the sum wraps mod 2^16.
  const glm::uvec2 frameShift = fixedPointPair(hash32(seed + 0x6A09E667u));
  const std::uint32_t halfStep = 8192u / static_cast<std::uint32_t>(gridSide(settings_.count));
  const glm::uvec2 tile(static_cast<std::uint32_t>(x) & 3u, static_cast<std::uint32_t>(y) & 3u);
  return toUnit((frameShift + (2u * tile + 1u) * halfStep) & 0xFFFFu);
}

glm::dvec2 LightSampleSet::unitSample(int x, int y, int index) const
{
  SL_CHECK(index >= 0 && index < count());
  // Both terms are multiples of 2^-16 below 1: the sum and fract are exact.
  return glm::fract(basePoints_[static_cast<std::size_t>(index)] + pixelShift(x, y));
}

glm::dvec3 LightSampleSet::point(const Light& light, int x, int y, int index) const
{
  const glm::dvec2 offset = lightPlaneOffset(light, unitSample(x, y, index));
  return light.type == LightType::Area ? light.center + offset.x * light.right() + offset.y * light.up : light.center;
}

glm::dvec2 lightPlaneOffset(const Light& light, const glm::dvec2& unitSquare)
{
  if (light.type != LightType::Area)
  {
    return glm::dvec2(0.0);
  }
  // The same products, in the same order, as pointOnAreaLight.
  if (light.shape == LightShape::Disk)
  {
    return (0.5 * light.size) * concentricDiskMap(unitSquare);
  }
  return glm::dvec2((unitSquare.x - 0.5) * light.size, (unitSquare.y - 0.5) * light.size);
}

} // namespace sl
