#include "vis/CanvasShapes.h"

#include "core/Error.h"
#include "vis/Canvas.h"

#include <algorithm>
#include <cmath>

namespace sl
{
namespace
{

void blendPixel(ImageU8& canvas, int x, int y, const std::array<std::uint8_t, 3>& rgb8, double opacity)
{
  for (int c = 0; c < 3; ++c)
  {
    std::uint8_t& value = canvas.at(x, y, c);
    value = opacity >= 1.0 ? rgb8[c] : static_cast<std::uint8_t>(std::lround((1.0 - opacity) * value + opacity * rgb8[c]));
  }
}

// Liang-Barsky: clips segment a-b to the box [lo, hi]; false when nothing is left.
bool clipSegment(glm::dvec2& a, glm::dvec2& b, const glm::dvec2& lo, const glm::dvec2& hi)
{
  double t0 = 0.0;
  double t1 = 1.0;
  const glm::dvec2 d = b - a;
  for (int axis = 0; axis < 2; ++axis)
  {
    const double p[2] = { -d[axis], d[axis] };
    const double q[2] = { a[axis] - lo[axis], hi[axis] - a[axis] };
    for (int side = 0; side < 2; ++side)
    {
      if (p[side] == 0.0)
      {
        if (q[side] < 0.0)
        {
          return false;
        }
        continue;
      }
      const double t = q[side] / p[side];
      if (p[side] < 0.0)
      {
        t0 = std::max(t0, t);
      }
      else
      {
        t1 = std::min(t1, t);
      }
    }
  }
  if (t0 > t1)
  {
    return false;
  }
  const glm::dvec2 start = a;
  a = start + t0 * d;
  b = start + t1 * d;
  return true;
}

} // namespace

void drawLine(ImageU8& canvas, const glm::dvec2& from, const glm::dvec2& to, const RgbColor& color, double widthPx,
  double opacity)
{
  SL_CHECK(canvas.components == 3);
  if (!std::isfinite(from.x) || !std::isfinite(from.y) || !std::isfinite(to.x) || !std::isfinite(to.y))
  {
    return;
  }
  const double radius = std::max(0.5, 0.5 * widthPx);
  // Only the part near the canvas matters; clipping first keeps far-away endpoints from costing a scan.
  glm::dvec2 a = from;
  glm::dvec2 b = to;
  const glm::dvec2 lo(-radius - 1.0);
  const glm::dvec2 hi(canvas.width + radius + 1.0, canvas.height + radius + 1.0);
  if (!clipSegment(a, b, lo, hi))
  {
    return;
  }
  const auto rgb8 = toRgb8(color);
  const glm::dvec2 d = b - a;
  const double lengthSquared = glm::dot(d, d);
  // Scan along the major axis; across it, only the pixels within reach of the segment.
  const int major = std::abs(d.x) >= std::abs(d.y) ? 0 : 1;
  const int minor = 1 - major;
  const int majorSize = major == 0 ? canvas.width : canvas.height;
  const int minorSize = major == 0 ? canvas.height : canvas.width;
  const int majorFirst = std::max(0, static_cast<int>(std::floor(std::min(a[major], b[major]) - radius - 0.5)));
  const int majorLast = std::min(majorSize - 1, static_cast<int>(std::ceil(std::max(a[major], b[major]) + radius - 0.5)));
  // Across the major axis the segment moves at most |slope| <= 1 per unit, so radius * sqrt(2) + 1 covers it.
  const double slope = d[major] != 0.0 ? d[minor] / d[major] : 0.0;
  const double reach = radius * std::sqrt(1.0 + slope * slope) + 1.0;
  for (int m = majorFirst; m <= majorLast; ++m)
  {
    const double centreMajor = m + 0.5;
    const double along = std::clamp(centreMajor, std::min(a[major], b[major]), std::max(a[major], b[major]));
    const double lineMinor = d[major] != 0.0 ? a[minor] + (along - a[major]) * slope : 0.5 * (a[minor] + b[minor]);
    const double spread = d[major] != 0.0 ? reach : reach + 0.5 * std::abs(d[minor]);
    const int minorFirst = std::max(0, static_cast<int>(std::floor(lineMinor - spread)));
    const int minorLast = std::min(minorSize - 1, static_cast<int>(std::ceil(lineMinor + spread)));
    for (int n = minorFirst; n <= minorLast; ++n)
    {
      glm::dvec2 centre;
      centre[major] = centreMajor;
      centre[minor] = n + 0.5;
      const double t = lengthSquared > 0.0 ? std::clamp(glm::dot(centre - a, d) / lengthSquared, 0.0, 1.0) : 0.0;
      const glm::dvec2 offset = centre - (a + t * d);
      if (glm::dot(offset, offset) <= radius * radius)
      {
        const int x = major == 0 ? m : n;
        const int y = major == 0 ? n : m;
        blendPixel(canvas, x, y, rgb8, opacity);
      }
    }
  }
}

void drawDashedLine(
  ImageU8& canvas, const glm::dvec2& a, const glm::dvec2& b, const RgbColor& color, double widthPx, double dashPx)
{
  const double length = glm::length(b - a);
  if (!(length > 0.0) || !(dashPx > 0.0))
  {
    drawLine(canvas, a, b, color, widthPx);
    return;
  }
  // Only the part near the canvas is dashed, so a segment reaching far outside costs no more than one inside.
  glm::dvec2 from = a;
  glm::dvec2 to = b;
  const glm::dvec2 lo(-widthPx - 1.0);
  const glm::dvec2 hi(canvas.width + widthPx + 1.0, canvas.height + widthPx + 1.0);
  if (!clipSegment(from, to, lo, hi))
  {
    return;
  }
  const glm::dvec2 unit = (b - a) / length;
  // Keep the dash pattern anchored at `a` so clipping does not shift it.
  const double startAt = glm::dot(from - a, unit);
  const double endAt = glm::dot(to - a, unit);
  for (double s = std::floor(startAt / (2.0 * dashPx)) * 2.0 * dashPx; s < endAt; s += 2.0 * dashPx)
  {
    const double dashStart = std::max(s, startAt);
    const double dashEnd = std::min(s + dashPx, endAt);
    if (dashEnd > dashStart)
    {
      drawLine(canvas, a + dashStart * unit, a + dashEnd * unit, color, widthPx);
    }
  }
}

void fillPolygon(ImageU8& canvas, const std::vector<glm::dvec2>& points, const RgbColor& color, double opacity)
{
  SL_CHECK(canvas.components == 3);
  if (points.size() < 3)
  {
    return;
  }
  double yMin = points.front().y;
  double yMax = points.front().y;
  for (const glm::dvec2& point : points)
  {
    if (!std::isfinite(point.x) || !std::isfinite(point.y))
    {
      return;
    }
    yMin = std::min(yMin, point.y);
    yMax = std::max(yMax, point.y);
  }
  const auto rgb8 = toRgb8(color);
  const int rowFirst = std::max(0, static_cast<int>(std::floor(yMin - 0.5)));
  const int rowLast = std::min(canvas.height - 1, static_cast<int>(std::ceil(yMax - 0.5)));
  std::vector<double> crossings;
  for (int y = rowFirst; y <= rowLast; ++y)
  {
    const double centreY = y + 0.5;
    crossings.clear();
    for (std::size_t i = 0; i < points.size(); ++i)
    {
      const glm::dvec2& p = points[i];
      const glm::dvec2& q = points[(i + 1) % points.size()];
      // Half-open in y, so a vertex on the scan line is counted once.
      if ((p.y <= centreY) != (q.y <= centreY))
      {
        crossings.push_back(p.x + (centreY - p.y) / (q.y - p.y) * (q.x - p.x));
      }
    }
    std::sort(crossings.begin(), crossings.end());
    for (std::size_t i = 0; i + 1 < crossings.size(); i += 2)
    {
      // Pixels whose centre x + 0.5 lies in [left, right).
      const double left = std::clamp(crossings[i], -1.0, canvas.width + 1.0);
      const double right = std::clamp(crossings[i + 1], -1.0, canvas.width + 1.0);
      const int xFirst = std::max(0, static_cast<int>(std::ceil(left - 0.5)));
      const int xEnd = std::min(canvas.width, static_cast<int>(std::ceil(right - 0.5)));
      for (int x = xFirst; x < xEnd; ++x)
      {
        blendPixel(canvas, x, y, rgb8, opacity);
      }
    }
  }
}

void strokePolygon(ImageU8& canvas, const std::vector<glm::dvec2>& points, const RgbColor& color, double widthPx)
{
  for (std::size_t i = 0; i < points.size() && points.size() >= 2; ++i)
  {
    drawLine(canvas, points[i], points[(i + 1) % points.size()], color, widthPx);
  }
}

void fillDisk(ImageU8& canvas, const glm::dvec2& centre, double radiusPx, const RgbColor& color)
{
  SL_CHECK(canvas.components == 3);
  if (!std::isfinite(centre.x) || !std::isfinite(centre.y) || !(radiusPx > 0.0))
  {
    return;
  }
  const auto rgb8 = toRgb8(color);
  const int xFirst = std::max(0, static_cast<int>(std::floor(centre.x - radiusPx - 0.5)));
  const int xLast = std::min(canvas.width - 1, static_cast<int>(std::ceil(centre.x + radiusPx - 0.5)));
  const int yFirst = std::max(0, static_cast<int>(std::floor(centre.y - radiusPx - 0.5)));
  const int yLast = std::min(canvas.height - 1, static_cast<int>(std::ceil(centre.y + radiusPx - 0.5)));
  for (int y = yFirst; y <= yLast; ++y)
  {
    for (int x = xFirst; x <= xLast; ++x)
    {
      const glm::dvec2 offset = glm::dvec2(x + 0.5, y + 0.5) - centre;
      if (glm::dot(offset, offset) <= radiusPx * radiusPx)
      {
        blendPixel(canvas, x, y, rgb8, 1.0);
      }
    }
  }
}

void blit(ImageU8& canvas, const ImageU8& source, int left, int bottom)
{
  SL_CHECK(canvas.components == source.components);
  for (int y = std::max(0, -bottom); y < source.height && bottom + y < canvas.height; ++y)
  {
    for (int x = std::max(0, -left); x < source.width && left + x < canvas.width; ++x)
    {
      for (int c = 0; c < source.components; ++c)
      {
        canvas.at(left + x, bottom + y, c) = source.at(x, y, c);
      }
    }
  }
}

} // namespace sl
