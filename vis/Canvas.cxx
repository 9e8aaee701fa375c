#include "vis/Canvas.h"

#include "core/Error.h"

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkStdString.h>
#include <vtkTextProperty.h>
#include <vtkTextRenderer.h>

#include <algorithm>
#include <cmath>

namespace sl
{

namespace
{

// Font sizes are given in points; at 72 dpi one point is one pixel.
constexpr int kTextDpi = 72;

vtkTextRenderer& textRenderer()
{
  vtkTextRenderer* renderer = vtkTextRenderer::GetInstance();
  SL_CHECK_MSG(renderer != nullptr,
    "no vtkTextRenderer registered: link VTK::RenderingFreeType and call vtk_module_autoinit");
  return *renderer;
}

void configureFont(vtkTextProperty& font, int fontPx, const RgbColor& color)
{
  // Courier, not Arial: VTK 9.1's embedded Arial draws '[' and ']' as round parentheses. Bold stays legible
  // at 12 px.
  font.SetFontFamilyToCourier();
  font.SetBold(true);
  font.SetFontSize(fontPx);
  font.SetColor(color[0], color[1], color[2]);
  font.SetJustificationToLeft();
  font.SetVerticalJustificationToBottom();
}

std::uint8_t blend(std::uint8_t background, double foreground, double alpha)
{
  return static_cast<std::uint8_t>(std::lround((1.0 - alpha) * background + alpha * 255.0 * foreground));
}

} // namespace

std::array<std::uint8_t, 3> toRgb8(const RgbColor& color)
{
  std::array<std::uint8_t, 3> rgb8{};
  for (int c = 0; c < 3; ++c)
    rgb8[c] = static_cast<std::uint8_t>(std::lround(std::clamp(color[c], 0.0, 1.0) * 255.0));
  return rgb8;
}

void fillRect(ImageU8& canvas, int left, int bottom, int width, int height, const RgbColor& color)
{
  SL_CHECK(canvas.components == 3);
  const auto rgb8 = toRgb8(color);
  const int xEnd = std::min(left + width, canvas.width);
  const int yEnd = std::min(bottom + height, canvas.height);
  for (int y = std::max(bottom, 0); y < yEnd; ++y)
    for (int x = std::max(left, 0); x < xEnd; ++x)
      for (int c = 0; c < 3; ++c)
        canvas.at(x, y, c) = rgb8[c];
}

void strokeRect(
  ImageU8& canvas, int left, int bottom, int width, int height, const RgbColor& color, int lineWidthPx)
{
  fillRect(canvas, left, bottom, width, lineWidthPx, color);
  fillRect(canvas, left, bottom + height - lineWidthPx, width, lineWidthPx, color);
  fillRect(canvas, left, bottom, lineWidthPx, height, color);
  fillRect(canvas, left + width - lineWidthPx, bottom, lineWidthPx, height, color);
}

TextSize measureText(const std::string& text, int fontPx)
{
  if (text.empty())
    return {};
  vtkNew<vtkTextProperty> font;
  configureFont(*font, fontPx, kBlack);
  int bounds[4] = { 0, 0, 0, 0 }; // xmin, xmax, ymin, ymax, inclusive
  SL_CHECK_MSG(textRenderer().GetBoundingBox(font, vtkStdString(text), bounds, kTextDpi),
    "cannot measure text '", text, "'");
  return { bounds[1] - bounds[0] + 1, bounds[3] - bounds[2] + 1 };
}

void drawText(ImageU8& canvas, const std::string& text, int fontPx, int left, int bottom, const RgbColor& color)
{
  SL_CHECK(canvas.components == 3);
  if (text.empty())
    return;
  vtkNew<vtkTextProperty> font;
  configureFont(*font, fontPx, color);
  vtkNew<vtkImageData> glyphs;
  int textSize[2] = { 0, 0 };
  SL_CHECK_MSG(textRenderer().RenderString(font, vtkStdString(text), glyphs, textSize, kTextDpi),
    "cannot render text '", text, "'");

  // The renderer returns RGBA unsigned chars, row 0 = bottom like the canvas, with the text in the
  // bottom-left textSize[0] x textSize[1] pixels (the rest is padding up to a power of two). Alpha is the
  // glyph coverage; blend the text colour with it.
  SL_CHECK(glyphs->GetScalarType() == VTK_UNSIGNED_CHAR && glyphs->GetNumberOfScalarComponents() == 4);
  const int* extent = glyphs->GetExtent();
  for (int ty = 0; ty < textSize[1]; ++ty)
  {
    const int y = bottom + ty;
    if (y < 0 || y >= canvas.height)
      continue;
    const auto* row =
      static_cast<const std::uint8_t*>(glyphs->GetScalarPointer(extent[0], extent[2] + ty, extent[4]));
    for (int tx = 0; tx < textSize[0]; ++tx)
    {
      const int x = left + tx;
      const double alpha = row[4 * tx + 3] / 255.0;
      if (x < 0 || x >= canvas.width || alpha == 0.0)
        continue;
      for (int c = 0; c < 3; ++c)
        canvas.at(x, y, c) = blend(canvas.at(x, y, c), color[c], alpha);
    }
  }
}

std::vector<std::string> wrapText(const std::string& text, int widthPx, int fontPx)
{
  std::vector<std::string> lines;
  std::string line;
  const auto fits = [&](const std::string& candidate) { return measureText(candidate, fontPx).width <= widthPx; };
  std::size_t at = 0;
  while (at < text.size())
  {
    const std::size_t space = text.find(' ', at);
    const std::string word = text.substr(at, space == std::string::npos ? std::string::npos : space - at);
    at = space == std::string::npos ? text.size() : space + 1;
    if (word.empty())
      continue;
    const std::string joined = line.empty() ? word : line + " " + word;
    if (fits(joined))
    {
      line = joined;
      continue;
    }
    if (!line.empty())
      lines.push_back(line);
    line.clear();
    // A word wider than the column: broken after its last '_' or '=' that fits (bias_constant_ / texels=0.5),
    // else between characters (at least one per line).
    std::string rest = word;
    while (!fits(rest))
    {
      std::size_t fitting = 1;
      while (fitting < rest.size() && fits(rest.substr(0, fitting + 1)))
        ++fitting;
      const std::size_t separator = rest.find_last_of("_=", fitting - 1);
      const std::size_t cut = separator != std::string::npos && separator + 1 < fitting ? separator + 1 : fitting;
      lines.push_back(rest.substr(0, cut));
      rest.erase(0, cut);
    }
    line = rest;
  }
  if (!line.empty() || lines.empty())
    lines.push_back(line);
  return lines;
}

} // namespace sl
