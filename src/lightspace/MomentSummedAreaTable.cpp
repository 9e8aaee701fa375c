#include "lightspace/MomentSummedAreaTable.h"

#include <algorithm>
#include <cmath>

namespace sl
{

MomentSatFormat int32MomentSatFormat(int maxKernelTexels)
{
  MomentSatFormat format;
  format.wide = false;
  const double area = static_cast<double>(maxKernelTexels) * maxKernelTexels;
  format.bits = std::clamp(32 - static_cast<int>(std::ceil(std::log2(area))), 1, 32);
  return format;
}

std::array<std::uint32_t, 4> momentSatTexel(float depth, float nearDepth, float farDepth, int bits)
{
  const float scale = std::ldexp(1.0f, bits);
  const std::uint32_t largest = static_cast<std::uint32_t>((std::uint64_t{ 1 } << bits) - 1u);
  const float z = std::clamp((depth - nearDepth) / (farDepth - nearDepth), 0.0f, 1.0f);
  const float z2 = z * z;
  const std::array<float, 4> moments{ z, z2, z2 * z, z2 * z2 };
  std::array<std::uint32_t, 4> quantised{};
  for (int k = 0; k < 4; ++k)
  {
    // m 2^bits is exact in float; below 2^bits <= 2^32 it converts without overflow.
    const float scaled = moments[static_cast<std::size_t>(k)] * scale;
    quantised[static_cast<std::size_t>(k)] =
      moments[static_cast<std::size_t>(k)] >= 1.0f ? largest : static_cast<std::uint32_t>(scaled);
  }
  return quantised;
}

MomentSatTable momentSummedAreaTable(const ImageF& shadowMapLinear, double nearDepth, double farDepth,
  const MomentSatFormat& format)
{
  const int width = shadowMapLinear.width;
  const int height = shadowMapLinear.height;
  MomentSatTable result{ Image<std::uint64_t>(width, height, 4), format };
  Image<std::uint64_t>& table = result.sums;
  const float nearFloat = static_cast<float>(nearDepth);
  const float farFloat = static_cast<float>(farDepth);
  for (int y = 0; y < height; ++y)
  {
    MomentSums row{};
    for (int x = 0; x < width; ++x)
    {
      const std::array<std::uint32_t, 4> texel =
        momentSatTexel(shadowMapLinear.at(x, y), nearFloat, farFloat, format.bits);
      for (int k = 0; k < 4; ++k)
      {
        row[static_cast<std::size_t>(k)] += texel[static_cast<std::size_t>(k)];
        table.at(x, y, k) = row[static_cast<std::size_t>(k)] + (y > 0 ? table.at(x, y - 1, k) : 0u);
      }
    }
  }
  return result;
}

Image<std::uint64_t> momentSummedAreaTableFromWords(const Image<std::uint32_t>& words)
{
  Image<std::uint64_t> table(words.width, words.height, 4);
  const bool wide = words.components == 8;
  for (int y = 0; y < words.height; ++y)
  {
    for (int x = 0; x < words.width; ++x)
    {
      for (int k = 0; k < 4; ++k)
      {
        const std::uint64_t high = wide ? words.at(x, y, 4 + k) : 0u;
        table.at(x, y, k) = (high << 32) | words.at(x, y, k);
      }
    }
  }
  return table;
}

MomentSums momentBoxSum(const Image<std::uint64_t>& table, glm::ivec2 lo, glm::ivec2 hi)
{
  MomentSums sum{};
  for (int k = 0; k < 4; ++k)
  {
    std::uint64_t value = table.at(hi.x, hi.y, k);
    if (lo.x > 0)
    {
      value -= table.at(lo.x - 1, hi.y, k);
    }
    if (lo.y > 0)
    {
      value -= table.at(hi.x, lo.y - 1, k);
    }
    if (lo.x > 0 && lo.y > 0)
    {
      value += table.at(lo.x - 1, lo.y - 1, k);
    }
    sum[static_cast<std::size_t>(k)] = value;
  }
  return sum;
}

namespace
{

glm::dvec4 decodedMomentSum(const MomentSums& sum, double scale)
{
  return glm::dvec4(static_cast<double>(sum[0]), static_cast<double>(sum[1]), static_cast<double>(sum[2]),
           static_cast<double>(sum[3])) /
    scale;
}

} // namespace

glm::dvec4 momentBoxMean(const MomentSatTable& table, glm::ivec2 lo, glm::ivec2 hi)
{
  const double texels = static_cast<double>(hi.x - lo.x + 1) * (hi.y - lo.y + 1);
  return decodedMomentSum(momentBoxSum(table.sums, lo, hi), table.format.scale()) / texels;
}

FractionalSpan fractionalSpan(double lower, double upper, int mapSize)
{
  lower = std::clamp(lower, 0.0, static_cast<double>(mapSize));
  upper = std::clamp(upper, 0.0, static_cast<double>(mapSize));
  FractionalSpan span;
  if (!(upper > lower))
  {
    // No area left: the texel holding the centre, whole.
    const int texel = std::clamp(static_cast<int>(std::floor(0.5 * (lower + upper))), 0, mapSize - 1);
    span.count = 1;
    span.first[0] = span.last[0] = texel;
    span.width[0] = 1.0;
    return span;
  }
  const int first = std::min(static_cast<int>(std::floor(lower)), mapSize - 1);
  const int last = std::max(static_cast<int>(std::ceil(upper)) - 1, first);
  if (first == last)
  {
    span.count = 1;
    span.first[0] = span.last[0] = first;
    span.width[0] = upper - lower;
    return span;
  }
  span.first[0] = span.last[0] = first;
  span.width[0] = (first + 1.0) - lower;
  span.count = 1;
  if (last - 1 >= first + 1)
  {
    span.first[1] = first + 1;
    span.last[1] = last - 1;
    span.width[1] = 1.0;
    span.count = 2;
  }
  span.first[static_cast<std::size_t>(span.count)] = span.last[static_cast<std::size_t>(span.count)] = last;
  span.width[static_cast<std::size_t>(span.count)] = upper - last;
  ++span.count;
  return span;
}

glm::dvec4 momentFractionalBoxMean(const MomentSatTable& table, glm::dvec2 boxMin, glm::dvec2 boxMax)
{
  const FractionalSpan spanX = fractionalSpan(boxMin.x, boxMax.x, table.sums.width);
  const FractionalSpan spanY = fractionalSpan(boxMin.y, boxMax.y, table.sums.height);
  glm::dvec4 sum(0.0);
  double area = 0.0;
  for (int j = 0; j < spanY.count; ++j)
  {
    for (int i = 0; i < spanX.count; ++i)
    {
      const std::size_t a = static_cast<std::size_t>(i);
      const std::size_t b = static_cast<std::size_t>(j);
      const glm::ivec2 lo(spanX.first[a], spanY.first[b]);
      const glm::ivec2 hi(spanX.last[a], spanY.last[b]);
      sum += spanX.width[a] * spanY.width[b] * decodedMomentSum(momentBoxSum(table.sums, lo, hi), table.format.scale());
      area += spanX.width[a] * spanY.width[b] * (hi.x - lo.x + 1) * (hi.y - lo.y + 1);
    }
  }
  return sum / area;
}

} // namespace sl
