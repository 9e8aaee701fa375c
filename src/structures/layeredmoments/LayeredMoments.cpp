#include "structures/layeredmoments/LayeredMoments.h"

#include <algorithm>
#include <cmath>

namespace sl
{

DepthLayer depthLayer(int layer, int layers, double nearDepth, double farDepth)
{
  const double width = (farDepth - nearDepth) / layers;
  DepthLayer interval;
  interval.nearEnd = nearDepth + layer * width;
  interval.farEnd = layer + 1 == layers ? farDepth : nearDepth + (layer + 1) * width;
  return interval;
}

int depthLayerIndex(double depth, int layers, double nearDepth, double farDepth)
{
  const double position = (depth - nearDepth) / (farDepth - nearDepth) * layers;
  return std::clamp(static_cast<int>(std::floor(position)), 0, layers - 1);
}

double warpIntoLayer(double depth, const DepthLayer& layer)
{
  return std::clamp((depth - layer.nearEnd) / layer.width(), 0.0, 1.0);
}

} // namespace sl
