#include "vis/BufferHeatMap.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace sl
{

ColorMapKind colorMapFor(BufferKind kind)
{
  switch (kind)
  {
    case BufferKind::Signed: return ColorMapKind::Diverging;
    case BufferKind::Categorical: return ColorMapKind::Categorical;
    case BufferKind::Continuous: return ColorMapKind::Viridis;
  }
  return ColorMapKind::Viridis;
}

HeatMapOptions bufferHeatMapOptions(const NamedImage& buffer, const ImageU8* validMask)
{
  HeatMapOptions options;
  options.title = buffer.name;
  options.unit = buffer.unit;
  options.colorMap = colorMapFor(buffer.kind);
  options.categoryLabels = buffer.categoryLabels;
  if (buffer.name == "visibility" || buffer.name == "coverage")
  {
    options.rangeMin = 0.0;
    options.rangeMax = 1.0;
  }
  else if (buffer.kind == BufferKind::Continuous)
  {
    // A few extreme values (texel_ratio where a surface runs parallel to the light) would flatten the
    // colour scale; clip the scale at the 99th percentile then. The title still gives the true range.
    std::vector<float> valid;
    for (std::size_t i = 0; i < buffer.image.pixelCount(); ++i)
    {
      if ((!validMask || validMask->data[i]) && std::isfinite(buffer.image.data[i]))
      {
        valid.push_back(buffer.image.data[i]);
      }
    }
    if (valid.size() > 100)
    {
      const auto percentile = valid.begin() + static_cast<std::ptrdiff_t>(0.99 * (valid.size() - 1));
      std::nth_element(valid.begin(), percentile, valid.end());
      const double p99 = *percentile;
      const double maximum = *std::max_element(percentile, valid.end());
      const double minimum = *std::min_element(valid.begin(), percentile + 1);
      if (maximum - minimum > 4.0 * (p99 - minimum) && p99 > minimum)
      {
        options.rangeMin = minimum;
        options.rangeMax = p99;
      }
    }
  }
  return options;
}

ImageU8 coverageMask(const NamedImage& coverage)
{
  ImageU8 mask(coverage.image.width, coverage.image.height, 1);
  for (std::size_t i = 0; i < mask.data.size(); ++i)
  {
    mask.data[i] = coverage.image.data[i] > 0.5f ? 1 : 0;
  }
  return mask;
}

} // namespace sl
