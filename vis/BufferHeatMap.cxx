#include "vis/BufferHeatMap.h"

#include "core/Error.h"

#include <bitset>
#include <cmath>
#include <cstdint>

namespace sl
{

ColorMapKind colorMapFor(BufferKind kind)
{
  switch (kind)
  {
    case BufferKind::Signed: return ColorMapKind::Diverging;
    case BufferKind::Categorical: return ColorMapKind::Categorical;
    case BufferKind::Continuous:
    case BufferKind::BitMask:
    case BufferKind::SummedArea: return ColorMapKind::Viridis;
  }
  return ColorMapKind::Viridis;
}

HeatMapOptions bufferHeatMapOptions(const NamedImage& buffer, const ImageU8* validMask)
{
  (void)validMask; // the scale is decided from the pixels with a value when the map is drawn (heatMapScale)
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
  else if (buffer.kind == BufferKind::BitMask)
  {
    const int bits = 16 * buffer.image.components;
    options.unit = format("bits set, of ", bits);
    options.rangeMin = 0.0;
    options.rangeMax = bits;
  }
  else
  {
    options.robustRange = true;
  }
  return options;
}

bool drawsHeatMap(const NamedImage& buffer)
{
  if (buffer.kind == BufferKind::SummedArea || buffer.image.empty())
    return false;
  return buffer.image.components == 1 || buffer.kind == BufferKind::BitMask;
}

ImageF heatMapValues(const NamedImage& buffer)
{
  if (buffer.kind != BufferKind::BitMask)
    return buffer.image;
  ImageF counts(buffer.image.width, buffer.image.height, 1, 0.0f);
  for (std::size_t pixel = 0; pixel < counts.pixelCount(); ++pixel)
  {
    int setBits = 0;
    for (int c = 0; c < buffer.image.components; ++c)
    {
      const float word = buffer.image.data[pixel * buffer.image.components + c];
      // 16 bits per float component, an exact integer; anything else is not a mask word.
      SL_CHECK_MSG(word >= 0.0f && word <= 65535.0f && word == std::floor(word), "bit mask ", buffer.name,
        ": component ", c, " of pixel ", pixel, " holds ", word, ", not a 16-bit word");
      setBits += static_cast<int>(std::bitset<16>(static_cast<std::uint32_t>(word)).count());
    }
    counts.data[pixel] = static_cast<float>(setBits);
  }
  return counts;
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

ImageU8 bufferValueMask(const NamedImage& buffer, const std::vector<NamedImage>& frameBuffers)
{
  const NamedImage* coverage = findNamed(frameBuffers, "coverage");
  ImageU8 mask = coverage ? coverageMask(*coverage) : ImageU8(buffer.image.width, buffer.image.height, 1, 1);
  const NamedImage* tested = findNamed(frameBuffers, "shadow_tested");
  if (buffer.domain == BufferDomain::ShadowTested && tested && tested->image.width == mask.width &&
    tested->image.height == mask.height)
  {
    for (std::size_t i = 0; i < mask.data.size(); ++i)
    {
      if (mask.data[i] != 0 && !(tested->image.data[i] > 0.5f))
        mask.data[i] = kNotApplicablePixel;
    }
  }
  return mask;
}

} // namespace sl
