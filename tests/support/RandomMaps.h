// Generated shadow maps for the light-space structure tests (unit and GPU), header-only so both suites share
// one definition.
#pragma once

#include "core/Image.h"

#include <algorithm>
#include <random>
#include <vector>

namespace sl::test
{

// A map of `size` x `size` with ties: depths from a few values, empty texels (2 x far = 20) among them, either
// independent per texel or as overlapping constant rectangles (occluder-like regions).
inline ImageF randomMapWithTies(int size, unsigned seed, bool blocks)
{
  const std::vector<float> values = { 1.0f, 1.5f, 2.0f, 3.0f, 20.0f };
  std::mt19937 generator(seed);
  std::uniform_int_distribution<std::size_t> pick(0, values.size() - 1);
  ImageF map(size, size, 1, 20.0f);
  if (!blocks)
  {
    for (float& depth : map.data)
    {
      depth = values[pick(generator)];
    }
    return map;
  }
  std::uniform_int_distribution<int> corner(0, size - 1);
  std::uniform_int_distribution<int> side(1, std::max(1, size / 6));
  for (int block = 0; block < 4 * size; ++block)
  {
    const int x0 = corner(generator);
    const int y0 = corner(generator);
    const int w = side(generator);
    const int h = side(generator);
    const float depth = values[pick(generator)];
    for (int y = y0; y < std::min(size, y0 + h); ++y)
    {
      for (int x = x0; x < std::min(size, x0 + w); ++x)
      {
        map.at(x, y) = depth;
      }
    }
  }
  return map;
}

} // namespace sl::test
