#include "scene/AlphaTexture.h"

#include "core/Error.h"
#include "io/ImageIO.h"

#include <glm/gtc/constants.hpp>
#include <glm/glm.hpp>

#include <cmath>
#include <cstdint>
#include <vector>

namespace sl
{

namespace
{

// Alpha of each pixel (AlphaTexture.h): the alpha channel when there is one, else the luminance.
ImageF alphaFromPng(const PngImage& png)
{
  const Image<std::uint16_t>& samples = png.samples;
  const double sampleMax = png.maxSample();
  ImageF alpha(samples.width, samples.height, 1);
  for (std::size_t pixel = 0; pixel < alpha.pixelCount(); ++pixel)
  {
    const std::uint16_t* texel = samples.data.data() + pixel * static_cast<std::size_t>(samples.components);
    double value = 0.0;
    switch (samples.components)
    {
    case 1: // gray: luminance is the value itself
      value = texel[0];
      break;
    case 2: // gray + alpha
      value = texel[1];
      break;
    case 3: // RGB: Rec. 709 luminance of the stored (non-linearised) values
      value = 0.2126 * texel[0] + 0.7152 * texel[1] + 0.0722 * texel[2];
      break;
    default: // RGBA
      value = texel[3];
      break;
    }
    alpha.data[pixel] = static_cast<float>(value / sampleMax);
  }
  return alpha;
}

// ---- procedural patterns --------------------------------------------------------------------------------

double fract(double x)
{
  return x - std::floor(x);
}

// splitmix64 (Steele, Lea, Flood 2014): tiny, well mixed, and the same sequence on every platform, which
// std::*_distribution does not guarantee.
class SplitMix64
{
public:
  explicit SplitMix64(std::uint64_t seed)
    : state_(seed)
  {
  }
  std::uint64_t next()
  {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double uniform01() { return static_cast<double>(next() >> 11) * 0x1.0p-53; } // in [0,1)

private:
  std::uint64_t state_;
};

constexpr std::uint64_t kLeavesSeed = 0x1EAF5EEDull;

} // namespace

ImageF readAlphaPng(const std::filesystem::path& file)
{
  // readPngImage throws "cannot read '<file>' (<why>)" and already puts row 0 at the bottom, our v = 0.
  return alphaFromPng(readPngImage(file));
}

ImageF makeFenceAlpha(int size)
{
  constexpr double kCellsPerUnit = 8.0;
  constexpr double kWireHalfWidth = 0.15; // of a cell, on each side: holes are fract() in (0.15, 0.85)
  ImageF alpha(size, size, 1);
  for (int y = 0; y < size; ++y)
  {
    for (int x = 0; x < size; ++x)
    {
      const double u = (x + 0.5) / size;
      const double v = (y + 0.5) / size;
      // 45-degree rotated grid; u + v and u - v change by integers when u or v does, so it tiles.
      const double a = fract(kCellsPerUnit * (u + v));
      const double b = fract(kCellsPerUnit * (u - v));
      const auto insideCell = [&](double f) { return f > kWireHalfWidth && f < 1.0 - kWireHalfWidth; };
      const bool hole = insideCell(a) && insideCell(b);
      alpha.at(x, y) = hole ? 0.0f : 1.0f;
    }
  }
  return alpha;
}

ImageF makeLeavesAlpha(int size)
{
  struct Ellipse
  {
    glm::dvec2 center;
    glm::dvec2 axis; // unit direction of the semi-major axis
    double semiMajor;
    double semiMinor;
  };
  // Sizes are tuned for ~50% coverage: with n ellipses of mean area A placed at random, the uncovered
  // fraction is about exp(-n A); n A ~ ln 2 gives one half.
  SplitMix64 random(kLeavesSeed);
  std::vector<Ellipse> ellipses;
  ellipses.reserve(kLeavesEllipseCount);
  for (int i = 0; i < kLeavesEllipseCount; ++i)
  {
    Ellipse leaf{};
    leaf.center = { random.uniform01(), random.uniform01() };
    const double angle = glm::pi<double>() * random.uniform01();
    leaf.axis = { std::cos(angle), std::sin(angle) };
    leaf.semiMajor = 0.06 + 0.05 * random.uniform01();
    leaf.semiMinor = leaf.semiMajor * (0.4 + 0.25 * random.uniform01());
    ellipses.push_back(leaf);
  }

  ImageF alpha(size, size, 1, 0.0f);
  for (int y = 0; y < size; ++y)
  {
    for (int x = 0; x < size; ++x)
    {
      const glm::dvec2 uv{ (x + 0.5) / size, (y + 0.5) / size };
      for (const Ellipse& leaf : ellipses)
      {
        // Nearest periodic image of the offset, so leaves crossing an edge continue on the other side.
        glm::dvec2 offset = uv - leaf.center;
        offset -= glm::round(offset);
        const double along = glm::dot(offset, leaf.axis) / leaf.semiMajor;
        const double across = (offset.x * -leaf.axis.y + offset.y * leaf.axis.x) / leaf.semiMinor;
        if (along * along + across * across <= 1.0)
        {
          alpha.at(x, y) = 1.0f;
          break;
        }
      }
    }
  }
  return alpha;
}

namespace
{

// Nearest texel under repeat wrap: texel i covers [i, i+1)/size, and coordinates wrap modulo 1.
int wrapTexel(double coordinate, int size)
{
  const double texel = std::floor(coordinate * size);
  if (!std::isfinite(texel))
  {
    return 0;
  }
  const long long wrapped = static_cast<long long>(std::fmod(texel, static_cast<double>(size)));
  return static_cast<int>(wrapped < 0 ? wrapped + size : wrapped);
}

} // namespace

bool alphaHoleAt(const ImageF& alpha, const glm::dvec2& uv)
{
  return alpha.at(wrapTexel(uv.x, alpha.width), wrapTexel(uv.y, alpha.height)) < 0.5f;
}

bool isProceduralAlphaName(const std::string& source)
{
  return source == "fence" || source == "leaves";
}

AlphaTexture makeAlphaTexture(const std::string& source, const std::filesystem::path& baseDir)
{
  AlphaTexture texture;
  texture.source = source;
  if (source == "fence")
    texture.alpha = makeFenceAlpha();
  else if (source == "leaves")
    texture.alpha = makeLeavesAlpha();
  else
    texture.alpha = readAlphaPng(baseDir / source);
  return texture;
}

} // namespace sl
