#include "gl/BandedPrefixSums.h"

#include "core/Error.h"

#include <vtk_glew.h>

#include <algorithm>
#include <string>

namespace sl
{

std::size_t BandedPrefixSums::bandBytesOfThisGl()
{
  static const std::size_t bytes = [] {
    const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    const std::string name = renderer ? renderer : "";
    if (name.find("llvmpipe") != std::string::npos || name.find("softpipe") != std::string::npos)
    {
      return kCpuBandBytes;
    }
    GLint64 largestBlock = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &largestBlock);
    return std::clamp<std::size_t>(static_cast<std::size_t>(largestBlock), kCpuBandBytes, kGpuBandBytes);
  }();
  return bytes;
}

int BandedPrefixSums::bandRowsFor(int size, int texelWords, std::size_t bandBytes)
{
  const std::size_t rowBytes = static_cast<std::size_t>(size) * static_cast<std::size_t>(texelWords) * 4;
  return static_cast<int>(std::clamp<std::size_t>(bandBytes / rowBytes, 1, static_cast<std::size_t>(size)));
}

void BandedPrefixSums::build(int size, const std::vector<Table>& tables,
  const std::function<void(int pass, int firstRow, int rows)>& dispatchPass)
{
  SL_CHECK(size > 0 && !tables.empty());
  // The rows of the tightest table decide the band, so that every table's band fits the band bytes.
  const std::size_t bandBytes = bandBytesOfThisGl();
  int bandRows = size;
  for (const Table& table : tables)
  {
    bandRows = std::min(bandRows, bandRowsFor(size, table.texelWords, bandBytes));
  }
  bool fits = size_ == size && bandRows_ == bandRows && buffers_.size() == tables.size();
  for (std::size_t k = 0; fits && k < tables.size(); ++k)
  {
    fits = buffers_[k].carry->words() == static_cast<std::size_t>(size) * static_cast<std::size_t>(tables[k].texelWords);
  }
  if (!fits)
  {
    buffers_.clear();
    for (const Table& table : tables)
    {
      const std::size_t rowWords = static_cast<std::size_t>(size) * static_cast<std::size_t>(table.texelWords);
      buffers_.push_back({ std::make_unique<StorageBuffer>(rowWords * static_cast<std::size_t>(bandRows)),
        std::make_unique<StorageBuffer>(rowWords) });
    }
    size_ = size;
    bandRows_ = bandRows;
  }
  for (std::size_t k = 0; k < tables.size(); ++k)
  {
    buffers_[k].carry->clear();
    buffers_[k].band->bind(static_cast<unsigned>(2 * k));
    buffers_[k].carry->bind(static_cast<unsigned>(2 * k + 1));
  }
  for (int firstRow = 0; firstRow < size; firstRow += bandRows)
  {
    const int rows = std::min(bandRows, size - firstRow);
    // The previous band's copy has read the buffer before pass 0 overwrites it; the clears are done.
    glMemoryBarrier(GL_PIXEL_BUFFER_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    dispatchPass(0, firstRow, rows);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    dispatchPass(1, firstRow, rows);
    // The column pass's stores must be visible to the copy below (a pixel unpack from the buffer).
    glMemoryBarrier(GL_PIXEL_BUFFER_BARRIER_BIT);
    for (std::size_t k = 0; k < tables.size(); ++k)
    {
      buffers_[k].band->copyToTexture(tables[k].texture, firstRow, size, rows, tables[k].format, tables[k].type);
    }
  }
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
  for (std::size_t k = 0; k < 2 * tables.size(); ++k)
  {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, static_cast<GLuint>(k), 0);
  }
}

std::size_t BandedPrefixSums::bytes() const
{
  std::size_t total = 0;
  for (const Buffers& buffers : buffers_)
  {
    total += 4 * (buffers.band->words() + buffers.carry->words());
  }
  return total;
}

} // namespace sl
