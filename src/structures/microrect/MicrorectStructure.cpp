#include "structures/microrect/MicrorectStructure.h"

#include "gl/GlResources.h"
#include "lightspace/Microrects.h"
#include "structures/microrect/vtkSLMicrorectPass.h"
#include "structures/shadowmap/ShadowMapStructure.h"
#include "passes/PassUtilities.h"

#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>

#include <string>

namespace sl
{
namespace
{

const MicrorectData& microrectData(const FrameResources& frame)
{
  return frame.structureData<MicrorectData>(microrectStructure().name);
}

// The two atlases as stored, and for k = 1..L how many level-k extents cover each texel (from the read-back
// extents, by a difference array), which shows how much microrects overlap (§5.2).
std::vector<NamedImage> exportMicrorects(const FrameResources& frame)
{
  const MicrorectData& data = microrectData(frame);
  const Image<std::uint32_t> extents = readUnsignedTextureExact(data.extentTexture, 4);
  const ImageF depths = readFloatTexture(data.depthTexture, 1);
  ImageF extentsAsFloat(extents.width, extents.height, 4);
  for (std::size_t i = 0; i < extents.data.size(); ++i)
  {
    extentsAsFloat.data[i] = static_cast<float>(extents.data[i]); // < 2^16: exact
  }
  const std::string atlas = "levels 1..L packed in an atlas (level 1 at the origin, the others stacked to its right)";
  std::vector<NamedImage> images;
  images.push_back({ "microrect_extent", extentsAsFloat, "texels",
    "extent x0, y0, x1, y1 (inclusive level-0 texels) of each microrect, " + atlas });
  images.push_back({ "microrect_depth", depths, "world units",
    "depth (min over the absorbed microrects) of each microrect, " + atlas });
  const Microrects read = Microrects::fromAtlases(readFloatTexture(frame.shadowMapLinear, 1), extents, depths);
  for (int level = 1; level <= read.levelCount(); ++level)
  {
    images.push_back({ "microrect_overlap_" + std::to_string(level), read.overlapCount(level), "microrects",
      "how many level-" + std::to_string(level) + " microrect extents cover this texel" });
  }
  return images;
}

} // namespace

std::vector<ShaderConstant> microrectBuildShaderConstants()
{
  return {
    { "CLAIMED_B", MicrorectClaims::kB, "pass 1 absorbed B (Microrects.h MicrorectClaims)" },
    { "CLAIMED_D", MicrorectClaims::kD, "pass 1 absorbed D (Microrects.h MicrorectClaims)" },
    { "CLAIMED_E", MicrorectClaims::kE, "pass 1 absorbed E (Microrects.h MicrorectClaims)" },
  };
}

ShaderDefines microrectBuildDefines(int pass)
{
  ShaderDefines defines = { { "MICRORECT_BUILD_PASS", std::to_string(pass) } };
  for (const ShaderConstant& constant : microrectBuildShaderConstants())
  {
    defines.emplace_back(constant.name, std::to_string(constant.value));
  }
  return defines;
}

const LightSpaceStructure& microrectStructure()
{
  static const LightSpaceStructure structure = [] {
    LightSpaceStructure s;
    s.name = "microrects";
    s.doc = "micro-occluders with per-texel rectangular extents, greedy two-pass merge per level (Schwarz & Stamminger 2008 §5.2)";
    s.builtFrom = { &shadowMapStructure() };
    s.createBuildPasses = [] {
      return std::vector<vtkSmartPointer<vtkSLStagePass>>{ vtkSmartPointer<vtkSLMicrorectPass>::New() };
    };
    s.exportImages = [](const FrameResources& frame, FrameResult&) { return exportMicrorects(frame); };
    // Extents 8 B + depth 4 B per atlas texel, and the claim scratch (1 B per level-1 texel), which the pass
    // keeps between frames.
    s.gpuBytes = [](const FrameResources& frame) {
      const MicrorectData& data = microrectData(frame);
      return textureBytes(data.extentTexture, 8) + textureBytes(data.depthTexture, 4) + textureBytes(data.claimTexture, 1);
    };
    s.shaderDefines = [](const FrameResources&) { return ShaderDefines{}; };
    s.bind = [](vtkShaderProgram* program, const FrameResources& frame) {
      const MicrorectData& data = microrectData(frame);
      setIntIfUsed(program, "microrectMapSize", data.mapSize);
      return std::vector<vtkTextureObject*>{ bindTexture(program, "microrectExtentTexture", data.extentTexture),
        bindTexture(program, "microrectDepthTexture", data.depthTexture) };
    };
    return s;
  }();
  return structure;
}

} // namespace sl
