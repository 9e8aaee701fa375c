// probe.png's layout (probeFigure, probe/Probe.h; drawn by probe/ProbeFigure.cxx): five panels on a
// 1200 x 800 RGB canvas, row 0 at the bottom.
//
//   +------------------+------------------+------------------+
//   | (a) image, pixel | (b) shadow-map   | (c) light plane  |   top row, 400 px tall
//   |     marked       |     crop         |                  |
//   +------------------+------------------+------------------+
//   | (d) cross-section through the light  | (e) key numbers  |   bottom row
//   |     centre and the receiver          |                  |
//   +-------------------------------------+------------------+
//
// Each panel has a title band on top and its content inset below it. Tests and the viewer read the geometry
// from here instead of repeating it.
#pragma once

#include "vis/ColorMap.h"

#include <glm/glm.hpp>

namespace sl
{

inline constexpr int kProbeFigurePanelSide = 400;
inline constexpr int kProbeFigureWidth = 3 * kProbeFigurePanelSide;
inline constexpr int kProbeFigureHeight = 2 * kProbeFigurePanelSide;
// Magenta marks the probed pixel (panel a), its texel (b) and the receiver (d): it is in none of the colour maps.
inline constexpr RgbColor kProbeMarkerColor{ 1.0, 0.0, 1.0 };

enum class ProbePanel
{
  Image,      // (a) frame.image with the pixel marked
  ShadowMap,  // (b) the shadow-map crop (viridis depth, colour bar), kernels, visited nodes, texels read
  LightPlane, // (c) the light's outline, back-projected polygons (diverging signed area), light samples
  Section,    // (d) casters cut by the plane through the light's centre and the receiver, rays, map depth steps
  Legend      // (e) technique, pixel, GPU and twin visibility, tolerance, the record's key quantities
};

struct FigureRect
{
  int left = 0;
  int bottom = 0;
  int width = 0;
  int height = 0;
};
FigureRect probeFigurePanel(ProbePanel panel);

// Where panel (a) draws an image of `imageSize` pixels: scaled by `scale` (the largest that fits, aspect kept,
// nearest-neighbour), centred in the panel's content; image position p (pixels, pixel centres at + 0.5) lands at
// figure position (left, bottom) + p * scale.
struct ImagePlacement
{
  double left = 0.0;
  double bottom = 0.0;
  double scale = 1.0;
  glm::dvec2 figureOf(const glm::dvec2& imagePosition) const { return glm::dvec2(left, bottom) + imagePosition * scale; }
};
ImagePlacement probeImagePlacement(glm::ivec2 imageSize);

} // namespace sl
