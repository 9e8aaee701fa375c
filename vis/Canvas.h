// Drawing onto an RGB canvas: an sl::ImageU8 with 3 components, row 0 = bottom (the Image convention), so
// every (left, bottom) below is measured from the canvas' bottom-left corner. Everything is clipped to the
// canvas. Text goes through VTK's vtkTextRenderer (FreeType, no graphics context needed); the program must link
// VTK::RenderingFreeType and run vtk_module_autoinit so that its renderer is registered.
#pragma once

#include "core/Image.h"
#include "vis/ColorMap.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace sl
{

inline constexpr RgbColor kWhite{ 1.0, 1.0, 1.0 };
inline constexpr RgbColor kBlack{ 0.0, 0.0, 0.0 };

// [0, 1] components to 8 bits, rounded to nearest (values outside [0, 1] are clamped).
std::array<std::uint8_t, 3> toRgb8(const RgbColor& color);

void fillRect(ImageU8& canvas, int left, int bottom, int width, int height, const RgbColor& color);
// A border `lineWidthPx` thick drawn inside the rectangle.
void strokeRect(
  ImageU8& canvas, int left, int bottom, int width, int height, const RgbColor& color, int lineWidthPx = 1);

struct TextSize
{
  int width = 0;
  int height = 0; // the font's line height (ascent + descent), the same for every string of one font size
};

// The size of `text` rendered at `fontPx` pixels (font size in points at 72 dpi).
TextSize measureText(const std::string& text, int fontPx);

// `text` broken into lines no wider than widthPx at fontPx: at spaces where a word fits, else after the word's last
// '_' or '=' that fits, else between characters. Never empty (an empty text is one empty line).
std::vector<std::string> wrapText(const std::string& text, int widthPx, int fontPx);

// Draws `text` (bold Courier, `fontPx` pixels) with its box's bottom-left at (left, bottom), alpha-blended.
void drawText(
  ImageU8& canvas, const std::string& text, int fontPx, int left, int bottom, const RgbColor& color = kBlack);

} // namespace sl
