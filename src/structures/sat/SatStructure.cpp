#include "structures/sat/SatStructure.h"

#include "frame/FrameResult.h"
#include "gl/GlResources.h"
#include "structures/sat/vtkSLSatPass.h"
#include "structures/shadowmap/ShadowMapStructure.h"
#include "passes/PassUtilities.h"

#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>

#include <algorithm>

namespace sl
{

SummedAreaTableSettings summedAreaTableSettings(const ParameterValues& values)
{
  SummedAreaTableSettings settings;
  settings.integer = values.choice("sat_precision") == "int32";
  return settings;
}

const SummedAreaTableData& summedAreaTableData(const FrameResources& frame)
{
  return frame.structureData<SummedAreaTableData>(summedAreaTableStructure().name);
}

namespace
{

std::vector<NamedImage> exportTable(const FrameResources& frame, FrameResult& result)
{
  // Exported as floats: for the int32 table these are the wrapped unsigned sums (only box differences of
  // them are meaningful), for the float table the centred sums. The int32 table is also kept exactly.
  const SummedAreaTableData& data = summedAreaTableData(frame);
  // Built in place: an initializer list would copy both tables once more.
  std::vector<NamedImage> images(2);
  images[0] = { "sat_z", {}, "", "summed-area table of z (centred, or 16-bit fixed point z_n wrapping mod 2^32)",
    BufferKind::SummedArea };
  images[1] = { "sat_z2", {}, "", "summed-area table of z^2 (centred, or 16-bit fixed point z_n^2 wrapping mod 2^32)",
    BufferKind::SummedArea };
  if (data.integer)
  {
    // Each component straight from the exact table (no two-component float copy: at 2048^2 it is 32 MB).
    result.integerSummedAreaTable = readUnsignedTextureExact(data.table, 2);
    const Image<std::uint32_t>& exact = *result.integerSummedAreaTable;
    for (int component = 0; component < 2; ++component)
    {
      ImageF& table = images[static_cast<std::size_t>(component)].image;
      table = ImageF(exact.width, exact.height, 1);
      for (std::size_t i = 0; i < table.data.size(); ++i)
      {
        table.data[i] = static_cast<float>(exact.data[2 * i + static_cast<std::size_t>(component)]);
      }
    }
  }
  else
  {
    const ImageF table = readFloatTexture(data.table, 2);
    images[0].image = table.channels(0, 1);
    images[1].image = table.channels(1, 1);
  }
  return images;
}

std::vector<vtkTextureObject*> bindTable(vtkShaderProgram* program, const FrameResources& frame)
{
  const SummedAreaTableData& data = summedAreaTableData(frame);
  program->SetUniformf("satDepthNear", static_cast<float>(frame.lightView.nearDepth));
  program->SetUniformf("satDepthFar", static_cast<float>(frame.lightView.farDepth));
  setFloatIfUsed(program, "satFixedPointScale", data.fixedPointScale);
  return { bindTexture(program, "satTable", data.table) };
}

} // namespace

const LightSpaceStructure& summedAreaTableStructure()
{
  static const LightSpaceStructure structure = [] {
    LightSpaceStructure s;
    s.name = "summed_area_table";
    s.doc = "summed-area table of the shadow map's (z, z^2): float (centred) or 32-bit integer (survey §6.4)";
    s.builtFrom = { &shadowMapStructure() };
    s.parameters = {
      { "sat_precision", 1, 0, 1, "", "float_centred: float SAT of z - (near + far) / 2; int32: 16-bit fixed point, exact box sums (survey §6.4)", { "float_centred", "int32" }, true },
    };
    s.createBuildPasses = [] {
      return std::vector<vtkSmartPointer<vtkSLStagePass>>{ vtkSmartPointer<vtkSLSatPass>::New() };
    };
    s.exportImages = exportTable;
    s.gpuBytes = [](const FrameResources& frame) {
      const SummedAreaTableData& data = summedAreaTableData(frame);
      return textureBytes(data.table, 8) + data.bandBytes;
    };
    s.shaderDefines = [](const FrameResources&) { return ShaderDefines{}; };
    s.bind = bindTable;
    return s;
  }();
  return structure;
}

} // namespace sl
