// Readers that refuse instead of crash: alpha-texture PNGs, .vti files and meshes (bad-input probe M/K cases),
// and writes that fail loudly (probe D17). Every bad file is built here, in a TempDir.
#include "core/Error.h"
#include "io/ImageIO.h"
#include "io/vtkSLOutputWindow.h"
#include "pipeline/ShadowRenderer.h"
#include "scene/AlphaTexture.h"
#include "scene/MeshIO.h"
#include "support/TempDir.h"
#include "vis/HeatMap.h"

#include <gtest/gtest.h>

#include <png.h>
#include <zlib.h>

#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkObject.h>
#include <vtkPointData.h>
#include <vtkStringArray.h>
#include <vtkXMLImageDataWriter.h>

#include <array>
#include <cmath>
#include <csetjmp>
#include <csignal>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

namespace sl
{
namespace
{

namespace fs = std::filesystem;

std::string readBytes(const fs::path& file)
{
  std::ifstream stream(file, std::ios::binary);
  return { std::istreambuf_iterator<char>(stream), std::istreambuf_iterator<char>() };
}

// Runs `action`, which must throw InputError; returns its message (empty, with a test failure, otherwise).
// Every error of this suite must be one line that names the file.
std::string inputErrorOf(const std::function<void()>& action, const fs::path& file)
{
  try
  {
    action();
  }
  catch (const InputError& error)
  {
    const std::string message = error.what();
    EXPECT_NE(message.find(file.filename().string()), std::string::npos) << "file not named: " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << "not one line: " << message;
    return message;
  }
  ADD_FAILURE() << file << " was accepted";
  return {};
}

// `text` is evaluated once (it is often an inputErrorOf call).
#define EXPECT_CONTAINS(text, part)                                                                     \
  do                                                                                                   \
  {                                                                                                    \
    const std::string containsText = (text);                                                           \
    EXPECT_NE(containsText.find(part), std::string::npos) << containsText;                             \
  } while (false)

// ---- PNG construction -----------------------------------------------------------------------------------

void appendBigEndian32(std::string& bytes, std::uint32_t value)
{
  for (int shift = 24; shift >= 0; shift -= 8)
    bytes.push_back(static_cast<char>((value >> shift) & 0xFF));
}

std::string pngChunk(const std::string& type, const std::string& data)
{
  std::string chunk;
  appendBigEndian32(chunk, static_cast<std::uint32_t>(data.size()));
  const std::string typeAndData = type + data;
  chunk += typeAndData;
  appendBigEndian32(chunk, static_cast<std::uint32_t>(crc32(0, reinterpret_cast<const Bytef*>(typeAndData.data()),
                             static_cast<uInt>(typeAndData.size()))));
  return chunk;
}

std::string headerData(std::uint32_t width, std::uint32_t height, int bitDepth, int colorType)
{
  std::string data;
  appendBigEndian32(data, width);
  appendBigEndian32(data, height);
  data += { static_cast<char>(bitDepth), static_cast<char>(colorType), 0, 0, 0 };
  return data;
}

std::string zlibCompressed(const std::string& raw)
{
  uLongf size = compressBound(static_cast<uLong>(raw.size()));
  std::string compressed(size, '\0');
  EXPECT_EQ(compress(reinterpret_cast<Bytef*>(compressed.data()), &size, reinterpret_cast<const Bytef*>(raw.data()),
              static_cast<uLong>(raw.size())),
    Z_OK);
  compressed.resize(size);
  return compressed;
}

// A PNG with every chunk's CRC right, so only the content is wrong: what the old chunk-and-CRC pre-check let
// through to VTK's crashing reader.
std::string handMadePng(const std::string& header, const std::string& imageData)
{
  return std::string("\x89PNG\r\n\x1a\n", 8) + pngChunk("IHDR", header) + pngChunk("IDAT", imageData) +
    pngChunk("IEND", "");
}

// Rows of an 8-bit gray image, each with filter byte `filter`.
std::string grayRows(int width, int rows, int filter)
{
  std::string raw;
  for (int y = 0; y < rows; ++y)
  {
    raw.push_back(static_cast<char>(filter));
    for (int x = 0; x < width; ++x)
      raw.push_back(static_cast<char>((x * 37 + y) & 0xFF));
  }
  return raw;
}

// A valid PNG written by libpng itself. `rowsTopFirst` holds samples (palette indices for palette images);
// 16-bit samples are stored big-endian as PNG requires, 1/2/4-bit ones packed by libpng.
struct PngSpec
{
  int width = 1;
  int height = 1;
  int colorType = PNG_COLOR_TYPE_GRAY;
  int bitDepth = 8;
  std::vector<std::vector<std::uint16_t>> rowsTopFirst;
  std::vector<png_color> palette;
  std::vector<png_byte> paletteAlpha;  // tRNS of a palette image
  int transparentGray = -1;            // tRNS of a gray image
  bool interlaced = false;
};

void appendToString(png_structp png, png_bytep data, png_size_t length)
{
  static_cast<std::string*>(png_get_io_ptr(png))->append(reinterpret_cast<const char*>(data), length);
}

std::string encodeWithLibpng(const PngSpec& spec)
{
  std::string out;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  // Rows packed before setjmp, so the longjmp (a test bug) skips no destructor.
  const int channels = spec.colorType == PNG_COLOR_TYPE_RGB_ALPHA ? 4
    : spec.colorType == PNG_COLOR_TYPE_RGB                          ? 3
    : spec.colorType == PNG_COLOR_TYPE_GRAY_ALPHA                   ? 2
                                                                    : 1;
  std::vector<std::vector<png_byte>> rows;
  for (const std::vector<std::uint16_t>& samples : spec.rowsTopFirst)
  {
    EXPECT_EQ(samples.size(), static_cast<std::size_t>(spec.width * channels));
    std::vector<png_byte> row;
    for (const std::uint16_t sample : samples)
    {
      if (spec.bitDepth == 16)
        row.push_back(static_cast<png_byte>(sample >> 8));
      row.push_back(static_cast<png_byte>(sample & 0xFF));
    }
    rows.push_back(std::move(row));
  }
  std::vector<png_bytep> rowPointers;
  for (std::vector<png_byte>& row : rows)
    rowPointers.push_back(row.data());
  png_color_16 transparent{};
  transparent.gray = static_cast<png_uint_16>(spec.transparentGray);

  if (setjmp(png_jmpbuf(png)))
  {
    ADD_FAILURE() << "libpng could not encode the test image";
    png_destroy_write_struct(&png, &info);
    return {};
  }
  png_set_write_fn(png, &out, &appendToString, nullptr);
  png_set_IHDR(png, info, static_cast<png_uint_32>(spec.width), static_cast<png_uint_32>(spec.height), spec.bitDepth,
    spec.colorType, spec.interlaced ? PNG_INTERLACE_ADAM7 : PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
    PNG_FILTER_TYPE_DEFAULT);
  if (!spec.palette.empty())
    png_set_PLTE(png, info, spec.palette.data(), static_cast<int>(spec.palette.size()));
  if (!spec.paletteAlpha.empty())
    png_set_tRNS(png, info, spec.paletteAlpha.data(), static_cast<int>(spec.paletteAlpha.size()), nullptr);
  if (spec.transparentGray >= 0)
    png_set_tRNS(png, info, nullptr, 0, &transparent);
  png_write_info(png, info);
  if (spec.bitDepth < 8)
    png_set_packing(png); // our rows hold one sample per byte
  png_write_image(png, rowPointers.data());
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return out;
}

void expectAlpha(const ImageF& alpha, const std::vector<std::vector<float>>& expectedTopFirst, const std::string& what)
{
  ASSERT_EQ(alpha.height, static_cast<int>(expectedTopFirst.size())) << what;
  for (int row = 0; row < alpha.height; ++row)
  {
    ASSERT_EQ(alpha.width, static_cast<int>(expectedTopFirst[row].size())) << what;
    for (int x = 0; x < alpha.width; ++x)
      // Row 0 of the result is the bottom of the picture.
      EXPECT_NEAR(alpha.at(x, alpha.height - 1 - row), expectedTopFirst[row][x], 1e-5)
        << what << ": pixel " << x << " of picture row " << row;
  }
}

// ---- alpha-texture PNGs ---------------------------------------------------------------------------------

TEST(ReadersPng, CorruptImageDataIsAnInputErrorNotACrash)
{
  const test::TempDir dir;
  struct Case
  {
    const char* id;
    const char* name;
    std::string bytes;
    const char* reason; // part of libpng's message
  };
  const std::string header8x8 = headerData(8, 8, 8, PNG_COLOR_TYPE_GRAY);
  const std::vector<Case> cases = {
    // M23: a zlib header followed by bytes that are no valid deflate block.
    { "M23", "garbage-zlib.png", handMadePng(header8x8, std::string("\x78\x9c", 2) + std::string(40, '\xff')),
      "IDAT" },
    // M24: a valid zlib stream holding 2 of the 8 rows.
    { "M24", "too-little-data.png", handMadePng(header8x8, zlibCompressed(grayRows(8, 2, 0))), "image data" },
    // M28: a 16384 x 16384 header with one row of data.
    { "M28", "huge-header-one-row.png",
      handMadePng(headerData(16384, 16384, 8, PNG_COLOR_TYPE_GRAY), zlibCompressed(grayRows(16384, 1, 0))),
      "image data" },
    // M29: every row with filter type 7 (0..4 exist).
    { "M29", "bad-filter.png", handMadePng(header8x8, zlibCompressed(grayRows(8, 8, 7))), "filter" },
  };
  for (const Case& c : cases)
  {
    SCOPED_TRACE(c.id);
    const fs::path file = dir.write(c.name, c.bytes);
    testing::internal::CaptureStderr();
    const std::string message = inputErrorOf([&] { readAlphaPng(file); }, file);
    const std::string printed = testing::internal::GetCapturedStderr();
    EXPECT_EQ(printed, "") << "libpng or VTK printed on their own";
    EXPECT_CONTAINS(message, "cannot read '" + file.string() + "' (");
    EXPECT_CONTAINS(message, c.reason);
    // readPng (compare tools, regression baselines) goes through the same decoder.
    EXPECT_CONTAINS(inputErrorOf([&] { readPng(file); }, file), c.reason);
  }
}

TEST(ReadersPng, StructuralProblemsNameTheirCause)
{
  const test::TempDir dir;
  const std::string valid = encodeWithLibpng({ 2, 1, PNG_COLOR_TYPE_GRAY, 8, { { 1, 2 } } });
  std::string badCrc = valid;
  badCrc[valid.size() - 20] ^= 0x5A; // inside IDAT: a critical chunk, so libpng refuses the file
  struct Case
  {
    const char* name;
    std::string bytes;
    const char* reason;
  };
  const std::vector<Case> cases = {
    { "text.png", "hello", "not a PNG file" },
    { "signature-only.png", valid.substr(0, 8), "(" },
    { "truncated.png", valid.substr(0, valid.size() / 2), "(" },
    { "bad-crc.png", badCrc, "(" },
    { "too-wide.png", handMadePng(headerData(16385, 1, 8, PNG_COLOR_TYPE_GRAY), zlibCompressed(grayRows(16385, 1, 0))),
      "too large (max 16384 per side)" },
    { "bad-color-type.png", handMadePng(headerData(1, 1, 8, 5), zlibCompressed(grayRows(1, 1, 0))), "(" },
  };
  for (const Case& c : cases)
  {
    SCOPED_TRACE(c.name);
    const fs::path file = dir.write(c.name, c.bytes);
    EXPECT_CONTAINS(inputErrorOf([&] { readAlphaPng(file); }, file), c.reason);
  }
  EXPECT_CONTAINS(inputErrorOf([&] { readAlphaPng(dir.path() / "missing.png"); }, "missing.png"), "(no such file)");
  fs::create_directory(dir.path() / "folder.png");
  EXPECT_CONTAINS(inputErrorOf([&] { readAlphaPng(dir.path() / "folder.png"); }, "folder.png"), "(not a regular file)");
}

TEST(ReadersPng, ValidPngsOfEveryColorTypeAndDepthDecodeToTheirAlpha)
{
  const test::TempDir dir;
  const png_color red{ 255, 0, 0 };
  const png_color green{ 0, 255, 0 };
  const png_color blue{ 0, 0, 255 };
  struct Case
  {
    const char* name;
    PngSpec spec;
    std::vector<std::vector<float>> alphaTopFirst;
  };
  const std::vector<Case> cases = {
    { "gray8", { 3, 2, PNG_COLOR_TYPE_GRAY, 8, { { 0, 51, 255 }, { 102, 204, 255 } } },
      { { 0.0f, 0.2f, 1.0f }, { 0.4f, 0.8f, 1.0f } } },
    { "gray16", { 3, 1, PNG_COLOR_TYPE_GRAY, 16, { { 0, 13107, 65535 } } }, { { 0.0f, 0.2f, 1.0f } } },
    { "gray1", { 4, 1, PNG_COLOR_TYPE_GRAY, 1, { { 1, 0, 0, 1 } } }, { { 1.0f, 0.0f, 0.0f, 1.0f } } },
    { "gray-alpha8", { 1, 1, PNG_COLOR_TYPE_GRAY_ALPHA, 8, { { 200, 102 } } }, { { 0.4f } } },
    { "gray-alpha16", { 1, 1, PNG_COLOR_TYPE_GRAY_ALPHA, 16, { { 9, 26214 } } }, { { 0.4f } } },
    // RGB: Rec. 709 luminance; pure green weighs 0.7152, pure red 0.2126.
    { "rgb8", { 2, 1, PNG_COLOR_TYPE_RGB, 8, { { 0, 255, 0, 255, 0, 0 } } }, { { 0.7152f, 0.2126f } } },
    { "rgb16", { 1, 1, PNG_COLOR_TYPE_RGB, 16, { { 0, 0, 65535 } } }, { { 0.0722f } } },
    { "rgba8", { 2, 1, PNG_COLOR_TYPE_RGB_ALPHA, 8, { { 10, 20, 30, 51, 40, 50, 60, 255 } } }, { { 0.2f, 1.0f } } },
    { "rgba16", { 1, 1, PNG_COLOR_TYPE_RGB_ALPHA, 16, { { 1, 2, 3, 13107 } } }, { { 0.2f } } },
    // Palette without tRNS: the luminance of the palette colours.
    { "palette", { 3, 1, PNG_COLOR_TYPE_PALETTE, 8, { { 0, 1, 2 } }, { red, green, blue } },
      { { 0.2126f, 0.7152f, 0.0722f } } },
    // Palette with tRNS: its alpha (entries beyond the tRNS list are opaque).
    { "palette-trns", { 3, 1, PNG_COLOR_TYPE_PALETTE, 8, { { 0, 1, 2 } }, { red, green, blue }, { 255, 0 } },
      { { 1.0f, 0.0f, 1.0f } } },
    // Gray with a transparent gray value: that value has alpha 0, the rest alpha 1.
    { "gray-trns", { 3, 1, PNG_COLOR_TYPE_GRAY, 8, { { 0, 7, 255 } }, {}, {}, 7 }, { { 1.0f, 0.0f, 1.0f } } },
  };
  for (const Case& c : cases)
  {
    SCOPED_TRACE(c.name);
    const fs::path file = dir.write(std::string(c.name) + ".png", encodeWithLibpng(c.spec));
    expectAlpha(readAlphaPng(file), c.alphaTopFirst, c.name);
  }

  // Interlaced (Adam7) files take the decoder's whole-image path; 5 x 5 covers every pass.
  PngSpec interlaced{ 5, 5, PNG_COLOR_TYPE_GRAY, 8 };
  interlaced.interlaced = true;
  std::vector<std::vector<float>> expected;
  for (int y = 0; y < 5; ++y)
  {
    interlaced.rowsTopFirst.emplace_back();
    expected.emplace_back();
    for (int x = 0; x < 5; ++x)
    {
      interlaced.rowsTopFirst.back().push_back(static_cast<std::uint16_t>(10 * (5 * y + x)));
      expected.back().push_back(static_cast<float>(10 * (5 * y + x)) / 255.0f);
    }
  }
  expectAlpha(readAlphaPng(dir.write("interlaced.png", encodeWithLibpng(interlaced))), expected, "interlaced");
}

TEST(ReadersPng, LibpngWarningsStaySilent)
{
  // A damaged ancillary chunk is a libpng warning (the chunk is dropped, the image is fine); by default
  // libpng prints it on stderr.
  const test::TempDir dir;
  const std::string valid = encodeWithLibpng({ 1, 1, PNG_COLOR_TYPE_GRAY, 8, { { 51 } } });
  std::string text = pngChunk("tEXt", std::string("Comment\0hello", 13));
  text[text.size() - 1] ^= 0x01; // bad CRC
  const std::size_t afterHeader = 8 + 25; // signature + IHDR chunk
  const fs::path file = dir.write("warning.png", valid.substr(0, afterHeader) + text + valid.substr(afterHeader));
  testing::internal::CaptureStderr();
  const ImageF alpha = readAlphaPng(file);
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  expectAlpha(alpha, { { 0.2f } }, "warning.png");
}

TEST(ReadersPng, ReadPngRoundTripsWritePng)
{
  const test::TempDir dir;
  ImageU8 rgb(3, 2, 3);
  for (std::size_t i = 0; i < rgb.data.size(); ++i)
    rgb.data[i] = static_cast<std::uint8_t>(17 * i + 3);
  const fs::path file = dir.path() / "round-trip.png";
  writePng(file, rgb);
  const ImageU8 back = readPng(file);
  EXPECT_EQ(back.width, 3);
  EXPECT_EQ(back.height, 2);
  EXPECT_EQ(back.data, rgb.data) << "rows or channels moved";

  // 16-bit gray: replicated into RGB and rounded to 8 bits (32896 / 257 = 128.0).
  const fs::path gray16 = dir.write("gray16.png", encodeWithLibpng({ 1, 1, PNG_COLOR_TYPE_GRAY, 16, { { 32896 } } }));
  EXPECT_EQ(readPng(gray16).data, (std::vector<std::uint8_t>{ 128, 128, 128 }));
}

// ---- .vti -----------------------------------------------------------------------------------------------

std::vector<NamedImage> noiseImages(int width, int height, int components)
{
  // Random values do not compress, so the file is as large as the data.
  std::mt19937 random(7);
  std::uniform_real_distribution<float> value(0.0f, 1.0f);
  NamedImage named;
  named.name = "noise";
  named.image = ImageF(width, height, components);
  for (float& v : named.image.data)
    v = value(random);
  return { named };
}

void writeVtkImage(const fs::path& file, vtkImageData* image)
{
  vtkNew<vtkXMLImageDataWriter> writer;
  writer->SetFileName(file.string().c_str());
  writer->SetInputData(image);
  ASSERT_EQ(writer->Write(), 1);
}

// A .vti whose header and one ASCII float array are ours to choose.
std::string asciiVti(const std::string& extent, const std::string& values)
{
  return "<?xml version=\"1.0\"?>\n"
         "<VTKFile type=\"ImageData\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
         "  <ImageData WholeExtent=\"" +
    extent + "\" Origin=\"0 0 0\" Spacing=\"1 1 1\">\n    <Piece Extent=\"" + extent +
    "\">\n      <PointData Scalars=\"v\">\n"
    "        <DataArray type=\"Float32\" Name=\"v\" format=\"ascii\">" +
    values + "</DataArray>\n      </PointData>\n    </Piece>\n  </ImageData>\n</VTKFile>\n";
}

TEST(ReadersVti, RoundTripAndCompleteFile)
{
  const test::TempDir dir;
  const fs::path file = dir.path() / "buffers.vti";
  std::vector<NamedImage> images = noiseImages(7, 5, 3);
  NamedImage second;
  second.name = "coverage";
  second.image = ImageF(7, 5, 1, 1.0f);
  images.push_back(second);
  writeVti(file, images);
  // Written through memory: the file must still end with the closing tag after the appended data.
  const std::string bytes = readBytes(file);
  EXPECT_EQ(bytes.substr(bytes.size() - 11), "</VTKFile>\n");
  const std::vector<NamedImage> back = readVti(file);
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[0].name, "noise");
  EXPECT_EQ(back[0].image.components, 3);
  EXPECT_EQ(back[0].image.data, images[0].image.data);
  EXPECT_EQ(back[1].name, "coverage");
  EXPECT_EQ(back[1].image.data, images[1].image.data);
}

TEST(ReadersVti, ThreeDimensionalExtentIsRefused)
{
  // K15 / H14: a 96 x 96 x 3 image overflowed the 96 x 96 copy.
  const test::TempDir dir;
  vtkNew<vtkImageData> volume;
  volume->SetDimensions(96, 96, 3);
  volume->AllocateScalars(VTK_FLOAT, 1);
  volume->GetPointData()->GetScalars()->Fill(0.0);
  const fs::path file = dir.path() / "volume.vti";
  writeVtkImage(file, volume);
  EXPECT_CONTAINS(inputErrorOf([&] { readVti(file); }, file), "a 3-D image (96x96x3); only 2-D images");
}

TEST(ReadersVti, ExtentsAndArraysAreCheckedBeforeCopying)
{
  const test::TempDir dir;
  // K13: a header claiming 100000^2 (VTK would try to allocate it; we copied into an image that size).
  const fs::path huge = dir.write("huge.vti", asciiVti("0 99999 0 99999 0 0", "0"));
  EXPECT_CONTAINS(inputErrorOf([&] { readVti(huge); }, huge), "100000x100000 is too large (max 16384 per side)");

  const fs::path empty = dir.write("empty.vti", asciiVti("0 -1 0 0 0 0", ""));
  EXPECT_CONTAINS(inputErrorOf([&] { readVti(empty); }, empty), "empty image");

  // Fewer values than pixels: VTK's own report, folded into one line.
  testing::internal::CaptureStderr();
  const fs::path shortArray = dir.write("short.vti", asciiVti("0 1 0 1 0 0", "1 2 3"));
  EXPECT_CONTAINS(inputErrorOf([&] { readVti(shortArray); }, shortArray), "not a readable VTK image file (");
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");

  vtkNew<vtkImageData> image;
  image->SetDimensions(4, 3, 1);
  vtkNew<vtkFloatArray> fiveComponents;
  fiveComponents->SetName("five");
  fiveComponents->SetNumberOfComponents(kMaxVtiComponents + 1);
  fiveComponents->SetNumberOfTuples(12);
  fiveComponents->Fill(0.0);
  image->GetPointData()->AddArray(fiveComponents);
  const fs::path five = dir.path() / "five.vti";
  writeVtkImage(five, image);
  EXPECT_CONTAINS(inputErrorOf([&] { readVti(five); }, five), "array 'five' has 257 components (1 to 256 supported)");

  image->GetPointData()->RemoveArray("five");
  vtkNew<vtkStringArray> labels;
  labels->SetName("labels");
  labels->SetNumberOfValues(12);
  image->GetPointData()->AddArray(labels);
  const fs::path text = dir.path() / "text.vti";
  writeVtkImage(text, image);
  EXPECT_CONTAINS(inputErrorOf([&] { readVti(text); }, text), "array 'labels' is not numeric");
}

TEST(ReadersVti, CorruptFilesGiveOneLineAndNothingFromVtk)
{
  const test::TempDir dir;
  const fs::path valid = dir.path() / "valid.vti";
  writeVti(valid, noiseImages(64, 64, 1));
  const std::string bytes = readBytes(valid);
  const std::size_t appended = bytes.find("<AppendedData");
  ASSERT_NE(appended, std::string::npos);
  std::string flippedData = bytes;
  for (std::size_t i = appended + 200; i < flippedData.size() - 100; i += 97)
    flippedData[i] ^= 0x20;
  std::string flippedHeader = bytes;
  flippedHeader[bytes.find("WholeExtent") + 3] ^= 0x01; // an attribute name VTK requires
  // Block headers VTK trusts (found by fuzzing): the first array's offset one byte off (a crash) and a block
  // count of 3.6e9 (hours of allocation).
  const std::size_t firstOffset = bytes.find("offset=\"0\"");
  ASSERT_NE(firstOffset, std::string::npos);
  std::string offByOne = bytes;
  offByOne[firstOffset + 8] = '1';
  std::string hugeBlockCount = bytes;
  const std::size_t data = bytes.find('_', appended) + 1;
  for (std::size_t i = 0; i < 4; ++i)
    hugeBlockCount[data + i] = '\xd6';
  struct Case
  {
    const char* id;
    const char* name;
    std::string content;
  };
  const std::vector<Case> cases = {
    { "fuzz", "offset-off-by-one.vti", offByOne },
    { "fuzz", "huge-block-count.vti", hugeBlockCount },
    { "K09", "truncated.vti", bytes.substr(0, bytes.size() / 2) },
    { "K10", "header-only.vti", bytes.substr(0, appended) },
    { "K14", "bit-flipped-data.vti", flippedData },
    { "K14", "bit-flipped-header.vti", flippedHeader },
  };
  for (const Case& c : cases)
  {
    SCOPED_TRACE(c.name);
    const fs::path file = dir.write(c.name, c.content);
    testing::internal::CaptureStderr();
    const std::string message = inputErrorOf([&] { readVti(file); }, file);
    EXPECT_EQ(testing::internal::GetCapturedStderr(), "") << c.id << ": VTK printed on its own";
    EXPECT_CONTAINS(message, file.string() + ": ");
    EXPECT_EQ(message.find("\x1b"), std::string::npos) << "colour codes: " << message;
    EXPECT_EQ(message.find("0x"), std::string::npos) << "object addresses: " << message;
  }
}

// ---- checked writes -------------------------------------------------------------------------------------

TEST(ReadersWrites, FullDiskIsAnInputErrorNamingFileAndReason)
{
  // /dev/full accepts the open and fails every write with ENOSPC.
  const fs::path full = "/dev/full";
  ASSERT_TRUE(fs::exists(full));
  EXPECT_CONTAINS(inputErrorOf([&] { writePng(full, ImageU8(4, 4, 3)); }, full), "No space left on device");
  EXPECT_CONTAINS(inputErrorOf([&] { writeVti(full, noiseImages(4, 4, 1)); }, full), "No space left on device");
  EXPECT_CONTAINS(
    inputErrorOf([&] { writeHeatMapPng(ImageF(8, 8, 1, 0.5f), nullptr, HeatMapOptions{}, full); }, full),
    "No space left on device");
}

// Runs `write` in a child process whose files may not grow beyond 64 KiB, with SIGXFSZ ignored so that the
// write fails with EFBIG instead of killing the process (probe D17's "ulimit -f 64"). Returns the message of
// the InputError the child caught, or a description of what happened instead.
std::string messageUnderFileSizeLimit(const std::function<void()>& write)
{
  int pipeEnds[2];
  if (::pipe(pipeEnds) != 0)
    return "pipe failed";
  const pid_t child = ::fork();
  if (child == 0)
  {
    ::close(pipeEnds[0]);
    std::signal(SIGXFSZ, SIG_IGN);
    const rlimit limit{ 64 * 1024, 64 * 1024 };
    ::setrlimit(RLIMIT_FSIZE, &limit);
    std::string report = "no exception";
    try
    {
      write();
    }
    catch (const InputError& error)
    {
      report = error.what();
    }
    catch (const std::exception& error)
    {
      report = std::string("other exception: ") + error.what();
    }
    [[maybe_unused]] const ssize_t written = ::write(pipeEnds[1], report.data(), report.size());
    ::_exit(0);
  }
  ::close(pipeEnds[1]);
  std::string message;
  char buffer[512];
  ssize_t count = 0;
  while ((count = ::read(pipeEnds[0], buffer, sizeof(buffer))) > 0)
    message.append(buffer, static_cast<std::size_t>(count));
  ::close(pipeEnds[0]);
  int status = 0;
  ::waitpid(child, &status, 0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    return "child died (status " + std::to_string(status) + ")";
  return message;
}

TEST(ReadersWrites, FileSizeLimitIsAnInputErrorNotASilentTruncation)
{
  // D17: buffers.vti was cut at 64 KiB, yet the run reported success.
  const test::TempDir dir;
  const fs::path vti = dir.path() / "buffers.vti";
  const std::string vtiMessage = messageUnderFileSizeLimit([&] { writeVti(vti, noiseImages(256, 256, 1)); });
  EXPECT_CONTAINS(vtiMessage, vti.string() + ": cannot write");
  EXPECT_CONTAINS(vtiMessage, "File too large");

  ImageU8 noise(256, 256, 3);
  std::mt19937 random(3);
  for (std::uint8_t& value : noise.data)
    value = static_cast<std::uint8_t>(random());
  const fs::path png = dir.path() / "image.png";
  const std::string pngMessage = messageUnderFileSizeLimit([&] { writePng(png, noise); });
  EXPECT_CONTAINS(pngMessage, png.string() + ": cannot write");
  EXPECT_CONTAINS(pngMessage, "File too large");
}

// ---- VTK's output window --------------------------------------------------------------------------------

TEST(ReadersVtkOutput, MessageLineDropsHeaderAddressesAndColour)
{
  EXPECT_EQ(vtkMessageLine("ERROR: In /build/vtk/IO/XML/vtkXMLReader.cxx, line 345\n"
                           "vtkXMLImageDataReader (0x55d1c0a0b2c0): Error parsing XML in stream at line 2\n"
                           "second line\n\n"),
    "Error parsing XML in stream at line 2");
  EXPECT_EQ(vtkMessageLine("\x1b[31mWarning: In a.cxx, line 1\n\x1b[0mAlgorithm vtkFoo (0xdeadbeef) returned "
                           "failure\x1b[0m\n"),
    "Algorithm vtkFoo returned failure");
  EXPECT_EQ(vtkMessageLine("\n  \n"), "");
}

TEST(ReadersVtkOutput, CapturesNestAndUncapturedMessagesAreCountedNotPrinted)
{
  installVtkOutputWindow();
  auto* window = vtkSLOutputWindow::SafeDownCast(vtkOutputWindow::GetInstance());
  ASSERT_NE(window, nullptr);
  vtkNew<vtkObject> object;
  {
    VtkErrorCapture outer;
    {
      VtkErrorCapture inner;
      vtkErrorWithObjectMacro(object, "inner problem");
      EXPECT_TRUE(inner.hasError());
      EXPECT_EQ(inner.firstError(), "inner problem");
    }
    vtkWarningWithObjectMacro(object, "outer warning");
    EXPECT_FALSE(outer.hasError()) << "the inner capture's error leaked out";
    ASSERT_EQ(outer.messages().size(), 1u);
    EXPECT_EQ(outer.messages()[0].kind, VtkErrorCapture::Kind::Warning);
    EXPECT_EQ(outer.messages()[0].line, "outer warning");
  }

  const vtkIdType before = window->GetUncapturedMessageCount();
  const bool printing = window->GetPrintUncaptured();
  window->PrintUncapturedOff();
  testing::internal::CaptureStderr();
  vtkErrorWithObjectMacro(object, "nobody listens");
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "") << "vtkLogger or the window printed";
  EXPECT_EQ(window->GetUncapturedMessageCount(), before + 1);

  // SHADOWLAB_VTK_LOG=1: one line each.
  window->PrintUncapturedOn();
  testing::internal::CaptureStderr();
  vtkErrorWithObjectMacro(object, "first\nsecond");
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "shadowlab: VTK error: first\n");
  window->SetPrintUncaptured(printing);
}

// ---- meshes ---------------------------------------------------------------------------------------------

const std::string kObjSquareVertices = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";

TEST(ReadersObj, NonFiniteOrNonNumericCoordinatesNameTheLine)
{
  // M44, M46, M06: OpenMesh skipped such a line and every later index shifted onto the wrong vertex.
  const test::TempDir dir;
  const std::vector<std::pair<std::string, std::string>> cases = {
    { "v nan 0 0", "'v' line: 'nan' is not a finite number" },
    { "v 1e999 0 0", "'v' line: '1e999' is out of range" },
    { "v 0 inf 0", "'v' line: 'inf' is not a finite number" },
    { "v 0 0 4e38", "'v' line: '4e38' is out of range (beyond 32-bit float)" },
    { "v 0 abc 0", "'v' line: 'abc' is not a number" },
    { "v 0 0", "'v' needs at least 3 numbers, got 2" },
    { "vt 0.5", "'vt' needs at least 2 numbers, got 1" },
    { "vn 0 nan 1", "'vn' line: 'nan' is not a finite number" },
  };
  for (std::size_t i = 0; i < cases.size(); ++i)
  {
    SCOPED_TRACE(cases[i].first);
    const fs::path file = dir.write(
      "bad" + std::to_string(i) + ".obj", "v 0 0 0\n# comment\n" + cases[i].first + "\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    EXPECT_CONTAINS(inputErrorOf([&] { loadMesh(file); }, file), file.string() + ":3: " + cases[i].second);
  }
}

TEST(ReadersObj, BadFaceIndicesNameTheLine)
{
  const test::TempDir dir;
  const std::vector<std::pair<std::string, std::string>> cases = {
    { "f 1 2 9", "vertex index 9 is out of range (the file has 4)" }, // M45: dropped silently before
    { "f 0 1 2", "vertex index 0 (OBJ indices start at 1)" },
    { "f -5 -1 -2", "relative vertex index -5 reaches before the first vertex (4 defined so far)" },
    { "f 1/7 2/1 3/1", "texture coordinate index 7 is out of range (the file has 1)" },
    { "f 1//2 2//1 3//1", "normal index 2 is out of range (the file has 1)" },
    { "f 1 x 3", "vertex index 'x' is not an integer" },
    { "f 1 2", "a face needs at least 3 corners, got 2" },
  };
  for (std::size_t i = 0; i < cases.size(); ++i)
  {
    SCOPED_TRACE(cases[i].first);
    const fs::path file = dir.write(
      "face" + std::to_string(i) + ".obj", kObjSquareVertices + "vt 0 0\nvn 0 0 1\nf 1 2 3\n" + cases[i].first + "\n");
    EXPECT_CONTAINS(inputErrorOf([&] { loadMesh(file); }, file), file.string() + ":8: " + cases[i].second);
  }
}

TEST(ReadersObj, ValidRelativeIndicesLoad)
{
  const test::TempDir dir;
  // -4 -3 -2 after four vertices: the first three, i.e. the same triangle as "f 1 2 3"; -1 is the last.
  const fs::path file = dir.write("relative.obj", kObjSquareVertices + "f -4 -3 -2\nf -4 -2 -1\n");
  const LoadedMesh loaded = loadMesh(file);
  EXPECT_EQ(loaded.mesh.triangleCount(), 2u);
  EXPECT_EQ(loaded.droppedDegenerateTriangles, 0u);
  ASSERT_EQ(loaded.mesh.positions.size(), 4u);
  double area = 0.0;
  for (std::size_t t = 0; t < loaded.mesh.triangleCount(); ++t)
  {
    const glm::dvec3 a = loaded.mesh.positions[loaded.mesh.indices[3 * t]];
    const glm::dvec3 b = loaded.mesh.positions[loaded.mesh.indices[3 * t + 1]];
    const glm::dvec3 c = loaded.mesh.positions[loaded.mesh.indices[3 * t + 2]];
    area += 0.5 * glm::length(glm::cross(b - a, c - a));
    EXPECT_GT(glm::cross(b - a, c - a).z, 0.0) << "triangle " << t << " lost its winding";
  }
  EXPECT_NEAR(area, 1.0, 1e-12) << "the two triangles must tile the unit square";
}

TEST(ReadersObj, RepeatedCornersAreCountedAsDegenerate)
{
  // M08-M10, M33, M39 (bad indices, inf coordinates, `f 1 1 2`) all said "empty mesh (no faces)". A repeated
  // corner makes degenerate triangles, dropped and counted.
  const test::TempDir dir;
  // OpenMesh keeps a face's distinct corners: `f 1 3 3 4` is the triangle 1 3 4 (one of its two fan
  // triangles lost), `f 1 1 2` has too few and is dropped (its one triangle lost).
  const fs::path mixed = dir.write("mixed.obj", kObjSquareVertices + "f 1 2 3\nf 1 1 2\nf 1 3 3 4\n");
  const LoadedMesh loaded = loadMesh(mixed);
  EXPECT_EQ(loaded.mesh.triangleCount(), 2u);
  EXPECT_EQ(loaded.droppedDegenerateTriangles, 2u);
  double area = 0.0;
  for (std::size_t t = 0; t < loaded.mesh.triangleCount(); ++t)
  {
    const glm::dvec3 a = loaded.mesh.positions[loaded.mesh.indices[3 * t]];
    const glm::dvec3 b = loaded.mesh.positions[loaded.mesh.indices[3 * t + 1]];
    const glm::dvec3 c = loaded.mesh.positions[loaded.mesh.indices[3 * t + 2]];
    area += 0.5 * glm::length(glm::cross(b - a, c - a));
  }
  EXPECT_NEAR(area, 1.0, 1e-12) << "triangles 1 2 3 and 1 3 4 tile the unit square";

  const fs::path onlyRepeated = dir.write("repeated.obj", kObjSquareVertices + "f 1 1 2\n");
  EXPECT_CONTAINS(inputErrorOf([&] { loadMesh(onlyRepeated); }, onlyRepeated), "all 1 triangles are degenerate");
}

// A binary little-endian PLY with float x y z (and nx ny nz when `normals` is given) and triangles.
std::string binaryPly(const std::vector<std::array<float, 3>>& positions,
  const std::vector<std::array<float, 3>>& normals, const std::vector<std::array<int, 3>>& triangles)
{
  std::string ply = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(positions.size()) +
    "\nproperty float x\nproperty float y\nproperty float z\n";
  if (!normals.empty())
    ply += "property float nx\nproperty float ny\nproperty float nz\n";
  ply += "element face " + std::to_string(triangles.size()) + "\nproperty list uchar int vertex_indices\nend_header\n";
  const auto append = [&ply](const void* data, std::size_t size) { ply.append(static_cast<const char*>(data), size); };
  for (std::size_t v = 0; v < positions.size(); ++v)
  {
    append(positions[v].data(), sizeof(positions[v]));
    if (!normals.empty())
      append(normals[v].data(), sizeof(normals[v]));
  }
  for (const std::array<int, 3>& triangle : triangles)
  {
    const unsigned char corners = 3;
    append(&corners, 1);
    append(triangle.data(), sizeof(triangle));
  }
  return ply;
}

TEST(ReadersPly, NonFiniteCoordinatesAndNormalsNameTheVertex)
{
  const test::TempDir dir;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const std::vector<std::array<int, 3>> triangles = { { 0, 1, 2 }, { 0, 2, 3 } };
  const std::vector<std::array<float, 3>> square = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 } };
  const std::vector<std::array<float, 3>> up(4, { 0, 0, 1 });

  std::vector<std::array<float, 3>> nanCorner = square;
  nanCorner[2][1] = nan;
  const fs::path nanFile = dir.write("nan.ply", binaryPly(nanCorner, {}, triangles));
  EXPECT_CONTAINS(inputErrorOf([&] { loadMesh(nanFile); }, nanFile), "vertex 2 has a non-finite coordinate");

  std::vector<std::array<float, 3>> infCorner = square;
  infCorner[3][0] = -inf;
  const fs::path infFile = dir.write("inf.ply", binaryPly(infCorner, {}, triangles));
  EXPECT_CONTAINS(inputErrorOf([&] { loadMesh(infFile); }, infFile), "vertex 3 has a non-finite coordinate");

  // M16/M17: NaN normals in an otherwise valid PLY said "empty mesh (no faces)".
  std::vector<std::array<float, 3>> nanNormals = up;
  nanNormals[1] = { nan, nan, nan };
  const fs::path normalFile = dir.write("nan-normal.ply", binaryPly(square, nanNormals, triangles));
  EXPECT_CONTAINS(inputErrorOf([&] { loadMesh(normalFile); }, normalFile), "vertex 1 has a non-finite normal");

  // The same file with finite normals loads, with the file's normals.
  const LoadedMesh loaded = loadMesh(dir.write("good.ply", binaryPly(square, up, triangles)));
  EXPECT_EQ(loaded.mesh.triangleCount(), 2u);
  for (const glm::vec3& normal : loaded.mesh.normals)
    EXPECT_EQ(normal, glm::vec3(0, 0, 1));
}

TEST(ReadersPly, FaceWithAVertexThatDoesNotExistIsNamed)
{
  // M08-M10, M33, M39 family: bad indices said "empty mesh (no faces)" or were dropped.
  const test::TempDir dir;
  const std::vector<std::array<float, 3>> square = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 } };
  const fs::path file = dir.write("bad-index.ply", binaryPly(square, {}, { { 0, 1, 2 }, { 0, 2, 7 } }));
  EXPECT_CONTAINS(inputErrorOf([&] { loadMesh(file); }, file), "face 1 uses vertex 7, but the file has 4 vertices");
}

TEST(ReadersOff, NonFiniteCoordinateAndBadIndexAreNamed)
{
  const test::TempDir dir;
  const fs::path good = dir.write("good.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n");
  EXPECT_EQ(loadMesh(good).mesh.triangleCount(), 2u);
  const fs::path badIndex = dir.write("bad-index.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 9\n");
  EXPECT_CONTAINS(inputErrorOf([&] { loadMesh(badIndex); }, badIndex), "face 1 uses vertex 9");
}

TEST(ReadersText, AsciiNumbersThatDoNotParseNameTheLine)
{
  // OpenMesh's text readers misread everything after such a number (an OFF face then named vertex 32671).
  const test::TempDir dir;
  const std::string plyHeader =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
    "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const fs::path ply = dir.write("nan.ply", plyHeader + "0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n");
  EXPECT_CONTAINS(
    inputErrorOf([&] { loadMesh(ply); }, ply), ply.string() + ":11: vertex 1: 'nan' is not a finite number");

  const fs::path off = dir.write("inf.off", "OFF\n# comment\n3 1 0\n0 0 0\n1 0 0\n1 inf 0\n3 0 1 2\n");
  EXPECT_CONTAINS(
    inputErrorOf([&] { loadMesh(off); }, off), off.string() + ":6: vertex 2: 'inf' is not a finite number");

  const fs::path stl = dir.write("nan.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                                            "vertex 1 1e999 0\nendloop\nendfacet\nendsolid x\n");
  EXPECT_CONTAINS(
    inputErrorOf([&] { loadMesh(stl); }, stl), stl.string() + ":6: 'vertex' line: '1e999' is out of range");
}

TEST(ReadersPly, RepeatedVertexInAFaceIsADegenerateTriangle)
{
  const test::TempDir dir;
  const std::vector<std::array<float, 3>> square = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 } };
  const LoadedMesh loaded = loadMesh(dir.write("repeat.ply", binaryPly(square, {}, { { 0, 1, 2 }, { 0, 0, 3 } })));
  EXPECT_EQ(loaded.mesh.triangleCount(), 1u);
  EXPECT_EQ(loaded.droppedDegenerateTriangles, 1u);
}

TEST(ReadersStl, BinaryFacetCountAndNonFiniteCorner)
{
  const test::TempDir dir;
  const auto binaryStl = [](const std::vector<std::array<std::array<float, 3>, 3>>& facets) {
    std::string stl(80, ' ');
    const auto count = static_cast<std::uint32_t>(facets.size());
    stl.append(reinterpret_cast<const char*>(&count), 4); // little-endian hosts
    for (const auto& corners : facets)
    {
      const std::array<float, 3> normal = { 0, 0, 1 };
      stl.append(reinterpret_cast<const char*>(normal.data()), 12);
      for (const std::array<float, 3>& corner : corners)
        stl.append(reinterpret_cast<const char*>(corner.data()), 12);
      stl.append(2, '\0');
    }
    return stl;
  };
  const std::array<std::array<float, 3>, 3> good = { { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 } } };
  const LoadedMesh loaded = loadMesh(dir.write("good.stl", binaryStl({ good })));
  EXPECT_EQ(loaded.mesh.triangleCount(), 1u);
  // STL has no vertex normals (OpenMesh left them uninitialised, sometimes NaN): the computed ones, +z here.
  for (const glm::vec3& normal : loaded.mesh.normals)
    EXPECT_EQ(normal, glm::vec3(0, 0, 1));
  EXPECT_TRUE(loaded.mesh.uvs.empty());
  std::array<std::array<float, 3>, 3> bad = good;
  bad[2][2] = std::numeric_limits<float>::quiet_NaN();
  const fs::path file = dir.write("nan.stl", binaryStl({ good, bad }));
  EXPECT_CONTAINS(inputErrorOf([&] { loadMesh(file); }, file), "facet 1 has a non-finite corner (0, 1, nan)");
}

TEST(ReadersText, HeadersThatCrashOrExhaustOpenMeshAreRefused)
{
  // Found by fuzzing (tests/fuzz/regressions/mesh): OpenMesh's PLY reader crashed on a property before any
  // element and looped forever on an unknown list type; its OFF and PLY readers reserve memory for counts
  // taken from a garbage header or a 229-byte file claiming 4e9 vertices.
  const test::TempDir dir;
  const std::string body = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  const std::string properties = "property float x\nproperty float y\nproperty float z\n";
  const std::string faces = "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const std::vector<std::pair<std::string, std::string>> plyCases = {
    { "ply\nformat ascii 1.0\nelnxent vertex 3\n" + properties + faces + body, "unknown header line 'elnxent'" },
    { "ply\nformat ascii 1.0\nproperty float x\nelement vertex 3\n" + properties + faces + body,
      "property before any element" },
    { "ply\nformat ascii 1.0\nelement vertex 3\n" + properties +
        "element face 1\nproperty list uchar intXYZ vertex_indices\nend_header\n" + body,
      "unknown type" },
    { "ply\nformat ascii 1.0\nelement vertex 4000000000\n" + properties + faces + body,
      "declares more elements than the 26 bytes after it can hold (4000000000 vertex, ...)" },
    { "ply\nformat ascii 1.0\nelement vertex 3\n" + properties + faces.substr(0, faces.size() - 11) + body,
      "PLY header: " },
  };
  for (std::size_t i = 0; i < plyCases.size(); ++i)
  {
    SCOPED_TRACE(plyCases[i].second);
    const fs::path file = dir.write("header" + std::to_string(i) + ".ply", plyCases[i].first);
    EXPECT_CONTAINS(inputErrorOf([&] { loadMesh(file); }, file), plyCases[i].second);
  }
  const fs::path garbage = dir.write("garbage.off", "OFFcomment40 5\xb6v0 5\xb6v\xaf");
  EXPECT_CONTAINS(
    inputErrorOf([&] { loadMesh(garbage); }, garbage), "corrupt or not an OFF file: the first word is 'OFFcomment40'");
  const fs::path huge = dir.write("huge.off", "OFF\n100000000 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  EXPECT_CONTAINS(
    inputErrorOf([&] { loadMesh(huge); }, huge), "declares 100000000 vertices and 1 faces, more than its");
  // The datasets' headers (comments, obj_info, binary) still pass: see MeshFiles.BunnyPlyDirect (SceneTest).
}

TEST(ReadersObj, NonManifoldCopiesKeepTheirTextureCoordinatesAndNormals)
{
  // The second face runs the first one's edges the other way round: OpenMesh adds it on copies of its
  // corners, which had uninitialised (NaN) texture coordinates (found by the mesh fuzz target's corpus).
  const test::TempDir dir;
  const fs::path file = dir.write("non-manifold.obj", kObjSquareVertices + "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\n"
                                                        "f 1/1/1 2/2/1 3/3/1 4/4/1\nf 3/3/1 2/2/1 1/1/1\n");
  const LoadedMesh loaded = loadMesh(file);
  EXPECT_EQ(loaded.mesh.triangleCount(), 3u);
  ASSERT_EQ(loaded.mesh.uvs.size(), loaded.mesh.positions.size());
  for (std::size_t v = 0; v < loaded.mesh.positions.size(); ++v)
  {
    // Every vertex of this file has uv = (x, y) and the normal +z.
    EXPECT_EQ(loaded.mesh.uvs[v], glm::vec2(loaded.mesh.positions[v].x, loaded.mesh.positions[v].y)) << "vertex " << v;
    EXPECT_EQ(loaded.mesh.normals[v], glm::vec3(0, 0, 1)) << "vertex " << v;
  }
}

TEST(ReadersVti, DataArrayAttributesAreCheckedBeforeVtkReads)
{
  // Fuzzing: a NumberOfComponents of "3.16..." and an array without a format cost VTK 9.1 tens of seconds and
  // gigabytes. Every DataArray must carry what the format allows, and declare one tuple per pixel.
  const test::TempDir dir;
  const fs::path valid = dir.path() / "valid.vti";
  writeVti(valid, noiseImages(8, 8, 3));
  const std::string bytes = readBytes(valid);
  const auto edited = [&bytes](const std::string& from, const std::string& to) {
    std::string copy = bytes;
    const std::size_t at = copy.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return at == std::string::npos ? copy : copy.replace(at, from.size(), to);
  };
  // An image of 8 x 7 pixels: the arrays written for 8 x 8 declare a block size that no longer matches.
  std::string smallerExtent = bytes;
  for (std::size_t at = 0; (at = smallerExtent.find("0 7 0 7 0 0", at)) != std::string::npos;)
    smallerExtent.replace(at, 11, "0 7 0 6 0 0");
  struct Case
  {
    const char* name;
    std::string content;
    const char* expected;
  };
  const std::vector<Case> cases = {
    { "fractional-components.vti", edited("NumberOfComponents=\"3\"", "NumberOfComponents=\"3.16\""),
      "array 'noise' has NumberOfComponents=\"3.16\" (an integer 1 to 256 expected)" },
    { "no-format.vti", edited("format=\"appended\"", ""), "array 'noise': format \"\" (appended, binary or ascii" },
    { "bit-type.vti", edited("type=\"Float32\"", "type=\"Bit\""), "array 'noise' is not numeric (type \"Bit\")" },
    { "fractional-offset.vti", edited("offset=\"0\"", "offset=\"0.5\""), "array 'noise': no valid offset" },
    { "wrong-size.vti", smallerExtent, "array 'noise': its data holds 768 bytes, the 56-pixel image needs 672" },
    { "inline-short.vti", asciiVti("0 2 0 0 0 0", "1 2"), "array 'v': its data holds 2 values, the 3-pixel image needs 3" },
  };
  for (const Case& c : cases)
  {
    SCOPED_TRACE(c.name);
    const fs::path file = dir.write(c.name, c.content);
    testing::internal::CaptureStderr();
    const std::string message = inputErrorOf([&] { readVti(file); }, file);
    EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
    EXPECT_CONTAINS(message, file.string() + ": ");
    EXPECT_CONTAINS(message, c.expected);
    EXPECT_EQ(message.find('\n'), std::string::npos);
  }
  // The checks refuse only what is wrong: the file they were derived from, and inline ASCII data, still read.
  EXPECT_EQ(readVti(valid).front().image.components, 3);
  const fs::path ascii = dir.write("ascii.vti", asciiVti("0 2 0 0 0 0", "1 2 3"));
  EXPECT_EQ(readVti(ascii).front().image.data, std::vector<float>({ 1.0f, 2.0f, 3.0f }));
}

TEST(ReadersText, BodiesThatShiftOpenMeshsTokenStreamAreRefused)
{
  // Found by fuzzing (tests/fuzz/regressions/mesh/*-hang*): OpenMesh reads PLY/OFF bodies as one token stream,
  // so a value too many or too few, a format line OpenMesh does not know or counts on the OFF keyword's line
  // made it read a negative list length as ~4e9 indices (minutes, gigabytes). The header is checked
  // strictly and every body line must hold exactly what the header says.
  const test::TempDir dir;
  const std::string properties = "property float x\nproperty float y\nproperty float z\n";
  const std::string faces = "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const std::string vertices = "0 0 0\n1 0 0\n0 1 0\n";
  const std::string header = "ply\nformat ascii 1.0\nelement vertex 3\n" + properties + faces;
  struct Case
  {
    const char* name;
    std::string content;
    const char* expected;
  };
  const std::vector<Case> cases = {
    { "nul.ply", "ply\nformat ascii " + std::string(4, '\0') + "1.0\nelement vertex 3\n" + properties + faces +
        vertices + "3 0 1 2\n",
      ":2: PLY header: control character in the header" },
    { "version.ply", "ply\nformat ascii 1.0ertex\nelement vertex 3\n" + properties + faces + vertices + "3 0 1 2\n",
      ":2: PLY header: unknown format line" },
    { "no-vertex.ply", "ply\nformat ascii 1.0\nend_header\n0 0 0\n", "PLY header: no 'element vertex' line" },
    { "negative-length.ply", header + vertices + "-26 0 1 2\n", ":13: face 0: list length '-26' is not a non-negative" },
    { "split-vertex.ply", header + "0 0\n0 1 0 0\n0 1 0\n3 0 1 2\n", ":10: vertex 0: the line holds 2 values, fewer" },
    { "long-face.ply", header + vertices + "3 0 1 2 7.5\n", ":13: face 0: the line holds 5 values, more" },
    { "float-index.ply", header + vertices + "3 0 1.5 2\n", "face 0: '1.5' is not an integer (int)" },
    { "short.ply", header + "0 0 0\n1 0 0\n", "the PLY data ends after 2 of the 3 'vertex' elements" },
    { "counts-on-keyword-line.off", "OFF 1\n2 10\n0 0 5\n3 0 5\n", ":1: OFF header: the keyword must be alone" },
    { "negative-corners.off", "OFF\n3 1 0\n" + vertices + "-1 0 1 2\n", ":6: face 0: corner count '-1'" },
    { "face-too-long.off", "OFF\n3 1 0\n" + vertices + "3 0 1 2 5\n", ":6: face 0: 3 corners, but 4 numbers follow" },
    { "face-too-short.off", "OFF\n3 1 0\n" + vertices + "4 0 1 2\n", ":6: face 0: 4 corners, but 3 numbers follow" },
  };
  for (const Case& c : cases)
  {
    SCOPED_TRACE(c.name);
    const fs::path file = dir.write(c.name, c.content);
    const std::string message = inputErrorOf([&] { loadMesh(file); }, file);
    EXPECT_CONTAINS(message, file.string());
    EXPECT_CONTAINS(message, c.expected);
    EXPECT_EQ(message.find('\n'), std::string::npos);
  }

  // Binary PLY: list lengths are read from the body; one longer than the rest of the file, or negative, is
  // refused before OpenMesh reads.
  const auto binaryFace = [&](const std::string& lengthType, std::int8_t length) {
    std::string ply = "ply\nformat binary_little_endian 1.0\nelement vertex 3\n" + properties +
      "element face 1\nproperty list " + lengthType + " int vertex_indices\nend_header\n";
    const std::array<float, 9> corners = { 0, 0, 0, 1, 0, 0, 0, 1, 0 };
    ply.append(reinterpret_cast<const char*>(corners.data()), sizeof(corners));
    ply.push_back(static_cast<char>(length));
    const std::array<std::int32_t, 3> indices = { 0, 1, 2 };
    ply.append(reinterpret_cast<const char*>(indices.data()), sizeof(indices));
    return ply;
  };
  const fs::path longList = dir.write("long-list.ply", binaryFace("uchar", 4));
  EXPECT_CONTAINS(inputErrorOf([&] { loadMesh(longList); }, longList), "the PLY data ends inside face 0");
  const fs::path negativeList = dir.write("negative-list.ply", binaryFace("char", -1));
  EXPECT_CONTAINS(inputErrorOf([&] { loadMesh(negativeList); }, negativeList), "face 0 has a negative list length");

  // What the rules are derived from still reads: exact lines, a C colour after an OFF face, binary lists.
  EXPECT_EQ(loadMesh(dir.write("good.ply", header + vertices + "3 0 1 2\n")).mesh.triangleCount(), 1u);
  EXPECT_EQ(loadMesh(dir.write("good.off", "OFF\n3 1 0\n\n" + vertices + "3 0 1 2\n")).mesh.triangleCount(), 1u);
  EXPECT_EQ(loadMesh(dir.write("colour.off", "COFF\n3 1 0\n0 0 0 255 0 0\n1 0 0 255 0 0\n0 1 0 255 0 0\n"
                                             "3 0 1 2 255 0 0\n")).mesh.triangleCount(), 1u);
  EXPECT_EQ(loadMesh(dir.write("good-binary.ply", binaryFace("uchar", 3))).mesh.triangleCount(), 1u);
}

} // namespace
} // namespace sl

namespace sl
{
namespace
{

// The pre-check decodes base64 block headers (inline binary data, and appended data with encoding="base64")
// with VTK's own decoder: files VTK writes in those modes must read back exactly.
TEST(ReadersVti, Base64InlineAndAppendedFilesReadBack)
{
  const test::TempDir dir;
  vtkNew<vtkImageData> data;
  data->SetDimensions(5, 3, 1);
  vtkNew<vtkFloatArray> values;
  values->SetName("visibility");
  values->SetNumberOfTuples(15);
  for (vtkIdType i = 0; i < 15; ++i)
    values->SetValue(i, static_cast<float>(i) / 16.0f);
  data->GetPointData()->AddArray(values);
  for (const bool appended : { false, true })
  {
    for (const bool compressed : { false, true })
    {
      const std::filesystem::path file =
        dir.path() / (std::string(appended ? "appended" : "inline") + (compressed ? "-zlib" : "") + ".vti");
      vtkNew<vtkXMLImageDataWriter> writer;
      writer->SetFileName(file.c_str());
      writer->SetInputData(data);
      if (appended)
      {
        writer->SetDataModeToAppended();
        writer->EncodeAppendedDataOn();
      }
      else
        writer->SetDataModeToBinary();
      if (compressed)
        writer->SetCompressorTypeToZLib();
      else
        writer->SetCompressorTypeToNone();
      ASSERT_EQ(writer->Write(), 1) << file;
      const std::vector<NamedImage> images = readVti(file);
      ASSERT_EQ(images.size(), 1u) << file;
      ASSERT_EQ(images[0].image.width, 5);
      ASSERT_EQ(images[0].image.height, 3);
      for (int i = 0; i < 15; ++i)
        EXPECT_EQ(images[0].image.data[static_cast<std::size_t>(i)], static_cast<float>(i) / 16.0f) << file << " " << i;
    }
  }
}

} // namespace
} // namespace sl
