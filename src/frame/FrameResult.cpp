#include "frame/FrameResult.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace sl
{

std::optional<int> FrameResult::shadowMapSize() const
{
  if (automaticMapSize)
  {
    return automaticMapSize->size;
  }
  return lightView ? std::optional<int>(lightView->resolution) : std::nullopt;
}

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
  // A technique may mark pixels in several buffers (dcs: counter_status and volume_count_status): a pixel marked in
  // any of them counts once; buffer and label name those that mark some pixel ("a / b" when several do).
  std::optional<CutShortPixels> marked;
  std::vector<bool> any;
  bool named = false; // a buffer that marks some pixel is named already
  for (const BufferSpec& spec : frame.descriptor->buffers)
  {
    const NamedImage* buffer = spec.cutShortCode >= 0 ? frame.find(spec.name) : nullptr;
    if (!buffer)
    {
      continue;
    }
    const std::string label = spec.categoryLabels.at(static_cast<std::size_t>(spec.cutShortCode));
    if (!marked)
    {
      marked = CutShortPixels{ spec.name, label, 0 };
    }
    const float code = static_cast<float>(spec.cutShortCode);
    any.resize(std::max(any.size(), buffer->image.data.size()), false);
    std::size_t here = 0;
    for (std::size_t i = 0; i < buffer->image.data.size(); ++i)
    {
      if (buffer->image.data[i] == code)
      {
        ++here;
        marked->count += any[i] ? 0 : 1;
        any[i] = true;
      }
    }
    if (here > 0)
    {
      marked->buffer = named ? marked->buffer + " / " + spec.name : spec.name;
      marked->label = named ? marked->label + " / " + label : label;
      named = true;
    }
  }
  return marked;
}

std::vector<FlaggedPixels> flaggedPixels(const FrameResult& frame)
{
  std::vector<FlaggedPixels> flagged;
  if (!frame.descriptor)
  {
    return flagged;
  }
  for (const BufferSpec& spec : frame.descriptor->buffers)
  {
    const NamedImage* buffer = std::isfinite(spec.flagAtOrAbove) ? frame.find(spec.name) : nullptr;
    if (!buffer)
    {
      continue;
    }
    const auto count = std::count_if(buffer->image.data.begin(), buffer->image.data.end(),
      [&](float value) { return static_cast<double>(value) >= spec.flagAtOrAbove; });
    flagged.push_back({ spec.name, spec.flagAtOrAbove, spec.flagWarning, static_cast<std::size_t>(count) });
  }
  return flagged;
}

const std::vector<BufferSpec>& commonBufferSpecs()
{
  static const std::vector<BufferSpec> specs = {
    { "visibility", "", "fraction of the light visible from the surface point, in [0, 1] (1 = fully lit); hard/pcf "
                        "sample area lights from their centre. 0 where coverage = 0" },
    { "position", "world units", "world-space position of the surface seen in the pixel (3 components)" },
    { "normal", "", "unit world-space normal, facing the camera (3 components)" },
    { "depth", "world units", "linear view depth along the camera axis" },
    { "coverage", "", "1 where a surface covers the pixel centre (multisampled frames: the first sample), 0 for background" },
    { "albedo", "", "surface albedo (3 components)" },
    { "receives_shadows", "", "1 where the surface receives shadows (the object's receive_shadows), else 0" },
    { "shadow_tested", "", "1 where the pixel reaches a shadow test: covered, receives shadows, and the light can reach "
                           "the surface (it faces the light, inside a spot's cone, in front of an area light), "
                           "decided on the CPU from position and normal as the shaders' lightCanReach; 0 elsewhere, "
                           "where buffers declared on shadow-tested pixels (depth_margin, depth_bias, ...) hold no "
                           "value and their heat maps are grey" },
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

const std::vector<BufferSpec>& multisampleBufferSpecs()
{
  static const std::vector<BufferSpec> specs = {
    { "msaa_distinct_samples", "samples", "multisampled frames (Schwarz and Stamminger 2008 §7): covered samples whose view depth "
                                           "differs from the first sample's s_z by more than tau (relative); 0 .. samples - 1" },
    { "msaa_interpolated_samples", "samples", "multisampled frames: samples that took the visibility of a 4-neighbour (the one "
                                               "whose s_z is closest to the sample's depth) instead of the pixel's" },
    { "msaa_pixel_visibility", "", "multisampled frames: the technique's visibility, evaluated once per pixel from the "
                                    "first sample (SS08 §7), before the resolve" },
    { "msaa_sample_depth", "world units", "multisampled frames: each sample's view depth (one component per sample; 0 where "
                                           "the sample is uncovered)" },
    { "msaa_sample_visibility", "", "multisampled frames: each sample's visibility after the resolve (one component per "
                                     "sample; 0 where uncovered); `visibility` is their mean over the covered samples where "
                                     "sample 0 is covered, else 0" },
  };
  return specs;
}

} // namespace sl
