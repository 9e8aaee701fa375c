#include "frame/FrameResult.h"

#include <algorithm>

namespace sl
{

const NamedImage* FrameResult::find(const std::string& name) const
{
  return findNamed(buffers, name);
}

std::optional<CutShortPixels> cutShortPixels(const FrameResult& frame)
{
  if (!frame.descriptor)
  {
    return std::nullopt;
  }
  for (const BufferSpec& spec : frame.descriptor->buffers)
  {
    const NamedImage* buffer = spec.cutShortCode >= 0 ? frame.find(spec.name) : nullptr;
    if (!buffer)
    {
      continue;
    }
    CutShortPixels marked{ spec.name, spec.categoryLabels.at(static_cast<std::size_t>(spec.cutShortCode)), 0 };
    const float code = static_cast<float>(spec.cutShortCode);
    marked.count = static_cast<std::size_t>(std::count(buffer->image.data.begin(), buffer->image.data.end(), code));
    return marked;
  }
  return std::nullopt;
}

const std::vector<BufferSpec>& commonBufferSpecs()
{
  static const std::vector<BufferSpec> specs = {
    { "visibility", "", "fraction of the light visible from the surface point, in [0, 1] (1 = fully lit); hard/pcf "
                        "sample area lights from their centre. 0 where coverage = 0" },
    { "position", "world units", "world-space position of the surface seen in the pixel (3 components)" },
    { "normal", "", "unit world-space normal, facing the camera (3 components)" },
    { "depth", "world units", "linear view depth along the camera axis" },
    { "coverage", "", "1 where a surface covers the pixel centre, 0 for background" },
    { "albedo", "", "surface albedo (3 components)" },
    { "receives_shadows", "", "1 where the surface receives shadows (the object's receive_shadows), else 0" },
  };
  return specs;
}

const std::vector<BufferSpec>& subLightBufferSpecs()
{
  static const std::vector<BufferSpec> specs = {
    { "sublight_visibility", "", "techniques with `sublights` = S (multi-view shadow maps, Yang et al. 2009 §5): the "
                                 "visibility of each of the S x S sub-lights, one component each, row by row from the "
                                 "light's (-right, -up) corner; `visibility` is their mean" },
  };
  return specs;
}

} // namespace sl
