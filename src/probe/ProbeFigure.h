// probe.png's layout (probeFigure, probe/Probe.h; drawn by probe/ProbeFigure.cxx): panels of 400 x 400 pixels
// (the section two wide), three to a row, row 0 at the bottom. Only panels with content are laid out (issue 31):
//
//   +------------------+------------------+------------------+
//   | (a) image, pixel | (b) shadow-map   | (c) light plane  |   (b) without a shadow map and (c) without
//   |     marked       |     crop         |                  |   anything recorded on the light are left out
//   +------------------+------------------+------------------+
//   | (d) cross-section through the light  | (e) penumbra     |   the algorithm panels: PCSS's similar triangles
//   |     centre and the receiver          |     estimate     |   (blocker search, average blocker depth,
//   +-------------------------------------+------------------+   penumbra width) and the Chebyshev bound of the
//   | (f) Chebyshev    | (g) key numbers  | (h) key numbers  |   moment techniques (mean, variance, t, p_max),
//   |     bound        |     page 1       |     page 2       |   ESM's exponential, the depth comparisons of
//   +------------------+------------------+------------------+   hard and pcf, lvsm's layers, msm's three-point
//                                                                 distribution, convsm's Fourier series, ss08's
//                                                                 level of quality and levels blended, izb's
//                                                                 light-space texel, where the
//                                                                 record has their quantities; then as many
//                                                                 key-number pages as the record needs.
//
// Panels are lettered in the order they are laid out. Each has a title band on top and its content inset below
// it. Tests and the viewer read the geometry from here instead of repeating it.
#pragma once

#include "core/Image.h"
#include "probe/Probe.h"
#include "vis/ColorMap.h"

#include <glm/glm.hpp>

#include <optional>
#include <string>
#include <vector>

namespace sl
{

inline constexpr int kProbeFigurePanelSide = 400;
inline constexpr int kProbeFigureColumns = 3;
inline constexpr int kProbeFigureWidth = kProbeFigureColumns * kProbeFigurePanelSide;
// Magenta marks the probed pixel (panel a), its texel (b) and the receiver (d): it is in none of the colour maps.
inline constexpr RgbColor kProbeMarkerColor{ 1.0, 0.0, 1.0 };

enum class ProbePanel
{
  Image,      // frame.image with the pixel marked
  ShadowMap,  // the shadow-map crop (viridis depth, colour bar), kernels, visited nodes, texels read, contour edges
  LightPlane, // the light's outline, back-projected polygons and contour edges (diverging signed area), wedges, samples
  Section,    // casters cut by the plane through the light's centre and the receiver, rays, map depth steps
  Penumbra,   // PCSS's similar triangles: light, search plane, average blocker depth, receiver, penumbra width
  Chebyshev,  // the one-tailed Chebyshev bound p_max(t) over t - mean, with the pixel's point
  Exponential, // ESM's exp(-c t) E[exp(c z)] over the normalized compared depth t, with the pixel's point
  Comparisons, // pcf, hard: the texels compared around the lookup, each lit or shadowed, with its stored depth
  Layers,      // lvsm: the layers along depth, the receiver's layer and each layer's Chebyshev bound
  MomentBound, // msm: the Hamburger 4MSM three-point distribution (support z_f, z_2, z_3 and weights) at the receiver
  Fourier,     // convsm: the filtered step's truncated Fourier series around the receiver's depth, its ringing
  LevelBlend,  // ss08: the level of quality, the two levels blended with their weights and each level's visibility
  IrregularTexel, // izb: the sample's light-space texel, its list's length, the triangles tested and covering
  Legend      // technique, pixel, GPU and twin visibility, tolerance, every recorded quantity (one or more pages)
};

struct FigureRect
{
  int left = 0;
  int bottom = 0;
  int width = 0;
  int height = 0;
};

// One laid-out panel: which, its page (key numbers only), letter and place on the figure.
struct ProbeFigurePanel
{
  ProbePanel panel = ProbePanel::Image;
  int page = 0;
  char letter = 'a';
  FigureRect rect;
};

struct ProbeFigureLayout
{
  int width = kProbeFigureWidth;
  int height = 0;
  std::vector<ProbeFigurePanel> panels; // in letter order
  // The panel's rect, none when the figure leaves it out.
  std::optional<FigureRect> rect(ProbePanel panel, int page = 0) const;
  char letter(ProbePanel panel, int page = 0) const; // '?' when left out
  int pages(ProbePanel panel) const;
};

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
ImagePlacement probeImagePlacement(const FigureRect& imagePanel, glm::ivec2 imageSize);

// A text the figure drew, for the tests: on which panel, and whether it lay wholly inside the canvas it was drawn on.
struct ProbeFigureText
{
  std::string text;
  ProbePanel panel = ProbePanel::Image;
  bool inside = true;
};

// A number a diagram computed from the record and drew (the layer the receiver's depth falls in, the lit fraction
// of the compared texels): the tests hold it against the recorded quantity or the GPU's buffer.
struct ProbeDrawnValue
{
  ProbePanel panel = ProbePanel::Image;
  std::string name;
  double value = 0.0;
};

// The figure and what went into it.
struct ProbeFigureDrawing
{
  ImageU8 image;
  ProbeFigureLayout layout;
  std::vector<ProbeFigureText> texts;         // every text drawn, in order
  std::vector<std::string> legendLines;       // the key numbers' lines before wrapping, each drawn in full
  std::vector<std::vector<std::string>> colorBarTicks; // each colour bar's tick labels, bottom to top
  std::vector<ProbeDrawnValue> drawnValues;   // what the algorithm diagrams computed and drew
  // The first drawn value called `name` on `panel`, none when not drawn.
  std::optional<double> drawnValue(ProbePanel panel, const std::string& name) const;
};
ProbeFigureDrawing drawProbeFigure(const ProbeResult& probe, const FrameResult& frame, const Scene& scene);

// The legend's text for a recorded quantity: "name value unit".
std::string probeQuantityText(const ProbeQuantity& quantity);

} // namespace sl
