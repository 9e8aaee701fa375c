#include "lightspace/LightSamples.h"

#include "core/Error.h"

#include <cmath>

namespace sl
{
std::uint64_t mix64(std::uint64_t value)
{
  value = (value ^ (value >> 30)) * 0xBF58476D1CE4E5B9ull;
  value = (value ^ (value >> 27)) * 0x94D049BB133111EBull;
  return value ^ (value >> 31);
}

double radicalInverse(unsigned base, std::uint64_t index)
{
  SL_CHECK(base >= 2);
  const double inverseBase = 1.0 / base;
  double factor = inverseBase;
  double result = 0.0;
  while (index > 0)
  {
    result += static_cast<double>(index % base) * factor;
    index /= base;
    factor *= inverseBase;
  }
  return result < 1.0 ? result : std::nextafter(1.0, 0.0);
}

glm::dvec2 concentricDiskMap(const glm::dvec2& unit)
{
  const glm::dvec2 offset = 2.0 * unit - 1.0;
  if (offset.x == 0.0 && offset.y == 0.0)
  {
    return glm::dvec2(0.0);
  }
  const double quarterPi = 0.78539816339744831;
  double radius = 0.0;
  double theta = 0.0;
  if (std::abs(offset.x) > std::abs(offset.y))
  {
    radius = offset.x;
    theta = quarterPi * (offset.y / offset.x);
  }
  else
  {
    radius = offset.y;
    theta = 2.0 * quarterPi - quarterPi * (offset.x / offset.y);
  }
  return radius * glm::dvec2(std::cos(theta), std::sin(theta));
}

glm::dvec3 pointOnAreaLight(const Light& light, const glm::dvec2& unitSquare)
{
  if (light.shape == LightShape::Disk)
  {
    const glm::dvec2 disk = (0.5 * light.size) * concentricDiskMap(unitSquare);
    return light.center + disk.x * light.right() + disk.y * light.up;
  }
  return light.center + (unitSquare.x - 0.5) * light.size * light.right() + (unitSquare.y - 0.5) * light.size * light.up;
}

std::vector<glm::dvec3> lightSamplePoints(const Light& light, int count, std::uint64_t seed)
{
  switch (light.type)
  {
    case LightType::Point:
    case LightType::Spot:
      return { light.center };
    case LightType::Directional:
      return {};
    case LightType::Area:
      break;
  }
  const std::uint64_t bits = mix64(seed + 0x9E3779B97F4A7C15ull); // splitmix64 step
  const glm::dvec2 rotation(static_cast<double>(bits >> 40) / 16777216.0, static_cast<double>((bits >> 16) & 0xFFFFFFu) / 16777216.0);
  std::vector<glm::dvec3> points;
  points.reserve(static_cast<std::size_t>(count));
  for (int k = 0; k < count; ++k)
  {
    glm::dvec2 unit((k + 0.5) / count, radicalInverse(2, static_cast<std::uint64_t>(k)));
    unit = glm::fract(unit + rotation);
    points.push_back(pointOnAreaLight(light, unit));
  }
  return points;
}

std::vector<Light> splitIntoSubLights(const Light& light, int perSide)
{
  SL_CHECK(light.type == LightType::Area && light.shape == LightShape::Square && perSide >= 1);
  std::vector<Light> subLights;
  const double step = light.size / perSide;
  for (int j = 0; j < perSide; ++j)
  {
    for (int i = 0; i < perSide; ++i)
    {
      Light subLight = light;
      subLight.center = light.center + light.right() * ((i + 0.5) * step - 0.5 * light.size) +
        light.up * ((j + 0.5) * step - 0.5 * light.size);
      subLight.size = step;
      subLight.intensity = light.intensity / (perSide * perSide);
      subLights.push_back(subLight);
    }
  }
  return subLights;
}

} // namespace sl
