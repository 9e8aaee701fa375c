#include "io/ImageIO.h"

#include "core/Error.h"
#include "io/OutputDirectory.h"
#include "io/vtkSLOutputWindow.h"
#include "core/NamedImage.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>

#include <png.h>

#include <vtkAbstractArray.h>
#include <vtkDataArray.h>
#include <vtkBase64Utilities.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPointData.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkUnsignedCharArray.h>
#include <vtkStructuredGrid.h>
#include <vtkXMLImageDataReader.h>
#include <vtkXMLImageDataWriter.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataWriter.h>
#include <vtkXMLStructuredGridWriter.h>
#include <vtkCompositeDataSet.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkXMLWriter.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <exception>
#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <memory>
#include <new>
#include <regex>
#include <sstream>
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


// VTK 9.1's XML reader trusts what a file declares: an array offset one byte off made it crash, a block count
// of 3.6e9 made it allocate and loop for hours, and a NumberOfComponents of "3.16" or a DataArray without a
// format made it spend tens of seconds and gigabytes (all found by fuzzing). So every DataArray is checked
// against the format and the file before VTK reads any data:
//  - type one of the numeric VTK XML types, NumberOfComponents (default 1) an integer 1..4, NumberOfTuples
//    (field data) an integer no larger than the pixel count;
//  - format "appended" with an integer offset inside the appended data, or "binary"/"ascii" inline data;
//  - the data it declares fits in the file, and its decoded size is exactly one tuple per pixel for point
//    data (no more than that for cell and field data), so what VTK allocates is bounded by the image.
// Binary layout (vtkXMLWriter), at the array's offset after the '_' marker (appended) or in the element's
// text (inline binary), raw or base64 as the file says: uncompressed, one header integer with the byte count,
// then the bytes; compressed, [block count, block size, last block size, compressed size of each block],
// then the blocks. Header integers are header_type (UInt32 or UInt64) in byte_order.
// The file as checkDataArrays reads it: its bytes, the XML part before any AppendedData, and how the binary data
// is laid out (vtkXMLWriter's header type, compression and byte order).
struct VtiLayout
{
  std::filesystem::path path;
  std::string bytes;
  std::string xml;
  std::size_t appendedTag = std::string::npos;
  std::size_t dataBegin = 0;  // just after the appended data's '_' marker (the file's size without one)
  bool appendedBase64 = false;
  std::size_t headerBytes = 4;
  bool compressed = false;
  bool bigEndian = false;

  InputError fail(const std::string& why) const
  {
    return InputError(format(path.string(), ": not a readable VTK image file (", why, ")"));
  }
};

std::map<std::string, std::string> xmlAttributes(const std::string& tag)
{
  static const std::regex attribute(R"re((\w+)\s*=\s*"([^"]*)")re");
  std::map<std::string, std::string> values;
  for (auto match = std::sregex_iterator(tag.begin(), tag.end(), attribute); match != std::sregex_iterator(); ++match)
    values[(*match)[1].str()] = (*match)[2].str();
  return values;
}

// An attribute that must be a whole integer: "3.16" or "3x" is not 3.
bool parseWholeInteger(const std::string& text, long long& value)
{
  const char* end = text.data() + text.size();
  const auto [last, error] = std::from_chars(text.data(), end, value);
  return !text.empty() && error == std::errc() && last == end;
}

// Reads the file and locates its appended data; nullopt for a file without a VTKFile element (VTK has already
// refused it).
std::optional<VtiLayout> readVtiLayout(const std::filesystem::path& path)
{
  VtiLayout layout;
  layout.path = path;
  std::ifstream stream(path, std::ios::binary);
  layout.bytes.assign(std::istreambuf_iterator<char>(stream), std::istreambuf_iterator<char>());
  const std::string& bytes = layout.bytes;

  // The appended data, if any: raw bytes or base64 text from just after the '_' marker to the end of the file.
  layout.appendedTag = bytes.find("<AppendedData");
  layout.dataBegin = bytes.size();
  if (layout.appendedTag != std::string::npos)
  {
    const std::size_t tagEnd = bytes.find('>', layout.appendedTag);
    if (tagEnd == std::string::npos)
      throw layout.fail("unterminated AppendedData element");
    const std::string tag = bytes.substr(layout.appendedTag, tagEnd - layout.appendedTag);
    if (tag.find("encoding=\"base64\"") != std::string::npos)
      layout.appendedBase64 = true;
    else if (tag.find("encoding=\"raw\"") == std::string::npos)
      throw layout.fail("AppendedData encoding is neither raw nor base64");
    // VTK's reader (vtkXMLDataParser::FindAppendedDataPosition) skips white space after the tag and then takes
    // the next byte as the '_' marker, whatever it is: require that byte to be '_', so the data VTK will read
    // is the data checked here.
    const std::size_t marker = bytes.find_first_not_of(" \t\n\r", tagEnd + 1);
    if (marker == std::string::npos || bytes[marker] != '_')
      throw layout.fail("the appended data does not start with '_' after the AppendedData element");
    layout.dataBegin = marker + 1;
  }

  layout.xml = bytes.substr(0, layout.appendedTag == std::string::npos ? bytes.size() : layout.appendedTag);
  const std::size_t fileTag = layout.xml.find("<VTKFile");
  if (fileTag == std::string::npos)
    return std::nullopt;
  std::map<std::string, std::string> fileAttributes =
    xmlAttributes(layout.xml.substr(fileTag, layout.xml.find('>', fileTag) - fileTag));
  layout.headerBytes = fileAttributes["header_type"] == "UInt64" ? 8 : 4;
  layout.compressed = !fileAttributes["compressor"].empty();
  layout.bigEndian = fileAttributes["byte_order"] == "BigEndian";
  return layout;
}

// One DataArray element: its attributes checked against the format and the image, and the size its data must
// decode to.
struct DataArrayDeclaration
{
  std::map<std::string, std::string> attributes;
  std::string label;           // "array 'NAME'"
  int typeBytes = 0;
  bool pointData = false;      // exactly one tuple per pixel; cell and field data no more than that
  long double imageBytes = 0;  // one tuple per pixel
  std::size_t tagEnd = 0;      // the element's '>'
};

DataArrayDeclaration declaredDataArray(const VtiLayout& layout, std::size_t tagBegin, long long pixelCount)
{
  static const std::map<std::string, int> kTypeBytes = { { "Int8", 1 }, { "UInt8", 1 }, { "Int16", 2 },
    { "UInt16", 2 }, { "Int32", 4 }, { "UInt32", 4 }, { "Int64", 8 }, { "UInt64", 8 }, { "Float32", 4 },
    { "Float64", 8 } };
  const std::string& xml = layout.xml;
  DataArrayDeclaration array;
  array.tagEnd = xml.find('>', tagBegin);
  if (array.tagEnd == std::string::npos)
    throw layout.fail("unterminated DataArray element");
  array.attributes = xmlAttributes(xml.substr(tagBegin, array.tagEnd - tagBegin));
  std::map<std::string, std::string>& attributes = array.attributes;
  array.label = "array '" + (attributes["Name"].empty() ? std::string("(unnamed)") : attributes["Name"]) + "'";
  const auto arrayError = [&](const std::string& why) {
    return InputError(format(layout.path.string(), ": ", array.label, " ", why));
  };

  const auto typeBytes = kTypeBytes.find(attributes["type"]);
  if (typeBytes == kTypeBytes.end())
    throw arrayError(format("is not numeric (type \"", attributes["type"], "\")"));
  array.typeBytes = typeBytes->second;
  long long components = 1;
  if (attributes.count("NumberOfComponents") != 0 && !parseWholeInteger(attributes["NumberOfComponents"], components))
    throw arrayError(format("has NumberOfComponents=\"", attributes["NumberOfComponents"], "\" (an integer 1 to ",
      kMaxVtiComponents, " expected)"));
  if (components < 1 || components > kMaxVtiComponents)
    throw arrayError(format("has ", components, " components (1 to ", kMaxVtiComponents, " supported)"));
  const std::size_t pointDataBegin = xml.find("<PointData");
  const std::size_t pointDataEnd = xml.find("</PointData>");
  array.pointData = pointDataBegin != std::string::npos && pointDataEnd != std::string::npos &&
    tagBegin > pointDataBegin && tagBegin < pointDataEnd;
  long long tuples = pixelCount;
  if (attributes.count("NumberOfTuples") != 0 &&
    (!parseWholeInteger(attributes["NumberOfTuples"], tuples) || tuples < 0 || tuples > pixelCount ||
      (array.pointData && tuples != pixelCount)))
    throw arrayError(format("has NumberOfTuples=\"", attributes["NumberOfTuples"], "\" (the image has ", pixelCount,
      " pixels)"));
  array.imageBytes = static_cast<long double>(pixelCount) * components * array.typeBytes;
  return array;
}

// A point-data array holds exactly one tuple per pixel; any other (cell or field data) no more.
void checkDecodedSize(const VtiLayout& layout, const DataArrayDeclaration& array, long double decodedBytes,
  const char* unit, long double perValue, long long pixelCount)
{
  if (array.pointData ? decodedBytes != array.imageBytes : decodedBytes > array.imageBytes)
    throw layout.fail(format(array.label, ": its data holds ", static_cast<unsigned long long>(decodedBytes / perValue),
      " ", unit, ", the ", pixelCount, "-pixel image needs ", static_cast<unsigned long long>(array.imageBytes / perValue)));
}

// An array's binary data in the file: where it starts, how much of the file it may use, base64 text or raw.
struct BinaryData
{
  std::string inlineText;  // inline binary data, white space removed
  const char* begin = nullptr;
  std::size_t available = 0;
  bool base64 = false;
};

BinaryData locateBinaryData(const VtiLayout& layout, DataArrayDeclaration& array)
{
  BinaryData data;
  const std::string& dataFormat = array.attributes["format"];
  if (dataFormat == "appended")
  {
    long long offset = -1;
    if (!parseWholeInteger(array.attributes["offset"], offset) || offset < 0)
      throw layout.fail(array.label + ": no valid offset");
    if (layout.appendedTag == std::string::npos)
      throw layout.fail(array.label + ": appended, but the file has no AppendedData");
    if (static_cast<unsigned long long>(offset) >= layout.bytes.size() - layout.dataBegin)
      throw layout.fail(array.label + ": its offset lies beyond the appended data");
    data.begin = layout.bytes.data() + layout.dataBegin + offset;
    data.available = layout.bytes.size() - layout.dataBegin - static_cast<std::size_t>(offset);
    data.base64 = layout.appendedBase64;
    return data;
  }
  if (dataFormat == "binary")
  {
    const std::string& xml = layout.xml;
    const std::size_t contentEnd = xml.find("</DataArray>", array.tagEnd);
    if (xml[array.tagEnd - 1] == '/' || contentEnd == std::string::npos)
      throw layout.fail(array.label + ": binary data without a closing </DataArray>");
    for (std::size_t i = array.tagEnd + 1; i < contentEnd; ++i)
      if (!std::isspace(static_cast<unsigned char>(xml[i])))
        data.inlineText.push_back(xml[i]);
    data.begin = data.inlineText.data();
    data.available = data.inlineText.size();
    data.base64 = true;
    return data;
  }
  throw layout.fail(format(array.label, ": format \"", dataFormat, "\" (appended, binary or ascii expected)"));
}

// The byte count the array's binary data decodes to, from its header, checked against what the file holds.
long double decodedByteCount(const VtiLayout& layout, const DataArrayDeclaration& array, const BinaryData& data)
{
  const std::size_t headerBytes = layout.headerBytes;
  // The first `count` bytes of the data, decoded; false if the file holds fewer.
  std::vector<unsigned char> header;
  const auto readHeader = [&](std::size_t count) {
    header.assign(count, 0);
    if (!data.base64)
    {
      if (count > data.available)
        return false;
      std::memcpy(header.data(), data.begin, count);
      return true;
    }
    // Only the few header bytes are decoded here; VTK decodes the data itself once the checks pass.
    const std::size_t characters = (count + 2) / 3 * 4;
    if (characters > data.available)
      return false;
    std::vector<unsigned char> decoded(characters);
    decoded.resize(vtkBase64Utilities::DecodeSafely(
      reinterpret_cast<const unsigned char*>(data.begin), characters, decoded.data(), decoded.size()));
    if (decoded.size() < count)
      return false;
    std::memcpy(header.data(), decoded.data(), count);
    return true;
  };
  const auto headerInteger = [&](std::size_t index) {
    std::uint64_t value = 0;
    for (std::size_t i = 0; i < headerBytes; ++i)
      value = (value << 8) | header[index * headerBytes + (layout.bigEndian ? i : headerBytes - 1 - i)];
    return static_cast<long double>(value);
  };
  // Bytes of the file that `decoded` bytes of data occupy (base64 needs 4 characters per 3 bytes).
  const auto fileBytes = [&](long double decoded) { return data.base64 ? std::ceil(decoded / 3) * 4 : decoded; };

  if (!layout.compressed)
  {
    if (!readHeader(headerBytes))
      throw layout.fail(array.label + ": its header runs past the end of the file");
    const long double decodedBytes = headerInteger(0);
    if (fileBytes(headerBytes + decodedBytes) > data.available)
      throw layout.fail(array.label + ": its data runs past the end of the file");
    return decodedBytes;
  }
  if (!readHeader(3 * headerBytes))
    throw layout.fail(array.label + ": its block header runs past the end of the file");
  const long double blocks = headerInteger(0);
  const long double blockSize = headerInteger(1);
  const long double lastBlockSize = headerInteger(2);
  if (fileBytes((3 + blocks) * headerBytes) > data.available ||
    !readHeader((3 + static_cast<std::size_t>(blocks)) * headerBytes))
    throw layout.fail(format(array.label, ": its header claims ", static_cast<unsigned long long>(blocks),
      " compressed blocks, more than the file holds"));
  long double compressedBytes = 0.0L;
  for (std::size_t block = 0; block < static_cast<std::size_t>(blocks); ++block)
    compressedBytes += headerInteger(3 + block);
  if (fileBytes((3 + blocks) * headerBytes + compressedBytes) > data.available)
    throw layout.fail(array.label + ": its compressed blocks run past the end of the file");
  if (blocks > 0 && (blockSize == 0 || lastBlockSize > blockSize))
    throw layout.fail(array.label + ": inconsistent compressed block sizes");
  return blocks == 0 ? 0.0L : (blocks - 1) * blockSize + (lastBlockSize == 0 ? blockSize : lastBlockSize);
}

void checkDataArrays(const std::filesystem::path& path, long long pixelCount)
{
  const std::optional<VtiLayout> layout = readVtiLayout(path);
  if (!layout)
    return; // VTK has already refused such a file
  const std::string& xml = layout->xml;
  for (std::size_t tagBegin = xml.find("<DataArray"); tagBegin != std::string::npos;
       tagBegin = xml.find("<DataArray", tagBegin + 1))
  {
    const std::size_t nameEnd = tagBegin + std::strlen("<DataArray");
    if (nameEnd < xml.size() && !std::isspace(static_cast<unsigned char>(xml[nameEnd])) && xml[nameEnd] != '/' &&
      xml[nameEnd] != '>')
      continue; // another element (<DataArrayX>), which VTK does not read as an array
    DataArrayDeclaration array = declaredDataArray(*layout, tagBegin, pixelCount);
    if (array.attributes["format"] == "ascii")
    {
      // VTK allocates one tuple per pixel before it parses the text: the values must be there.
      const std::size_t contentEnd = xml.find("</DataArray>", array.tagEnd);
      if (xml[array.tagEnd - 1] == '/' || contentEnd == std::string::npos)
        throw layout->fail(array.label + ": ascii data without a closing </DataArray>");
      std::istringstream values(xml.substr(array.tagEnd + 1, contentEnd - array.tagEnd - 1));
      const auto count = std::distance(std::istream_iterator<std::string>(values), std::istream_iterator<std::string>());
      checkDecodedSize(*layout, array, static_cast<long double>(count) * array.typeBytes, "values", array.typeBytes,
        pixelCount);
      continue;
    }
    const BinaryData data = locateBinaryData(*layout, array);
    checkDecodedSize(*layout, array, decodedByteCount(*layout, array, data), "bytes", 1.0L, pixelCount);
  }
}
} // namespace

namespace
{

// A VTK XML file (zlib, appended raw binary), encoded in memory and written by writeEncodedFile:
// vtkXMLWriter::Write() returns 1 even when the disk fills up halfway (bad-input probe D17), and its own file
// output gives no reason.
void writeXmlDataFile(const std::filesystem::path& path, vtkXMLWriter* writer)
{
  const VtkErrorCapture capture;
  writer->SetCompressorTypeToZLib();
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();
  writer->WriteToOutputStringOn();
  const int written = writer->Write();
  SL_CHECK_MSG(written == 1 && writer->GetErrorCode() == 0 && !capture.hasError(), "encoding ", path.string(),
    " in memory failed: ", capture.firstError());
  writeEncodedFile(path, writer->GetOutputString());
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
  vtkNew<vtkXMLImageDataWriter> writer;
  writer->SetInputData(data);
  writeXmlDataFile(path, writer);
}

void writeVtp(const std::filesystem::path& path, vtkPolyData* polyData)
{
  SL_CHECK(polyData);
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputData(polyData);
  writeXmlDataFile(path, writer);
}

namespace
{

// XML attribute text: the five characters XML reserves, escaped.
std::string xmlAttribute(const std::string& text)
{
  std::string escaped;
  for (const char c : text)
  {
    switch (c)
    {
      case '&': escaped += "&amp;"; break;
      case '<': escaped += "&lt;"; break;
      case '>': escaped += "&gt;"; break;
      case '"': escaped += "&quot;"; break;
      case '\'': escaped += "&apos;"; break;
      default: escaped += c;
    }
  }
  return escaped;
}

std::string blockName(vtkMultiBlockDataSet* blocks, unsigned int index)
{
  vtkInformation* metaData = blocks->HasMetaData(index) ? blocks->GetMetaData(index) : nullptr;
  const char* name = metaData != nullptr ? metaData->Get(vtkCompositeDataSet::NAME()) : nullptr;
  return name != nullptr ? name : "block" + std::to_string(index);
}

// Writes one leaf under `pieceDir` and returns its file name relative to the index's directory.
std::string writeLeaf(vtkDataObject* leaf, const std::filesystem::path& pieceDir, const std::string& stem)
{
  if (auto* polyData = vtkPolyData::SafeDownCast(leaf))
  {
    writeVtp(pieceDir / (stem + ".vtp"), polyData);
    return stem + ".vtp";
  }
  if (auto* grid = vtkStructuredGrid::SafeDownCast(leaf))
  {
    // probe.vtm's shadow-map crop: texels placed in world space (probe/ProbeDataSet.cxx).
    vtkNew<vtkXMLStructuredGridWriter> writer;
    writer->SetInputData(grid);
    writeXmlDataFile(pieceDir / (stem + ".vts"), writer);
    return stem + ".vts";
  }
  auto* image = vtkImageData::SafeDownCast(leaf);
  SL_CHECK_MSG(image != nullptr, "writeVtm: a leaf of type ", leaf->GetClassName(),
    " (only vtkPolyData, vtkStructuredGrid and vtkImageData)");
  vtkNew<vtkXMLImageDataWriter> writer;
  writer->SetInputData(image);
  writeXmlDataFile(pieceDir / (stem + ".vti"), writer);
  return stem + ".vti";
}

} // namespace

void writeVtm(const std::filesystem::path& path, vtkMultiBlockDataSet* blocks)
{
  SL_CHECK(blocks);
  const std::string stem = path.stem().string();
  const std::filesystem::path pieceDir = path.parent_path() / stem;
  std::error_code error;
  std::filesystem::create_directory(pieceDir, error);
  if (error)
  {
    throw InputError(pieceDir.string() + ": cannot create directory (" + error.message() + ")");
  }
  std::string index = "<?xml version=\"1.0\"?>\n<VTKFile type=\"vtkMultiBlockDataSet\" version=\"1.0\" "
                      "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n  <vtkMultiBlockDataSet>\n";
  for (unsigned int b = 0; b < blocks->GetNumberOfBlocks(); ++b)
  {
    const std::string name = blockName(blocks, b);
    vtkDataObject* block = blocks->GetBlock(b);
    if (auto* children = vtkMultiBlockDataSet::SafeDownCast(block))
    {
      index += "    <Block index=\"" + std::to_string(b) + "\" name=\"" + xmlAttribute(name) + "\">\n";
      for (unsigned int c = 0; c < children->GetNumberOfBlocks(); ++c)
      {
        vtkDataObject* leaf = children->GetBlock(c);
        if (leaf == nullptr)
        {
          continue;
        }
        const std::string file =
          writeLeaf(leaf, pieceDir, stem + "_" + std::to_string(b) + "_" + std::to_string(c));
        index += "      <DataSet index=\"" + std::to_string(c) + "\" name=\"" + xmlAttribute(blockName(children, c)) +
          "\" file=\"" + xmlAttribute(stem + "/" + file) + "\"/>\n";
      }
      index += "    </Block>\n";
    }
    else if (block != nullptr)
    {
      const std::string file = writeLeaf(block, pieceDir, stem + "_" + std::to_string(b));
      index += "    <DataSet index=\"" + std::to_string(b) + "\" name=\"" + xmlAttribute(name) + "\" file=\"" +
        xmlAttribute(stem + "/" + file) + "\"/>\n";
    }
  }
  index += "  </vtkMultiBlockDataSet>\n</VTKFile>\n";
  writeEncodedFile(path, index);
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

  checkDataArrays(path, width * height);
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
    if (components < 1 || components > kMaxVtiComponents)
    {
      throw InputError(
        format(file, ": array '", arrayName, "' has ", components, " components (1 to ", kMaxVtiComponents, " supported)"));
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

void writePng(const std::filesystem::path& path, const ImageU8& rgb,
  const std::vector<std::pair<std::string, std::string>>& text)
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
  for (const auto& [keyword, value] : text)
  {
    writer->AddText(keyword.c_str(), value.c_str());
  }
  writer->WriteToMemoryOn();
  writer->Write();
  vtkUnsignedCharArray* png = writer->GetResult();
  SL_CHECK_MSG(writer->GetErrorCode() == 0 && !capture.hasError() && png != nullptr && png->GetNumberOfValues() > 0,
    "encoding ", path.string(), " in memory failed: ", capture.firstError());
  writeEncodedFile(path,
    std::string(reinterpret_cast<const char*>(png->GetPointer(0)), static_cast<std::size_t>(png->GetNumberOfValues())));
}

std::string readPngText(const std::filesystem::path& path, const std::string& keyword)
{
  std::ifstream stream(path, std::ios::binary);
  char signature[kPngSignatureBytes] = {};
  if (!stream.read(signature, sizeof(signature)) || std::memcmp(signature, "\x89PNG\r\n\x1a\n", 8) != 0)
  {
    return "";
  }
  // Chunks: 4-byte big-endian length, 4-byte type, data, 4-byte CRC. Text is looked for up to the image data,
  // where writePng puts it; a chunk longer than a text chunk can sensibly be is skipped unread.
  for (;;)
  {
    unsigned char header[8];
    if (!stream.read(reinterpret_cast<char*>(header), sizeof(header)))
    {
      return "";
    }
    const std::uint32_t length = (std::uint32_t{ header[0] } << 24) | (std::uint32_t{ header[1] } << 16) |
      (std::uint32_t{ header[2] } << 8) | header[3];
    const std::string type(reinterpret_cast<const char*>(header) + 4, 4);
    if (type == "IDAT" || type == "IEND")
    {
      return "";
    }
    if (type == "tEXt" && length <= 65536)
    {
      std::string data(length, '\0');
      if (!stream.read(data.data(), length))
      {
        return "";
      }
      const std::size_t separator = data.find('\0');
      if (separator != std::string::npos && data.compare(0, separator, keyword) == 0 && separator == keyword.size())
      {
        return data.substr(separator + 1);
      }
      stream.seekg(4, std::ios::cur); // CRC
    }
    else
    {
      stream.seekg(std::streamoff{ length } + 4, std::ios::cur);
    }
  }
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
