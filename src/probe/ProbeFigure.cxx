// probe.png (probe/Probe.h, layout in probe/ProbeFigure.h): what a probe recorded, drawn on a CPU canvas (vis/Canvas.h,
// vis/CanvasShapes.h), so it renders the same with or without a graphics context. Magnitudes (depths) use
// viridis (perceptually uniform), signed areas the diverging blue-white-red map (ColorBrewer RdBu: colour-blind
// safe), categories (node decisions) the Tableau 10 palette; marks that must read without colour (occluding or
// read texels, blocked or visible samples) differ in shape or fill as well.
#include "probe/ProbeFigure.h"

#include "lightspace/LayeredMoments.h"
#include "probe/Probe.h"
#include "probe/ProbeGeometry.h"
#include "vis/Canvas.h"
#include "vis/CanvasShapes.h"
#include "vis/ColorKey.h"
#include "vis/ColorMap.h"
#include "vis/HeatMap.h"
#include "vis/NumberText.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <string>
#include <vector>

namespace sl
{
namespace
{

constexpr int kTitleFontPx = 14;
constexpr int kBodyFontPx = 12;
constexpr int kInsetPx = 8;
constexpr int kTitleBandPx = 26;
constexpr int kKeyLinePx = 17; // one line of a panel's key at kBodyFontPx

constexpr RgbColor kPanelBorder{ 0.75, 0.75, 0.75 };
constexpr RgbColor kDarkGrey{ 0.3, 0.3, 0.3 };
constexpr RgbColor kLightGrey{ 0.65, 0.65, 0.65 };
constexpr RgbColor kLightColor{ 1.0, 0.85, 0.2 };      // the light's extent (gold)
constexpr RgbColor kRayColor{ 0.84, 0.15, 0.16 };       // rays to the light's ends
constexpr RgbColor kDepthStepColor{ 1.0, 0.5, 0.05 };   // the shadow map's stored depths in the section
constexpr RgbColor kCasterColor{ 0.12, 0.12, 0.12 };
constexpr RgbColor kContourColor{ 0.0, 0.75, 0.85 };    // contour edges in the map (cyan: not in viridis' range)
constexpr RgbColor kSearchColor{ 0.84, 0.15, 0.16 };    // PCSS's blocker search
constexpr RgbColor kPenumbraColor{ 0.12, 0.47, 0.71 };  // PCSS's penumbra estimate

// A panel-local rectangle in continuous pixel coordinates.
struct Box
{
  double left = 0.0;
  double bottom = 0.0;
  double width = 0.0;
  double height = 0.0;
};

Box contentBox(const FigureRect& panel)
{
  return { double(kInsetPx), double(kInsetPx), double(panel.width - 2 * kInsetPx),
    double(panel.height - 2 * kInsetPx - kTitleBandPx) };
}

std::string numberText(double value, int digits = 4)
{
  return readableNumber(value, digits);
}

// What the figure being drawn wrote (ProbeFigureDrawing::texts): the tests check from it that nothing was cut.
struct FigureTextLog
{
  std::vector<ProbeFigureText>* texts = nullptr;
  std::vector<ProbeDrawnValue>* drawn = nullptr;
  ProbePanel panel = ProbePanel::Image;
};
thread_local FigureTextLog tFigureTextLog;

// drawText, logged with whether the text lies wholly inside `canvas`.
void putText(ImageU8& canvas, const std::string& text, int fontPx, int x, int y, const RgbColor& color = kBlack)
{
  drawText(canvas, text, fontPx, x, y, color);
  if (tFigureTextLog.texts != nullptr && !text.empty())
  {
    const TextSize size = measureText(text, fontPx);
    const bool inside = x >= 0 && y >= 0 && x + size.width <= canvas.width && y + size.height <= canvas.height;
    tFigureTextLog.texts->push_back({ text, tFigureTextLog.panel, inside });
  }
}

int textWidth(const std::string& text, int fontPx)
{
  return measureText(text, fontPx).width;
}

// The largest font size from `fontPx` down to 9 at which `text` fits `maxWidthPx` (titles shrink rather than lose
// their end).
int fittingFontPx(const std::string& text, int fontPx, int maxWidthPx)
{
  while (fontPx > 9 && textWidth(text, fontPx) > maxWidthPx)
  {
    --fontPx;
  }
  return fontPx;
}

// Breaks `text` at spaces into lines of at most `maxWidthPx`.
std::vector<std::string> wrapText(const std::string& text, int fontPx, int maxWidthPx)
{
  const int charWidth = std::max(1, (textWidth("MMMMMMMMMM", fontPx) + 9) / 10);
  const std::size_t maxChars = static_cast<std::size_t>(std::max(8, maxWidthPx / charWidth));
  std::vector<std::string> lines;
  std::string line;
  std::size_t start = 0;
  while (start <= text.size())
  {
    std::size_t end = text.find(' ', start);
    if (end == std::string::npos)
    {
      end = text.size();
    }
    std::string word = text.substr(start, end - start);
    while (word.size() > maxChars)
    {
      if (!line.empty())
      {
        lines.push_back(line);
        line.clear();
      }
      lines.push_back(word.substr(0, maxChars));
      word = word.substr(maxChars);
    }
    if (!line.empty() && line.size() + 1 + word.size() > maxChars)
    {
      lines.push_back(line);
      line.clear();
    }
    line += (line.empty() ? "" : " ") + word;
    start = end + 1;
  }
  if (!line.empty())
  {
    lines.push_back(line);
  }
  return lines;
}

ImageU8 newPanel(const FigureRect& rect, const std::string& title)
{
  ImageU8 panel(rect.width, rect.height, 3, 255);
  strokeRect(panel, 0, 0, rect.width, rect.height, kPanelBorder, 1);
  const int fontPx = fittingFontPx(title, kTitleFontPx, rect.width - 2 * kInsetPx);
  const int textHeight = measureText("Ag", fontPx).height;
  putText(panel, title, fontPx, kInsetPx, rect.height - kTitleBandPx + (kTitleBandPx - textHeight) / 2, kBlack);
  return panel;
}

// A note centred in `box`, wrapped to its width.
void drawCentredNote(ImageU8& panel, const Box& box, const std::string& note)
{
  const std::vector<std::string> lines = wrapText(note, kBodyFontPx, int(box.width));
  const int lineHeight = measureText("Ag", kBodyFontPx).height + 2;
  int y = int(box.bottom + 0.5 * (box.height + lines.size() * lineHeight)) - lineHeight;
  for (const std::string& line : lines)
  {
    const TextSize size = measureText(line, kBodyFontPx);
    putText(panel, line, kBodyFontPx, int(box.left + std::max(0.0, 0.5 * (box.width - size.width))), y, kDarkGrey);
    y -= lineHeight;
  }
}

// A 2-D region mapped to a box with equal scales on both axes, centred.
struct View2D
{
  glm::dvec2 centre{ 0.0 };
  glm::dvec2 boxCentre{ 0.0 };
  double scale = 1.0;
  glm::dvec2 toPx(const glm::dvec2& p) const { return boxCentre + (p - centre) * scale; }
};

View2D fitView(glm::dvec2 lo, glm::dvec2 hi, const Box& box, double marginFraction)
{
  glm::dvec2 extent = hi - lo;
  const double largest = std::max({ extent.x, extent.y, 1e-12 });
  extent = glm::max(extent, glm::dvec2(1e-3 * largest)) * (1.0 + 2.0 * marginFraction);
  View2D view;
  view.centre = 0.5 * (lo + hi);
  view.boxCentre = glm::dvec2(box.left + 0.5 * box.width, box.bottom + 0.5 * box.height);
  view.scale = std::min(box.width / extent.x, box.height / extent.y);
  return view;
}

// Magenta on black, so it reads on any background: a square of half side `halfPx` and four arms.
void drawMarker(ImageU8& canvas, const glm::dvec2& centre, double halfPx)
{
  const double armStart = halfPx + 3.0;
  const double armEnd = armStart + 10.0;
  const glm::dvec2 corners[4] = { centre + glm::dvec2(-halfPx, -halfPx), centre + glm::dvec2(halfPx, -halfPx),
    centre + glm::dvec2(halfPx, halfPx), centre + glm::dvec2(-halfPx, halfPx) };
  const glm::dvec2 directions[4] = { { 1, 0 }, { -1, 0 }, { 0, 1 }, { 0, -1 } };
  for (const auto& [color, width] : { std::pair<RgbColor, double>{ kBlack, 4.0 }, { kProbeMarkerColor, 2.0 } })
  {
    for (int i = 0; i < 4; ++i)
    {
      drawLine(canvas, corners[i], corners[(i + 1) % 4], color, width);
      drawLine(canvas, centre + directions[i] * armStart, centre + directions[i] * armEnd, color, width);
    }
  }
}

// One entry of a panel's key: a small sample of the mark, then its label; returns the x after it.
using SwatchPainter = void (*)(ImageU8&, const glm::dvec2&, const RgbColor&);
int drawKeyEntry(ImageU8& panel, int x, int y, const std::string& label, SwatchPainter paint, const RgbColor& color)
{
  paint(panel, glm::dvec2(x + 7.0, y + 7.0), color);
  putText(panel, label, kBodyFontPx, x + 17, y, kBlack);
  return x + 17 + textWidth(label, kBodyFontPx) + 12;
}

// The diverging map's negative end: a contour edge's swatch.
RgbColor areaColorKeySample(const ColorMap& diverging)
{
  return diverging.map(0.1);
}

// A panel's key: entries flowed left to right and wrapped to the panel's width, every label in full.
struct KeyEntry
{
  std::string label;
  SwatchPainter paint = nullptr; // nullptr: a line of text (grey), no swatch
  RgbColor color = kBlack;
};

int keyEntryWidth(const KeyEntry& entry)
{
  return (entry.paint != nullptr ? 17 : 0) + textWidth(entry.label, kBodyFontPx) + 12;
}

// The entries as lines of (entry, x offset); an entry wider than the line gets its label wrapped into text lines.
std::vector<std::vector<std::pair<KeyEntry, int>>> keyRows(const std::vector<KeyEntry>& entries, int widthPx)
{
  std::vector<std::vector<std::pair<KeyEntry, int>>> rows(1);
  int x = 0;
  for (const KeyEntry& entry : entries)
  {
    const int width = keyEntryWidth(entry);
    if (width - 12 > widthPx || entry.paint == nullptr)
    {
      if (!rows.back().empty())
      {
        rows.emplace_back();
      }
      const int swatch = entry.paint != nullptr ? 17 : 0;
      bool first = true;
      for (const std::string& line : wrapText(entry.label, kBodyFontPx, widthPx - swatch))
      {
        if (!first)
        {
          rows.emplace_back();
        }
        rows.back().push_back({ KeyEntry{ line, first ? entry.paint : nullptr, entry.color }, first ? 0 : swatch });
        first = false;
      }
      rows.emplace_back();
      x = 0;
      continue;
    }
    if (x > 0 && x + width - 12 > widthPx)
    {
      rows.emplace_back();
      x = 0;
    }
    rows.back().push_back({ entry, x });
    x += width;
  }
  if (rows.back().empty())
  {
    rows.pop_back();
  }
  return rows;
}

int keyHeight(const std::vector<KeyEntry>& entries, int widthPx)
{
  return static_cast<int>(keyRows(entries, widthPx).size()) * kKeyLinePx + 4;
}

// Draws the key with its first line's bottom at `top` - kKeyLinePx.
void drawKey(ImageU8& panel, const std::vector<KeyEntry>& entries, int left, int top, int widthPx)
{
  int y = top - kKeyLinePx;
  for (const auto& row : keyRows(entries, widthPx))
  {
    for (const auto& [entry, x] : row)
    {
      if (entry.paint != nullptr)
      {
        drawKeyEntry(panel, left + x, y, entry.label, entry.paint, entry.color);
      }
      else
      {
        putText(panel, entry.label, kBodyFontPx, left + x, y, x > 0 ? kBlack : kDarkGrey);
      }
    }
    y -= kKeyLinePx;
  }
}

// A vertical colour bar from `valueMin` (bottom) to `valueMax` (top): the heat maps' key (vis/ColorKey.h), so its
// ticks get the digits to differ as theirs do. colorBarWidth is its width; drawColorBar returns the tick labels.
int colorBarWidth(const ColorMap& colorMap, double valueMin, double valueMax)
{
  return ColorKey::continuous(colorMap, valueMin, valueMax, kBodyFontPx).width();
}

std::vector<std::string> drawColorBar(ImageU8& panel, const ColorMap& colorMap, double valueMin, double valueMax,
  int left, int bottom, int height)
{
  const ColorKey key = ColorKey::continuous(colorMap, valueMin, valueMax, kBodyFontPx);
  key.draw(panel, left, bottom, std::max(height, key.minHeight()));
  return key.tickLabels();
}

void paintLineSwatch(ImageU8& canvas, const glm::dvec2& c, const RgbColor& color)
{
  drawLine(canvas, c - glm::dvec2(7, 0), c + glm::dvec2(7, 0), color, 3.0);
}

void paintBoxSwatch(ImageU8& canvas, const glm::dvec2& c, const RgbColor& color)
{
  strokePolygon(canvas, { c + glm::dvec2(-6, -6), c + glm::dvec2(6, -6), c + glm::dvec2(6, 6), c + glm::dvec2(-6, 6) },
    kBlack, 4.0);
  strokePolygon(canvas, { c + glm::dvec2(-6, -6), c + glm::dvec2(6, -6), c + glm::dvec2(6, 6), c + glm::dvec2(-6, 6) },
    color, 2.0);
}

void paintFilledSquare(ImageU8& canvas, const glm::dvec2& c, const RgbColor& color)
{
  fillPolygon(canvas, { c + glm::dvec2(-5, -5), c + glm::dvec2(5, -5), c + glm::dvec2(5, 5), c + glm::dvec2(-5, 5) }, kBlack);
  fillPolygon(canvas, { c + glm::dvec2(-4, -4), c + glm::dvec2(4, -4), c + glm::dvec2(4, 4), c + glm::dvec2(-4, 4) }, color);
}

void paintDot(ImageU8& canvas, const glm::dvec2& c, const RgbColor& color)
{
  fillDisk(canvas, c, 4.0, kBlack);
  fillDisk(canvas, c, 2.5, color);
}

// The marker's square alone (its arms would run into the label).
void paintMarkerSwatch(ImageU8& canvas, const glm::dvec2& c, const RgbColor& color)
{
  const std::vector<glm::dvec2> square = { c + glm::dvec2(-4, -4), c + glm::dvec2(4, -4), c + glm::dvec2(4, 4),
    c + glm::dvec2(-4, 4) };
  strokePolygon(canvas, square, kBlack, 4.0);
  strokePolygon(canvas, square, color, 2.0);
}

// --- (a) the image with the pixel marked -----------------------------------------------------------------------

// "(b) " for the panel's letter.
std::string panelTag(char letter)
{
  return std::string("(") + letter + ") ";
}

ImageU8 imagePanel(const ProbeResult& probe, const FrameResult& frame, const FigureRect& rect, char letter)
{
  ImageU8 panel = newPanel(rect, format(panelTag(letter), "image ", frame.image.width, "x", frame.image.height, ", pixel ",
    probe.pixel.x, ",", probe.pixel.y));
  const Box box = contentBox(rect);
  if (frame.image.empty() || frame.image.components < 3)
  {
    drawCentredNote(panel, box, "no shaded image in this frame");
    return panel;
  }
  const ImagePlacement placement = probeImagePlacement(rect, { frame.image.width, frame.image.height });
  const double left = placement.left - rect.left;
  const double bottom = placement.bottom - rect.bottom;
  const int xEnd = int(std::ceil(left + frame.image.width * placement.scale));
  const int yEnd = int(std::ceil(bottom + frame.image.height * placement.scale));
  for (int y = int(std::floor(bottom)); y < yEnd; ++y)
  {
    for (int x = int(std::floor(left)); x < xEnd; ++x)
    {
      // Nearest neighbour: the image pixel under this canvas pixel's centre.
      const int ix = int(std::floor((x + 0.5 - left) / placement.scale));
      const int iy = int(std::floor((y + 0.5 - bottom) / placement.scale));
      if (ix < 0 || iy < 0 || ix >= frame.image.width || iy >= frame.image.height || x < 0 || y < 0 ||
        x >= panel.width || y >= panel.height)
      {
        continue;
      }
      for (int c = 0; c < 3; ++c)
      {
        panel.at(x, y, c) = frame.image.at(ix, iy, c);
      }
    }
  }
  const glm::dvec2 centre = glm::dvec2(left, bottom) + (glm::dvec2(probe.pixel) + 0.5) * placement.scale;
  drawMarker(panel, centre, std::max(0.5 * placement.scale + 2.0, 5.0));
  return panel;
}

// --- (b) the shadow-map crop ------------------------------------------------------------------------------------

// The crop of the shadow map drawn at `scale` pixels a texel, and where a texel position lands on it.
struct CropCanvas
{
  ImageU8 map;
  double scale = 1.0;
  glm::ivec2 cropLo{ 0 };

  glm::dvec2 toMap(const glm::dvec2& uvTexels) const { return (uvTexels - glm::dvec2(cropLo)) * scale; }
  std::vector<glm::dvec2> rectangle(const glm::dvec2& lo, const glm::dvec2& hi) const
  {
    const glm::dvec2 a = toMap(lo);
    const glm::dvec2 b = toMap(hi);
    return { a, { b.x, a.y }, b, { a.x, b.y } };
  }
};

// The crop's depths on viridis (texels without a caster in kInvalidPixelColor), on a canvas of their own so that
// rectangles reaching past the crop (an HSM's root node) are clipped to it.
CropCanvas paintDepthCrop(const ProbeCropArrays& arrays, const TexelRect& crop, const ImageU8& valid,
  const ValueRange& range, const ColorMap& viridis, double scale)
{
  CropCanvas canvas;
  canvas.scale = scale;
  canvas.cropLo = crop.lo;
  const int drawnWidth = std::max(1, int(std::floor(crop.size.x * scale)));
  const int drawnHeight = std::max(1, int(std::floor(crop.size.y * scale)));
  canvas.map = ImageU8(drawnWidth, drawnHeight, 3);
  for (int y = 0; y < drawnHeight; ++y)
  {
    for (int x = 0; x < drawnWidth; ++x)
    {
      const int tx = std::min(crop.size.x - 1, int((x + 0.5) / scale));
      const int ty = std::min(crop.size.y - 1, int((y + 0.5) / scale));
      const RgbColor color = valid.at(tx, ty) ? viridis.map((arrays.depth.at(tx, ty) - range.min) / (range.max - range.min))
                                              : kInvalidPixelColor;
      const auto rgb8 = toRgb8(color);
      for (int c = 0; c < 3; ++c)
      {
        canvas.map.at(x, y, c) = rgb8[c];
      }
    }
  }
  return canvas;
}

// The hierarchy nodes the probe visited, largest first so the finer ones stay visible, coloured by decision; then
// the kernels, white on black.
void drawNodesAndKernels(CropCanvas& canvas, const ProbeRecord& record, const std::vector<std::string>& decisions)
{
  std::vector<std::size_t> order(record.nodes.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  const auto nodeArea = [&](const ProbeNode& node) {
    return (double(node.hi.x) - node.lo.x + 1.0) * (double(node.hi.y) - node.lo.y + 1.0);
  };
  std::stable_sort(order.begin(), order.end(),
    [&](std::size_t a, std::size_t b) { return nodeArea(record.nodes[a]) > nodeArea(record.nodes[b]); });
  for (const std::size_t n : order)
  {
    const ProbeNode& node = record.nodes[n];
    strokePolygon(canvas.map, canvas.rectangle(glm::dvec2(node.lo), glm::dvec2(node.hi) + 1.0),
      ColorMap::categoryColor(labelCode(decisions, node.decision)), 2.0);
  }
  for (const ProbeKernel& kernel : record.kernels)
  {
    strokePolygon(canvas.map, canvas.rectangle(kernel.lo, kernel.hi), kBlack, 4.0);
    strokePolygon(canvas.map, canvas.rectangle(kernel.lo, kernel.hi), kWhite, 2.0);
  }
}

// Texels read: a small white dot with a black rim; occluding ones a larger black square with a white rim (size and
// fill, not colour, tell them apart). Sized to the texel, at least a few pixels.
void drawTexelsRead(CropCanvas& canvas, const ProbeCropArrays& arrays, const TexelRect& crop)
{
  const double dotRadius = std::max(1.5, 0.12 * canvas.scale);
  const double squareHalf = std::max(2.0, 0.28 * canvas.scale);
  const auto square = [&](const glm::dvec2& c, double half) {
    return std::vector<glm::dvec2>{ c + glm::dvec2(-half, -half), c + glm::dvec2(half, -half), c + glm::dvec2(half, half),
      c + glm::dvec2(-half, half) };
  };
  for (int y = 0; y < crop.size.y; ++y)
  {
    for (int x = 0; x < crop.size.x; ++x)
    {
      if (!arrays.read.at(x, y))
      {
        continue;
      }
      const glm::dvec2 c = canvas.toMap(glm::dvec2(crop.lo) + glm::dvec2(x + 0.5, y + 0.5));
      if (arrays.occluding.at(x, y))
      {
        fillPolygon(canvas.map, square(c, squareHalf + 1.0), kWhite);
        fillPolygon(canvas.map, square(c, squareHalf), kBlack);
      }
      else
      {
        fillDisk(canvas.map, c, dotRadius + 1.0, kBlack);
        fillDisk(canvas.map, c, dotRadius, kWhite);
      }
    }
  }
}

// The key below the map: the marks, then every node decision (categorical colours) in full, then the crop's texel
// range.
std::vector<KeyEntry> shadowMapKey(const ProbeRecord& record, const std::vector<std::string>& decisions,
  const TexelRect& crop, int mapWidth)
{
  std::vector<KeyEntry> entries = { { "kernel", paintBoxSwatch, kWhite }, { "read", paintDot, kWhite },
    { "occluding", paintFilledSquare, kBlack }, { "receiver", paintMarkerSwatch, kProbeMarkerColor } };
  if (!record.mapPolygons.empty())
  {
    entries.push_back({ "pixel", paintBoxSwatch, kProbeMarkerColor });
  }
  if (!record.contourEdges.empty())
  {
    entries.push_back({ "contour edge", paintLineSwatch, kContourColor });
  }
  for (std::size_t d = 0; d < decisions.size(); ++d)
  {
    entries.push_back({ decisions[d], paintBoxSwatch, ColorMap::categoryColor(long(d)) });
  }
  entries.push_back({ format("texels ", crop.lo.x, "..", crop.lo.x + crop.size.x - 1, " x ", crop.lo.y, "..",
    crop.lo.y + crop.size.y - 1, " of ", mapWidth), nullptr, kDarkGrey });
  return entries;
}

// The contour edges the technique found (their shadow-map texel coordinates), over the crop.
void drawContourEdgesInMap(CropCanvas& canvas, const ProbeRecord& record)
{
  for (const ProbeContourEdge& edge : record.contourEdges)
  {
    drawLine(canvas.map, canvas.toMap(edge.a), canvas.toMap(edge.b), kBlack, 4.0);
    drawLine(canvas.map, canvas.toMap(edge.a), canvas.toMap(edge.b), kContourColor, 2.0);
  }
}

ImageU8 shadowMapPanel(const ProbeResult& probe, const ProbeSetting& setting, const FigureRect& rect, char letter,
  std::vector<std::vector<std::string>>& colorBarTicks)
{
  // With views that partition the pixels (cascades) the map is the pixel's own view's, named in the title.
  const ProbeMap& map = setting.map;
  ImageU8 panel = newPanel(rect, panelTag(letter) + (map.label.empty() ? std::string("shadow map: linear depth [world units]")
      : map.exportName + ", linear depth"));
  const Box box = contentBox(rect);
  const ImageF* depthMap = map.depth;
  if (depthMap == nullptr || map.view == nullptr)
  {
    drawCentredNote(panel, box, "no shadow map in this frame");
    return panel;
  }
  const LightView& view = *map.view;
  const ProbeRecord& record = probe.record;
  const TexelRect crop = probeShadowMapCrop(record, setting.receiver.uvTexels, depthMap->width);
  if (crop.empty())
  {
    drawCentredNote(panel, box, "nothing recorded in the shadow map");
    return panel;
  }
  const ProbeCropArrays arrays = probeCropArrays(record, *depthMap, crop);

  // Colour range over the crop's texels that hold a caster.
  ImageU8 valid(arrays.depth.width, arrays.depth.height, 1, 0);
  for (std::size_t i = 0; i < arrays.depth.pixelCount(); ++i)
  {
    valid.data[i] = isEmptyShadowMapTexel(view, arrays.depth.data[i]) ? 0 : 1;
  }
  HeatMapOptions options;
  options.colorMap = ColorMapKind::Viridis;
  const ValueRange range = colorMapRange(validValueRange(arrays.depth, &valid), options);
  const ColorMap viridis(ColorMapKind::Viridis);
  const int barWidth = colorBarWidth(viridis, range.min, range.max);

  // Layout: the map on the left, its colour bar on the right, the key below, the view's label above.
  const std::vector<std::string> decisions = nodeDecisionLabels(record);
  const std::vector<KeyEntry> keyEntries = shadowMapKey(record, decisions, crop, depthMap->width);
  const double keyBand = keyHeight(keyEntries, int(box.width));
  const std::vector<std::string> labelLines =
    map.label.empty() ? std::vector<std::string>() : wrapText(map.label, kBodyFontPx, int(box.width));
  const double labelBand = labelLines.size() * double(kKeyLinePx) + (labelLines.empty() ? 0.0 : 2.0);
  const Box mapBox{ box.left, box.bottom + keyBand, box.width - barWidth - 6.0, box.height - keyBand - labelBand };
  const double scale = std::min(mapBox.width / crop.size.x, mapBox.height / crop.size.y);
  colorBarTicks.push_back(drawColorBar(panel, viridis, range.min, range.max, int(mapBox.left + mapBox.width + 6.0),
    int(mapBox.bottom), int(mapBox.height)));

  CropCanvas canvas = paintDepthCrop(arrays, crop, valid, range, viridis, scale);
  drawNodesAndKernels(canvas, record, decisions);
  drawTexelsRead(canvas, arrays, crop);
  drawContourEdgesInMap(canvas, record);
  if (setting.receiver.uvTexels)
  {
    drawMarker(canvas.map, canvas.toMap(*setting.receiver.uvTexels), 3.0);
  }
  // The pixel's footprint in the map (a warp's included), in the probed pixel's magenta, over the receiver's
  // marker: an undersampled pixel's is smaller than a texel and would hide under it.
  for (const ProbeMapPolygon& polygon : record.mapPolygons)
  {
    std::vector<glm::dvec2> points;
    for (const glm::dvec2& point : polygon.points)
    {
      points.push_back(canvas.toMap(point));
    }
    strokePolygon(canvas.map, points, kBlack, 4.0);
    strokePolygon(canvas.map, points, kProbeMarkerColor, 2.0);
  }
  const int mapLeft = int(mapBox.left + 0.5 * (mapBox.width - canvas.map.width));
  const int mapBottom = int(mapBox.bottom + 0.5 * (mapBox.height - canvas.map.height));
  blit(panel, canvas.map, mapLeft, mapBottom);
  strokeRect(panel, mapLeft - 1, mapBottom - 1, canvas.map.width + 2, canvas.map.height + 2, kDarkGrey, 1);
  drawKey(panel, keyEntries, int(box.left), int(box.bottom + keyBand), int(box.width));
  // Which view of the partition, and the pixels it serves (its split depths), over the map's top edge.
  int labelY = int(box.bottom + box.height) - kKeyLinePx;
  for (const std::string& line : labelLines)
  {
    putText(panel, line, kBodyFontPx, int(box.left), labelY, kDarkGrey);
    labelY -= kKeyLinePx;
  }
  return panel;
}

// --- (c) the light plane -----------------------------------------------------------------------------------------

// Whether the record holds anything to draw on the light plane (panel (c) is left out otherwise).
bool hasLightPlaneContent(const ProbeRecord& record)
{
  return !record.lightPolygons.empty() || !record.contourEdges.empty() || !record.lightSamples.empty();
}

// The polygons' roles with their counts ("wedge of caster 1: M_e = 1, 5 samples changed"), in order.
std::vector<std::string> polygonRoleLines(const ProbeRecord& record)
{
  std::vector<std::pair<std::string, std::size_t>> roles;
  for (const ProbeLightPolygon& polygon : record.lightPolygons)
  {
    const auto found = std::find_if(roles.begin(), roles.end(), [&](const auto& r) { return r.first == polygon.role; });
    if (found == roles.end())
    {
      roles.emplace_back(polygon.role, 1);
    }
    else
    {
      ++found->second;
    }
  }
  std::vector<std::string> lines;
  for (const auto& [role, count] : roles)
  {
    lines.push_back(count > 1 ? format(role, " (x", count, ")") : role);
  }
  return lines;
}

ImageU8 lightPlanePanel(const ProbeResult& probe, const ProbeSetting& setting, const FigureRect& rect, char letter,
  std::vector<std::vector<std::string>>& colorBarTicks)
{
  ImageU8 panel = newPanel(rect, panelTag(letter) + "light plane (light's view), signed area");
  const Box box = contentBox(rect);
  const ProbeRecord& record = probe.record;
  const Light& light = *setting.light;

  std::vector<glm::dvec2> outline;
  for (const glm::dvec3& p : lightOutline(light))
  {
    outline.push_back(setting.lightFrame.lightFromWorld(p));
  }
  double maxArea = 0.0;
  for (const ProbeLightPolygon& polygon : record.lightPolygons)
  {
    maxArea = std::max(maxArea, std::abs(polygon.signedArea));
  }
  for (const ProbeContourEdge& edge : record.contourEdges)
  {
    maxArea = std::max(maxArea, std::abs(edge.signedArea));
  }
  const bool hasAreas = !record.lightPolygons.empty() || !record.contourEdges.empty();
  const ColorMap diverging(ColorMapKind::Diverging);
  const double areaRange = maxArea > 0.0 ? maxArea : 1.0;
  const int barWidth = colorBarWidth(diverging, -areaRange, areaRange);

  // The key: the marks, each polygon role (a wedge's caster and the samples it changed), the totals.
  std::vector<KeyEntry> keyEntries = { { "light", paintLineSwatch, kBlack } };
  if (!record.lightSamples.empty())
  {
    keyEntries.push_back({ "blocked", paintDot, kBlack });
    keyEntries.push_back({ "visible sample", paintDot, kWhite });
  }
  if (!record.contourEdges.empty())
  {
    keyEntries.push_back({ "contour edge back-projected (coloured by its signed area)", paintLineSwatch,
      areaColorKeySample(diverging) });
  }
  const std::vector<std::string> polygonRoles = polygonRoleLabels(record);
  const std::vector<std::string> roleLines = polygonRoleLines(record);
  for (std::size_t r = 0; r < roleLines.size(); ++r)
  {
    keyEntries.push_back({ roleLines[r], paintBoxSwatch, ColorMap::categoryColor(long(r)) });
  }
  {
    double areaSum = 0.0;
    for (const ProbeLightPolygon& polygon : record.lightPolygons)
    {
      areaSum += polygon.signedArea;
    }
    std::string summary = format(record.lightPolygons.size() + record.droppedPolygons, " polygons");
    if (!record.lightPolygons.empty())
    {
      summary += ", sum " + numberText(areaSum) +
        (light.type == LightType::Area ? " (light's area " + numberText(light.area()) + ")" : "");
    }
    if (!record.contourEdges.empty())
    {
      summary += format(", ", record.contourEdges.size() + record.droppedEdges, " contour edges");
    }
    keyEntries.push_back({ summary, nullptr, kDarkGrey });
  }
  if (keyHeight(keyEntries, int(box.width)) > 0.45 * box.height)
  {
    // Too many roles to leave the plane room: the key-number pages list them (addRecordCounts).
    const auto roles = polygonRoleLines(record);
    keyEntries.erase(std::remove_if(keyEntries.begin(), keyEntries.end(), [&](const KeyEntry& entry) {
      return entry.paint == paintBoxSwatch && std::find(roles.begin(), roles.end(), entry.label) != roles.end();
    }), keyEntries.end());
    keyEntries.insert(keyEntries.end() - 1, KeyEntry{ format(roles.size(), " polygon roles: listed in the key numbers"),
      nullptr, kDarkGrey });
  }
  const double keyBand = keyHeight(keyEntries, int(box.width));
  const Box planeBox{ box.left, box.bottom + keyBand, box.width - (hasAreas ? barWidth + 6.0 : 0.0), box.height - keyBand };
  if (hasAreas)
  {
    colorBarTicks.push_back(drawColorBar(panel, diverging, -areaRange, areaRange, int(planeBox.left + planeBox.width + 6.0),
      int(planeBox.bottom), int(planeBox.height)));
  }

  // The view: the light and a margin around it; without an outline (a point light), whatever was recorded.
  glm::dvec2 lo(1e300);
  glm::dvec2 hi(-1e300);
  const auto include = [&](const glm::dvec2& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  };
  for (const glm::dvec2& p : outline)
  {
    include(p);
  }
  if (outline.empty())
  {
    include(glm::dvec2(0.0));
    for (const ProbeLightPolygon& polygon : record.lightPolygons)
    {
      for (const glm::dvec2& p : polygon.points)
      {
        include(p);
      }
    }
    for (const ProbeLightSample& sample : record.lightSamples)
    {
      include(sample.position);
    }
    if (hi.x - lo.x <= 0.0 && hi.y - lo.y <= 0.0)
    {
      lo -= 1.0;
      hi += 1.0;
    }
  }
  const View2D view = fitView(lo, hi, planeBox, 0.15);
  ImageU8 plane(int(planeBox.width), int(planeBox.height), 3, 255);
  const glm::dvec2 planeOrigin(planeBox.left, planeBox.bottom);
  const auto toPx = [&](const glm::dvec2& p) { return view.toPx(p) - planeOrigin; };
  const auto areaColor = [&](double signedArea) { return diverging.map(0.5 + 0.5 * signedArea / areaRange); };

  if (!outline.empty())
  {
    std::vector<glm::dvec2> outlinePx;
    for (const glm::dvec2& p : outline)
    {
      outlinePx.push_back(toPx(p));
    }
    fillPolygon(plane, outlinePx, { 0.96, 0.96, 0.96 });
  }
  for (const ProbeLightPolygon& polygon : record.lightPolygons)
  {
    std::vector<glm::dvec2> points;
    for (const glm::dvec2& p : polygon.points)
    {
      points.push_back(toPx(p));
    }
    fillPolygon(plane, points, areaColor(polygon.signedArea), 0.7);
    // The outline in its role's colour (the key's swatch): which wedge or micropatch it is.
    const RgbColor roleColor = ColorMap::categoryColor(labelCode(polygonRoles, polygon.role));
    strokePolygon(plane, points, kBlack, points.size() > 2 ? 1.0 : 4.0);
    strokePolygon(plane, points, roleColor, points.size() > 2 ? 1.0 : 2.0);
  }
  for (const ProbeContourEdge& edge : record.contourEdges)
  {
    drawLine(plane, toPx(edge.lightA), toPx(edge.lightB), kBlack, 4.0);
    drawLine(plane, toPx(edge.lightA), toPx(edge.lightB), areaColor(edge.signedArea), 2.0);
  }
  if (!outline.empty())
  {
    std::vector<glm::dvec2> outlinePx;
    for (const glm::dvec2& p : outline)
    {
      outlinePx.push_back(toPx(p));
    }
    strokePolygon(plane, outlinePx, kBlack, 2.0);
  }
  if (!outline.empty())
  {
    const glm::dvec2 centre = toPx(glm::dvec2(0.0));
    drawLine(plane, centre - glm::dvec2(5, 0), centre + glm::dvec2(5, 0), kDarkGrey, 1.0);
    drawLine(plane, centre - glm::dvec2(0, 5), centre + glm::dvec2(0, 5), kDarkGrey, 1.0);
  }
  // Samples: blocked filled black, visible white with a black rim.
  for (const ProbeLightSample& sample : record.lightSamples)
  {
    paintDot(plane, toPx(sample.position), sample.blocked ? kBlack : kWhite);
  }
  if (outline.empty() && record.lightPolygons.empty() && record.lightSamples.empty())
  {
    const char* lightTypes[] = { "an area", "a point", "a directional", "a spot" };
    drawCentredNote(plane, { 0, 0, double(plane.width), double(plane.height) },
      std::string(lightTypes[static_cast<int>(light.type)]) + " light: no extent");
  }
  else if (record.lightPolygons.empty() && record.contourEdges.empty() && record.lightSamples.empty())
  {
    drawCentredNote(plane, { 0, 0, double(plane.width), 40.0 }, "the technique recorded nothing on the light");
  }
  blit(panel, plane, int(planeBox.left), int(planeBox.bottom));

  drawKey(panel, keyEntries, int(box.left), int(box.bottom + keyBand), int(box.width));
  return panel;
}

// --- (d) the cross-section ---------------------------------------------------------------------------------------

// 1, 2 or 5 x 10^k, the largest not above `limit`.
double niceLength(double limit)
{
  const double decade = std::pow(10.0, std::floor(std::log10(limit)));
  for (const double mantissa : { 5.0, 2.0, 1.0 })
  {
    if (mantissa * decade <= limit)
    {
      return mantissa * decade;
    }
  }
  return decade;
}

ImageU8 sectionPanel(const Scene& scene, const ProbeSetting& setting, const FigureRect& rect, char letter)
{
  const ProbeLightFrame& lightFrame = setting.lightFrame;
  const ProbeReceiver& receiver = setting.receiver;
  const Light& light = *setting.light;
  const ProbeSection section = probeSection(lightFrame.eyeWs, lightFrame.axisWs, receiver.position, receiver.normal);
  ImageU8 panel = newPanel(rect, panelTag(letter) + "section through the light's centre and the receiver, containing " +
      (section.usesReceiverNormal ? "the receiver's normal" : "the light's axis"));
  const Box box = contentBox(rect);
  const double halfExtent = lightHalfExtentInSection(light, section);
  const glm::dvec2 lightCentre = section.toSection(lightFrame.eyeWs);
  const glm::dvec2 receiverPoint = section.toSection(receiver.position);
  const bool directional = light.type == LightType::Directional;
  std::vector<KeyEntry> keyEntries = { { "casters", paintLineSwatch, kCasterColor },
    { "non-casters", paintLineSwatch, kLightGrey }, { "shadow-map depth per texel", paintLineSwatch, kDepthStepColor },
    { "light", paintLineSwatch, kLightColor },
    { directional ? "ray to the light" : "rays to its ends", paintLineSwatch, kRayColor },
    { "receiver", paintMarkerSwatch, kProbeMarkerColor } };
  if (setting.map.depth == nullptr || setting.map.view == nullptr)
  {
    keyEntries.erase(keyEntries.begin() + 2); // no map, no depth steps
  }
  const double keyBand = keyHeight(keyEntries, int(box.width));
  const Box sectionBox{ box.left, box.bottom + keyBand, box.width, box.height - keyBand };

  // Where the rays go: the light's two ends (its centre for a point light); a directional light's rays are
  // parallel, back along its direction to the eye's plane.
  std::vector<glm::dvec2> rayEnds;
  if (directional)
  {
    rayEnds.push_back(section.toSection(receiver.position - lightFrame.axisWs * receiver.depthLin));
  }
  else if (halfExtent > 0.0)
  {
    rayEnds = { lightCentre - glm::dvec2(halfExtent, 0.0), lightCentre + glm::dvec2(halfExtent, 0.0) };
  }
  else
  {
    rayEnds.push_back(lightCentre);
  }
  const std::vector<SectionSegment> segments = sceneSection(scene, section);
  // The view: the light, the receiver and the rays between them; a directional light's eye is only a place
  // behind the scene, so there the view holds the receiver and the scene's cut instead.
  glm::dvec2 lo = receiverPoint;
  glm::dvec2 hi = receiverPoint;
  const auto include = [&](const glm::dvec2& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  };
  if (directional)
  {
    for (const SectionSegment& segment : segments)
    {
      include(segment.a);
      include(segment.b);
    }
  }
  else
  {
    include(lightCentre);
    for (const glm::dvec2& p : rayEnds)
    {
      include(p);
    }
  }
  const View2D view = fitView(lo, hi, sectionBox, 0.12);
  ImageU8 canvas(int(sectionBox.width), int(sectionBox.height), 3, 255);
  const glm::dvec2 canvasOrigin(sectionBox.left, sectionBox.bottom);
  const auto toPx = [&](const glm::dvec2& p) { return view.toPx(p) - canvasOrigin; };

  // The shadow map's stored depths along the section: a step per texel, risers along the texel edges' rays.
  const ImageF* depthMap = setting.map.depth;
  if (depthMap != nullptr && setting.map.view != nullptr)
  {
    const std::vector<SectionTexelColumn> columns =
      sectionShadowMapColumns(*setting.map.view, *depthMap, section, receiver.position);
    for (std::size_t i = 0; i < columns.size(); ++i)
    {
      if (columns[i].joinsPrevious && i > 0)
      {
        drawLine(canvas, toPx(columns[i - 1].exit), toPx(columns[i].enter), kDepthStepColor, 2.0);
      }
      drawLine(canvas, toPx(columns[i].enter), toPx(columns[i].exit), kDepthStepColor, 2.0);
    }
  }
  for (const SectionSegment& segment : segments)
  {
    drawLine(canvas, toPx(segment.a), toPx(segment.b), segment.castsShadows ? kCasterColor : kLightGrey, 2.0);
  }
  drawDashedLine(canvas, toPx(receiverPoint), toPx(directional ? rayEnds.front() : lightCentre), kDarkGrey, 1.0, 5.0);
  for (const glm::dvec2& end : rayEnds)
  {
    drawLine(canvas, toPx(receiverPoint), toPx(end), kRayColor, 1.5);
  }
  if (halfExtent > 0.0)
  {
    drawLine(canvas, toPx(rayEnds[0]), toPx(rayEnds[1]), kBlack, 7.0);
    drawLine(canvas, toPx(rayEnds[0]), toPx(rayEnds[1]), kLightColor, 4.0);
  }
  else if (!directional)
  {
    fillDisk(canvas, toPx(lightCentre), 6.0, kBlack);
    fillDisk(canvas, toPx(lightCentre), 4.0, kLightColor);
  }
  // The receiver and its normal (projected into the section).
  const glm::dvec2 normalInSection(glm::dot(receiver.normal, section.across), glm::dot(receiver.normal, section.towardLight));
  const glm::dvec2 normalTip = toPx(receiverPoint) + normalInSection * 30.0;
  drawLine(canvas, toPx(receiverPoint), normalTip, kBlack, 4.0);
  drawLine(canvas, toPx(receiverPoint), normalTip, kProbeMarkerColor, 2.0);
  drawMarker(canvas, toPx(receiverPoint), 3.0);

  // Scale bar, bottom right.
  const double barLength = niceLength(0.25 * canvas.width / view.scale);
  const glm::dvec2 barEnd(canvas.width - 12.0, 14.0);
  const glm::dvec2 barStart = barEnd - glm::dvec2(barLength * view.scale, 0.0);
  drawLine(canvas, barStart, barEnd, kBlack, 2.0);
  drawLine(canvas, barStart - glm::dvec2(0, 4), barStart + glm::dvec2(0, 4), kBlack, 2.0);
  drawLine(canvas, barEnd - glm::dvec2(0, 4), barEnd + glm::dvec2(0, 4), kBlack, 2.0);
  const std::string barLabel = numberText(barLength) + " world units";
  putText(canvas, barLabel, kBodyFontPx, int(barEnd.x) - textWidth(barLabel, kBodyFontPx), int(barEnd.y) + 6, kBlack);
  blit(panel, canvas, int(sectionBox.left), int(sectionBox.bottom));

  drawKey(panel, keyEntries, int(box.left), int(box.bottom + keyBand), int(box.width));
  return panel;
}

// --- the algorithm panels ------------------------------------------------------------------------------------------

// The first of `names` the record holds (in any group), or nullptr.
const ProbeQuantity* findAny(const ProbeRecord& record, std::initializer_list<const char*> names)
{
  for (const char* name : names)
  {
    if (const ProbeQuantity* quantity = record.find(name); quantity != nullptr && !quantity->value.empty())
    {
      return quantity;
    }
  }
  return nullptr;
}

// PCSS's penumbra estimate (Fernando 2005; VSSM Alg. 1 L7-L16) as the record gives it: the light's width w_light,
// the search plane's depth n (the map's near plane), the receiver's depth d_r and, where blockers were found, the
// average blocker depth d_b. pcss, savsm (through pcssReference) and vssm record these.
struct PenumbraEstimate
{
  double lightSize = 0.0;
  double searchDepth = 0.0;
  double receiverDepth = 0.0;
  std::optional<double> blockerDepth;        // none: no blocker in the search region (lit)
  std::optional<double> recordedPenumbra;    // the twin's penumbra_width, where it records one
  std::optional<double> recordedSearchWidth; // blocker_kernel_world_size
  double searchWidth() const { return lightSize * (receiverDepth - searchDepth) / receiverDepth; }
  double penumbraWidth() const { return lightSize * (receiverDepth - *blockerDepth) / *blockerDepth; }
};

std::optional<PenumbraEstimate> penumbraEstimateOf(const ProbeRecord& record, const ProbeSetting& setting)
{
  const ProbeQuantity* lightSize = record.find("light_size");
  const ProbeQuantity* searchDepth = findAny(record, { "search_plane_depth", "near_depth" });
  if (lightSize == nullptr || searchDepth == nullptr || lightSize->value.empty() || !(lightSize->value[0] > 0.0))
  {
    return std::nullopt;
  }
  PenumbraEstimate estimate;
  estimate.lightSize = lightSize->value[0];
  estimate.searchDepth = searchDepth->value[0];
  const ProbeQuantity* receiverDepth = record.find("receiver_depth");
  estimate.receiverDepth = receiverDepth != nullptr && !receiverDepth->value.empty() ? receiverDepth->value[0]
                                                                                    : setting.receiver.depthLin;
  if (!(estimate.receiverDepth > 0.0))
  {
    return std::nullopt;
  }
  if (const ProbeQuantity* blocker = record.find("avg_blocker_depth"); blocker != nullptr && !blocker->value.empty() &&
    blocker->value[0] > 0.0)
  {
    estimate.blockerDepth = blocker->value[0];
  }
  if (const ProbeQuantity* penumbra = record.find("penumbra_width"); penumbra != nullptr && !penumbra->value.empty())
  {
    estimate.recordedPenumbra = penumbra->value[0];
  }
  if (const ProbeQuantity* search = record.find("blocker_kernel_world_size"); search != nullptr && !search->value.empty())
  {
    estimate.recordedSearchWidth = search->value[0];
  }
  return estimate;
}

// Lines of text under a diagram, top down from `top`; returns the y under the last.
int drawTextLines(ImageU8& panel, const std::vector<std::pair<std::string, RgbColor>>& lines, int left, int top,
  int widthPx)
{
  int y = top - kKeyLinePx;
  for (const auto& [text, color] : lines)
  {
    for (const std::string& line : wrapText(text, kBodyFontPx, widthPx))
    {
      putText(panel, line, kBodyFontPx, left, y, color);
      y -= kKeyLinePx;
    }
  }
  return y;
}

int wrappedLineCount(const std::vector<std::pair<std::string, RgbColor>>& lines, int widthPx)
{
  int count = 0;
  for (const auto& line : lines)
  {
    count += static_cast<int>(wrapText(line.first, kBodyFontPx, widthPx).size());
  }
  return count;
}

// The similar triangles of PCSS in the section's units (x across, y up, the light at depth 0): the light's ends
// to the receiver cross the search plane over w_i = w_light (d_r - n) / d_r (step 1's search region); a blocker
// edge at the average blocker depth seen from the light's ends spans w_penumbra = w_light (d_r - d_b) / d_b on
// the receiver (Fernando 2005, step 2). The receiver and the blocker edge share x = 0: a schematic of the
// pixel's numbers, not the scene's geometry (panel (d) has that).
ImageU8 penumbraPanel(const PenumbraEstimate& estimate, const FigureRect& rect, char letter)
{
  ImageU8 panel = newPanel(rect, panelTag(letter) + "PCSS penumbra estimate (similar triangles)");
  const Box box = contentBox(rect);
  const double w = estimate.lightSize;
  const double n = estimate.searchDepth;
  const double dr = estimate.receiverDepth;
  std::vector<std::pair<std::string, RgbColor>> lines;
  lines.push_back({ "w_light " + numberText(w) + ", search plane n " + numberText(n) + ", receiver d_r " +
      numberText(dr) + " (linear depth)", kBlack });
  lines.push_back({ "step 1, search width w_i = w_light (d_r - n) / d_r = " + numberText(w) + " (" + numberText(dr) +
      " - " + numberText(n) + ") / " + numberText(dr) + " = " + numberText(estimate.searchWidth()) + " world units" +
      (estimate.recordedSearchWidth ? " (recorded " + numberText(*estimate.recordedSearchWidth) + ")" : ""),
    kSearchColor });
  if (estimate.blockerDepth)
  {
    const double db = *estimate.blockerDepth;
    lines.push_back({ "average blocker depth d_b " + numberText(db), kBlack });
    lines.push_back({ "step 2, w_penumbra = w_light (d_r - d_b) / d_b = " + numberText(w) + " (" + numberText(dr) + " - " +
        numberText(db) + ") / " + numberText(db) + " = " + numberText(estimate.penumbraWidth()) + " world units" +
        (estimate.recordedPenumbra ? " (recorded " + numberText(*estimate.recordedPenumbra) + ")" : ""),
      kPenumbraColor });
  }
  else
  {
    lines.push_back({ "no blocker in the search region: lit, no penumbra estimate", kDarkGrey });
  }
  // One line more on top for the diagram's stretch, when it has one.
  const int textBand = (wrappedLineCount(lines, int(box.width)) + 1) * kKeyLinePx + 4;
  drawTextLines(panel, lines, int(box.left), int(box.bottom) + textBand - kKeyLinePx, int(box.width));

  // Diagram: x across, y = -depth. Labels on the right take a fixed strip.
  const double labelStrip = 9.0 * textWidth("M", kBodyFontPx);
  const Box diagram{ box.left, box.bottom + textBand, box.width - labelStrip, box.height - textBand };
  const double penumbraHalf = estimate.blockerDepth ? 0.5 * estimate.penumbraWidth() : 0.0;
  const double halfWidth = std::max({ 0.5 * w, penumbraHalf, 1e-9 });
  // Across stretched to the diagram's width where the light is narrow beside the depths: an affine map keeps
  // the ratios along each plane, so the triangles still give w_i and w_penumbra; the text names the stretch.
  const double depthScale = 0.84 * diagram.height / dr;
  const double acrossScale = std::max(depthScale, 0.84 * diagram.width / (2.0 * halfWidth));
  const auto px = [&](double x, double depth) {
    return glm::dvec2(diagram.left + 0.5 * diagram.width + x * acrossScale,
      diagram.bottom + 0.5 * diagram.height + (0.5 * dr - depth) * depthScale);
  };
  if (acrossScale > 1.05 * depthScale)
  {
    putText(panel, "diagram: across stretched x" + numberText(acrossScale / depthScale, 2) + " against depth",
      kBodyFontPx, int(box.left), int(box.bottom) + textBand - kKeyLinePx, kDarkGrey);
  }
  const double right = diagram.left + diagram.width;
  const auto planeLabel = [&](double depth, const std::string& label, const RgbColor& color, int raisePx = 0) {
    putText(panel, label, kBodyFontPx, int(right) + 4, int(px(0.0, depth).y) - 5 + raisePx, color);
  };
  // The search plane's label above the blocker's where the two planes are closer than a line (d_b near n).
  const bool planesClose = estimate.blockerDepth && std::abs(px(0, n).y - px(0, *estimate.blockerDepth).y) < kKeyLinePx;
  // Planes: search, blocker, receiver.
  drawDashedLine(panel, { diagram.left, px(0, n).y }, { right, px(0, n).y }, kSearchColor, 1.0, 5.0);
  planeLabel(n, "n " + numberText(n, 3), kSearchColor, planesClose ? kKeyLinePx : 0);
  drawLine(panel, { diagram.left, px(0, dr).y }, { right, px(0, dr).y }, kLightGrey, 2.0);
  planeLabel(dr, "d_r " + numberText(dr, 3), kBlack);
  // Step 1: the light's ends to the receiver, and the search region they cut from the search plane.
  const double searchHalf = 0.5 * estimate.searchWidth();
  drawLine(panel, px(-0.5 * w, 0.0), px(0.0, dr), kSearchColor, 1.0);
  drawLine(panel, px(0.5 * w, 0.0), px(0.0, dr), kSearchColor, 1.0);
  drawLine(panel, px(-searchHalf, n), px(searchHalf, n), kSearchColor, 4.0);
  if (estimate.blockerDepth)
  {
    const double db = *estimate.blockerDepth;
    // A blocker reaching from the left to its edge at x = 0, at the average blocker depth.
    drawLine(panel, { diagram.left, px(0, db).y }, px(0.0, db), kCasterColor, 4.0);
    drawDashedLine(panel, px(0.0, db), { right, px(0, db).y }, kCasterColor, 1.0, 5.0);
    planeLabel(db, "d_b " + numberText(db, 3), kBlack);
    // Step 2: the light's ends through the blocker's edge, on to the receiver: the penumbra.
    drawLine(panel, px(-0.5 * w, 0.0), px(penumbraHalf, dr), kPenumbraColor, 1.5);
    drawLine(panel, px(0.5 * w, 0.0), px(-penumbraHalf, dr), kPenumbraColor, 1.5);
    drawLine(panel, px(-penumbraHalf, dr) + glm::dvec2(0, -4), px(penumbraHalf, dr) + glm::dvec2(0, -4), kPenumbraColor,
      4.0);
  }
  // The light on top, and the receiver point.
  drawLine(panel, px(-0.5 * w, 0.0), px(0.5 * w, 0.0), kBlack, 7.0);
  drawLine(panel, px(-0.5 * w, 0.0), px(0.5 * w, 0.0), kLightColor, 4.0);
  planeLabel(0.0, "w_light " + numberText(w, 3), kBlack);
  drawMarker(panel, px(0.0, dr), 3.0);
  return panel;
}

// The one-tailed Chebyshev bound of the moment techniques (Donnelly & Lauritzen 2006; VSSM Eq. 1): with the
// filter region's mean mu and variance sigma^2, P(x >= t) <= p_max(t) = sigma^2 / (sigma^2 + (t - mu)^2) for
// t > mu, 1 otherwise. vsm and savsm record mean, variance, the compared depth t and p_max; vssm its pooled
// planar sub-kernels' mean offset mu - t, variance and bound (Eq. 5).
struct ChebyshevPoint
{
  double variance = 0.0;
  double offset = 0.0; // t - mu
  std::optional<double> mean;
  std::optional<double> comparedDepth;
  double recordedBound = 0.0;
  std::string boundName;
  double bound() const { return offset <= 0.0 ? 1.0 : variance / (variance + offset * offset); }
};

std::optional<ChebyshevPoint> chebyshevPointOf(const ProbeRecord& record)
{
  ChebyshevPoint point;
  if (const ProbeQuantity* pMax = record.find("p_max"); pMax != nullptr && !pMax->value.empty())
  {
    const ProbeQuantity* mean = record.find("mean");
    const ProbeQuantity* variance = record.find("variance");
    const ProbeQuantity* t = record.find("compared_depth");
    if (mean == nullptr || variance == nullptr || t == nullptr || mean->value.empty() || variance->value.empty() ||
      t->value.empty())
    {
      return std::nullopt;
    }
    // The three in one depth space (lvsm's moments are in warped depth, its compared_depth linear): else the
    // bound drawn would not be the one the technique took.
    if (mean->unit != t->unit || variance->unit != mean->unit + "^2")
    {
      return std::nullopt;
    }
    point.mean = mean->value[0];
    point.comparedDepth = t->value[0];
    point.variance = variance->value[0];
    point.offset = t->value[0] - mean->value[0];
    point.recordedBound = pMax->value[0];
    point.boundName = "p_max";
    return point;
  }
  const ProbeQuantity* offset = record.find("pooled_mean_offset");
  const ProbeQuantity* variance = record.find("pooled_variance");
  const ProbeQuantity* bound = record.find("chebyshev_unoccluded");
  if (offset == nullptr || variance == nullptr || bound == nullptr || offset->value.empty() || variance->value.empty() ||
    bound->value.empty() || variance->unit != offset->unit + "^2")
  {
    return std::nullopt;
  }
  point.variance = variance->value[0];
  point.offset = -offset->value[0]; // the record's offset is mu - t
  point.recordedBound = bound->value[0];
  point.boundName = "chebyshev_unoccluded";
  return point;
}

ImageU8 chebyshevPanel(const ChebyshevPoint& point, const FigureRect& rect, char letter)
{
  ImageU8 panel = newPanel(rect, panelTag(letter) + "Chebyshev bound p_max(t) over t - mean");
  const Box box = contentBox(rect);
  std::vector<std::pair<std::string, RgbColor>> lines;
  if (point.mean && point.comparedDepth)
  {
    lines.push_back({ "moments: mean " + numberText(*point.mean, 6) + " (linear depth), variance " +
        numberText(point.variance) + " (linear depth^2)", kBlack });
    lines.push_back({ "t " + numberText(*point.comparedDepth, 6) + ", t - mean " + numberText(point.offset), kBlack });
  }
  else
  {
    lines.push_back({ "pooled planar sub-kernels (Eq. 5): variance " + numberText(point.variance) +
        " (linear depth^2), t - mean " + numberText(point.offset) + " (linear depth)", kBlack });
  }
  lines.push_back({ point.offset <= 0.0
      ? "t <= mean: p_max = 1 (the bound does not apply, lit)"
      : "p_max = var / (var + (t - mean)^2) = " + numberText(point.bound()) + " (recorded " + point.boundName + " " +
        numberText(point.recordedBound) + ")",
    kRayColor });
  const int textBand = wrappedLineCount(lines, int(box.width)) * kKeyLinePx + 4;
  drawTextLines(panel, lines, int(box.left), int(box.bottom) + textBand, int(box.width));

  // Axes: x = t - mean from a little below 0 to past the pixel's point and 3 standard deviations; y = 0 .. 1.
  const double sigma = std::sqrt(std::max(0.0, point.variance));
  // Past 6 sigma the bound is flat at this scale: the axis stops there and the point sits at its end, labelled.
  const bool pointOffAxis = sigma > 0.0 && point.offset > 6.0 * sigma;
  const double xMax = pointOffAxis ? 6.0 * sigma : std::max({ 3.0 * sigma, 1.3 * std::abs(point.offset), 1e-9 });
  const double xMin = -0.25 * xMax;
  const int axisLabelPx = kKeyLinePx + 4;
  const int leftLabelPx = textWidth("0.5", kBodyFontPx) + 10;
  const Box plot{ box.left + leftLabelPx, box.bottom + textBand + axisLabelPx + kKeyLinePx, box.width - leftLabelPx - 10.0,
    box.height - textBand - axisLabelPx - kKeyLinePx - 8.0 };
  const auto px = [&](double x, double y) {
    return glm::dvec2(plot.left + (x - xMin) / (xMax - xMin) * plot.width, plot.bottom + y * plot.height);
  };
  drawLine(panel, px(xMin, 0.0), px(xMax, 0.0), kBlack, 1.0);
  drawLine(panel, { plot.left, plot.bottom }, { plot.left, plot.bottom + plot.height }, kBlack, 1.0);
  drawDashedLine(panel, px(0.0, 0.0), px(0.0, 1.0), kLightGrey, 1.0, 4.0);
  for (const double y : { 0.0, 0.5, 1.0 })
  {
    const std::string label = numberText(y);
    drawLine(panel, px(xMin, y) - glm::dvec2(4, 0), px(xMin, y), kBlack, 1.0);
    putText(panel, label, kBodyFontPx, int(plot.left) - 6 - textWidth(label, kBodyFontPx), int(px(xMin, y).y) - 5);
  }
  const std::vector<double> xTicks = { 0.0, 0.5 * xMax, xMax };
  const std::vector<std::string> xLabels = distinctTickLabels(xTicks);
  for (std::size_t i = 0; i < xTicks.size(); ++i)
  {
    const glm::dvec2 at = px(xTicks[i], 0.0);
    drawLine(panel, at, at - glm::dvec2(0, 4), kBlack, 1.0);
    const int width = textWidth(xLabels[i], kBodyFontPx);
    putText(panel, xLabels[i], kBodyFontPx, std::min(int(at.x) - width / 2, int(box.left + box.width) - width),
      int(at.y) - 6 - kKeyLinePx + 4);
  }
  putText(panel, "t - mean (linear depth)", kBodyFontPx, int(box.left + leftLabelPx), int(box.bottom) + textBand);
  // The curve, then the pixel's point on it.
  glm::dvec2 previous = px(xMin, 1.0);
  for (int i = 1; i <= 200; ++i)
  {
    const double x = xMin + (xMax - xMin) * i / 200.0;
    const double y = x <= 0.0 ? 1.0 : point.variance / (point.variance + x * x);
    const glm::dvec2 next = px(x, y);
    drawLine(panel, previous, next, kPenumbraColor, 2.0);
    previous = next;
  }
  const glm::dvec2 at = px(std::min(point.offset, xMax), point.bound());
  drawDashedLine(panel, glm::dvec2(at.x, plot.bottom), at, kDarkGrey, 1.0, 4.0);
  fillDisk(panel, at, 6.0, kBlack);
  fillDisk(panel, at, 4.0, kRayColor);
  if (pointOffAxis)
  {
    const std::string label = "t - mean " + numberText(point.offset) + " (" + numberText(point.offset / sigma, 3) +
      " sigma) ->";
    putText(panel, label, kBodyFontPx, int(plot.left + plot.width) - textWidth(label, kBodyFontPx), int(at.y) + 10,
      kRayColor);
  }
  if (sigma > 0.0)
  {
    const glm::dvec2 sigmaAt = px(sigma, 0.5);
    drawLine(panel, sigmaAt - glm::dvec2(0, 4), sigmaAt + glm::dvec2(0, 4), kDarkGrey, 1.0);
    putText(panel, "sigma", kBodyFontPx, int(sigmaAt.x) + 5, int(sigmaAt.y) + 4, kDarkGrey);
  }
  return panel;
}

// --- (e) the key numbers -----------------------------------------------------------------------------------------

std::string vectorText(const std::vector<double>& value)
{
  std::string text;
  for (std::size_t i = 0; i < value.size(); ++i)
  {
    text += (i == 0 ? "" : ", ") + numberText(value[i]);
  }
  return value.size() == 1 ? text : "(" + text + ")";
}

// ESM's test (Annen et al. 2008): the step "d <= z" replaced by exp(c (z_n - t_n)), filtered as
// E[exp(c z_n)] exp(-c t_n) and clamped to [0, 1], in depths normalized to [0, 1] between the map's near and far.
struct ExponentialTest
{
  double exponent = 0.0;      // c
  double moment = 0.0;        // E[exp(c z_n)] over the filter region
  double comparedDepth = 0.0; // t_n
  double recordedVisibility = 0.0;
  double visibility(double t) const { return std::clamp(moment * std::exp(-exponent * t), 0.0, 1.0); }
};

std::optional<ExponentialTest> exponentialTestOf(const ProbeRecord& record)
{
  const ProbeQuantity* exponent = record.find("esm_exponent");
  const ProbeQuantity* moment = record.find("exponential_moment");
  const ProbeQuantity* t = record.find("normalized_compared_depth");
  const ProbeQuantity* visibility = record.find("visibility");
  if (exponent == nullptr || moment == nullptr || t == nullptr || visibility == nullptr || exponent->value.empty() ||
    moment->value.empty() || t->value.empty() || visibility->value.empty() || !(exponent->value[0] > 0.0))
  {
    return std::nullopt;
  }
  return ExponentialTest{ exponent->value[0], moment->value[0], t->value[0], visibility->value[0] };
}

ImageU8 exponentialPanel(const ExponentialTest& test, const FigureRect& rect, char letter)
{
  ImageU8 panel = newPanel(rect, panelTag(letter) + "ESM: exp(-c t) E[exp(c z)] over t");
  const Box box = contentBox(rect);
  // Where the filtered exponential crosses 1: the depth the occluders' exponential mean stands for.
  const double edge = std::log(std::max(test.moment, 1e-300)) / test.exponent;
  std::vector<std::pair<std::string, RgbColor>> lines = {
    { "c " + numberText(test.exponent) + ", E[exp(c z)] " + numberText(test.moment) + " (depths normalized to [0, 1])",
      kBlack },
    { "t " + numberText(test.comparedDepth, 6) + "; the estimate falls from 1 at t = ln(E[exp(c z)]) / c = " +
        numberText(edge),
      kBlack },
    { "visibility = clamp(E[exp(c z)] exp(-c t), 0, 1) = " + numberText(test.visibility(test.comparedDepth)) +
        " (recorded " + numberText(test.recordedVisibility) + ")",
      kRayColor },
  };
  const int textBand = wrappedLineCount(lines, int(box.width)) * kKeyLinePx + 4;
  drawTextLines(panel, lines, int(box.left), int(box.bottom) + textBand, int(box.width));

  // Axes: t over [0, 1] (the normalized depth range), visibility 0 .. 1.
  const int axisLabelPx = kKeyLinePx + 4;
  const int leftLabelPx = textWidth("0.5", kBodyFontPx) + 10;
  const Box plot{ box.left + leftLabelPx, box.bottom + textBand + axisLabelPx + kKeyLinePx, box.width - leftLabelPx - 10.0,
    box.height - textBand - axisLabelPx - kKeyLinePx - 8.0 };
  const auto px = [&](double x, double y) { return glm::dvec2(plot.left + x * plot.width, plot.bottom + y * plot.height); };
  drawLine(panel, px(0.0, 0.0), px(1.0, 0.0), kBlack, 1.0);
  drawLine(panel, px(0.0, 0.0), px(0.0, 1.0), kBlack, 1.0);
  for (const double y : { 0.0, 0.5, 1.0 })
  {
    const std::string label = numberText(y);
    drawLine(panel, px(0.0, y) - glm::dvec2(4, 0), px(0.0, y), kBlack, 1.0);
    putText(panel, label, kBodyFontPx, int(plot.left) - 6 - textWidth(label, kBodyFontPx), int(px(0.0, y).y) - 5);
  }
  for (const double x : { 0.0, 0.5, 1.0 })
  {
    const std::string label = numberText(x);
    const glm::dvec2 at = px(x, 0.0);
    drawLine(panel, at, at - glm::dvec2(0, 4), kBlack, 1.0);
    const int width = textWidth(label, kBodyFontPx);
    putText(panel, label, kBodyFontPx, std::min(int(at.x) - width / 2, int(box.left + box.width) - width),
      int(at.y) - 6 - kKeyLinePx + 4);
  }
  putText(panel, "t, normalized compared depth", kBodyFontPx, int(box.left + leftLabelPx), int(box.bottom) + textBand);
  glm::dvec2 previous = px(0.0, test.visibility(0.0));
  for (int i = 1; i <= 400; ++i)
  {
    const double x = i / 400.0;
    const glm::dvec2 next = px(x, test.visibility(x));
    drawLine(panel, previous, next, kPenumbraColor, 2.0);
    previous = next;
  }
  const double shownT = std::clamp(test.comparedDepth, 0.0, 1.0);
  const glm::dvec2 at = px(shownT, test.visibility(test.comparedDepth));
  drawDashedLine(panel, glm::dvec2(at.x, plot.bottom), at, kDarkGrey, 1.0, 4.0);
  fillDisk(panel, at, 6.0, kBlack);
  fillDisk(panel, at, 4.0, kRayColor);
  return panel;
}

// --- the diagrams of pcf and hard, lvsm, msm and convsm (issue 31) --------------------------------------------------

// A number a diagram computed from the record and drew (ProbeFigureDrawing::drawnValues).
void logDrawnValue(const std::string& name, double value)
{
  if (tFigureTextLog.drawn != nullptr)
  {
    tFigureTextLog.drawn->push_back({ tFigureTextLog.panel, name, value });
  }
}

// The scalar quantity `name`, none when the record lacks it.
std::optional<double> recordedScalar(const ProbeRecord& record, const std::string& name)
{
  const ProbeQuantity* quantity = record.find(name);
  if (quantity == nullptr || quantity->value.empty())
  {
    return std::nullopt;
  }
  return quantity->value[0];
}

// A plot's frame: x over [xMin, xMax] and y over [yMin, yMax] in `plot` (panel pixels).
struct PlotFrame
{
  Box plot;
  double xMin = 0.0;
  double xMax = 1.0;
  double yMin = 0.0;
  double yMax = 1.0;
  glm::dvec2 px(double x, double y) const
  {
    return { plot.left + (x - xMin) / (xMax - xMin) * plot.width, plot.bottom + (y - yMin) / (yMax - yMin) * plot.height };
  }
};

// Axes in `box` above a text band of `textBand` pixels: the y ticks given, the x ticks given (else the ends and
// the middle), every
// label with the digits to differ, and the x axis named under its labels (as the Chebyshev and ESM panels).
PlotFrame drawPlotFrame(ImageU8& panel, const Box& box, int textBand, double xMin, double xMax, double yMin,
  double yMax, const std::string& xName, const std::vector<double>& yTicks, std::vector<double> xTicks = {})
{
  PlotFrame frame;
  frame.xMin = xMin;
  frame.xMax = xMax > xMin ? xMax : xMin + 1.0;
  frame.yMin = yMin;
  frame.yMax = yMax > yMin ? yMax : yMin + 1.0;
  const std::vector<std::string> yLabels = distinctTickLabels(yTicks);
  int yLabelWidth = 0;
  for (const std::string& label : yLabels)
  {
    yLabelWidth = std::max(yLabelWidth, textWidth(label, kBodyFontPx));
  }
  const int axisLabelPx = kKeyLinePx + 4;
  const int leftLabelPx = yLabelWidth + 10;
  frame.plot = { box.left + leftLabelPx, box.bottom + textBand + axisLabelPx + kKeyLinePx,
    box.width - leftLabelPx - 10.0, box.height - textBand - axisLabelPx - kKeyLinePx - 8.0 };
  drawLine(panel, { frame.plot.left, frame.plot.bottom }, { frame.plot.left + frame.plot.width, frame.plot.bottom },
    kBlack, 1.0);
  drawLine(panel, { frame.plot.left, frame.plot.bottom }, { frame.plot.left, frame.plot.bottom + frame.plot.height },
    kBlack, 1.0);
  for (std::size_t i = 0; i < yTicks.size(); ++i)
  {
    const glm::dvec2 at = frame.px(frame.xMin, yTicks[i]);
    drawLine(panel, at - glm::dvec2(4, 0), at, kBlack, 1.0);
    putText(panel, yLabels[i], kBodyFontPx, int(frame.plot.left) - 6 - textWidth(yLabels[i], kBodyFontPx), int(at.y) - 5);
  }
  if (xTicks.empty())
  {
    xTicks = { frame.xMin, 0.5 * (frame.xMin + frame.xMax), frame.xMax };
  }
  const std::vector<std::string> xLabels = distinctTickLabels(xTicks);
  for (std::size_t i = 0; i < xTicks.size(); ++i)
  {
    const glm::dvec2 at = frame.px(xTicks[i], frame.yMin);
    drawLine(panel, at, at - glm::dvec2(0, 4), kBlack, 1.0);
    const int width = textWidth(xLabels[i], kBodyFontPx);
    putText(panel, xLabels[i], kBodyFontPx,
      std::clamp(int(at.x) - width / 2, int(box.left), int(box.left + box.width) - width), int(at.y) - 6 - kKeyLinePx + 4);
  }
  // The axis name shrinks rather than run off the panel.
  const int nameWidthPx = int(box.width) - leftLabelPx;
  putText(panel, xName, fittingFontPx(xName, kBodyFontPx, nameWidthPx), int(box.left + leftLabelPx),
    int(box.bottom) + textBand);
  return frame;
}

// The text lines on top of a diagram, and the band they take.
int drawDiagramText(ImageU8& panel, const Box& box, const std::vector<std::pair<std::string, RgbColor>>& lines)
{
  const int textBand = wrappedLineCount(lines, int(box.width)) * kKeyLinePx + 4;
  drawTextLines(panel, lines, int(box.left), int(box.bottom) + textBand, int(box.width));
  return textBand;
}

// pcf's taps and hard's nearest texel (Williams 1978; Reeves et al. 1987 §3): every texel the filter compared,
// with its stored depth, the compared depth and whether the texel lies in front (shadowed), grouped by texel (a
// Poisson-disk kernel may read one twice). visibility is the weighted share of passed comparisons.
struct ComparedTexel
{
  glm::ivec2 texel{ 0 };
  double storedDepth = 0.0;
  bool occluding = false;
  double weight = 0.0;
  int reads = 0;
};

struct ComparisonGrid
{
  std::vector<ComparedTexel> texels;
  std::string role;
  double comparedDepth = 0.0;
  double litWeight = 0.0;
  double totalWeight = 0.0;
  std::size_t reads = 0;
  std::size_t droppedReads = 0;
  std::optional<glm::dvec2> lookup;
  std::optional<double> recordedVisibility;
  bool polygonIdsDecide = false;
  glm::ivec2 lo{ 0 };
  glm::ivec2 hi{ 0 };
};

std::optional<ComparisonGrid> comparisonGridOf(const ProbeRecord& record, const ProbeSetting& setting)
{
  // Only the filters whose answer is the share of passed comparisons (hard's one texel, pcf's taps); the other
  // techniques' compared texels (a light-leak PCF, PCSS's filter) serve diagrams of their own.
  const bool isHard = std::any_of(
    record.kernels.begin(), record.kernels.end(), [](const ProbeKernel& kernel) { return kernel.role == "nearest texel"; });
  if (!isHard && record.find("lit_taps") == nullptr)
  {
    return std::nullopt;
  }
  ComparisonGrid grid;
  for (const ProbeTexel& texel : record.texels)
  {
    if (std::isnan(texel.comparedDepth))
    {
      continue;
    }
    auto found = std::find_if(
      grid.texels.begin(), grid.texels.end(), [&](const ComparedTexel& seen) { return seen.texel == texel.texel; });
    if (found == grid.texels.end())
    {
      grid.texels.push_back({ texel.texel, texel.storedDepth, texel.occluding, 0.0, 0 });
      found = grid.texels.end() - 1;
    }
    found->weight += texel.weight;
    found->reads += 1;
    grid.litWeight += texel.occluding ? 0.0 : texel.weight;
    grid.totalWeight += texel.weight;
    grid.comparedDepth = texel.comparedDepth;
    grid.role = texel.role;
    ++grid.reads;
  }
  if (grid.texels.empty() || !(grid.totalWeight > 0.0))
  {
    return std::nullopt;
  }
  grid.droppedReads = record.droppedTexels;
  grid.lookup = setting.receiver.uvTexels;
  grid.recordedVisibility = recordedScalar(record, "visibility");
  grid.polygonIdsDecide = record.find("receiver_polygon_id") != nullptr;
  grid.lo = grid.hi = grid.texels.front().texel;
  for (const ComparedTexel& texel : grid.texels)
  {
    grid.lo = glm::min(grid.lo, texel.texel);
    grid.hi = glm::max(grid.hi, texel.texel);
  }
  return grid;
}

ImageU8 comparisonsPanel(const ComparisonGrid& grid, const FigureRect& rect, char letter)
{
  ImageU8 panel = newPanel(rect, panelTag(letter) + "depth comparisons: texels lit or shadowed");
  const Box box = contentBox(rect);
  const bool windowDepth = grid.role.find("window depth") != std::string::npos;
  const std::string unit = windowDepth ? "window depth" : "linear depth";
  const double litFraction = grid.litWeight / grid.totalWeight;
  std::size_t shadowed = 0;
  for (const ComparedTexel& texel : grid.texels)
  {
    shadowed += texel.occluding ? 1 : 0;
  }
  std::vector<std::pair<std::string, RgbColor>> lines = {
    { "compared depth d - bias " + numberText(grid.comparedDepth, 6) + " (" + unit + "); a texel is lit where d - bias <= its stored depth",
      kBlack },
    { format(grid.texels.size(), " texels (", grid.reads, " reads, ", grid.role, "): ", grid.texels.size() - shadowed,
        " lit (white), ", shadowed, " shadowed (black)"),
      kBlack },
    { "weighted lit share = " + numberText(litFraction) +
        (grid.recordedVisibility ? " (recorded visibility " + numberText(*grid.recordedVisibility) + ")" : ""),
      kRayColor },
  };
  if (grid.polygonIdsDecide)
  {
    lines.push_back({ "depth_layer=polygon_id: the ids decide, these depth tests only fill the margins", kDarkGrey });
  }
  if (grid.droppedReads > 0)
  {
    lines.push_back({ format(grid.droppedReads, " more reads over the recorder's cap are not drawn"), kRayColor });
  }
  logDrawnValue("lit_fraction", litFraction);
  logDrawnValue("texels", double(grid.texels.size()));
  const int textBand = drawDiagramText(panel, box, lines);

  // The grid: texel i spans [i, i + 1]; a cell a texel, a margin of half a texel round the kernel.
  const glm::dvec2 lo = glm::dvec2(grid.lo) - 0.5;
  const glm::dvec2 hi = glm::dvec2(grid.hi) + 1.5;
  const Box gridBox{ box.left, box.bottom + textBand + 4.0, box.width, box.height - textBand - 8.0 };
  const View2D view = fitView(lo, hi, gridBox, 0.0);
  const double cellPx = view.scale;
  // Labels where a cell holds them: its stored depth, and its weight where the taps weigh texels differently.
  const bool weightsDiffer = std::any_of(grid.texels.begin(), grid.texels.end(),
    [&](const ComparedTexel& texel) { return std::abs(texel.weight - grid.texels.front().weight) > 1e-9; });
  const std::string sampleLabel = numberText(grid.texels.front().storedDepth, 4);
  const bool depthFits = cellPx >= textWidth(sampleLabel, kBodyFontPx) + 8.0 && cellPx >= 2.0 * kKeyLinePx;
  const bool weightFits = depthFits && weightsDiffer && cellPx >= 3.0 * kKeyLinePx;
  for (const ComparedTexel& texel : grid.texels)
  {
    const glm::dvec2 corner = view.toPx(glm::dvec2(texel.texel));
    const int side = std::max(1, int(std::floor(cellPx)));
    const RgbColor fill = texel.occluding ? kCasterColor : kWhite;
    fillRect(panel, int(corner.x), int(corner.y), side, side, fill);
    strokeRect(panel, int(corner.x), int(corner.y), side, side, kLightGrey, 1);
    if (depthFits)
    {
      const RgbColor ink = texel.occluding ? kWhite : kBlack;
      const std::string depth = numberText(texel.storedDepth, 4);
      const int rowY = int(corner.y + 0.5 * cellPx) - (weightFits ? 0 : kKeyLinePx / 2) + 2;
      putText(panel, depth, kBodyFontPx, int(corner.x + 0.5 * (cellPx - textWidth(depth, kBodyFontPx))), rowY, ink);
      if (weightFits)
      {
        const std::string weight = "w " + numberText(texel.weight, 3);
        putText(panel, weight, kBodyFontPx, int(corner.x + 0.5 * (cellPx - textWidth(weight, kBodyFontPx))),
          rowY - kKeyLinePx, ink);
      }
    }
  }
  if (grid.lookup)
  {
    drawMarker(panel, view.toPx(*grid.lookup), 3.0);
  }
  return panel;
}

// lvsm (Lauritzen & McCool 2008): the light's depth range cut into layers [p_i, q_i]; the receiver's depth t falls in
// one, warped there to phi_i(t) = (t - p_i) / (q_i - p_i); each layer's moments give a Chebyshev bound at phi_j(t).
struct LayerBounds
{
  std::vector<double> ends;     // layer_end_0 .. layer_end_L, linear depth
  double comparedDepth = 0.0;   // t
  std::optional<double> recordedLayer;
  std::vector<std::optional<double>> layerPMax; // layer j's bound (layer_bound=tightest), none where not recorded
  std::optional<double> ownPMax;
  std::optional<double> pMax;
  std::optional<double> warpedDepth;
  std::optional<double> mean;
  std::optional<double> variance;
  std::optional<double> boundSource;
};

std::optional<LayerBounds> layerBoundsOf(const ProbeRecord& record)
{
  LayerBounds bounds;
  for (int i = 0;; ++i)
  {
    const std::optional<double> end = recordedScalar(record, format("layer_end_", i));
    if (!end)
    {
      break;
    }
    bounds.ends.push_back(*end);
  }
  const std::optional<double> t = recordedScalar(record, "compared_depth");
  if (bounds.ends.size() < 2 || !t)
  {
    return std::nullopt;
  }
  bounds.comparedDepth = *t;
  bounds.recordedLayer = recordedScalar(record, "layer");
  for (std::size_t j = 0; j + 1 < bounds.ends.size(); ++j)
  {
    bounds.layerPMax.push_back(recordedScalar(record, format("layer", j, "_p_max")));
  }
  bounds.ownPMax = recordedScalar(record, "own_layer_p_max");
  bounds.pMax = recordedScalar(record, "p_max");
  bounds.warpedDepth = recordedScalar(record, "warped_depth");
  bounds.mean = recordedScalar(record, "mean");
  bounds.variance = recordedScalar(record, "variance");
  bounds.boundSource = recordedScalar(record, "bound_source");
  return bounds;
}

ImageU8 layersPanel(const LayerBounds& bounds, const FigureRect& rect, char letter)
{
  ImageU8 panel = newPanel(rect, panelTag(letter) + "layers along depth, each layer's Chebyshev bound");
  const Box box = contentBox(rect);
  // The layer and the warp from the recorded ends, as the twin and the shader take them (lightspace/LayeredMoments.h).
  const int layer = depthLayerIndex(bounds.comparedDepth, bounds.ends);
  const double p = bounds.ends[std::size_t(layer)];
  const double q = bounds.ends[std::size_t(layer) + 1];
  const double warped = warpIntoLayer(bounds.comparedDepth, depthLayer(layer, bounds.ends));
  logDrawnValue("layer", layer);
  logDrawnValue("warped_depth", warped);
  std::vector<std::pair<std::string, RgbColor>> lines = {
    { format(bounds.ends.size() - 1, " layers; t ", numberText(bounds.comparedDepth, 6), " (linear depth) in layer ", layer,
        " [p, q] = [", numberText(p, 5), ", ", numberText(q, 5), "]",
        bounds.recordedLayer ? " (recorded layer " + numberText(*bounds.recordedLayer) + ")" : std::string()),
      kBlack },
    { "phi(t) = (t - p) / (q - p) = " + numberText(warped) +
        (bounds.mean && bounds.variance ? ", moments in the layer: mean " + numberText(*bounds.mean) + ", variance " +
              numberText(*bounds.variance) + " (warped depth)"
                                         : std::string()),
      kBlack },
  };
  if (bounds.ownPMax)
  {
    lines.push_back({ "own layer's bound " + numberText(*bounds.ownPMax) +
        (bounds.pMax ? "; p_max taken " + numberText(*bounds.pMax) : std::string()) +
        (bounds.boundSource ? (*bounds.boundSource < 0.0 ? " (from vsm's bound)"
                                                         : " (from layer " + numberText(*bounds.boundSource) + ")")
                            : std::string()),
      kRayColor });
  }
  const int textBand = drawDiagramText(panel, box, lines);

  // A margin of 3 % each side, so a receiver at the far end (the last layer's q) stays in sight.
  const double lo = std::min(bounds.ends.front(), bounds.comparedDepth);
  const double hi = std::max(bounds.ends.back(), bounds.comparedDepth);
  const double margin = 0.03 * std::max(hi - lo, 1e-9);
  const PlotFrame frame = drawPlotFrame(panel, box, textBand, lo - margin, hi + margin, 0.0, 1.0,
    "linear depth (bars: layer j's bound at phi_j(t))", { 0.0, 0.5, 1.0 },
    { bounds.ends.front(), 0.5 * (bounds.ends.front() + bounds.ends.back()), bounds.ends.back() });
  for (std::size_t j = 0; j + 1 < bounds.ends.size(); ++j)
  {
    const glm::dvec2 a = frame.px(bounds.ends[j], 0.0);
    const glm::dvec2 b = frame.px(bounds.ends[j + 1], 1.0);
    const RgbColor band = int(j) == layer ? RgbColor{ 1.0, 0.93, 0.6 } : (j % 2 ? RgbColor{ 0.93, 0.93, 0.93 } : kWhite);
    fillRect(panel, int(a.x) + 1, int(a.y) + 1, std::max(1, int(b.x - a.x) - 1), int(b.y - a.y) - 1, band);
    drawLine(panel, { a.x, a.y }, { a.x, b.y }, kDarkGrey, 1.0);
    const std::optional<double> bound = int(j) == layer && !bounds.layerPMax[j] ? bounds.ownPMax : bounds.layerPMax[j];
    if (bound)
    {
      // The bar in the middle third of the layer's band.
      const double barLeft = a.x + (b.x - a.x) / 3.0;
      const double barWidth = std::max(2.0, (b.x - a.x) / 3.0);
      const double top = frame.px(bounds.ends[j], std::clamp(*bound, 0.0, 1.0)).y;
      fillRect(panel, int(barLeft), int(a.y), int(barWidth), std::max(1, int(top - a.y)), kPenumbraColor);
    }
    // The layer's index in its band's left third, beside the bar, where the band is wide enough.
    const std::string label = format(j);
    if (b.x - a.x >= 3.0 * (textWidth(label, kBodyFontPx) + 6))
    {
      putText(panel, label, kBodyFontPx, int(a.x) + 4, int(b.y) - kKeyLinePx, int(j) == layer ? kBlack : kDarkGrey);
    }
  }
  drawLine(panel, frame.px(bounds.ends.back(), 0.0), frame.px(bounds.ends.back(), 1.0), kDarkGrey, 1.0);
  const glm::dvec2 at = frame.px(bounds.comparedDepth, 0.0);
  drawLine(panel, at, frame.px(bounds.comparedDepth, 1.0), kBlack, 4.0);
  drawLine(panel, at, frame.px(bounds.comparedDepth, 1.0), kProbeMarkerColor, 2.0);
  return panel;
}

// The Hamburger 4MSM of msm and of msmsoft's filter step (Peters & Klein 2015, Alg. 3): the biased moments b' are
// matched by a distribution on three depths, z_f (the receiver's) and the roots z_2 <= z_3 of the quadratic, with
// weights w_f, w_2, w_3; the shadow intensity is the weight of the support points in front of z_f (clamped to [0, 1]).
struct MomentDistribution
{
  std::vector<double> moments;       // b_1 .. b_4
  std::vector<double> biasedMoments; // b'_1 .. b'_4
  double fragmentDepth = 0.0;        // z_f
  double supportNear = 0.0;          // z_2
  double supportFar = 0.0;           // z_3
  std::vector<double> weights;       // w_f, w_2, w_3
  std::optional<double> recordedIntensity;
  double intensity() const
  {
    double inFront = 0.0;
    inFront += supportNear < fragmentDepth ? weights[1] : 0.0;
    inFront += supportFar < fragmentDepth ? weights[2] : 0.0;
    return std::clamp(inFront, 0.0, 1.0);
  }
};

std::optional<MomentDistribution> momentDistributionOf(const ProbeRecord& record)
{
  const ProbeQuantity* weights = record.find("support_weights");
  const std::optional<double> zf = recordedScalar(record, "fragment_depth");
  const std::optional<double> z2 = recordedScalar(record, "support_depth_near");
  const std::optional<double> z3 = recordedScalar(record, "support_depth_far");
  if (weights == nullptr || weights->value.size() != 3 || !zf || !z2 || !z3)
  {
    return std::nullopt;
  }
  MomentDistribution distribution;
  distribution.fragmentDepth = *zf;
  distribution.supportNear = *z2;
  distribution.supportFar = *z3;
  distribution.weights = weights->value;
  distribution.recordedIntensity = recordedScalar(record, "shadow_intensity");
  const auto fourMoments = [&](const char* first3, const char* fourth) {
    std::vector<double> values;
    if (const ProbeQuantity* three = record.find(first3); three != nullptr && three->value.size() == 3)
    {
      values = three->value;
      if (const std::optional<double> last = recordedScalar(record, fourth))
      {
        values.push_back(*last);
      }
    }
    return values;
  };
  // msm's moments over its box; msmsoft's over the penumbra kernel, whose reconstruction the support is.
  distribution.moments = fourMoments("power_moments", "power_moment_4");
  if (distribution.moments.empty())
  {
    distribution.moments = fourMoments("filter_moments", "filter_moment_4");
  }
  distribution.biasedMoments = fourMoments("biased_moments", "biased_moment_4");
  return distribution;
}

ImageU8 momentBoundPanel(const MomentDistribution& distribution, const FigureRect& rect, char letter)
{
  ImageU8 panel = newPanel(rect, panelTag(letter) + "MSM Alg. 3: three-point distribution");
  const Box box = contentBox(rect);
  const auto momentText = [](const std::vector<double>& values) {
    std::string text;
    for (std::size_t i = 0; i < values.size(); ++i)
    {
      text += (i ? ", " : "") + numberText(values[i], 5);
    }
    return "(" + text + ")";
  };
  const double intensity = distribution.intensity();
  logDrawnValue("shadow_intensity", intensity);
  std::vector<std::pair<std::string, RgbColor>> lines;
  if (distribution.moments.size() == 4)
  {
    lines.push_back({ "moments b = E[z, z^2, z^3, z^4] " + momentText(distribution.moments), kBlack });
  }
  if (distribution.biasedMoments.size() == 4)
  {
    lines.push_back({ "biased b' " + momentText(distribution.biasedMoments), kBlack });
  }
  lines.push_back({ "stems as tall as the weights; black: in front of the receiver z_f (magenta), grey: behind", kDarkGrey });
  lines.push_back({ "support z_f " + numberText(distribution.fragmentDepth, 5) + " (the receiver), z_2 " +
      numberText(distribution.supportNear, 5) + ", z_3 " + numberText(distribution.supportFar, 5) + "; weights " +
      momentText(distribution.weights),
    kBlack });
  lines.push_back({ "shadow intensity = weight in front of z_f = " + numberText(intensity) +
      (distribution.recordedIntensity ? " (recorded " + numberText(*distribution.recordedIntensity) + ")" : ""),
    kRayColor });
  const int textBand = drawDiagramText(panel, box, lines);

  const double xLo = std::min({ 0.0, distribution.supportNear, distribution.fragmentDepth });
  const double xHi = std::max({ 1.0, distribution.supportFar, distribution.fragmentDepth });
  const double xMin = xLo - 0.03 * (xHi - xLo);
  const double xMax = xHi + 0.03 * (xHi - xLo);
  const PlotFrame frame = drawPlotFrame(panel, box, textBand, xMin, xMax, 0.0, 1.0,
    "moment depth z (stems: weights)", { 0.0, 0.5, 1.0 }, { 0.0, 0.5, 1.0 });
  const struct
  {
    double depth;
    double weight;
    const char* name;
  } points[] = { { distribution.supportNear, distribution.weights[1], "z_2" },
    { distribution.supportFar, distribution.weights[2], "z_3" },
    { distribution.fragmentDepth, distribution.weights[0], "z_f" } };
  for (const auto& point : points)
  {
    const bool isReceiver = std::string(point.name) == "z_f";
    const bool inFront = !isReceiver && point.depth < distribution.fragmentDepth;
    const RgbColor color = isReceiver ? kProbeMarkerColor : inFront ? kCasterColor : kLightGrey;
    const glm::dvec2 foot = frame.px(point.depth, 0.0);
    const glm::dvec2 head = frame.px(point.depth, std::clamp(point.weight, 0.0, 1.0));
    if (isReceiver)
    {
      drawDashedLine(panel, foot, frame.px(point.depth, 1.0), kProbeMarkerColor, 2.0, 5.0);
    }
    drawLine(panel, foot, head, color, 4.0);
    fillDisk(panel, head, 6.0, kBlack);
    fillDisk(panel, head, 4.0, color);
    // Labels above their disks (clear of the axis' labels): the support points' right of their stems, the
    // receiver's left, so z_f beside a support point of similar weight keeps both; each flips where it would
    // leave the plot.
    const int labelWidth = textWidth(point.name, kBodyFontPx);
    const bool roomRight = head.x + 8 + labelWidth <= frame.plot.left + frame.plot.width;
    const bool roomLeft = head.x - 8 - labelWidth >= box.left;
    const bool labelLeft = isReceiver ? roomLeft : !roomRight;
    putText(panel, point.name, kBodyFontPx, labelLeft ? int(head.x) - 8 - labelWidth : int(head.x) + 8,
      int(head.y) + 4, kBlack);
  }
  return panel;
}

// convsm (Annen et al. 2007): the test H(z - d) as its Fourier series truncated to M terms, filtered over the kernel:
// f(d) = 1/2 + 2 sum_k sigma_k / c_k E[sin(c_k (z - d))], recorded at nine depths d' around the receiver's d_s; and,
// for comparison, the same M terms for one occluder at d_s, whose overshoot is the truncation's ringing.
struct FourierSeries
{
  std::vector<glm::dvec2> filtered;   // (d', f(d')), in order
  std::vector<double> frequencies;    // c_k
  std::vector<double> dampings;       // sigma_k
  int terms = 0;                      // M
  double seriesDepth = 0.0;           // d_s
  std::optional<double> recordedReconstruction;
  std::optional<double> scale;
  std::optional<double> visibility;
  double stepAt(double depth) const
  {
    double sum = 0.5;
    for (std::size_t k = 0; k < frequencies.size(); ++k)
    {
      sum += 2.0 * dampings[k] / frequencies[k] * std::sin(frequencies[k] * (seriesDepth - depth));
    }
    return sum;
  }
};

std::optional<FourierSeries> fourierSeriesOf(const ProbeRecord& record)
{
  FourierSeries series;
  for (int j = 0;; ++j)
  {
    const ProbeQuantity* sample = record.find(format("reconstructed_step_", j));
    if (sample == nullptr || sample->value.size() != 2)
    {
      break;
    }
    series.filtered.push_back({ sample->value[0], sample->value[1] });
  }
  const std::optional<double> terms = recordedScalar(record, "terms");
  const std::optional<double> ds = recordedScalar(record, "d_series");
  if (series.filtered.size() < 2 || !terms || !ds)
  {
    return std::nullopt;
  }
  for (int k = 1; k <= int(*terms); ++k)
  {
    const std::optional<double> c = recordedScalar(record, format("c_", k));
    const std::optional<double> sigma = recordedScalar(record, format("sigma_", k));
    if (!c || !sigma)
    {
      break;
    }
    series.frequencies.push_back(*c);
    series.dampings.push_back(*sigma);
  }
  series.terms = int(*terms);
  if (int(series.frequencies.size()) != series.terms)
  {
    // Without every c_k and sigma_k the step's series is not the one the technique took: no grey curve.
    series.frequencies.clear();
    series.dampings.clear();
  }
  series.seriesDepth = *ds;
  series.recordedReconstruction = recordedScalar(record, "reconstruction");
  series.scale = recordedScalar(record, "reconstruction_scale");
  series.visibility = recordedScalar(record, "visibility");
  return series;
}

ImageU8 fourierPanel(const FourierSeries& series, const FigureRect& rect, char letter)
{
  ImageU8 panel = newPanel(rect, panelTag(letter) + format("CSM: the step's Fourier series, M = ", series.terms));
  const Box box = contentBox(rect);
  // The recorded sample at d_s itself (d' = d_s + 0 / 2M): the receiver's reconstruction.
  std::optional<double> atReceiver;
  double overshoot = 0.0;
  double dMin = series.filtered.front().x;
  double dMax = series.filtered.front().x;
  for (const glm::dvec2& sample : series.filtered)
  {
    if (std::abs(sample.x - series.seriesDepth) < 1e-12 && !atReceiver)
    {
      atReceiver = sample.y;
    }
    overshoot = std::max({ overshoot, sample.y - 1.0, -sample.y });
    dMin = std::min(dMin, sample.x);
    dMax = std::max(dMax, sample.x);
  }
  if (atReceiver)
  {
    logDrawnValue("reconstruction", *atReceiver);
  }
  logDrawnValue("overshoot", overshoot);
  double stepOvershoot = 0.0;
  std::vector<glm::dvec2> stepCurve;
  if (!series.frequencies.empty())
  {
    for (int i = 0; i <= 300; ++i)
    {
      const double depth = dMin + (dMax - dMin) * i / 300.0;
      const double value = series.stepAt(depth);
      stepCurve.push_back({ depth, value });
      stepOvershoot = std::max({ stepOvershoot, value - 1.0, -value });
    }
  }
  logDrawnValue("step_overshoot", stepOvershoot);
  std::vector<std::pair<std::string, RgbColor>> lines = {
    { "d_s " + numberText(series.seriesDepth, 5) + " (the receiver's depth in the series); blue: f(d') filtered over the kernel at " +
        format(series.filtered.size()) + " recorded d'",
      kBlack },
    { "grey: the M-term series of one occluder at d_s, overshoot " + numberText(stepOvershoot, 3) +
        " (ringing); filtered overshoot " + numberText(overshoot, 3),
      kDarkGrey },
    { "f(d_s) = " + (atReceiver ? numberText(*atReceiver) : std::string("n/a")) +
        (series.recordedReconstruction ? " (recorded " + numberText(*series.recordedReconstruction) + ")" : "") +
        (series.scale && series.visibility
            ? "; visibility = clamp(" + numberText(*series.scale, 3) + " f, 0, 1) = " + numberText(*series.visibility)
            : std::string()),
      kRayColor },
  };
  const int textBand = drawDiagramText(panel, box, lines);
  double yMin = -0.2;
  double yMax = 1.2;
  for (const glm::dvec2& point : series.filtered)
  {
    yMin = std::min(yMin, point.y);
    yMax = std::max(yMax, point.y);
  }
  for (const glm::dvec2& point : stepCurve)
  {
    yMin = std::min(yMin, point.y);
    yMax = std::max(yMax, point.y);
  }
  // A margin of 3 % each side: the recorded depths stop at the series' domain end, where a receiver may sit.
  const double dMargin = 0.03 * std::max(dMax - dMin, 1e-9);
  const PlotFrame frame = drawPlotFrame(panel, box, textBand, dMin - dMargin, dMax + dMargin, yMin, yMax,
    "d', compared depth in the series (s d_n)", { 0.0, 0.5, 1.0 });
  for (const double level : { 0.0, 1.0 })
  {
    drawDashedLine(panel, frame.px(dMin, level), frame.px(dMax, level), kLightGrey, 1.0, 4.0);
  }
  for (std::size_t i = 1; i < stepCurve.size(); ++i)
  {
    drawLine(panel, frame.px(stepCurve[i - 1].x, stepCurve[i - 1].y), frame.px(stepCurve[i].x, stepCurve[i].y), kLightGrey, 2.0);
  }
  for (std::size_t i = 1; i < series.filtered.size(); ++i)
  {
    drawLine(panel, frame.px(series.filtered[i - 1].x, series.filtered[i - 1].y),
      frame.px(series.filtered[i].x, series.filtered[i].y), kPenumbraColor, 2.0);
  }
  for (const glm::dvec2& sample : series.filtered)
  {
    const bool outside = sample.y < 0.0 || sample.y > 1.0;
    fillDisk(panel, frame.px(sample.x, sample.y), 4.0, outside ? kRayColor : kPenumbraColor);
  }
  drawDashedLine(panel, frame.px(series.seriesDepth, yMin), frame.px(series.seriesDepth, yMax), kProbeMarkerColor, 2.0, 5.0);
  if (atReceiver)
  {
    drawMarker(panel, frame.px(series.seriesDepth, *atReceiver), 3.0);
  }
  return panel;
}

// ss08's level of quality (Schwarz & Stamminger 2008, §4.2): the smoothed LOQ l at the pixel picks the levels
// floor(l) and ceil(l) of the micro-occluder hierarchy, weighted 1 - a and a (a from l's fractional part through the
// blend band); each level's back-projection gives V(level), and V = (1 - a) V(floor l) + a V(ceil l).
struct LevelBlend
{
  double loq = 0.0;
  std::optional<double> blendBand;
  std::vector<std::pair<int, double>> levels;  // level, its weight (floor first)
  std::vector<double> levelVisibility;         // V(level), same order
  std::optional<double> recordedVisibility;
  double visibility() const
  {
    double sum = 0.0;
    for (std::size_t k = 0; k < levels.size(); ++k)
    {
      sum += levels[k].second * levelVisibility[k];
    }
    return sum;
  }
};

std::optional<LevelBlend> levelBlendOf(const ProbeRecord& record)
{
  const std::optional<double> loq = recordedScalar(record, "loq");
  const std::optional<double> weightFloor = recordedScalar(record, "weight_floor");
  const std::optional<double> weightCeil = recordedScalar(record, "weight_ceil");
  if (!loq || !weightFloor || !weightCeil)
  {
    return std::nullopt;
  }
  LevelBlend blend;
  blend.loq = *loq;
  blend.blendBand = recordedScalar(record, "blend_band");
  blend.recordedVisibility = recordedScalar(record, "visibility");
  // Each level's V sits in its group "level <k> (floor)" or "level <k> (ceil)", in that order.
  for (const ProbeQuantity& quantity : record.quantities)
  {
    int level = 0;
    char role[8] = {};
    if (quantity.name != "level_visibility" || quantity.value.empty() ||
      std::sscanf(quantity.group.c_str(), "level %d (%7[a-z])", &level, role) != 2)
    {
      continue;
    }
    const bool isFloor = std::string(role) == "floor";
    blend.levels.push_back({ level, isFloor ? *weightFloor : *weightCeil });
    blend.levelVisibility.push_back(quantity.value[0]);
  }
  if (blend.levels.empty())
  {
    return std::nullopt;
  }
  return blend;
}

ImageU8 levelBlendPanel(const LevelBlend& blend, const FigureRect& rect, char letter)
{
  ImageU8 panel = newPanel(rect, panelTag(letter) + "SS08 §4.2: level of quality and the levels blended");
  const Box box = contentBox(rect);
  const double visibility = blend.visibility();
  logDrawnValue("visibility", visibility);
  logDrawnValue("loq", blend.loq);
  std::string levelsText;
  std::string sumText;
  for (std::size_t k = 0; k < blend.levels.size(); ++k)
  {
    levelsText += format(k ? ", " : "", "level ", blend.levels[k].first, " weight ", numberText(blend.levels[k].second),
      " V ", numberText(blend.levelVisibility[k]));
    sumText += (k ? " + " : "") + numberText(blend.levels[k].second) + " x " + numberText(blend.levelVisibility[k]);
  }
  std::vector<std::pair<std::string, RgbColor>> lines = {
    { "LOQ l = " + numberText(blend.loq) + " levels (the smoothed LOQ map at the pixel)" +
        (blend.blendBand ? ", blend band " + numberText(*blend.blendBand) : std::string()),
      kBlack },
    { levelsText + " (bars: weights, dots: each level's V)", kBlack },
    { "V = " + sumText + " = " + numberText(visibility) +
        (blend.recordedVisibility ? " (recorded " + numberText(*blend.recordedVisibility) + ")" : ""),
      kRayColor },
  };
  const int textBand = drawDiagramText(panel, box, lines);
  int maxLevel = int(std::ceil(blend.loq));
  for (const auto& level : blend.levels)
  {
    maxLevel = std::max(maxLevel, level.first);
  }
  maxLevel = std::max(maxLevel + 1, 2);
  std::vector<double> levelTicks;
  for (int level = 0; level <= maxLevel; level += std::max(1, maxLevel / 4))
  {
    levelTicks.push_back(level);
  }
  const PlotFrame frame = drawPlotFrame(panel, box, textBand, -0.5, maxLevel + 0.5, 0.0, 1.0,
    "level of the micro-occluder hierarchy", { 0.0, 0.5, 1.0 }, levelTicks);
  for (std::size_t k = 0; k < blend.levels.size(); ++k)
  {
    const double level = blend.levels[k].first;
    const glm::dvec2 foot = frame.px(level - 0.3, 0.0);
    const glm::dvec2 top = frame.px(level + 0.3, std::clamp(blend.levels[k].second, 0.0, 1.0));
    fillRect(panel, int(foot.x), int(foot.y), std::max(1, int(top.x - foot.x)), std::max(1, int(top.y - foot.y)), kLightGrey);
    const glm::dvec2 dot = frame.px(level, std::clamp(blend.levelVisibility[k], 0.0, 1.0));
    fillDisk(panel, dot, 6.0, kBlack);
    fillDisk(panel, dot, 4.0, kPenumbraColor);
  }
  drawDashedLine(panel, frame.px(blend.loq, 0.0), frame.px(blend.loq, 1.0), kProbeMarkerColor, 2.0, 5.0);
  const glm::dvec2 at = frame.px(blend.loq, std::clamp(visibility, 0.0, 1.0));
  drawMarker(panel, at, 3.0);
  return panel;
}

// izb (Johnson et al. 2005; Aila & Laine 2004): the receiver's sample lands in one texel of the light-space grid
// (a cube face for a point light), whose list holds the samples there; every caster triangle whose conservative
// cover holds that texel is tested against the sample, and the sample is lit unless one covers it. The record holds
// the texel and the counts, not the triangles' shapes: the diagram draws the texel around the sample and lists them.
struct IrregularTexel
{
  int face = 0;
  glm::dvec2 position{ 0.0 };    // in the face, texels
  double triangleTests = 0.0;
  std::optional<double> gpuTriangleTests;
  std::optional<double> gpuListLength;
  std::vector<std::string> covering;       // "triangle_12", ...: cover the sample
  std::vector<std::string> withinRounding; // "triangle_7 (within rounding)", ...
  bool sharedEdgePair = false;
  std::optional<double> recordedVisibility;
  double visibility() const { return covering.empty() && !sharedEdgePair ? 1.0 : 0.0; }
};

std::optional<IrregularTexel> irregularTexelOf(const ProbeRecord& record)
{
  const std::optional<double> face = recordedScalar(record, "face");
  const ProbeQuantity* texel = record.find("texel");
  const std::optional<double> tests = recordedScalar(record, "izb_triangle_tests");
  if (!face || texel == nullptr || texel->value.size() != 2 || !tests)
  {
    return std::nullopt;
  }
  IrregularTexel result;
  result.face = int(*face);
  result.position = { texel->value[0], texel->value[1] };
  result.triangleTests = *tests;
  result.gpuTriangleTests = recordedScalar(record, "gpu_izb_triangle_tests");
  result.gpuListLength = recordedScalar(record, "gpu_izb_list_length");
  for (const ProbeQuantity& quantity : record.quantities)
  {
    // "triangle_<i> (covers)" shadows the sample; "(within rounding)" only makes the pixel ambiguous.
    const std::string covers = " (covers)";
    const bool isTriangle = quantity.name.rfind("triangle_", 0) == 0;
    if (isTriangle && quantity.name.size() > covers.size() &&
      quantity.name.compare(quantity.name.size() - covers.size(), covers.size(), covers) == 0)
    {
      result.covering.push_back(quantity.name.substr(0, quantity.name.size() - covers.size()));
    }
    else if (isTriangle)
    {
      result.withinRounding.push_back(quantity.name);
    }
  }
  result.sharedEdgePair = record.find("shared_edge_pair") != nullptr;
  result.recordedVisibility = recordedScalar(record, "visibility");
  return result;
}

ImageU8 irregularTexelPanel(const IrregularTexel& texel, const FigureRect& rect, char letter)
{
  ImageU8 panel = newPanel(rect, panelTag(letter) + "IZB: the sample's light-space texel");
  const Box box = contentBox(rect);
  const double visibility = texel.visibility();
  logDrawnValue("visibility", visibility);
  logDrawnValue("covering_triangles", double(texel.covering.size()));
  const glm::ivec2 cell(int(std::floor(texel.position.x)), int(std::floor(texel.position.y)));
  std::string coveringText;
  for (std::size_t i = 0; i < texel.covering.size(); ++i)
  {
    coveringText += (i ? ", " : "") + texel.covering[i];
  }
  std::vector<std::pair<std::string, RgbColor>> lines = {
    { format("face ", texel.face, ", texel (", cell.x, ", ", cell.y, "), sample at (", numberText(texel.position.x, 6),
        ", ", numberText(texel.position.y, 6), ") texels"),
      kBlack },
    { "its list: " + (texel.gpuListLength ? numberText(*texel.gpuListLength) : std::string("?")) +
        " samples (GPU); triangles whose cover holds it: " + numberText(texel.triangleTests) +
        (texel.gpuTriangleTests ? " (GPU " + numberText(*texel.gpuTriangleTests) + ")" : ""),
      kBlack },
    { texel.covering.empty() ? std::string("no tested triangle covers the sample")
                             : "covering the sample, between it and the light: " + coveringText,
      texel.covering.empty() ? kDarkGrey : kBlack },
  };
  if (!texel.withinRounding.empty())
  {
    std::string text;
    for (std::size_t i = 0; i < texel.withinRounding.size(); ++i)
    {
      text += (i ? ", " : "") + texel.withinRounding[i];
    }
    lines.push_back({ "within float rounding of the sample (ambiguous, not covering): " + text, kDarkGrey });
  }
  if (texel.sharedEdgePair)
  {
    lines.push_back({ "two triangles sharing the edge the sample lies on (README.md, Shared edges)", kBlack });
  }
  lines.push_back({ "V = " + numberText(visibility) + (texel.covering.empty() && !texel.sharedEdgePair ? " (lit)" : " (covered)") +
      (texel.recordedVisibility ? " (recorded " + numberText(*texel.recordedVisibility) + ")" : ""),
    kRayColor });
  const int textBand = drawDiagramText(panel, box, lines);

  // The texel and its eight neighbours, the sample's texel filled (dark where covered), the sample marked.
  const Box gridBox{ box.left, box.bottom + textBand + 4.0, box.width, box.height - textBand - 8.0 };
  const View2D view = fitView(glm::dvec2(cell) - 1.0, glm::dvec2(cell) + 2.0, gridBox, 0.02);
  const int side = std::max(1, int(std::floor(view.scale)));
  for (int dy = -1; dy <= 1; ++dy)
  {
    for (int dx = -1; dx <= 1; ++dx)
    {
      const glm::dvec2 corner = view.toPx(glm::dvec2(cell + glm::ivec2(dx, dy)));
      const bool own = dx == 0 && dy == 0;
      const RgbColor fill = !own ? kWhite : visibility < 1.0 ? kCasterColor : RgbColor{ 1.0, 0.93, 0.6 };
      fillRect(panel, int(corner.x), int(corner.y), side, side, fill);
      strokeRect(panel, int(corner.x), int(corner.y), side, side, own ? kBlack : kLightGrey, own ? 2 : 1);
    }
  }
  drawMarker(panel, view.toPx(texel.position), 4.0);
  return panel;
}

} // namespace

std::string probeQuantityText(const ProbeQuantity& quantity)
{
  const std::string value = quantity.text.empty() ? vectorText(quantity.value) : quantity.text;
  return quantity.name + " " + value + (quantity.unit.empty() ? "" : " " + quantity.unit);
}

namespace
{

// The legend's lines, each with its colour.
class LegendLines
{
public:
  void add(const std::string& text, const RgbColor& color = kBlack) { lines_.emplace_back(text, color); }
  const std::vector<std::pair<std::string, RgbColor>>& lines() const { return lines_; }

private:
  std::vector<std::pair<std::string, RgbColor>> lines_;
};

// What was probed and whether the GPU and the twin agree; the light and the receiver.
void addProbeSummary(LegendLines& lines, const ProbeResult& probe, const ProbeSetting& setting)
{
  const Light& light = *setting.light;
  lines.add("technique " + probe.technique);
  lines.add(format("pixel ", probe.pixel.x, ",", probe.pixel.y, " (row 0 at the bottom)"));
  lines.add("GPU visibility  " + numberText(probe.gpuVisibility, 6));
  lines.add("twin visibility " + numberText(probe.outcome.visibility, 6) +
    (probe.outcome.evaluated ? "" : " (no shadow test)"));
  const bool agrees = probe.agrees();
  lines.add("|GPU - twin| " + numberText(probe.difference(), 3) + ", tolerance " + numberText(probe.outcome.tolerance, 3) +
      ": " + (agrees ? "agree" : "DIFFER"),
    agrees ? RgbColor{ 0.0, 0.35, 0.0 } : RgbColor{ 0.75, 0.0, 0.0 });
  if (!probe.outcome.ambiguity.empty())
  {
    lines.add("ambiguous: " + probe.outcome.ambiguity, kDarkGrey);
  }
  lines.add("twin: " + probe.outcome.twin, kDarkGrey);
  lines.add(std::string("light ") + lightTypeName(light.type) +
    (light.type == LightType::Area ? std::string(" ") + lightShapeName(light.shape) + ", size " + numberText(light.size)
                                   : ""));
  const glm::dvec3& p = setting.receiver.position;
  lines.add("receiver (" + numberText(p.x) + ", " + numberText(p.y) + ", " + numberText(p.z) + ")");
  lines.add("receiver depth " + numberText(setting.receiver.depthLin, 6) + " (linear)");
  if (setting.receiver.bias)
  {
    lines.add("depth bias " + numberText(*setting.receiver.bias));
  }
  if (setting.receiver.uvTexels)
  {
    lines.add("shadow-map position (" + numberText(setting.receiver.uvTexels->x, 6) + ", " +
      numberText(setting.receiver.uvTexels->y, 6) + ") texels");
  }
}

// One line for the kernels of a role, with their size range and their labels' counts (vssm records dozens of
// sub-kernels, yfgl09 one per packet pixel).
std::string kernelRoleLine(const ProbeRecord& record, const std::string& role)
{
  std::size_t count = 0;
  glm::dvec2 smallest(1e300);
  glm::dvec2 largest(0.0);
  std::vector<std::pair<std::string, std::size_t>> labels;
  for (const ProbeKernel& kernel : record.kernels)
  {
    if (kernel.role != role)
    {
      continue;
    }
    ++count;
    smallest = glm::min(smallest, kernel.hi - kernel.lo);
    largest = glm::max(largest, kernel.hi - kernel.lo);
    if (!kernel.label.empty())
    {
      const auto found =
        std::find_if(labels.begin(), labels.end(), [&](const auto& entry) { return entry.first == kernel.label; });
      if (found == labels.end())
      {
        labels.emplace_back(kernel.label, 1);
      }
      else
      {
        ++found->second;
      }
    }
  }
  const auto range = [](double lo, double hi) { return lo == hi ? numberText(lo) : numberText(lo) + ".." + numberText(hi); };
  std::string labelText;
  for (const auto& [label, labelCount] : labels)
  {
    labelText += (labelText.empty() ? "" : ", ") + (count == 1 ? label : label + " " + std::to_string(labelCount));
  }
  return std::string("kernel ") + role + (count > 1 ? format(" x", count) : std::string()) + ": " +
    range(smallest.x, largest.x) + " x " + range(smallest.y, largest.y) + " texels" +
    (labelText.empty() ? "" : " (" + labelText + ")");
}

// The record's counts: texels read, kernels by role, nodes by decision, light polygons, contour edges, samples.
void addRecordCounts(LegendLines& lines, const ProbeRecord& record)
{
  std::size_t compared = 0;
  std::size_t occluding = 0;
  for (const ProbeTexel& texel : record.texels)
  {
    compared += std::isnan(texel.comparedDepth) ? 0 : 1;
    occluding += texel.occluding ? 1 : 0;
  }
  if (!record.texels.empty() || record.droppedTexels > 0)
  {
    lines.add(format("texels read ", record.texels.size() + record.droppedTexels, " (compared ", compared,
      ", occluding ", occluding, record.droppedTexels > 0 ? format("; ", record.droppedTexels, " not kept") : std::string(),
      ")"));
  }
  for (const std::string& role : kernelRoleLabels(record))
  {
    lines.add(kernelRoleLine(record, role));
  }
  if (!record.nodes.empty() || record.droppedNodes > 0)
  {
    std::string byDecision;
    for (const std::string& decision : nodeDecisionLabels(record))
    {
      const auto count = std::count_if(record.nodes.begin(), record.nodes.end(),
        [&](const ProbeNode& node) { return node.decision == decision; });
      byDecision += (byDecision.empty() ? "" : ", ") + decision + " " + std::to_string(count);
    }
    lines.add(format("nodes visited ", record.nodes.size() + record.droppedNodes, " (", byDecision, ")"));
  }
  if (!record.lightPolygons.empty() || record.droppedPolygons > 0)
  {
    double sum = 0.0;
    for (const ProbeLightPolygon& polygon : record.lightPolygons)
    {
      sum += polygon.signedArea;
    }
    lines.add(format("light polygons ", record.lightPolygons.size() + record.droppedPolygons, ", signed area sum ",
      numberText(sum)));
    for (const std::string& role : polygonRoleLines(record))
    {
      lines.add("- " + role);
    }
  }
  if (!record.contourEdges.empty() || record.droppedEdges > 0)
  {
    lines.add(format("contour edges ", record.contourEdges.size() + record.droppedEdges));
  }
  if (!record.lightSamples.empty())
  {
    const auto blocked = std::count_if(record.lightSamples.begin(), record.lightSamples.end(),
      [](const ProbeLightSample& sample) { return sample.blocked; });
    lines.add(format("light samples ", record.lightSamples.size(), " (blocked ", blocked, ")"));
  }
}

// The record's other quantities, in the twin's order (the receiver's already shown are left out).
// A group name "<prefix> <index>" (vssm's "blocker sub-kernel 12"): the prefix, or "" when it has no index.
std::string indexedGroupPrefix(const std::string& group)
{
  const std::size_t space = group.rfind(' ');
  if (space == std::string::npos || space + 1 >= group.size() ||
    group.find_first_not_of("0123456789", space + 1) != std::string::npos)
  {
    return {};
  }
  return group.substr(0, space);
}

std::string quantityValueText(const ProbeQuantity& quantity)
{
  return quantity.text.empty() ? vectorText(quantity.value) : quantity.text;
}

// The record's other quantities, in the twin's order, under their steps' headings (the receiver's already shown
// are left out). Runs of three or more groups "<prefix> <index>" that record the same quantities (vssm's
// sub-kernels, one group each) become a table: one heading naming the columns with their units, then one line a
// group, "<index>: value | value | ...", every value in full.
void addRecordedQuantities(LegendLines& lines, const ProbeRecord& record)
{
  static const char* shown[] = { "position", "normal", "receiver_depth", "depth_bias", "shadow_map_position" };
  struct Group
  {
    std::string name;
    std::vector<const ProbeQuantity*> quantities;
  };
  std::vector<Group> groups;
  for (const ProbeQuantity& quantity : record.quantities)
  {
    if (quantity.group == "receiver" && std::find(std::begin(shown), std::end(shown), quantity.name) != std::end(shown))
    {
      continue;
    }
    if (groups.empty() || groups.back().name != quantity.group)
    {
      groups.push_back({ quantity.group, {} });
    }
    groups.back().quantities.push_back(&quantity);
  }
  const auto sameColumns = [](const Group& a, const Group& b) {
    if (a.quantities.size() != b.quantities.size())
    {
      return false;
    }
    for (std::size_t i = 0; i < a.quantities.size(); ++i)
    {
      if (a.quantities[i]->name != b.quantities[i]->name || a.quantities[i]->unit != b.quantities[i]->unit)
      {
        return false;
      }
    }
    return true;
  };
  for (std::size_t g = 0; g < groups.size();)
  {
    const std::string prefix = indexedGroupPrefix(groups[g].name);
    std::size_t end = g + 1;
    while (!prefix.empty() && end < groups.size() && indexedGroupPrefix(groups[end].name) == prefix &&
      sameColumns(groups[g], groups[end]))
    {
      ++end;
    }
    if (end - g >= 3)
    {
      std::string columns;
      for (const ProbeQuantity* quantity : groups[g].quantities)
      {
        columns += (columns.empty() ? "" : " | ") + quantity->name + (quantity->unit.empty() ? "" : " [" + quantity->unit + "]");
      }
      lines.add(format("-- ", prefix, " (", end - g, " groups, one line each): ", columns, " --"), kDarkGrey);
      for (std::size_t k = g; k < end; ++k)
      {
        std::string row = groups[k].name.substr(prefix.size() + 1) + ":";
        for (std::size_t i = 0; i < groups[k].quantities.size(); ++i)
        {
          row += (i == 0 ? " " : " | ") + quantityValueText(*groups[k].quantities[i]);
        }
        lines.add(row);
      }
      g = end;
      continue;
    }
    // The twin's steps as headings, in its order.
    lines.add("-- " + (groups[g].name.empty() ? std::string("recorded") : groups[g].name) + " --", kDarkGrey);
    for (const ProbeQuantity* quantity : groups[g].quantities)
    {
      lines.add(probeQuantityText(*quantity));
    }
    ++g;
  }
}

// The key numbers wrapped to a page's width, and how many rows a page holds.
struct LegendPages
{
  std::vector<std::string> lines; // before wrapping
  std::vector<std::pair<std::string, RgbColor>> rows;
  int rowsPerPage = 1;
  int pageCount() const { return std::max(1, int((rows.size() + rowsPerPage - 1) / rowsPerPage)); }
};

LegendPages legendPages(const ProbeResult& probe, const ProbeSetting& setting)
{
  LegendLines lines;
  addProbeSummary(lines, probe, setting);
  addRecordCounts(lines, probe.record);
  addRecordedQuantities(lines, probe.record);
  const Box box = contentBox({ 0, 0, kProbeFigurePanelSide, kProbeFigurePanelSide });
  LegendPages pages;
  const int lineHeight = measureText("Ag", kBodyFontPx).height + 2;
  const int rowsPerPage = std::max(1, int(box.height) / lineHeight);
  pages.rowsPerPage = rowsPerPage;
  for (const auto& [text, color] : lines.lines())
  {
    pages.lines.push_back(text);
    bool first = true;
    // Wrapped two characters short, so the continuation rows' indent fits too.
    const std::vector<std::string> wrapped = wrapText(text, kBodyFontPx, int(box.width) - textWidth("  ", kBodyFontPx));
    const int rowsLeft = rowsPerPage - int(pages.rows.size() % std::size_t(rowsPerPage));
    if (int(wrapped.size()) > rowsLeft && int(wrapped.size()) <= rowsPerPage)
    {
      // A wrapped line starts the next page rather than break across two.
      pages.rows.insert(pages.rows.end(), std::size_t(rowsLeft), { std::string(), kBlack });
    }
    for (const std::string& line : wrapped)
    {
      // Continuation rows are indented so a wrapped quantity reads as one.
      pages.rows.emplace_back(first ? line : "  " + line, color);
      first = false;
    }
  }
  return pages;
}

ImageU8 legendPanel(const LegendPages& pages, int page, const FigureRect& rect, char letter)
{
  const int pageCount = pages.pageCount();
  ImageU8 panel = newPanel(rect, panelTag(letter) + "key numbers" +
      (pageCount > 1 ? format(", page ", page + 1, " of ", pageCount) : std::string()));
  const Box box = contentBox(rect);
  const int lineHeight = measureText("Ag", kBodyFontPx).height + 2;
  int y = int(box.bottom + box.height) - lineHeight;
  const std::size_t first = std::size_t(page) * std::size_t(pages.rowsPerPage);
  for (std::size_t row = first; row < std::min(pages.rows.size(), first + std::size_t(pages.rowsPerPage)); ++row)
  {
    putText(panel, pages.rows[row].first, kBodyFontPx, int(box.left), y, pages.rows[row].second);
    y -= lineHeight;
  }
  return panel;
}

// Panels in the figure's order with their widths in cells, packed three cells to a row: a two-cell panel that
// does not fit the row's end waits for the next row while the one-cell panels after it fill the gap.
ProbeFigureLayout layoutPanels(const std::vector<std::pair<ProbeFigurePanel, int>>& wanted)
{
  ProbeFigureLayout layout;
  struct Cell
  {
    ProbeFigurePanel panel;
    int row;
    int column;
    int span;
  };
  std::vector<Cell> placed;
  std::vector<std::pair<ProbeFigurePanel, int>> pending = wanted;
  int row = 0;
  while (!pending.empty())
  {
    int column = 0;
    while (column < kProbeFigureColumns)
    {
      const auto fits = std::find_if(pending.begin(), pending.end(),
        [&](const auto& entry) { return entry.second <= kProbeFigureColumns - column; });
      if (fits == pending.end())
      {
        break;
      }
      placed.push_back({ fits->first, row, column, fits->second });
      column += fits->second;
      pending.erase(fits);
    }
    ++row;
  }
  layout.height = row * kProbeFigurePanelSide;
  char letter = 'a';
  for (Cell& cell : placed)
  {
    cell.panel.letter = letter++;
    cell.panel.rect = { cell.column * kProbeFigurePanelSide, layout.height - (cell.row + 1) * kProbeFigurePanelSide,
      cell.span * kProbeFigurePanelSide, kProbeFigurePanelSide };
    layout.panels.push_back(cell.panel);
  }
  return layout;
}

} // namespace

std::optional<FigureRect> ProbeFigureLayout::rect(ProbePanel panel, int page) const
{
  for (const ProbeFigurePanel& placed : panels)
  {
    if (placed.panel == panel && placed.page == page)
    {
      return placed.rect;
    }
  }
  return std::nullopt;
}

char ProbeFigureLayout::letter(ProbePanel panel, int page) const
{
  for (const ProbeFigurePanel& placed : panels)
  {
    if (placed.panel == panel && placed.page == page)
    {
      return placed.letter;
    }
  }
  return '?';
}

int ProbeFigureLayout::pages(ProbePanel panel) const
{
  return static_cast<int>(
    std::count_if(panels.begin(), panels.end(), [&](const ProbeFigurePanel& placed) { return placed.panel == panel; }));
}

std::optional<double> ProbeFigureDrawing::drawnValue(ProbePanel panel, const std::string& name) const
{
  for (const ProbeDrawnValue& drawn : drawnValues)
  {
    if (drawn.panel == panel && drawn.name == name)
    {
      return drawn.value;
    }
  }
  return std::nullopt;
}

ImagePlacement probeImagePlacement(const FigureRect& rect, glm::ivec2 imageSize)
{
  const Box box = contentBox(rect);
  ImagePlacement placement;
  if (imageSize.x <= 0 || imageSize.y <= 0)
  {
    return placement;
  }
  placement.scale = std::min(box.width / imageSize.x, box.height / imageSize.y);
  // Whole canvas pixels for the image's corner, so an integer scale maps pixels onto whole blocks.
  placement.left = rect.left + std::floor(box.left + 0.5 * (box.width - imageSize.x * placement.scale));
  placement.bottom = rect.bottom + std::floor(box.bottom + 0.5 * (box.height - imageSize.y * placement.scale));
  return placement;
}

ProbeFigureDrawing drawProbeFigure(const ProbeResult& probe, const FrameResult& frame, const Scene& scene)
{
  const ProbeSetting setting = probeSetting(probe, frame, scene);
  const ProbeRecord& record = probe.record;
  const LegendPages pages = legendPages(probe, setting);
  const std::optional<PenumbraEstimate> penumbra = penumbraEstimateOf(record, setting);
  const std::optional<ChebyshevPoint> chebyshev = chebyshevPointOf(record);
  const std::optional<ExponentialTest> exponential = exponentialTestOf(record);
  const std::optional<ComparisonGrid> comparisons = comparisonGridOf(record, setting);
  const std::optional<LayerBounds> layers = layerBoundsOf(record);
  const std::optional<MomentDistribution> momentBound = momentDistributionOf(record);
  const std::optional<FourierSeries> fourier = fourierSeriesOf(record);
  const std::optional<LevelBlend> levelBlend = levelBlendOf(record);
  const std::optional<IrregularTexel> irregularTexel = irregularTexelOf(record);

  // Only panels with content: no map, nothing on the light, no algorithm quantities leave theirs out.
  std::vector<std::pair<ProbeFigurePanel, int>> wanted;
  const auto want = [&](ProbePanel panel, int span, int page = 0) { wanted.push_back({ { panel, page, 'a', {} }, span }); };
  want(ProbePanel::Image, 1);
  if (setting.map.depth != nullptr && setting.map.view != nullptr)
  {
    want(ProbePanel::ShadowMap, 1);
  }
  if (hasLightPlaneContent(record))
  {
    want(ProbePanel::LightPlane, 1);
  }
  want(ProbePanel::Section, 2);
  if (penumbra)
  {
    want(ProbePanel::Penumbra, 1);
  }
  if (chebyshev)
  {
    want(ProbePanel::Chebyshev, 1);
  }
  if (exponential)
  {
    want(ProbePanel::Exponential, 1);
  }
  if (comparisons)
  {
    want(ProbePanel::Comparisons, 1);
  }
  if (layers)
  {
    want(ProbePanel::Layers, 1);
  }
  if (momentBound)
  {
    want(ProbePanel::MomentBound, 1);
  }
  if (fourier)
  {
    want(ProbePanel::Fourier, 1);
  }
  if (levelBlend)
  {
    want(ProbePanel::LevelBlend, 1);
  }
  if (irregularTexel)
  {
    want(ProbePanel::IrregularTexel, 1);
  }
  for (int page = 0; page < pages.pageCount(); ++page)
  {
    want(ProbePanel::Legend, 1, page);
  }

  ProbeFigureDrawing drawing;
  drawing.layout = layoutPanels(wanted);
  drawing.legendLines = pages.lines;
  drawing.image = ImageU8(drawing.layout.width, drawing.layout.height, 3, 255);
  tFigureTextLog.texts = &drawing.texts;
  tFigureTextLog.drawn = &drawing.drawnValues;
  struct ResetLog
  {
    ~ResetLog()
    {
      tFigureTextLog.texts = nullptr;
      tFigureTextLog.drawn = nullptr;
    }
  } resetLog;
  for (const ProbeFigurePanel& placed : drawing.layout.panels)
  {
    tFigureTextLog.panel = placed.panel;
    ImageU8 panel;
    switch (placed.panel)
    {
      case ProbePanel::Image:
        panel = imagePanel(probe, frame, placed.rect, placed.letter);
        break;
      case ProbePanel::ShadowMap:
        panel = shadowMapPanel(probe, setting, placed.rect, placed.letter, drawing.colorBarTicks);
        break;
      case ProbePanel::LightPlane:
        panel = lightPlanePanel(probe, setting, placed.rect, placed.letter, drawing.colorBarTicks);
        break;
      case ProbePanel::Section:
        panel = sectionPanel(scene, setting, placed.rect, placed.letter);
        break;
      case ProbePanel::Penumbra:
        panel = penumbraPanel(*penumbra, placed.rect, placed.letter);
        break;
      case ProbePanel::Chebyshev:
        panel = chebyshevPanel(*chebyshev, placed.rect, placed.letter);
        break;
      case ProbePanel::Exponential:
        panel = exponentialPanel(*exponential, placed.rect, placed.letter);
        break;
      case ProbePanel::Comparisons:
        panel = comparisonsPanel(*comparisons, placed.rect, placed.letter);
        break;
      case ProbePanel::Layers:
        panel = layersPanel(*layers, placed.rect, placed.letter);
        break;
      case ProbePanel::MomentBound:
        panel = momentBoundPanel(*momentBound, placed.rect, placed.letter);
        break;
      case ProbePanel::Fourier:
        panel = fourierPanel(*fourier, placed.rect, placed.letter);
        break;
      case ProbePanel::LevelBlend:
        panel = levelBlendPanel(*levelBlend, placed.rect, placed.letter);
        break;
      case ProbePanel::IrregularTexel:
        panel = irregularTexelPanel(*irregularTexel, placed.rect, placed.letter);
        break;
      case ProbePanel::Legend:
        panel = legendPanel(pages, placed.page, placed.rect, placed.letter);
        break;
    }
    blit(drawing.image, panel, placed.rect.left, placed.rect.bottom);
  }
  return drawing;
}

ImageU8 probeFigure(const ProbeResult& probe, const FrameResult& frame, const Scene& scene)
{
  return drawProbeFigure(probe, frame, scene).image;
}

} // namespace sl
