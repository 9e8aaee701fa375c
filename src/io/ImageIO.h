// File formats for frame outputs. All take images with row 0 at the bottom (our Image convention) and
// write them the right way up. Each throws InputError naming the path when it cannot write.
#pragma once

#include "core/Image.h"

#include <filesystem>
#include <string>
#include <vector>

namespace sl
{

struct NamedImage;

// One vtkImageData (XML, zlib-compressed, appended raw binary): dimensions width x height x 1, spacing 1,
// origin 0, one point-data array per image (float, 1 or 3 components). Opens in ParaView.
void writeVti(const std::filesystem::path& path, const std::vector<NamedImage>& images);
// Reads back the arrays of a .vti written by writeVti (tests, compare tools). Throws InputError.
std::vector<NamedImage> readVti(const std::filesystem::path& path);

void writePng(const std::filesystem::path& path, const ImageU8& rgb);
ImageU8 readPng(const std::filesystem::path& path); // RGB, row 0 at the bottom
// Single-channel 32-bit float OpenEXR; the channel is "Y" so viewers show it as grey.
void writeExr(const std::filesystem::path& path, const ImageF& values);
ImageF readExr(const std::filesystem::path& path);

} // namespace sl
