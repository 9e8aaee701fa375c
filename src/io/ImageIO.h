// File formats for frame outputs. All take images with row 0 at the bottom (our Image convention) and
// write them the right way up.
//
// Writes are checked end to end: files are encoded in memory, written with every system call checked
// (writeFileChecked), and the size on disk is compared with what was encoded, so a full disk or a file-size
// limit is an InputError "<file>: cannot write (<system's reason>)" and never a truncated file reported as
// success. Readers refuse what they cannot represent with an InputError naming the file (and the array),
// never a crash: PNGs are decoded by libpng with its setjmp error path, .vti files are checked before any
// copy, and VTK's own error text is folded into the message (see io/vtkSLOutputWindow.h).
#pragma once

#include "core/Image.h"

#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

class vtkPolyData;
class vtkMultiBlockDataSet;

namespace sl
{

struct NamedImage;


// One vtkImageData (XML, zlib-compressed, appended raw binary): dimensions width x height x 1, spacing 1,
// origin 0, one point-data array per image (float, 1 or 3 components). Opens in ParaView.
void writeVti(const std::filesystem::path& path, const std::vector<NamedImage>& images);
// vtkPolyData as a .vtp (XML, appended zlib), written like writeVti.
void writeVtp(const std::filesystem::path& path, vtkPolyData* polyData);
// A vtkMultiBlockDataSet as <stem>.vtm plus one file per leaf under <stem>/ (vtkPolyData .vtp, vtkImageData .vti,
// vtkStructuredGrid .vts),
// blocks nested at most two deep (blocks of leaves), names from vtkCompositeDataSet::NAME(). Every file is
// written and checked like writeVtp; the index is the XML vtkXMLMultiBlockDataReader (ParaView) reads.
void writeVtm(const std::filesystem::path& path, vtkMultiBlockDataSet* blocks);
// Reads back the arrays of a 2-D .vti (tests, compare tools): dimensions width x height x 1 with
// 1 <= width, height <= kMaxImageSide; every named point-data array numeric, 1..4 components, one tuple
// per pixel (converted to float). Throws InputError naming the file (and the array) otherwise.
// The most components readVti accepts in one array: per-light-sample arrays hold up to 256 (dcs's
// sample_depth_complexity, the reference's sample_crossings at N = 256).
constexpr int kMaxVtiComponents = 256;
std::vector<NamedImage> readVti(const std::filesystem::path& path);

// `text`: tEXt chunks (keyword, Latin-1 value) written before the image data, e.g. montage's signature.
void writePng(const std::filesystem::path& path, const ImageU8& rgb,
  const std::vector<std::pair<std::string, std::string>>& text = {});
// The value of the first uncompressed tEXt chunk with `keyword` before the image data, or "" when there is none or
// `path` is not a readable PNG. Walks the chunk headers only (no decoding): montage uses it to recognise its own
// files before replacing one.
std::string readPngText(const std::filesystem::path& path, const std::string& keyword);
// RGB, row 0 at the bottom: gray is replicated, alpha ignored, 16-bit samples rounded to 8 bits.
ImageU8 readPng(const std::filesystem::path& path);

// A PNG as decoded by libpng: palette images expanded to RGB, a tRNS chunk to an alpha channel, 1/2/4-bit
// gray to 8 bits; 16-bit files keep 16 bits. `samples` has 1 (gray), 2 (gray + alpha), 3 (RGB) or 4 (RGBA)
// components, each in 0..maxSample(); row 0 is the bottom row of the picture.
struct PngImage
{
  Image<std::uint16_t> samples;
  int bitDepth = 8; // 8 or 16
  double maxSample() const { return bitDepth == 16 ? 65535.0 : 255.0; }
};
// The one PNG decoder (alpha textures, readPng). Throws InputError "cannot read '<file>' (<why>)" for a
// missing or non-regular file, a non-PNG, a PNG larger than kMaxImageSide per side, or any corruption
// libpng reports (its own words, e.g. "IDAT: invalid block type", "Not enough image data").
PngImage readPngImage(const std::filesystem::path& path);

// Single-channel 32-bit float OpenEXR; the channel is "Y" so viewers show it as grey.
void writeExr(const std::filesystem::path& path, const ImageF& values);
ImageF readExr(const std::filesystem::path& path);

} // namespace sl
