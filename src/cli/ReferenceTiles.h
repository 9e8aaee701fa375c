// A ray-traced reference split into row tiles (issue 32): `reference --tile K/N` traces only tile K's rows (the
// G-buffer is rendered whole, it is cheap), and `reference-merge` puts N such tiles back together. Every pixel's
// light samples depend on (seed, x, y, sample index) alone (reference/LightSampler.h), never on the thread or the
// rows around it, so the merged buffers.vti equals the single-process one bit for bit.
#pragma once

#include <string>

namespace sl
{

struct RowTile
{
  int index = 0;    // K
  int count = 1;    // N
  int rowBegin = 0; // rows [rowBegin, rowEnd) of the image
  int rowEnd = 0;
};

// "K/N" for an image `height` rows high: tile K of N equal bands of rows (the last ones one row shorter when N does
// not divide the height). InputError naming --tile when K/N is malformed or N exceeds the height.
RowTile parseRowTile(const std::string& text, int height);

} // namespace sl
