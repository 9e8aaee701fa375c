#include "techniques/SamplingPatterns.h"

#include <algorithm>
#include <cmath>
#include <random>

namespace sl
{

const std::vector<glm::dvec2>& poissonDisk()
{
  static const std::vector<glm::dvec2> disk = [] {
    // Mitchell's best-candidate sampling: each new point is the farthest of k candidates from the
    // points so far. std::mt19937's output sequence is fixed by the standard; the conversion to [0, 1)
    // is done here (not by a distribution, whose algorithm is implementation-defined).
    std::mt19937 generator(20091122u);
    const auto uniform = [&generator] { return static_cast<double>(generator() >> 8) * (1.0 / 16777216.0); };
    std::vector<glm::dvec2> points;
    while (static_cast<int>(points.size()) < maxPoissonSamples)
    {
      glm::dvec2 best(0.0);
      double bestDistance = -1.0;
      const int candidates = 10 * (static_cast<int>(points.size()) + 1);
      for (int c = 0; c < candidates; ++c)
      {
        const double radius = std::sqrt(uniform());
        const double angle = 6.283185307179586 * uniform();
        const glm::dvec2 candidate(radius * std::cos(angle), radius * std::sin(angle));
        double nearest = 1e300;
        for (const glm::dvec2& point : points)
        {
          nearest = std::min(nearest, glm::length(candidate - point));
        }
        if (nearest > bestDistance)
        {
          bestDistance = nearest;
          best = candidate;
        }
      }
      points.push_back(best);
    }
    return points;
  }();
  return disk;
}

const std::vector<float>& poissonDiskFloats()
{
  static const std::vector<float> floats = [] {
    std::vector<float> values;
    for (const glm::dvec2& point : poissonDisk())
    {
      values.push_back(static_cast<float>(point.x));
      values.push_back(static_cast<float>(point.y));
    }
    return values;
  }();
  return floats;
}

std::uint32_t pixelHash(std::uint32_t x, std::uint32_t y)
{
  std::uint32_t v = x * 1664525u + y * 1013904223u;
  v ^= v >> 16;
  v *= 0x7feb352du;
  v ^= v >> 15;
  v *= 0x846ca68bu;
  v ^= v >> 16;
  return v;
}

double pixelHashAngle(std::uint32_t x, std::uint32_t y)
{
  return static_cast<double>(pixelHash(x, y)) * (6.283185307179586 / 4294967296.0);
}

glm::dmat2 pixelRotation(int x, int y)
{
  const double angle = pixelHashAngle(static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y));
  return glm::dmat2(std::cos(angle), std::sin(angle), -std::sin(angle), std::cos(angle));
}

} // namespace sl
