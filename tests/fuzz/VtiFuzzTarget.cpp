// libFuzzer target: readVti, the reader behind `compare` and bench's reference cache.
//
// readVti takes a path, so each input is written to a file of this process's own (ScratchDirectory) and read
// back from there. After a file is accepted, every image must hold exactly width x height x components
// values: the heap overflow of probe case K15 (a 3-D extent copied into a 2-D image) broke exactly that.
#include "FuzzSupport.h"

#include "core/Error.h"
#include "io/ImageIO.h"
#include "pipeline/ShadowRenderer.h"

#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  static const sl::fuzz::ScratchDirectory scratch;
  const std::filesystem::path file = scratch.write("input.vti", data, size);
  try
  {
    const std::vector<sl::NamedImage> images = sl::readVti(file);
    for (const sl::NamedImage& named : images)
    {
      const sl::ImageF& image = named.image;
      sl::fuzz::expect(image.width > 0 && image.height > 0 && image.components > 0,
        "readVti accepted array '" + named.name + "' with an empty shape");
      sl::fuzz::expect(image.data.size() == image.pixelCount() * static_cast<std::size_t>(image.components),
        "readVti: array '" + named.name + "' holds a different number of values than its shape");
      sl::fuzz::expect(image.width == images.front().image.width && image.height == images.front().image.height,
        "readVti: arrays of one file with different sizes");
    }
  }
  catch (const sl::InputError&)
  {
    // A refused file: the normal outcome for most of what the fuzzer writes.
  }
  return 0;
}
