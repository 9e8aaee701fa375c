// A plain CPU image: width x height pixels of `components` values each.
// Convention (same as OpenGL read-back and vtkImageData): row 0 is the BOTTOM row, x grows right.
#pragma once

#include "core/Error.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace sl
{

// The largest image side anything in ShadowLab renders, reads or writes (camera resolution, --resolution, PNG
// and .vti files): 16384, the GL_MAX_TEXTURE_SIZE of the renderers it runs on.
constexpr int kMaxImageSide = 16384;

template <typename T>
struct Image
{
  int width = 0;
  int height = 0;
  int components = 1;
  std::vector<T> data;

  Image() = default;
  Image(int w, int h, int c, T fill = T())
    : width(w)
    , height(h)
    , components(c)
    , data(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * static_cast<std::size_t>(c), fill)
  {
    SL_CHECK(w >= 0 && h >= 0 && c > 0);
  }

  bool empty() const { return data.empty(); }
  std::size_t pixelCount() const { return static_cast<std::size_t>(width) * static_cast<std::size_t>(height); }
  std::size_t index(int x, int y, int c = 0) const
  {
    SL_DCHECK(x >= 0 && x < width && y >= 0 && y < height && c >= 0 && c < components);
    return (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) *
      static_cast<std::size_t>(components) +
      static_cast<std::size_t>(c);
  }
  T& at(int x, int y, int c = 0) { return data[index(x, y, c)]; }
  const T& at(int x, int y, int c = 0) const { return data[index(x, y, c)]; }

  // The w x h pixels starting at (x0, y0), which must lie inside.
  Image crop(int x0, int y0, int w, int h) const
  {
    SL_CHECK(x0 >= 0 && y0 >= 0 && x0 + w <= width && y0 + h <= height);
    Image result(w, h, components);
    for (int y = 0; y < h; ++y)
    {
      for (int x = 0; x < w; ++x)
      {
        for (int c = 0; c < components; ++c)
        {
          result.at(x, y, c) = at(x0 + x, y0 + y, c);
        }
      }
    }
    return result;
  }

  // Components [first, first + count) of every pixel.
  Image channels(int first, int count) const
  {
    SL_CHECK(first >= 0 && count > 0 && first + count <= components);
    Image result(width, height, count);
    for (std::size_t i = 0; i < pixelCount(); ++i)
    {
      for (int c = 0; c < count; ++c)
      {
        result.data[i * static_cast<std::size_t>(count) + static_cast<std::size_t>(c)] =
          data[i * static_cast<std::size_t>(components) + static_cast<std::size_t>(first + c)];
      }
    }
    return result;
  }
};

using ImageF = Image<float>;
using ImageU8 = Image<std::uint8_t>;

} // namespace sl
