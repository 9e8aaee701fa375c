// probe.png (probe/Probe.h, layout in probe/ProbeFigure.h): what a probe recorded, drawn on a CPU canvas (vis/Canvas.h,
// vis/CanvasShapes.h), so it renders the same with or without a graphics context. Magnitudes (depths) use
// viridis (perceptually uniform), signed areas the diverging blue-white-red map (ColorBrewer RdBu: colour-blind
// safe), categories (node decisions) the Tableau 10 palette; marks that must read without colour (occluding or
// read texels, blocked or visible samples) differ in shape or fill as well.
#include "probe/ProbeFigure.h"

#include "probe/Probe.h"
#include "probe/ProbeGeometry.h"
#include "vis/Canvas.h"
#include "vis/CanvasShapes.h"
#include "vis/ColorKey.h"
#include "vis/ColorMap.h"
#include "vis/HeatMap.h"

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
  if (!std::isfinite(value))
  {
    return std::isnan(value) ? "n/a" : (value > 0 ? "inf" : "-inf");
  }
  char text[64];
  std::snprintf(text, sizeof(text), "%.*g", digits, value);
  return text;
}

int textWidth(const std::string& text, int fontPx)
{
  return measureText(text, fontPx).width;
}

// Cuts `text` to `maxWidthPx`, ending in "..." when cut (Courier: every character is as wide).
std::string fitText(const std::string& text, int fontPx, int maxWidthPx)
{
  if (text.empty() || textWidth(text, fontPx) <= maxWidthPx)
  {
    return text;
  }
  const int charWidth = std::max(1, textWidth("MMMMMMMMMM", fontPx) / 10);
  const int keep = std::max(0, maxWidthPx / charWidth - 3);
  return text.substr(0, static_cast<std::size_t>(keep)) + "...";
}

// Breaks `text` at spaces into lines of at most `maxWidthPx`.
std::vector<std::string> wrapText(const std::string& text, int fontPx, int maxWidthPx)
{
  const int charWidth = std::max(1, textWidth("MMMMMMMMMM", fontPx) / 10);
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
  const int textHeight = measureText("Ag", kTitleFontPx).height;
  drawText(panel, fitText(title, kTitleFontPx, rect.width - 2 * kInsetPx), kTitleFontPx, kInsetPx,
    rect.height - kTitleBandPx + (kTitleBandPx - textHeight) / 2, kBlack);
  return panel;
}

void drawCentredNote(ImageU8& panel, const Box& box, const std::string& note)
{
  const TextSize size = measureText(note, kBodyFontPx);
  drawText(panel, fitText(note, kBodyFontPx, int(box.width)), kBodyFontPx,
    int(box.left + std::max(0.0, 0.5 * (box.width - size.width))), int(box.bottom + 0.5 * (box.height - size.height)),
    kDarkGrey);
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
  drawText(panel, label, kBodyFontPx, x + 17, y, kBlack);
  return x + 17 + textWidth(label, kBodyFontPx) + 12;
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

ImageU8 imagePanel(const ProbeResult& probe, const FrameResult& frame)
{
  const FigureRect rect = probeFigurePanel(ProbePanel::Image);
  ImageU8 panel = newPanel(rect, format("(a) image ", frame.image.width, "x", frame.image.height, ", pixel ",
    probe.pixel.x, ",", probe.pixel.y));
  const Box box = contentBox(rect);
  if (frame.image.empty() || frame.image.components < 3)
  {
    drawCentredNote(panel, box, "no shaded image in this frame");
    return panel;
  }
  const ImagePlacement placement = probeImagePlacement({ frame.image.width, frame.image.height });
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

// The key below the map: the marks on the first line, the node decisions (two to a line, cut to fit; the legend
// and probe.vtm have them in full) or the crop's texel range on the next two.
void drawShadowMapKey(ImageU8& panel, const Box& box, const std::vector<std::string>& decisions, const TexelRect& crop,
  int mapWidth)
{
  const int keyTop = int(box.bottom + 2 * kKeyLinePx + 2);
  int x = int(box.left);
  x = drawKeyEntry(panel, x, keyTop, "kernel", paintBoxSwatch, kWhite);
  x = drawKeyEntry(panel, x, keyTop, "read", paintDot, kWhite);
  x = drawKeyEntry(panel, x, keyTop, "occluding", paintFilledSquare, kBlack);
  x = drawKeyEntry(panel, x, keyTop, "receiver", paintMarkerSwatch, kProbeMarkerColor);
  drawKeyEntry(panel, x, keyTop, "pixel", paintBoxSwatch, kProbeMarkerColor);
  if (decisions.empty())
  {
    drawText(panel, format("texels ", crop.lo.x, "..", crop.lo.x + crop.size.x - 1, " x ", crop.lo.y, "..",
      crop.lo.y + crop.size.y - 1, " of ", mapWidth), kBodyFontPx, int(box.left), int(box.bottom), kDarkGrey);
  }
  const double slotWidth = 0.5 * box.width;
  for (std::size_t d = 0; d < decisions.size(); ++d)
  {
    const int line = int(d / 2);
    const int slotLeft = int(box.left + (d % 2) * slotWidth);
    const int slotBottom = int(box.bottom + (1 - line) * kKeyLinePx);
    if (line == 1 && d % 2 == 1 && decisions.size() > 4)
    {
      drawText(panel, format("+", decisions.size() - d, " more decisions"), kBodyFontPx, slotLeft, slotBottom, kDarkGrey);
      break;
    }
    drawKeyEntry(panel, slotLeft, slotBottom, fitText(decisions[d], kBodyFontPx, int(slotWidth) - 24), paintBoxSwatch,
      ColorMap::categoryColor(long(d)));
  }
}

ImageU8 shadowMapPanel(const ProbeResult& probe, const FrameResult& frame, const ProbeSetting& setting)
{
  const FigureRect rect = probeFigurePanel(ProbePanel::ShadowMap);
  // With views that partition the pixels (cascades) the map is the pixel's own view's, named in the title.
  const ProbeMap& map = setting.map;
  ImageU8 panel = newPanel(rect, map.label.empty() ? std::string("(b) shadow map: linear depth [world units]")
      : "(b) " + map.exportName + ", linear depth");
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
  const ColorKey key = ColorKey::continuous(viridis, range.min, range.max, kBodyFontPx);

  // Layout: the map on the left, its colour bar on the right, three key lines below.
  const double keyBand = 3.0 * kKeyLinePx + 4.0;
  const double labelBand = map.label.empty() ? 0.0 : kKeyLinePx + 2.0; // the view's label above the map
  const Box mapBox{ box.left, box.bottom + keyBand, box.width - key.width() - 6.0, box.height - keyBand - labelBand };
  const double scale = std::min(mapBox.width / crop.size.x, mapBox.height / crop.size.y);
  key.draw(panel, int(mapBox.left + mapBox.width + 6.0), int(mapBox.bottom),
    std::max(key.minHeight(), int(mapBox.height)));

  CropCanvas canvas = paintDepthCrop(arrays, crop, valid, range, viridis, scale);
  const std::vector<std::string> decisions = nodeDecisionLabels(record);
  drawNodesAndKernels(canvas, record, decisions);
  drawTexelsRead(canvas, arrays, crop);
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
  drawShadowMapKey(panel, box, decisions, crop, depthMap->width);
  if (!map.label.empty())
  {
    // Which view of the partition, and the pixels it serves (its split depths), over the map's top edge.
    drawText(panel, fitText(map.label, kBodyFontPx, int(box.width)), kBodyFontPx, int(box.left),
      int(box.bottom + box.height) - measureText("Ag", kBodyFontPx).height, kDarkGrey);
  }
  return panel;
}

// --- (c) the light plane -----------------------------------------------------------------------------------------

ImageU8 lightPlanePanel(const ProbeResult& probe, const ProbeSetting& setting)
{
  const FigureRect rect = probeFigurePanel(ProbePanel::LightPlane);
  ImageU8 panel = newPanel(rect, "(c) light plane (light's view), signed area");
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
  const ColorKey key = ColorKey::continuous(diverging, -areaRange, areaRange, kBodyFontPx);
  const double keyBand = 2.0 * kKeyLinePx + 4.0;
  const Box planeBox{ box.left, box.bottom + keyBand, box.width - (hasAreas ? key.width() + 6.0 : 0.0), box.height - keyBand };
  if (hasAreas)
  {
    key.draw(panel, int(planeBox.left + planeBox.width + 6.0), int(planeBox.bottom),
      std::max(key.minHeight(), int(planeBox.height)));
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
    strokePolygon(plane, points, kDarkGrey, 1.0);
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

  const int keyTop = int(box.bottom + kKeyLinePx + 2);
  int x = int(box.left);
  x = drawKeyEntry(panel, x, keyTop, "light", paintLineSwatch, kBlack);
  x = drawKeyEntry(panel, x, keyTop, "blocked", paintDot, kBlack);
  drawKeyEntry(panel, x, keyTop, "visible sample", paintDot, kWhite);
  double areaSum = 0.0;
  for (const ProbeLightPolygon& polygon : record.lightPolygons)
  {
    areaSum += polygon.signedArea;
  }
  std::string summary = format(record.lightPolygons.size(), " polygons");
  if (!record.lightPolygons.empty())
  {
    summary += ", sum " + numberText(areaSum) + (light.type == LightType::Area ? " (light's area " + numberText(light.area()) + ")" : "");
  }
  if (!record.contourEdges.empty())
  {
    summary += format(", ", record.contourEdges.size(), " edges");
  }
  drawText(panel, fitText(summary, kBodyFontPx, int(box.width)), kBodyFontPx, int(box.left), int(box.bottom), kDarkGrey);
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

ImageU8 sectionPanel(const FrameResult& frame, const Scene& scene, const ProbeSetting& setting)
{
  const FigureRect rect = probeFigurePanel(ProbePanel::Section);
  const ProbeLightFrame& lightFrame = setting.lightFrame;
  const ProbeReceiver& receiver = setting.receiver;
  const Light& light = *setting.light;
  const ProbeSection section = probeSection(lightFrame.eyeWs, lightFrame.axisWs, receiver.position, receiver.normal);
  ImageU8 panel = newPanel(rect, std::string("(d) section through the light's centre and the receiver, containing ") +
      (section.usesReceiverNormal ? "the receiver's normal" : "the light's axis"));
  const Box box = contentBox(rect);
  const double keyBand = kKeyLinePx + 4.0;
  const Box sectionBox{ box.left, box.bottom + keyBand, box.width, box.height - keyBand };

  const double halfExtent = lightHalfExtentInSection(light, section);
  const glm::dvec2 lightCentre = section.toSection(lightFrame.eyeWs);
  const glm::dvec2 receiverPoint = section.toSection(receiver.position);
  const bool directional = light.type == LightType::Directional;
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
  drawText(canvas, barLabel, kBodyFontPx, int(barEnd.x) - textWidth(barLabel, kBodyFontPx), int(barEnd.y) + 6, kBlack);
  blit(panel, canvas, int(sectionBox.left), int(sectionBox.bottom));

  int x = int(box.left);
  const int y = int(box.bottom);
  x = drawKeyEntry(panel, x, y, "casters", paintLineSwatch, kCasterColor);
  x = drawKeyEntry(panel, x, y, "non-casters", paintLineSwatch, kLightGrey);
  x = drawKeyEntry(panel, x, y, "shadow-map depth per texel", paintLineSwatch, kDepthStepColor);
  x = drawKeyEntry(panel, x, y, "light", paintLineSwatch, kLightColor);
  x = drawKeyEntry(panel, x, y, directional ? "ray to the light" : "rays to its ends", paintLineSwatch, kRayColor);
  drawKeyEntry(panel, x, y, "receiver", paintMarkerSwatch, kProbeMarkerColor);
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

std::string quantityText(const ProbeQuantity& quantity)
{
  const std::string value = quantity.text.empty() ? vectorText(quantity.value) : quantity.text;
  return quantity.name + " " + value + (quantity.unit.empty() ? "" : " " + quantity.unit);
}

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
void addRecordedQuantities(LegendLines& lines, const ProbeRecord& record)
{
  static const char* shown[] = { "position", "normal", "receiver_depth", "depth_bias", "shadow_map_position" };
  bool first = true;
  for (const ProbeQuantity& quantity : record.quantities)
  {
    if (quantity.group == "receiver" && std::find(std::begin(shown), std::end(shown), quantity.name) != std::end(shown))
    {
      continue;
    }
    if (first)
    {
      lines.add("-- recorded --", kDarkGrey);
      first = false;
    }
    lines.add(quantityText(quantity));
  }
}

ImageU8 legendPanel(const ProbeResult& probe, const ProbeSetting& setting)
{
  const FigureRect rect = probeFigurePanel(ProbePanel::Legend);
  ImageU8 panel = newPanel(rect, "(e) key numbers");
  const Box box = contentBox(rect);
  LegendLines lines;
  addProbeSummary(lines, probe, setting);
  addRecordCounts(lines, probe.record);
  addRecordedQuantities(lines, probe.record);

  // Top down, wrapped to the panel, as far as they fit.
  const int lineHeight = measureText("Ag", kBodyFontPx).height + 2;
  int y = int(box.bottom + box.height) - lineHeight;
  for (const auto& [text, color] : lines.lines())
  {
    for (const std::string& line : wrapText(text, kBodyFontPx, int(box.width)))
    {
      if (y < box.bottom)
      {
        return panel;
      }
      drawText(panel, fitText(line, kBodyFontPx, int(box.width)), kBodyFontPx, int(box.left), y, color);
      y -= lineHeight;
    }
  }
  return panel;
}

} // namespace

FigureRect probeFigurePanel(ProbePanel panel)
{
  const int side = kProbeFigurePanelSide;
  switch (panel)
  {
    case ProbePanel::Image:
      return { 0, side, side, side };
    case ProbePanel::ShadowMap:
      return { side, side, side, side };
    case ProbePanel::LightPlane:
      return { 2 * side, side, side, side };
    case ProbePanel::Section:
      return { 0, 0, 2 * side, side };
    case ProbePanel::Legend:
      return { 2 * side, 0, side, side };
  }
  return {};
}

ImagePlacement probeImagePlacement(glm::ivec2 imageSize)
{
  const FigureRect rect = probeFigurePanel(ProbePanel::Image);
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

ImageU8 probeFigure(const ProbeResult& probe, const FrameResult& frame, const Scene& scene)
{
  const ProbeSetting setting = probeSetting(probe, frame, scene);
  ImageU8 figure(kProbeFigureWidth, kProbeFigureHeight, 3, 255);
  const auto place = [&](ProbePanel which, const ImageU8& panel) {
    const FigureRect rect = probeFigurePanel(which);
    blit(figure, panel, rect.left, rect.bottom);
  };
  place(ProbePanel::Image, imagePanel(probe, frame));
  place(ProbePanel::ShadowMap, shadowMapPanel(probe, frame, setting));
  place(ProbePanel::LightPlane, lightPlanePanel(probe, setting));
  place(ProbePanel::Section, sectionPanel(frame, scene, setting));
  place(ProbePanel::Legend, legendPanel(probe, setting));
  return figure;
}

} // namespace sl
