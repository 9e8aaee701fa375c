// Summed-area tables built band by band (structures/sat, structures/momentsat): the rows' prefix sums and then the
// columns' are computed in a storage buffer that holds a band of rows, and each finished band is copied into the
// table's texture. On llvmpipe a shader's storage-buffer stores cost a fraction of its image stores, and a band small
// enough to stay in the processor's cache keeps the column pass (a walk down each column) from waiting on memory;
// the band also bounds the extra memory, whatever the map's size. The column pass continues from a carry per column,
// so the sums are added in the same order as in one pass over the whole map, and the table does not depend on the
// band height.
#pragma once

#include "gl/ComputeProgram.h"

#include <cstddef>
#include <functional>
#include <memory>
#include <vector>

namespace sl
{

class BandedPrefixSums
{
public:
  // One table of size x size texels: its texture, the format and type of its texels as the copy names them
  // (GL_RG_INTEGER/GL_UNSIGNED_INT, GL_RG/GL_FLOAT, ...) and a texel's size in 32-bit words.
  struct Table
  {
    unsigned int texture = 0;
    unsigned int format = 0;
    unsigned int type = 0;
    int texelWords = 0;
  };

  // The most bytes of a band buffer on a CPU rasterizer (llvmpipe): small enough for the processor's cache, large
  // enough that the dispatches per band do not dominate (measured against 1 and 32 MiB: src/structures/README.md).
  // A GPU gets bands of up to kGpuBandBytes (within GL_MAX_SHADER_STORAGE_BLOCK_SIZE): there a band of few rows
  // leaves most of it idle in the row pass (one invocation per row); a 2048^2 SAT is one band. The table is the same
  // whatever the band height.
  static constexpr std::size_t kCpuBandBytes = std::size_t(4) << 20;
  static constexpr std::size_t kGpuBandBytes = std::size_t(64) << 20;
  // The band bytes of the current GL context's renderer (one renderer per process: the result is kept).
  static std::size_t bandBytesOfThisGl();
  // The rows of a band of at most `bandBytes` of a table `size` texels wide with texels of `texelWords` words (at
  // least 1, at most size).
  static int bandRowsFor(int size, int texelWords, std::size_t bandBytes);

  // Builds `tables` (each size x size) band by band. Table k's band buffer is bound at storage binding 2k, its
  // carry (one texel per column, the table's row above the band, zero above the first) at 2k + 1. For each band,
  // `dispatchPass(pass, firstRow, rows)` must run pass 0 (rows' prefix sums of the band's rows firstRow ..
  // firstRow + rows - 1 into the band buffer, row-major) and then pass 1 (columns' prefix sums in place, from and
  // into the carry); the band is then copied into rows firstRow .. of each texture. The buffers are kept for the
  // next build of the same size and tables.
  void build(int size, const std::vector<Table>& tables,
    const std::function<void(int pass, int firstRow, int rows)>& dispatchPass);

  // The bytes of the band and carry buffers held.
  std::size_t bytes() const;

private:
  struct Buffers
  {
    std::unique_ptr<StorageBuffer> band;
    std::unique_ptr<StorageBuffer> carry;
  };
  std::vector<Buffers> buffers_;
  int size_ = 0;
  int bandRows_ = 0;
};

} // namespace sl
