#include "io/ImageIO.h"

#include "core/Error.h"
#include "io/OutputDirectory.h"
#include "io/vtkSLOutputWindow.h"
#include "passes/ShadowRenderer.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>

#include <png.h>

#include <vtkAbstractArray.h>
#include <vtkDataArray.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPointData.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkUnsignedCharArray.h>
#include <vtkXMLImageDataReader.h>
#include <vtkXMLImageDataWriter.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <exception>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <new>
#include <regex>
#include <system_error>

namespace sl
{

namespace
{

// ---- checked writes -------------------------------------------------------------------------------------

// Writes an encoded file with writeFileChecked's checks (open, every write, close: the system's reason on
// failure), then compares the size on disk with what was encoded: a write that the kernel accepted but the
// filesystem did not keep must not pass as a complete file either.
void writeEncodedFile(const std::filesystem::path& path, const std::string& bytes)
{
  writeFileChecked(path, bytes);
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error))
    return; // a device such as /dev/null has no size to compare
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  if (error || size != bytes.size())
    throw InputError(format(path.string(), ": cannot write (the file on disk has ",
      error ? std::string("an unknown size") : std::to_string(size), " of ", bytes.size(), " bytes)"));
}

// ---- PNG decoding (libpng) --------------------------------------------------------------------------------
// libpng reports a corrupt file by calling the error function, which must not return: ours records libpng's
// message and longjmps back to the setjmp in decodeWithLibpng, the function that calls png_read_*. (VTK 9.1's
// vtkPNGReader arms setjmp in a helper that has already returned, so a corrupt file crashed the process.)
// Everything decodeWithLibpng allocates lives in PngDecodeState, owned by its caller, so the longjmp skips no
// destructor.

struct PngDecodeState
{
  std::string error; // libpng's message, or ours, when decoding gave up
  png_uint_32 width = 0;
  png_uint_32 height = 0;
  int channels = 0;
  int bitDepth = 0;
  std::size_t rowBytes = 0;
  std::vector<unsigned char> rows; // decoded rows, top row first
  std::vector<png_bytep> rowPointers;
};

[[noreturn]] void onPngError(png_structp png, png_const_charp message)
{
  auto* state = static_cast<PngDecodeState*>(png_get_error_ptr(png));
  state->error = message != nullptr && *message != '\0' ? message : "libpng gave no reason";
  png_longjmp(png, 1);
}

// libpng warns about things it recovers from (a bad sRGB profile, an unknown critical-looking chunk); the
// image is still right, and a warning on stderr would break the one-line contract.
void onPngWarning(png_structp, png_const_charp) {}

constexpr std::size_t kPngSignatureBytes = 8;

// False with state.error set when libpng (or the size limit) refused the file.
bool decodeWithLibpng(png_structp png, png_infop info, std::FILE* file, PngDecodeState& state)
{
  if (setjmp(png_jmpbuf(png)))
    return false;
  png_init_io(png, file);
  png_set_sig_bytes(png, static_cast<int>(kPngSignatureBytes)); // the caller checked the signature
  png_read_info(png, info);
  state.width = png_get_image_width(png, info);
  state.height = png_get_image_height(png, info);
  if (state.width > static_cast<png_uint_32>(kMaxImageSide) ||
    state.height > static_cast<png_uint_32>(kMaxImageSide))
  {
    state.error = format("PNG of ", state.width, "x", state.height, " is too large (max ", kMaxImageSide,
      " per side)");
    return false;
  }
  // Palette -> RGB, tRNS -> alpha channel, 1/2/4-bit gray -> 8 bits. 16-bit samples are kept.
  png_set_expand(png);
  const int passes = png_set_interlace_handling(png);
  png_read_update_info(png, info);
  state.channels = png_get_channels(png, info);
  state.bitDepth = png_get_bit_depth(png, info);
  state.rowBytes = png_get_rowbytes(png, info);
  if (passes == 1)
  {
    // Row by row, growing the buffer as rows arrive: a header that claims 16384 x 16384 over one row of data
    // costs one row of memory before libpng reports the missing data.
    for (png_uint_32 y = 0; y < state.height; ++y)
    {
      state.rows.resize(state.rowBytes * (std::size_t{ y } + 1));
      png_read_row(png, state.rows.data() + state.rowBytes * y, nullptr);
    }
  }
  else
  {
    // Interlaced (Adam7): every pass revisits every row, so the whole image is needed at once.
    state.rows.resize(state.rowBytes * state.height);
    state.rowPointers.resize(state.height);
    for (png_uint_32 y = 0; y < state.height; ++y)
      state.rowPointers[y] = state.rows.data() + state.rowBytes * y;
    png_read_image(png, state.rowPointers.data());
  }
  png_read_end(png, nullptr);
  return true;
}

// ---- .vti reading -----------------------------------------------------------------------------------------

void throwIfVtkFailed(const std::filesystem::path& path, const VtkErrorCapture& capture, vtkAlgorithm& reader)
{
  if (capture.hasError() || reader.GetErrorCode() != 0)
    throw InputError(format(path.string(), ": not a readable VTK image file (",
      capture.hasError() ? capture.firstError() : std::string("the VTK reader failed"), ")"));
}


// VTK 9.1's XML reader trusts the block headers of raw appended data: an array offset one byte off made it
// crash, and a block count of 3.6e9 made it allocate and loop for hours (both found by fuzzing). So the
// headers are checked against the file, and each point-data array's size against the image, before VTK reads
// any data. Layout (vtkXMLWriter): per array at `offset` after the '_' marker, uncompressed: one header
// integer with the byte count, then the bytes; compressed: [block count, block size, last block size,
// compressed size of each block], then the blocks. Header integers are header_type (UInt32 or UInt64) in
// byte_order. Base64 appended data and inline arrays are left to VTK.
void checkAppendedData(const std::filesystem::path& path, long long pixelCount)
{
  std::ifstream stream(path, std::ios::binary);
  const std::string bytes{ std::istreambuf_iterator<char>(stream), std::istreambuf_iterator<char>() };
  const std::size_t appendedTag = bytes.find("<AppendedData");
  if (appendedTag == std::string::npos)
    return;
  const auto fail = [&path](const std::string& why) {
    return InputError(format(path.string(), ": not a readable VTK image file (", why, ")"));
  };
  const std::size_t tagEnd = bytes.find('>', appendedTag);
  if (tagEnd == std::string::npos)
    throw fail("unterminated AppendedData element");
  if (bytes.compare(appendedTag, tagEnd - appendedTag, "<AppendedData encoding=\"raw\"") != 0)
    return;
  const std::size_t marker = bytes.find('_', tagEnd);
  if (marker == std::string::npos)
    throw fail("no appended data after the AppendedData element");
  const std::size_t dataBegin = marker + 1;
  const long double dataLength = static_cast<long double>(bytes.size() - dataBegin);

  static const std::regex attribute(R"re((\w+)\s*=\s*"([^"]*)")re");
  const auto attributesOf = [](const std::string& tag) {
    std::map<std::string, std::string> values;
    for (auto match = std::sregex_iterator(tag.begin(), tag.end(), attribute); match != std::sregex_iterator(); ++match)
      values[(*match)[1].str()] = (*match)[2].str();
    return values;
  };
  const std::string xml = bytes.substr(0, appendedTag);
  const std::size_t fileTag = xml.find("<VTKFile");
  if (fileTag == std::string::npos)
    return; // VTK has already refused such a file
  std::map<std::string, std::string> fileAttributes =
    attributesOf(xml.substr(fileTag, xml.find('>', fileTag) - fileTag));
  const std::size_t headerBytes = fileAttributes["header_type"] == "UInt64" ? 8 : 4;
  const bool compressed = !fileAttributes["compressor"].empty();
  const bool bigEndian = fileAttributes["byte_order"] == "BigEndian";
  // Header integer at `at` bytes after the marker; the caller keeps `at + headerBytes` within the data.
  const auto headerInteger = [&](long double at) {
    std::uint64_t value = 0;
    const std::size_t start = dataBegin + static_cast<std::size_t>(at);
    for (std::size_t i = 0; i < headerBytes; ++i)
    {
      const auto byte = static_cast<unsigned char>(bytes[start + (bigEndian ? i : headerBytes - 1 - i)]);
      value = (value << 8) | byte;
    }
    return static_cast<long double>(value);
  };

  static const std::map<std::string, int> kTypeBytes = { { "Int8", 1 }, { "UInt8", 1 }, { "Int16", 2 },
    { "UInt16", 2 }, { "Int32", 4 }, { "UInt32", 4 }, { "Int64", 8 }, { "UInt64", 8 }, { "Float32", 4 },
    { "Float64", 8 } };
  const std::size_t pointDataBegin = xml.find("<PointData");
  const std::size_t pointDataEnd = xml.find("</PointData>");
  static const std::regex dataArrayTag(R"(<DataArray\b[^>]*>)");
  for (auto match = std::sregex_iterator(xml.begin(), xml.end(), dataArrayTag); match != std::sregex_iterator();
       ++match)
  {
    std::map<std::string, std::string> array = attributesOf(match->str());
    if (array["format"] != "appended")
      continue;
    const std::string name = array["Name"].empty() ? std::string("(unnamed)") : array["Name"];
    const std::string arrayName = "array '" + name + "'";
    long long offsetValue = -1;
    const std::string& offsetText = array["offset"];
    if (std::from_chars(offsetText.data(), offsetText.data() + offsetText.size(), offsetValue).ec != std::errc() ||
      offsetValue < 0)
      throw fail(arrayName + ": no valid offset");
    const auto offset = static_cast<long double>(offsetValue);
    if (offset + headerBytes > dataLength)
      throw fail(arrayName + ": its offset lies beyond the appended data");

    long double decodedBytes = 0.0L;
    if (!compressed)
    {
      decodedBytes = headerInteger(offset);
      if (offset + headerBytes + decodedBytes > dataLength)
        throw fail(arrayName + ": its data runs past the end of the file");
    }
    else
    {
      if (offset + 3 * headerBytes > dataLength)
        throw fail(arrayName + ": its block header runs past the end of the file");
      const long double blocks = headerInteger(offset);
      const long double blockSize = headerInteger(offset + headerBytes);
      const long double lastBlockSize = headerInteger(offset + 2 * headerBytes);
      const long double headerEnd = offset + (3 + blocks) * headerBytes;
      if (headerEnd > dataLength)
        throw fail(format(arrayName, ": its header claims ", static_cast<unsigned long long>(blocks),
          " compressed blocks, more than the file holds"));
      long double compressedBytes = 0.0L;
      for (long double block = 0; block < blocks; ++block)
        compressedBytes += headerInteger(offset + (3 + block) * headerBytes);
      if (headerEnd + compressedBytes > dataLength)
        throw fail(arrayName + ": its compressed blocks run past the end of the file");
      if (blocks > 0 && (blockSize == 0 || lastBlockSize > blockSize))
        throw fail(arrayName + ": inconsistent compressed block sizes");
      decodedBytes = blocks == 0 ? 0.0L : (blocks - 1) * blockSize + (lastBlockSize == 0 ? blockSize : lastBlockSize);
    }

    const auto typeBytes = kTypeBytes.find(array["type"]);
    long long components = 1;
    if (!array["NumberOfComponents"].empty())
      std::from_chars(array["NumberOfComponents"].data(),
        array["NumberOfComponents"].data() + array["NumberOfComponents"].size(), components);
    if (typeBytes == kTypeBytes.end() || components < 1)
      continue; // VTK refuses or handles these itself
    const long double imageBytes = static_cast<long double>(pixelCount) * components * typeBytes->second;
    const bool pointData = pointDataBegin != std::string::npos && pointDataEnd != std::string::npos &&
      static_cast<std::size_t>(match->position()) > pointDataBegin &&
      static_cast<std::size_t>(match->position()) < pointDataEnd;
    // A point-data array holds exactly one tuple per pixel; any other (cell or field data) no more.
    if (pointData ? decodedBytes != imageBytes : decodedBytes > imageBytes)
      throw fail(format(arrayName, ": its data holds ", static_cast<unsigned long long>(decodedBytes),
        " bytes, the ", pixelCount, "-pixel image needs ", static_cast<unsigned long long>(imageBytes)));
  }
}
} // namespace

void writeVti(const std::filesystem::path& path, const std::vector<NamedImage>& images)
{
  SL_CHECK(!images.empty());
  vtkNew<vtkImageData> data;
  data->SetDimensions(images.front().image.width, images.front().image.height, 1);
  data->SetSpacing(1.0, 1.0, 1.0);
  data->SetOrigin(0.0, 0.0, 0.0);
  for (const NamedImage& named : images)
  {
    SL_CHECK(named.image.width == images.front().image.width && named.image.height == images.front().image.height);
    vtkNew<vtkFloatArray> array;
    array->SetName(named.name.c_str());
    array->SetNumberOfComponents(named.image.components);
    array->SetNumberOfTuples(static_cast<vtkIdType>(named.image.pixelCount()));
    std::memcpy(array->GetPointer(0), named.image.data.data(), named.image.data.size() * sizeof(float));
    data->GetPointData()->AddArray(array);
  }
  data->GetPointData()->SetActiveScalars(images.front().name.c_str());
  // Encoded in memory and written by writeEncodedFile: vtkXMLWriter::Write() returns 1 even when the disk
  // fills up halfway (bad-input probe D17), and its own file output gives no reason.
  const VtkErrorCapture capture;
  vtkNew<vtkXMLImageDataWriter> writer;
  writer->SetInputData(data);
  writer->SetCompressorTypeToZLib();
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();
  writer->WriteToOutputStringOn();
  const int written = writer->Write();
  SL_CHECK_MSG(written == 1 && writer->GetErrorCode() == 0 && !capture.hasError(), "encoding ", path.string(),
    " in memory failed: ", capture.firstError());
  writeEncodedFile(path, writer->GetOutputString());
}

std::vector<NamedImage> readVti(const std::filesystem::path& path)
{
  const std::string file = path.string();
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error))
  {
    throw InputError(file + (std::filesystem::exists(path, error) ? ": not a regular file" : ": no such file"));
  }
  // VTK reports a truncated or corrupt file as error text; the capture turns it into our one line.
  const VtkErrorCapture capture;
  vtkNew<vtkXMLImageDataReader> reader;
  if (!reader->CanReadFile(file.c_str()))
  {
    throw InputError(file + ": not a VTK XML image file (.vti)");
  }
  reader->SetFileName(file.c_str());

  // The extent comes from the XML header; check it before VTK allocates arrays for it (K13: 100000^2) and
  // before we copy into an image of that size (K15: a 96x96x3 file overflowed a 96x96 image).
  reader->UpdateInformation();
  throwIfVtkFailed(path, capture, *reader);
  int extent[6] = { 0, -1, 0, -1, 0, -1 };
  reader->GetOutputInformation(0)->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent);
  const long long width = static_cast<long long>(extent[1]) - extent[0] + 1;
  const long long height = static_cast<long long>(extent[3]) - extent[2] + 1;
  const long long depth = static_cast<long long>(extent[5]) - extent[4] + 1;
  if (width < 1 || height < 1 || depth < 1)
  {
    throw InputError(format(file, ": empty image (", std::max(width, 0LL), "x", std::max(height, 0LL), "x",
      std::max(depth, 0LL), ")"));
  }
  if (depth != 1)
  {
    throw InputError(
      format(file, ": a 3-D image (", width, "x", height, "x", depth, "); only 2-D images (depth 1) are supported"));
  }
  if (width > kMaxImageSide || height > kMaxImageSide)
  {
    throw InputError(
      format(file, ": image of ", width, "x", height, " is too large (max ", kMaxImageSide, " per side)"));
  }

  checkAppendedData(path, width * height);
  reader->Update();
  throwIfVtkFailed(path, capture, *reader);
  vtkImageData* data = reader->GetOutput();
  int dimensions[3] = { 0, 0, 0 };
  data->GetDimensions(dimensions);
  if (dimensions[0] != width || dimensions[1] != height || dimensions[2] != 1)
  {
    throw InputError(format(file, ": not a readable VTK image file (read ", dimensions[0], "x", dimensions[1], "x",
      dimensions[2], " of the ", width, "x", height, "x1 its header declares)"));
  }
  const auto pixelCount = static_cast<vtkIdType>(width * height);

  std::vector<NamedImage> images;
  vtkPointData* pointData = data->GetPointData();
  for (int a = 0; a < pointData->GetNumberOfArrays(); ++a)
  {
    vtkAbstractArray* abstractArray = pointData->GetAbstractArray(a);
    if (abstractArray == nullptr || abstractArray->GetName() == nullptr)
    {
      continue; // an unnamed array cannot be asked for
    }
    const std::string arrayName = abstractArray->GetName();
    vtkDataArray* array = vtkDataArray::SafeDownCast(abstractArray);
    if (array == nullptr)
    {
      throw InputError(format(file, ": array '", arrayName, "' is not numeric (", abstractArray->GetClassName(), ")"));
    }
    const int components = array->GetNumberOfComponents();
    if (components < 1 || components > 4)
    {
      throw InputError(format(file, ": array '", arrayName, "' has ", components, " components (1 to 4 supported)"));
    }
    if (array->GetNumberOfTuples() != pixelCount)
    {
      throw InputError(format(file, ": array '", arrayName, "' has ", array->GetNumberOfTuples(),
        " tuples, the image has ", width, "x", height, " = ", pixelCount, " pixels"));
    }
    NamedImage named;
    named.name = arrayName;
    named.image = ImageF(static_cast<int>(width), static_cast<int>(height), components);
    for (vtkIdType t = 0; t < pixelCount; ++t)
    {
      for (int c = 0; c < components; ++c)
      {
        named.image.data[static_cast<std::size_t>(t) * components + c] = static_cast<float>(array->GetComponent(t, c));
      }
    }
    images.push_back(std::move(named));
  }
  return images;
}

void writePng(const std::filesystem::path& path, const ImageU8& rgb)
{
  SL_CHECK(rgb.components == 3 && rgb.width > 0 && rgb.height > 0);
  // vtkImageData has the same bottom-up row order as Image; vtkPNGWriter writes its top row (highest y)
  // first, which is the flip a PNG (top row first) needs.
  vtkNew<vtkImageData> data;
  data->SetDimensions(rgb.width, rgb.height, 1);
  data->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  std::memcpy(data->GetScalarPointer(), rgb.data.data(), rgb.data.size());
  // Encoded in memory, written by writeEncodedFile (see writeVti).
  const VtkErrorCapture capture;
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputData(data);
  writer->WriteToMemoryOn();
  writer->Write();
  vtkUnsignedCharArray* png = writer->GetResult();
  SL_CHECK_MSG(writer->GetErrorCode() == 0 && !capture.hasError() && png != nullptr && png->GetNumberOfValues() > 0,
    "encoding ", path.string(), " in memory failed: ", capture.firstError());
  writeEncodedFile(path,
    std::string(reinterpret_cast<const char*>(png->GetPointer(0)), static_cast<std::size_t>(png->GetNumberOfValues())));
}

PngImage readPngImage(const std::filesystem::path& path)
{
  const std::string file = path.string();
  const auto fail = [&file](const std::string& why) {
    return InputError(format("cannot read '", file, "' (", why, ")"));
  };
  std::error_code error;
  if (!std::filesystem::exists(path, error))
    throw fail("no such file");
  if (!std::filesystem::is_regular_file(path, error))
    throw fail("not a regular file");
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> stream(std::fopen(file.c_str(), "rb"), &std::fclose);
  if (!stream)
    throw fail(std::strerror(errno));
  std::array<png_byte, kPngSignatureBytes> signature{};
  if (std::fread(signature.data(), 1, signature.size(), stream.get()) != signature.size() ||
    png_sig_cmp(signature.data(), 0, signature.size()) != 0)
    throw fail("not a PNG file");

  PngDecodeState state;
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &state, &onPngError, &onPngWarning);
  png_infop info = png != nullptr ? png_create_info_struct(png) : nullptr;
  struct ReadStructGuard // frees libpng's structures on every way out
  {
    png_structp& png;
    png_infop& info;
    ~ReadStructGuard() { png_destroy_read_struct(&png, &info, nullptr); }
  } readStructGuard{ png, info };
  if (png == nullptr || info == nullptr)
    throw std::bad_alloc();
  if (!decodeWithLibpng(png, info, stream.get(), state))
    throw fail(state.error);

  PngImage image;
  image.bitDepth = state.bitDepth;
  image.samples = Image<std::uint16_t>(static_cast<int>(state.width), static_cast<int>(state.height), state.channels);
  const std::size_t samplesPerRow = std::size_t{ state.width } * static_cast<std::size_t>(state.channels);
  for (png_uint_32 row = 0; row < state.height; ++row)
  {
    // PNG rows run top to bottom; ours bottom to top.
    const unsigned char* source = state.rows.data() + state.rowBytes * row;
    std::uint16_t* target = image.samples.data.data() + samplesPerRow * (state.height - 1 - row);
    for (std::size_t i = 0; i < samplesPerRow; ++i)
    {
      // 16-bit PNG samples are big-endian.
      target[i] = state.bitDepth == 16 ? static_cast<std::uint16_t>((source[2 * i] << 8) | source[2 * i + 1])
                                       : source[i];
    }
  }
  return image;
}

ImageU8 readPng(const std::filesystem::path& path)
{
  const PngImage png = readPngImage(path);
  const Image<std::uint16_t>& samples = png.samples;
  ImageU8 rgb(samples.width, samples.height, 3);
  const int colorChannels = samples.components >= 3 ? 3 : 1; // RGB(A) or gray(+alpha)
  for (std::size_t pixel = 0; pixel < rgb.pixelCount(); ++pixel)
  {
    for (int c = 0; c < 3; ++c)
    {
      const std::uint16_t value = samples.data[pixel * samples.components + std::min(c, colorChannels - 1)];
      // 16 -> 8 bits rounded to nearest: v * 255 / 65535.
      rgb.data[pixel * 3 + c] = png.bitDepth == 16 ? static_cast<std::uint8_t>((value * 255u + 32767u) / 65535u)
                                                   : static_cast<std::uint8_t>(value);
    }
  }
  return rgb;
}

void writeExr(const std::filesystem::path& path, const ImageF& values)
{
  SL_CHECK(values.components == 1);
  try
  {
    Imf::Header header(values.width, values.height);
    header.channels().insert("Y", Imf::Channel(Imf::FLOAT));
    Imf::OutputFile file(path.string().c_str(), header);
    // EXR rows run top to bottom; point the frame buffer at our last row and walk up (negative y stride).
    const std::size_t rowBytes = sizeof(float) * static_cast<std::size_t>(values.width);
    const char* lastRow = reinterpret_cast<const char*>(values.data.data()) + rowBytes * (values.height - 1);
    Imf::FrameBuffer frameBuffer;
    frameBuffer.insert("Y", Imf::Slice(Imf::FLOAT, const_cast<char*>(lastRow), sizeof(float),
                              -static_cast<std::ptrdiff_t>(rowBytes)));
    file.setFrameBuffer(frameBuffer);
    file.writePixels(values.height);
  }
  catch (const std::exception& error)
  {
    throw InputError(path.string() + ": cannot write the OpenEXR file (" + error.what() + ")");
  }
}

ImageF readExr(const std::filesystem::path& path)
{
  try
  {
    Imf::InputFile file(path.string().c_str());
    const Imath::Box2i window = file.header().dataWindow();
    const int width = window.max.x - window.min.x + 1;
    const int height = window.max.y - window.min.y + 1;
    ImageF values(width, height, 1);
    const std::size_t rowBytes = sizeof(float) * static_cast<std::size_t>(width);
    char* lastRow = reinterpret_cast<char*>(values.data.data()) + rowBytes * (height - 1);
    // Slice base is addressed with the data window's origin: base + x * xStride + y * yStride.
    char* base = lastRow - static_cast<std::ptrdiff_t>(window.min.x) * static_cast<std::ptrdiff_t>(sizeof(float)) +
      static_cast<std::ptrdiff_t>(window.min.y) * static_cast<std::ptrdiff_t>(rowBytes);
    Imf::FrameBuffer frameBuffer;
    frameBuffer.insert("Y", Imf::Slice(Imf::FLOAT, base, sizeof(float), -static_cast<std::ptrdiff_t>(rowBytes)));
    file.setFrameBuffer(frameBuffer);
    file.readPixels(window.min.y, window.max.y);
    return values;
  }
  catch (const std::exception& error)
  {
    throw InputError(path.string() + ": cannot read the OpenEXR file (" + error.what() + ")");
  }
}

} // namespace sl
