#include "lightspace/AutomaticMapSize.h"

#include "core/Error.h"
#include "lightspace/CameraView.h"
#include "lightspace/PartitionViews.h"
#include "lightspace/ShadowMapMath.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sl
{

int powerOfTwoAtLeast(double value)
{
  int size = 1;
  while (size < value && size < (1 << 30))
  {
    size *= 2;
  }
  return size;
}

int powerOfTwoAtMost(double value)
{
  int size = 1;
  while (2.0 * size <= value && size < (1 << 30))
  {
    size *= 2;
  }
  return size;
}

AutomaticMapSize automaticMapSize(const CameraView& camera, const Light& light, const std::vector<LightView>& views,
  double marginTexels, const ImageF& position, const ImageF& normal, int maxSize, double texelsPerPixel)
{
  SL_CHECK(!views.empty() && position.width == normal.width && position.height == normal.height && texelsPerPixel > 0.0);
  AutomaticMapSize choice;
  choice.texelsPerPixel = texelsPerPixel;
  const double pixels = static_cast<double>(position.width) * position.height;
  choice.pixelStride = std::max(1, static_cast<int>(std::ceil(std::sqrt(pixels / kAutomaticMapMaxSamples))));
  std::vector<double> required;
  for (int y = choice.pixelStride / 2; y < position.height; y += choice.pixelStride)
  {
    for (int x = choice.pixelStride / 2; x < position.width; x += choice.pixelStride)
    {
      const glm::dvec3 pWs(position.at(x, y, 0), position.at(x, y, 1), position.at(x, y, 2));
      const glm::dvec3 nWs(normal.at(x, y, 0), normal.at(x, y, 1), normal.at(x, y, 2));
      if (position.at(x, y, 3) <= 0.5f || normal.at(x, y, 3) <= 0.5f || !lightCanReach(light, pWs, nWs))
      {
        continue;
      }
      double finest = std::numeric_limits<double>::infinity();
      for (const LightView& view : views)
      {
        double edgeFraction = 0.0;
        if (views.size() > 1 && !mapHolds(view, marginTexels, pWs, edgeFraction))
        {
          continue;
        }
        if (view.projection == LightProjection::Perspective && !((view.viewFromWorld * glm::dvec4(pWs, 1.0)).z < 0.0))
        {
          continue; // behind the light's centre: this view does not hold it
        }
        const SamplingError error = samplingError(camera, view, x + 0.5, y + 0.5, pWs, nWs);
        const double ratio = std::max(error.texelRatioS, error.texelRatioT);
        if (ratio > 0.0 && std::isfinite(ratio))
        {
          finest = std::min(finest, texelsPerPixel * ratio * (view.resolution - 2.0 * marginTexels));
        }
      }
      if (std::isfinite(finest))
      {
        required.push_back(finest);
      }
    }
  }
  choice.samples = static_cast<int>(required.size());
  const int smallest = std::max(kAutomaticMapMinSize, powerOfTwoAtLeast(2.0 * marginTexels + 16.0));
  if (required.empty())
  {
    choice.size = std::min(smallest, maxSize);
    return choice;
  }
  const std::size_t rank = std::min(required.size() - 1,
    static_cast<std::size_t>(std::ceil(kAutomaticMapQuantile * static_cast<double>(required.size()))) - 1);
  std::nth_element(required.begin(), required.begin() + static_cast<std::ptrdiff_t>(rank), required.end());
  choice.requiredTexels = required[rank];
  const int wanted = powerOfTwoAtLeast(choice.requiredTexels + 2.0 * marginTexels);
  choice.capped = wanted > maxSize;
  choice.size = std::clamp(wanted, std::min(smallest, maxSize), maxSize);
  return choice;
}

} // namespace sl
