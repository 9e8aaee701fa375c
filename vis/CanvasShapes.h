// Lines, polygons and dots on an RGB canvas (vis/Canvas.h: an ImageU8 with 3 components, row 0 at the bottom,
// everything clipped to the canvas), for figures that draw geometry (probe.png). Coordinates are continuous
// canvas coordinates: pixel (x, y) covers [x, x + 1] x [y, y + 1], its centre is (x + 0.5, y + 0.5); a pixel is
// painted when its centre is inside the shape. No anti-aliasing: exact colours stay testable.
#pragma once

#include "core/Image.h"
#include "vis/ColorMap.h"

#include <glm/glm.hpp>

#include <vector>

namespace sl
{

// A segment `widthPx` wide with round caps: every pixel whose centre lies within max(widthPx, 1) / 2 of it (a
// 1-pixel line has no gaps: each column or row it spans has a centre that near). `opacity` blends over what is
// there.
void drawLine(ImageU8& canvas, const glm::dvec2& a, const glm::dvec2& b, const RgbColor& color, double widthPx = 1.0,
  double opacity = 1.0);
// The same, drawn as dashes `dashPx` long with gaps as long.
void drawDashedLine(
  ImageU8& canvas, const glm::dvec2& a, const glm::dvec2& b, const RgbColor& color, double widthPx, double dashPx);

// A simple or self-intersecting polygon filled with the even-odd rule, blended with `opacity`.
void fillPolygon(ImageU8& canvas, const std::vector<glm::dvec2>& points, const RgbColor& color, double opacity = 1.0);
// Its closed outline.
void strokePolygon(ImageU8& canvas, const std::vector<glm::dvec2>& points, const RgbColor& color, double widthPx = 1.0);

// Every pixel whose centre lies within `radiusPx` of `centre`.
void fillDisk(ImageU8& canvas, const glm::dvec2& centre, double radiusPx, const RgbColor& color);

// Copies `source` into `canvas` with its bottom-left pixel at (left, bottom), clipped.
void blit(ImageU8& canvas, const ImageU8& source, int left, int bottom);

} // namespace sl
