// A named per-pixel (or per-texel) image with what a reader needs to interpret it: unit, documentation, and how
// to colour it. Buffers of a frame, light-space exports and arrays read back from a .vti are NamedImages.
#pragma once

#include "core/Image.h"

#include <algorithm>
#include <string>
#include <vector>

namespace sl
{

enum class BufferKind
{
  Continuous, // heat map with a sequential colour map
  Signed,     // diverging colour map about 0
  Categorical // integer classes with labels
};

struct NamedImage
{
  std::string name;
  ImageF image;
  std::string unit;
  std::string doc;
  BufferKind kind = BufferKind::Continuous;
  std::vector<std::string> categoryLabels;
};

// The image called `name` in `images`, or nullptr.
inline const NamedImage* findNamed(const std::vector<NamedImage>& images, const std::string& name)
{
  const auto found =
    std::find_if(images.begin(), images.end(), [&](const NamedImage& named) { return named.name == name; });
  return found == images.end() ? nullptr : &*found;
}

} // namespace sl
