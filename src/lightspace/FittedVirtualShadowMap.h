// Adaptive partitioning (survey §4.3.3): fitted virtual shadow maps (FVSM, Giegl & Wimmer 2007 as the survey describes
// them). A pre-pass records, for each visible receiver, where it queries the shadow map and the map resolution it
// requires there; the samples are scattered on the CPU into a low-resolution grid over the focused light window that
// keeps the maximum required resolution per cell; a quadtree derived from the grid gives the tiles, each with its own
// fixed-size shadow map (fvsm_tile_size texels per side), refined while its texels are coarser than a sample in it
// requires, up to fvsm_max_level (Fig. 16: a maximum refinement of 32 x 32) and fvsm_max_tiles.
//
// Required resolution (survey Eq. 2 per axis, one texel per pixel): with texel_ratio_s = r_s pixels per texel for a
// texel of size T_s along the map's s axis, the sample needs texels no larger than T_s / r_s. In texels across the
// root rectangle (width W_s): R = max(W_s r_s / T_s, W_t r_t / T_t), independent of the map the ratio was measured in.
// A tile at level L spans W / 2^L and holds tile_size - 2 margin texels inside its filter margin, so its
// texel_ratio is R / ((tile_size - 2 margin) 2^L) per axis at most: the requirement is met iff
// (tile_size - 2 margin) 2^L >= R. The root rectangle is the focused window without its margin (LightView.h).
//
// Coordinates: "light xy" is the light view's x, y (world units, orthographic) or x / depth, y / depth (tangents,
// perspective), the units of LightView::window. The grid is 2^fvsm_max_level cells per side, the finest level's;
// a leaf at level L is a block of 2^(max_level - L) cells, so the grid's per-cell maximum decides exactly.
//
// A leaf is one "partition view" (Cascades.h's multi-view framework): the root's light frame and depth range with its
// rectangle (grown by the margin) as window; it owns the receivers inside its rectangle (four world-space half-spaces:
// planes parallel to the light direction for an orthographic light, through its centre for a perspective one), and
// each pixel reads the leaf whose rectangle holds its light xy (containment). Empty leaves get no map.
#pragma once

#include "core/Image.h"
#include "lightspace/LightView.h"

#include <glm/glm.hpp>

#include <vector>

namespace sl
{

struct CameraView;

struct FvsmSettings
{
  bool enabled = false; // fvsm = off | on
  int tileSize = 256;   // fvsm_tile_size: texels per tile side
  int maxLevel = 5;     // fvsm_max_level: the finest tiles are 2^max_level per side of the root (5: 32 x 32)
  int maxTiles = 64;    // fvsm_max_tiles: the most leaves (shadow maps) a frame may use
  bool active() const { return enabled; }
};

// Throws InputError naming the key when FVSM is combined with something it cannot serve (cascades, a warp).
void requireFvsmCombination(const FvsmSettings& settings, int cascades, bool warped);

// A light point's light xy (see above).
glm::dvec2 lightXYOf(const LightView& view, const glm::dvec3& pWs);

// The pre-pass: per pixel, -1 where the map is not queried (uncovered, not receiving, out of the light's reach) else
// the required resolution R (texels across `rootRect`), and the query's light xy.
struct FvsmPrepass
{
  int width = 0, height = 0;
  std::vector<double> requiredResolution; // width * height, row 0 at the bottom
  std::vector<glm::dvec2> lightXY;
  int samples = 0;
};

// `rootView`: the focused map (unwarped) over `rootRect`; position and normal as the G-buffer (xyz, w = coverage /
// receives shadows).
FvsmPrepass requiredResolutions(const CameraView& camera, const Light& light, const LightView& rootView,
  const glm::dvec4& rootRect, const ImageF& position, const ImageF& normal);

// Whether texels of `effective` (texels across the root) serve a sample requiring `required`; a relative 1e-9 of
// slack, so a requirement computed as exactly a power of two times the tile's is met.
inline bool resolutionMet(double effective, double required)
{
  return required <= effective * (1.0 + 1e-9);
}

struct FvsmTile
{
  int level = 0;
  glm::ivec2 cell{ 0 };           // its index among the 2^level x 2^level tiles of its level
  glm::dvec4 rect{ 0.0 };         // xMin, xMax, yMin, yMax in light xy
  double requiredResolution = 0;  // the largest R of a sample in it
  double effectiveResolution = 0; // (tile_size - 2 margin) 2^level: texels across the root rectangle
  int samples = 0;
  bool met() const { return resolutionMet(effectiveResolution, requiredResolution); }
};

struct FvsmQuadtree
{
  FvsmSettings settings;
  double marginTexels = 1.0;
  glm::dvec4 rootRect{ 0.0 };
  int gridSize = 1;                       // 2^max_level
  std::vector<double> requiredGrid;       // gridSize^2, row-major from the bottom: the max R per cell, 0 if empty
  std::vector<int> sampleGrid;            // samples per cell
  std::vector<int> tileOfCell;            // the leaf holding each cell, -1 where no sample lies
  std::vector<FvsmTile> tiles;            // by level, then row, then column
  bool budgetReached = false;             // a leaf needed a split that fvsm_max_tiles did not allow
  bool levelReached = false;              // a leaf at max_level still needed more

  // The cell of light xy (clamped to the grid: a point on the root's far edge belongs to the last cell).
  glm::ivec2 cellOf(const glm::dvec2& lightXY) const;
  // The leaf whose rectangle holds light xy, -1 where none (a cell with no sample).
  int tileAt(const glm::dvec2& lightXY) const;
  double effectiveResolution(int level) const;
};

// Scatters the samples into the grid and derives the quadtree: the root splits into its (non-empty) quadrants while
// a sample in it needs more than effectiveResolution(level), worst deficit first, until max_level or max_tiles.
FvsmQuadtree buildFvsmQuadtree(const FvsmPrepass& prepass, const glm::dvec4& rootRect, const FvsmSettings& settings,
  double marginTexels);

// The world-space half-spaces (dot(plane, (pWs, 1)) >= 0 inside) of the points whose light xy lies in rect.
std::vector<glm::dvec4> tileOwnerPlanes(const LightView& rootView, const glm::dvec4& rect);

// The leaf's view: the root's frame and depth range, its rectangle grown so marginTexels of tile_size lie outside.
LightView tileView(const LightView& rootView, const glm::dvec4& rect, int tileSize, double marginTexels);

// The rectangle a focused window (LightView::window, resolution texels, marginTexels of them outside the receivers)
// was grown from (LightView.cpp setWindowAndProjection, unsnapped).
glm::dvec4 receiverRectOf(const glm::dvec4& window, int resolution, double marginTexels);

// A fitted FVSM: the root view (focused on every receiver), the pre-pass, the quadtree and one view per leaf.
struct FittedVirtualShadowMap
{
  LightView rootView;
  FvsmPrepass prepass;
  FvsmQuadtree quadtree;
  std::vector<LightView> views; // one per quadtree tile, same order
  // Per pixel: the leaf whose map it reads (-1 where the map is not queried) and whether its R was met.
  int tileOfPixel(int x, int y) const;
  bool pixelMet(int x, int y) const;
  int unmetPixels() const;
};

// The whole fit: the root focus (fitLightView at tile_size), the pre-pass on the read-back G-buffer, the quadtree and
// the leaves' views.
FittedVirtualShadowMap fitFvsm(const Light& light, const Scene& scene, ReceiverSource& receivers,
  const FocusSettings& focus, const FvsmSettings& settings, const CameraView& camera, const ImageF& position,
  const ImageF& normal);

} // namespace sl
