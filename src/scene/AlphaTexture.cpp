#include "scene/AlphaTexture.h"

#include "core/Error.h"

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>
#include <vtkPointData.h>
#include <vtkType.h>

#include <glm/gtc/constants.hpp>
#include <glm/glm.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <limits>
#include <system_error>
#include <vector>

namespace sl
{

namespace
{

// ---- PNG structure check --------------------------------------------------------------------------------
// vtkPNGReader (VTK 9.1) arms libpng's setjmp inside a helper that has already returned when libpng reports a
// broken file, so a truncated or corrupt PNG crashes the process instead of failing the read. We therefore
// walk the PNG's chunk structure ourselves first (signature, chunk lengths, CRCs, IHDR sanity, IDAT present,
// IEND last) and hand VTK only files that pass. This catches truncation and random corruption; it does not
// decompress the image data.

constexpr std::array<unsigned char, 8> kPngSignature = { 0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n' };
constexpr std::uint32_t kMaxPngSide = 16384; // larger alpha masks are almost certainly a mistake

std::uint32_t crc32(const unsigned char* bytes, std::size_t count)
{
  // Bitwise CRC-32 (ISO-HDLC, the polynomial PNG uses); fast enough for the few files a scene names.
  std::uint32_t crc = 0xFFFFFFFFu;
  for (std::size_t i = 0; i < count; ++i)
  {
    crc ^= bytes[i];
    for (int bit = 0; bit < 8; ++bit)
      crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return crc ^ 0xFFFFFFFFu;
}

std::uint32_t readBigEndian32(const unsigned char* bytes)
{
  return (std::uint32_t{ bytes[0] } << 24) | (std::uint32_t{ bytes[1] } << 16) | (std::uint32_t{ bytes[2] } << 8) |
    std::uint32_t{ bytes[3] };
}

bool isValidColorTypeAndDepth(unsigned colorType, unsigned bitDepth)
{
  switch (colorType)
  {
  case 0: // gray
    return bitDepth == 1 || bitDepth == 2 || bitDepth == 4 || bitDepth == 8 || bitDepth == 16;
  case 3: // palette
    return bitDepth == 1 || bitDepth == 2 || bitDepth == 4 || bitDepth == 8;
  case 2: // RGB
  case 4: // gray + alpha
  case 6: // RGBA
    return bitDepth == 8 || bitDepth == 16;
  default:
    return false;
  }
}

// Empty when `bytes` is a structurally sound PNG, else what is wrong with it.
std::string pngStructureProblem(const std::vector<unsigned char>& bytes)
{
  if (bytes.size() < kPngSignature.size() || !std::equal(kPngSignature.begin(), kPngSignature.end(), bytes.begin()))
    return "not a PNG file";
  std::size_t offset = kPngSignature.size();
  bool sawHeader = false;
  bool sawImageData = false;
  while (true)
  {
    // A chunk is: 4-byte length, 4-byte type, `length` bytes of data, 4-byte CRC of type + data.
    if (bytes.size() - offset < 12)
      return "corrupt PNG: truncated before the IEND chunk";
    const std::uint32_t length = readBigEndian32(&bytes[offset]);
    if (length > bytes.size() - offset - 12)
      return "corrupt PNG: truncated chunk";
    const unsigned char* typeAndData = &bytes[offset + 4];
    const std::string type(reinterpret_cast<const char*>(typeAndData), 4);
    if (crc32(typeAndData, 4 + std::size_t{ length }) != readBigEndian32(typeAndData + 4 + length))
      return format("corrupt PNG: bad CRC in chunk '", type, "'");
    const unsigned char* data = typeAndData + 4;

    if (!sawHeader)
    {
      if (type != "IHDR" || length != 13)
        return "corrupt PNG: first chunk is not a valid IHDR";
      const std::uint32_t width = readBigEndian32(data);
      const std::uint32_t height = readBigEndian32(data + 4);
      if (width == 0 || height == 0)
        return "corrupt PNG: zero image size";
      if (width > kMaxPngSide || height > kMaxPngSide)
        return format("PNG of ", width, "x", height, " is too large (max ", kMaxPngSide, " per side)");
      if (!isValidColorTypeAndDepth(data[9], data[8]))
        return "corrupt PNG: invalid color type / bit depth";
      sawHeader = true;
    }
    else if (type == "IDAT")
    {
      sawImageData = true;
    }
    else if (type == "IEND")
    {
      return sawImageData ? std::string() : "corrupt PNG: no image data (IDAT)";
    }
    offset += 12 + std::size_t{ length };
  }
}

std::vector<unsigned char> readFileBytes(const std::filesystem::path& file)
{
  std::ifstream stream(file, std::ios::binary);
  if (!stream)
    throw InputError(format("cannot read '", file.string(), "' (cannot open file)"));
  return { std::istreambuf_iterator<char>(stream), std::istreambuf_iterator<char>() };
}

// ---- VTK read -------------------------------------------------------------------------------------------

// Collects VTK error/warning events of one reader, so they become our InputError instead of console text.
struct VtkMessageCollector
{
  std::string firstMessage;

  static void onEvent(vtkObject*, unsigned long, void* clientData, void* callData)
  {
    auto* self = static_cast<VtkMessageCollector*>(clientData);
    if (self->firstMessage.empty() && callData != nullptr)
      self->firstMessage = static_cast<const char*>(callData);
  }
};

std::string oneLine(std::string text)
{
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r'))
    text.pop_back();
  for (char& c : text)
    if (c == '\n' || c == '\r')
      c = ' ';
  return text;
}

template <typename Channel>
ImageF alphaFromPixels(const Channel* pixels, int width, int height, int components)
{
  const double channelMax = static_cast<double>(std::numeric_limits<Channel>::max());
  ImageF alpha(width, height, 1);
  for (std::size_t pixel = 0; pixel < alpha.pixelCount(); ++pixel)
  {
    const Channel* texel = pixels + pixel * static_cast<std::size_t>(components);
    double value = 0.0;
    switch (components)
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
    alpha.data[pixel] = static_cast<float>(value / channelMax);
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
  std::error_code error;
  if (!std::filesystem::exists(file, error))
    throw InputError(format("cannot read '", file.string(), "' (no such file)"));
  if (!std::filesystem::is_regular_file(file, error))
    throw InputError(format("cannot read '", file.string(), "' (not a regular file)"));
  const std::string problem = pngStructureProblem(readFileBytes(file));
  if (!problem.empty())
    throw InputError(format("cannot read '", file.string(), "' (", problem, ")"));

  VtkMessageCollector messages;
  vtkNew<vtkCallbackCommand> onMessage;
  onMessage->SetCallback(&VtkMessageCollector::onEvent);
  onMessage->SetClientData(&messages);
  vtkNew<vtkPNGReader> reader;
  // Observing the events keeps VTK from printing them (vtkErrorMacro prints only when nobody listens).
  reader->AddObserver(vtkCommand::ErrorEvent, onMessage);
  reader->AddObserver(vtkCommand::WarningEvent, onMessage);
  reader->SetFileName(file.string().c_str());
  reader->Update();

  vtkImageData* const image = reader->GetOutput();
  int dimensions[3] = { 0, 0, 0 };
  image->GetDimensions(dimensions);
  const int components = image->GetNumberOfScalarComponents();
  if (!messages.firstMessage.empty() || reader->GetErrorCode() != 0 || dimensions[0] <= 0 || dimensions[1] <= 0 ||
    image->GetPointData() == nullptr || image->GetScalarPointer() == nullptr)
    throw InputError(format("cannot read '", file.string(), "' (",
      messages.firstMessage.empty() ? "vtkPNGReader failed" : oneLine(messages.firstMessage), ")"));
  SL_CHECK_MSG(components >= 1 && components <= 4, "PNG with ", components, " components");

  // vtkPNGReader already flips rows so that row 0 is the bottom of the picture, our v = 0.
  switch (image->GetScalarType())
  {
  case VTK_UNSIGNED_CHAR:
    return alphaFromPixels(static_cast<const std::uint8_t*>(image->GetScalarPointer()), dimensions[0], dimensions[1],
      components);
  case VTK_UNSIGNED_SHORT:
    return alphaFromPixels(static_cast<const std::uint16_t*>(image->GetScalarPointer()), dimensions[0],
      dimensions[1], components);
  default:
    throw InputError(format("cannot read '", file.string(), "' (unexpected PNG sample type ",
      image->GetScalarTypeAsString(), ")"));
  }
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
