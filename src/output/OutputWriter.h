// Writes a rendered frame into an output directory, atomically and under the output contract of
// OutputDirectory.h: everything goes to a temporary sibling directory first, which takes the place of --out
// only when every file was written. A failure leaves no partial output (an existing --out is kept as it was).
//
// Files: buffers.vti, light_space.vti (when a light-space structure was built), image.png,
// visibility.exr, heatmap_<buffer>.png per scalar buffer, open_in_paraview.py (output/ParaViewScript.h), stats.json. docs/outputs.md documents each.
#pragma once

#include "io/OutputDirectory.h"
#include "frame/FrameResult.h"

#include <filesystem>
#include <nlohmann/json.hpp>

namespace sl
{

struct OutputContext
{
  std::filesystem::path sceneFile;
  int lightIndex = 0;
  std::size_t droppedDegenerateTriangles = 0;
};

nlohmann::json frameStats(const FrameResult& frame, const OutputContext& context);
// min/max/mean/non-finite count of a buffer over the pixels of its domain: where `valueMask` (vis/BufferHeatMap.h
// bufferValueMask, same size) is neither 0 (no surface) nor kNotApplicablePixel; all pixels when it is null.
// domain_pixels counts them; category_pixels (categorical buffers) counts every covered pixel.
nlohmann::json bufferSummary(const NamedImage& named, const ImageU8* valueMask);
// bufferSummary of each buffer, keyed by name, with "domain" naming its pixels: a buffer declared on shadow-tested
// pixels (BufferDomain::ShadowTested) over those where shadow_tested is 1, the others over the covered pixels (the
// "coverage" buffer); coverage itself, and every buffer of a set without coverage, over the whole image.
nlohmann::json bufferSummaries(const std::vector<NamedImage>& buffers);
// buffers.vti (+ light_space.vti when not empty), image.png (when given and not empty), visibility.exr
// (when a visibility buffer exists), a heat map per scalar buffer and open_in_paraview.py, into an existing directory.
void writeBufferFiles(const std::vector<NamedImage>& buffers, const std::vector<NamedImage>& lightSpace,
  const ImageU8* image, const std::filesystem::path& dir);
void writeJson(const nlohmann::json& json, const std::filesystem::path& path);
// Every write checked (writeFileChecked): InputError naming the file when it cannot be written completely.
void writeFrameOutputs(const FrameResult& frame, const OutputContext& context, const OutputTarget& target);

} // namespace sl
