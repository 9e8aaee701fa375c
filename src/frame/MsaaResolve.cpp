#include "frame/MsaaResolve.h"

#include "core/Error.h"

#include <array>
#include <cmath>

namespace sl
{

MsaaResolved msaaResolve(const MsaaResolveInputs& inputs, double depthTolerance)
{
  const ImageF& pixelVisibility = *inputs.pixelVisibility;
  const ImageF& sampleDepth = *inputs.sampleDepth;
  const int width = pixelVisibility.width;
  const int height = pixelVisibility.height;
  const int samples = sampleDepth.components;
  SL_CHECK(inputs.firstCoverage->width == width && inputs.firstDepth->width == width && sampleDepth.width == width);
  const float tolerance = static_cast<float>(depthTolerance); // the shader's uniform
  const auto firstCovered = [&](int x, int y) { return inputs.firstCoverage->at(x, y) > 0.5f; };
  constexpr std::array<std::array<int, 2>, 4> kNeighbours{ { { -1, 0 }, { 1, 0 }, { 0, -1 }, { 0, 1 } } };

  MsaaResolved resolved{ ImageF(width, height, 1), ImageF(width, height, samples), ImageF(width, height, 1),
    ImageF(width, height, 1) };
  for (int y = 0; y < height; ++y)
  {
    for (int x = 0; x < width; ++x)
    {
      const bool covered = firstCovered(x, y);
      const float firstDepth = inputs.firstDepth->at(x, y);
      const float visibility = covered ? pixelVisibility.at(x, y) : 0.0f;
      int distinct = 0;
      int interpolated = 0;
      int coveredSamples = 0;
      float sum = 0.0f;
      for (int s = 0; s < samples; ++s)
      {
        const float depth = sampleDepth.at(x, y, s);
        if (depth == 0.0f)
        {
          continue;
        }
        float value = visibility;
        if (!covered || std::fabs(depth - firstDepth) > tolerance * firstDepth)
        {
          ++distinct;
          float best = covered ? std::fabs(depth - firstDepth) : 3.0e38f;
          bool fromNeighbour = false;
          value = covered ? visibility : 0.0f;
          for (const auto& offset : kNeighbours)
          {
            const int nx = x + offset[0];
            const int ny = y + offset[1];
            if (nx < 0 || ny < 0 || nx >= width || ny >= height || !firstCovered(nx, ny))
            {
              continue;
            }
            const float difference = std::fabs(depth - inputs.firstDepth->at(nx, ny));
            if (difference < best)
            {
              best = difference;
              value = pixelVisibility.at(nx, ny);
              fromNeighbour = true;
            }
          }
          interpolated += fromNeighbour ? 1 : 0;
        }
        resolved.sampleVisibility.at(x, y, s) = value;
        sum += value;
        ++coveredSamples;
      }
      resolved.visibility.at(x, y) = covered && coveredSamples > 0 ? sum / static_cast<float>(coveredSamples) : 0.0f;
      resolved.distinctSamples.at(x, y) = static_cast<float>(distinct);
      resolved.interpolatedSamples.at(x, y) = static_cast<float>(interpolated);
    }
  }
  return resolved;
}

} // namespace sl
