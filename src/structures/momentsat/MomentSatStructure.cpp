#include "structures/momentsat/MomentSatStructure.h"

#include "frame/FrameResult.h"
#include "gl/GlResources.h"
#include "lightspace/MomentSummedAreaTable.h"
#include "passes/PassUtilities.h"
#include "structures/momentsat/vtkSLMomentSatPass.h"
#include "structures/shadowmap/ShadowMapStructure.h"

#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>

namespace sl
{

MomentSatFormat momentSatFormat(const ParameterValues& values)
{
  if (values.choice("moment_sat_precision") == "int32")
  {
    return int32MomentSatFormat(values.getInt("moment_sat_max_kernel_texels"));
  }
  return MomentSatFormat{};
}

const MomentSatData& momentSatData(const FrameResources& frame)
{
  return frame.structureData<MomentSatData>(momentSatStructure().name);
}

namespace
{

// The table's words are not useful as images (wrapping low words, high words that only grow): exported are the
// per-texel moments decoded from the table (each texel's one-texel box sum / 2^32, what every box mean sums), and the
// exact words are kept for tests (FrameResult::momentSummedAreaTable).
std::vector<NamedImage> exportMomentSat(const FrameResources& frame, FrameResult& result)
{
  const MomentSatData& data = momentSatData(frame);
  const bool wide = data.format.wide;
  Image<std::uint32_t> words(
    static_cast<int>(data.low->GetWidth()), static_cast<int>(data.low->GetHeight()), wide ? 8 : 4);
  if (wide)
  {
    const Image<std::uint32_t> low = readUnsignedTextureExact(data.low, 4);
    const Image<std::uint32_t> high = readUnsignedTextureExact(data.high, 4);
    for (std::size_t texel = 0; texel < low.pixelCount(); ++texel)
    {
      for (std::size_t k = 0; k < 4; ++k)
      {
        words.data[8 * texel + k] = low.data[4 * texel + k];
        words.data[8 * texel + 4 + k] = high.data[4 * texel + k];
      }
    }
  }
  else
  {
    words = readUnsignedTextureExact(data.low, 4);
  }
  const double scale = data.format.scale();
  const char* names[4] = { "moment_sat_texel_1", "moment_sat_texel_2", "moment_sat_texel_3", "moment_sat_texel_4" };
  const char* docs[4] = { "z of the texel as the moment SAT holds it (fixed point floor(z 2^b) / 2^b, decoded from its box sum)",
    "z^2 of the texel as the moment SAT holds it", "z^3 of the texel as the moment SAT holds it",
    "z^4 of the texel as the moment SAT holds it" };
  std::vector<NamedImage> images(4);
  for (int k = 0; k < 4; ++k)
  {
    images[static_cast<std::size_t>(k)] = { names[k], ImageF(words.width, words.height, 1), "", docs[k] };
  }
  // Each texel's one-texel box sum, straight from the words (no 64-bit copy of the table: 2 GiB at 8192^2); int32
  // sums wrap, and a one-texel box is exact modulo 2^32.
  const auto sum = [&words, wide](int x, int y, int k) -> std::uint64_t {
    if (x < 0 || y < 0)
    {
      return 0u;
    }
    const std::uint64_t high = wide ? words.at(x, y, 4 + k) : 0u;
    return (high << 32) | words.at(x, y, k);
  };
  for (int y = 0; y < words.height; ++y)
  {
    for (int x = 0; x < words.width; ++x)
    {
      for (int k = 0; k < 4; ++k)
      {
        std::uint64_t texel = sum(x, y, k) - sum(x - 1, y, k) - sum(x, y - 1, k) + sum(x - 1, y - 1, k);
        texel = wide ? texel : (texel & 0xFFFFFFFFu);
        images[static_cast<std::size_t>(k)].image.at(x, y) = static_cast<float>(static_cast<double>(texel) / scale);
      }
    }
  }
  result.momentSummedAreaTable = std::move(words);
  return images;
}

} // namespace

const LightSpaceStructure& momentSatStructure()
{
  static const LightSpaceStructure structure = [] {
    LightSpaceStructure s;
    s.name = "moment_sat";
    s.doc = "summed-area table of the four power moments (z, z^2, z^3, z^4), 32-bit fixed point per texel, exact 64-bit "
            "sums (Peters et al. 2016, moment soft shadow mapping)";
    s.builtFrom = { &shadowMapStructure() };
    s.parameters = {
      { "moment_sat_precision", 0, 0, 1, "",
        "int64: 32-bit fixed point per texel, 64-bit sums, every box exact; int32 (the authors' form): "
        "32 - ceil(log2(w^2)) bits per texel, 32-bit sums that wrap, exact for boxes up to w x w texels "
        "(w = moment_sat_max_kernel_texels; larger boxes are flagged)", { "int64", "int32" }, true },
      { "moment_sat_max_kernel_texels", 256, 2, 4096, "texels",
        "int32: the width w of the largest box the table sums exactly (256: 16 bits per texel)", {}, true },
    };
    s.createBuildPasses = [] {
      return std::vector<vtkSmartPointer<vtkSLStagePass>>{ vtkSmartPointer<vtkSLMomentSatPass>::New() };
    };
    s.exportImages = exportMomentSat;
    s.gpuBytes = [](const FrameResources& frame) {
      const MomentSatData& data = momentSatData(frame);
      return textureBytes(data.low, 16) + (data.high ? textureBytes(data.high, 16) : 0u) + data.bandBytes;
    };
    s.shaderDefines = [](const FrameResources&) { return ShaderDefines{}; };
    s.bind = [](vtkShaderProgram* program, const FrameResources& frame) {
      const MomentSatData& data = momentSatData(frame);
      setFloatIfUsed(program, "momentSatScale", data.format.scale());
      setFloatIfUsed(program, "momentSatExactTexels", data.format.exactTexels());
      std::vector<vtkTextureObject*> bound{ bindTexture(program, "momentSatLow", data.low) };
      if (data.high)
      {
        bound.push_back(bindTexture(program, "momentSatHigh", data.high));
      }
      return bound;
    };
    return s;
  }();
  return structure;
}

} // namespace sl
