// The tiles of a light-space map that the frame's receivers read (issue 33: a structure costs what is read). A
// moment-map lookup with prefilter = blur reads one texel, the one holding the receiver's projection
// (prefilteredFetch, common/MomentLookup.glsl), so the blur is needed only there, and each blur pass only over what
// the next one reads: the final (vertical) pass over the receivers' tiles, the horizontal pass over those grown by
// the box's reach along y, the moments from depth over those grown along x.
#pragma once

#include "core/Image.h"

#include <cstdint>
#include <vector>

namespace sl
{

class StorageBuffer;

// A rectangle of texels, [x, x + width) x [y, y + height).
struct TileRect
{
  int x = 0;
  int y = 0;
  int width = 0;
  int height = 0;
};

class ReceiverTiles
{
public:
  ReceiverTiles() = default;
  // No tile marked, over a mapSize^2 map cut into tileTexels^2 tiles (the last row and column may be partial).
  ReceiverTiles(int mapSize, int tileTexels);
  // Every tile marked: the whole map.
  static ReceiverTiles wholeMap(int mapSize, int tileTexels);
  // The tile edge, in texels, for a map of mapSize^2: about 64 tiles a side, 8 to 32 texels.
  static int tileTexelsFor(int mapSize);

  int mapSize() const { return mapSize_; }
  int tileTexels() const { return tileTexels_; }
  int tilesPerSide() const { return tilesPerSide_; }
  bool marked(int tileX, int tileY) const;
  void mark(int tileX, int tileY);
  // Marks tile i of a row-major list of tilesPerSide^2 flags (non-zero: marked), as the GPU marking writes them
  // (shaders/ReceiverTiles.glsl); a non-zero word after them marks every tile.
  void markFromFlags(const std::vector<std::uint32_t>& flags);
  int markedCount() const;
  int texelCount() const; // texels in the marked tiles (partial tiles count their part)

  // Every tile holding a texel within reachX (along x) or reachY (along y) texels of a texel of a marked tile:
  // what a separable pass reading that far must have built before it.
  ReceiverTiles grown(int reachX, int reachY) const;
  // The marked tiles as rectangles of texels (runs along each row of tiles, clipped to the map), for scissored draws.
  std::vector<TileRect> rectangles() const;
  // 1 on each texel of a marked tile, 0 elsewhere (mapSize^2).
  ImageF texelMask() const;

private:
  int mapSize_ = 0;
  int tileTexels_ = 1;
  int tilesPerSide_ = 0;
  std::vector<std::uint8_t> marked_;
};

// Where the blur runs: the horizontal pass over `horizontal`, the vertical one over `vertical` (the receivers'
// tiles); the source must hold valid texels over `horizontal` grown by the reach along x. `sparse`: instead of the
// two passes, one compute invocation per pixel's footprint of listed texels (shaders/SparseBoxBlur.glsl) from
// `readTexelBuffer` (shaders/ReceiverTiles.glsl's list), which needs the source over the texels' boxes (`horizontal`
// grown along x).
struct PrefilterRegion
{
  std::vector<TileRect> horizontal;
  std::vector<TileRect> vertical;
  bool sparse = false;
  const StorageBuffer* readTexelBuffer = nullptr;
  int readTexelCount = 0;
};

// A prefilter built only where the receivers read (prefilter_region = receivers): the vertical pass over the
// receivers' tiles, the horizontal one over those grown by the box's reach along y, the unfiltered values over those
// grown again along x (without a blur, over the receivers' tiles).
struct ReceiverPrefilterPlan
{
  ReceiverTiles read;            // the receivers' tiles
  PrefilterRegion blur;
  std::vector<TileRect> source; // where the unfiltered values are computed
  int horizontalTiles = 0;       // 0 without a blur or when sparse (no horizontal pass)
  int sourceTiles = 0;
  // The texels the receivers read (x | y << 16, four per receiving pixel: its footprint, with repeats where the map's
  // edge narrows it or receivers share a texel), when the marking listed them all; the blur then runs only on them (sparse) if that is cheaper than its tiles, and only they are built.
  std::vector<std::uint32_t> readTexels;
  // The texels that hold the prefiltered value when the blur is not sparse: the last draw's rectangles.
  std::vector<TileRect> built;

  // 1 on each texel holding the prefiltered value (the listed texels when sparse, else the receivers' tiles), 0
  // elsewhere.
  ImageF builtMask() const;
};
// The plan for the receivers' tiles `read` and, when the marking listed them all, the texels `readTexels`. A draw
// whose tiles cover more than wholeDrawFraction of the map draws the whole map instead: one draw, not a rectangle
// per run of tiles, for almost the same texels.
ReceiverPrefilterPlan planReceiverPrefilter(const ReceiverTiles& read, int blurTexels,
  std::vector<std::uint32_t> readTexels = {});
constexpr double wholeDrawFraction = 0.5;
// Turns a sparse plan of blurTexels into the blur over its tiles (for a build whose sparse path would cost more).
void planOverTiles(ReceiverPrefilterPlan& plan, int blurTexels);
// Turns a blurred plan that lists its texels into the sparse blur (for a build whose sparse path costs less than
// sparseBlurIsCheaper, fetches alone, says); a plan without a list is left as it is.
void planSparse(ReceiverPrefilterPlan& plan);
// Whether marking the receivers' tiles can pay at all: with fewer than receiverRegionTexelsPerPixel map texels per
// pixel the focused map's tiles are nearly all read (measured, README.md), and the whole map is built unmarked.
constexpr long long receiverRegionTexelsPerPixel = 16;
bool receiverRegionCanPay(long long pixels, int mapSize);
// Whether listing the texels the receivers read can pay: a sparse blur of width blurTexels wins only with fewer
// than 2 / w texels listed per texel of the map, and the marking lists 4 per receiving pixel.
bool receiverTexelListCanPay(long long pixels, int mapSize, int blurTexels);
// Sparse when its w^2 fetches per listed texel are fewer than the two passes' w fetches per texel of their tiles.
bool sparseBlurIsCheaper(long long listedTexels, int blurTexels, long long horizontalTexels, long long verticalTexels);

// How far a box of boxTexels (BoxBlur.glsl's taps -(w - 1)/2 .. w/2) reaches from its centre texel, the larger side.
int boxBlurReach(int boxTexels);

} // namespace sl
