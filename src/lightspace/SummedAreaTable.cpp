#include "lightspace/SummedAreaTable.h"

#include <algorithm>
#include <cmath>

namespace sl
{
namespace
{

double normalised(double z, double nearDepth, double farDepth)
{
  return (std::clamp(z, nearDepth, farDepth) - nearDepth) / (farDepth - nearDepth);
}

std::uint32_t fixedPoint(double value, double scale)
{
  return static_cast<std::uint32_t>(std::lround(value * scale));
}

template <typename Value, typename Table>
Value cornerSum(const Table& table, glm::ivec2 lo, glm::ivec2 hi, int component)
{
  Value sum = static_cast<Value>(table.at(hi.x, hi.y, component));
  if (lo.x > 0)
  {
    sum -= static_cast<Value>(table.at(lo.x - 1, hi.y, component));
  }
  if (lo.y > 0)
  {
    sum -= static_cast<Value>(table.at(hi.x, lo.y - 1, component));
  }
  if (lo.x > 0 && lo.y > 0)
  {
    sum += static_cast<Value>(table.at(lo.x - 1, lo.y - 1, component));
  }
  return sum;
}

} // namespace

double satFixedPointScale(int mapSize)
{
  const int bits = std::min(16, 32 - static_cast<int>(std::ceil(std::log2(static_cast<double>(mapSize) * mapSize))));
  return std::ldexp(1.0, bits) - 1.0;
}

Image<std::uint32_t> integerSummedAreaTable(const ImageF& shadowMapLinear, double nearDepth, double farDepth)
{
  const int width = shadowMapLinear.width;
  const int height = shadowMapLinear.height;
  const double scale = satFixedPointScale(width);
  Image<std::uint32_t> table(width, height, 2);
  for (int y = 0; y < height; ++y)
  {
    std::uint32_t rowFirst = 0;
    std::uint32_t rowSecond = 0;
    for (int x = 0; x < width; ++x)
    {
      // The GPU computes z_n in float; a value exactly between two fixed-point steps could round either way,
      // which the tests tolerate by comparing box sums, not single entries (see SavsmTest).
      const double zNormalized = normalised(shadowMapLinear.at(x, y), nearDepth, farDepth);
      rowFirst += fixedPoint(zNormalized, scale);
      rowSecond += fixedPoint(zNormalized * zNormalized, scale);
      const std::uint32_t belowFirst = y > 0 ? table.at(x, y - 1, 0) : 0u;
      const std::uint32_t belowSecond = y > 0 ? table.at(x, y - 1, 1) : 0u;
      table.at(x, y, 0) = rowFirst + belowFirst;
      table.at(x, y, 1) = rowSecond + belowSecond;
    }
  }
  return table;
}

BoxMoments exactBoxMoments(const ImageF& shadowMapLinear, glm::ivec2 lo, glm::ivec2 hi, double nearDepth,
  double farDepth, bool integer)
{
  double sum = 0.0;
  double sumSquares = 0.0;
  const double scale = satFixedPointScale(shadowMapLinear.width);
  for (int y = lo.y; y <= hi.y; ++y)
  {
    for (int x = lo.x; x <= hi.x; ++x)
    {
      double z = std::clamp(static_cast<double>(shadowMapLinear.at(x, y)), nearDepth, farDepth);
      double zSquared = z * z;
      if (integer)
      {
        const double zNormalized = normalised(z, nearDepth, farDepth);
        const double range = farDepth - nearDepth;
        z = nearDepth + fixedPoint(zNormalized, scale) / scale * range;
        // E[z^2] is rebuilt from the quantised z_n^2, as the lookup does.
        const double secondNormalized = fixedPoint(zNormalized * zNormalized, scale) / scale;
        zSquared = secondNormalized; // normalised; converted below
      }
      sum += z;
      sumSquares += zSquared;
    }
  }
  const double count = static_cast<double>(hi.x - lo.x + 1) * (hi.y - lo.y + 1);
  BoxMoments moments;
  moments.mean = sum / count;
  if (integer)
  {
    const double range = farDepth - nearDepth;
    const double meanNormalized = (moments.mean - nearDepth) / range;
    moments.variance = std::max(sumSquares / count - meanNormalized * meanNormalized, 0.0) * range * range;
  }
  else
  {
    moments.variance = std::max(sumSquares / count - moments.mean * moments.mean, 0.0);
  }
  return moments;
}

BoxMoments boxMomentsFromFloatTable(const ImageF& table, glm::ivec2 lo, glm::ivec2 hi, double nearDepth, double farDepth)
{
  const double count = static_cast<double>(hi.x - lo.x + 1) * (hi.y - lo.y + 1);
  const double meanCentred = cornerSum<double>(table, lo, hi, 0) / count;
  BoxMoments moments;
  moments.mean = meanCentred + 0.5 * (nearDepth + farDepth);
  moments.variance = std::max(cornerSum<double>(table, lo, hi, 1) / count - meanCentred * meanCentred, 0.0);
  return moments;
}

BoxMoments boxMomentsFromIntegerTable(const Image<std::uint32_t>& table, glm::ivec2 lo, glm::ivec2 hi,
  double nearDepth, double farDepth)
{
  const double count = static_cast<double>(hi.x - lo.x + 1) * (hi.y - lo.y + 1);
  const double scale = satFixedPointScale(table.width);
  const double meanNormalized = cornerSum<std::uint32_t>(table, lo, hi, 0) / (scale * count);
  const double secondNormalized = cornerSum<std::uint32_t>(table, lo, hi, 1) / (scale * count);
  const double range = farDepth - nearDepth;
  BoxMoments moments;
  moments.mean = nearDepth + meanNormalized * range;
  moments.variance = std::max(secondNormalized - meanNormalized * meanNormalized, 0.0) * range * range;
  return moments;
}

} // namespace sl
