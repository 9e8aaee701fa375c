#include "structures/sat/vtkSLSatPass.h"

#include "core/Error.h"
#include "gl/BandedPrefixSums.h"
#include "gl/GlResources.h"
#include "gl/ShaderLibrary.h"
#include "structures/sat/SatStructure.h"
#include "passes/FrameResources.h"
#include "passes/PassUtilities.h"
#include "lightspace/SummedAreaTable.h"

#include <vtkObjectFactory.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkRenderState.h>
#include <vtkRenderer.h>
#include <vtkTextureObject.h>
#include <vtk_glew.h>

#include <algorithm>
#include <cmath>

vtkStandardNewMacro(vtkSLSatPass);

vtkSLSatPass::vtkSLSatPass() = default;
vtkSLSatPass::~vtkSLSatPass() = default;

void vtkSLSatPass::Execute(const vtkRenderState* state)
{
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(state->GetRenderer()->GetRenderWindow());
  sl::FrameResources& frame = *this->Frame;
  SL_CHECK_MSG(frame.hasLightView && frame.shadowMapLinear, "the shadow map must be built before its SAT");
  const bool integer = sl::summedAreaTableSettings(frame.parameters).integer;
  const int size = frame.lightView.resolution;
  // int32: b bits of fixed point so that a box of the whole map sums below 2^32 (SatBuild.glsl).
  const double fixedPointScale = sl::satFixedPointScale(size);

  // The table of the previous frame (or sub-light) is reused when it fits: both passes overwrite every
  // texel, and a fresh 2048^2 table (32 MB) costs llvmpipe more wall time than building it.
  const unsigned internalFormat = integer ? GL_RG32UI : GL_RG32F;
  if (!this->Table || this->Table->GetContext() != window || this->Table->GetWidth() != static_cast<unsigned>(size) ||
    this->Table->GetHeight() != static_cast<unsigned>(size) || this->TableInternalFormat != internalFormat)
  {
    auto table = vtkSmartPointer<vtkTextureObject>::New();
    table->SetContext(window);
    table->SetInternalFormat(internalFormat);
    table->SetFormat(integer ? GL_RG_INTEGER : GL_RG);
    table->SetDataType(integer ? GL_UNSIGNED_INT : GL_FLOAT);
    table->SetMinificationFilter(vtkTextureObject::Nearest);
    table->SetMagnificationFilter(vtkTextureObject::Nearest);
    table->SetWrapS(vtkTextureObject::ClampToEdge);
    table->SetWrapT(vtkTextureObject::ClampToEdge);
    if (!table->Allocate2D(size, size, 2, integer ? VTK_UNSIGNED_INT : VTK_FLOAT))
    {
      throw sl::GraphicsError("cannot allocate the summed-area table");
    }
    this->Table = table;
    this->TableInternalFormat = internalFormat;
  }
  vtkTextureObject* table = this->Table;
  frame.shadowMapLinear->Activate();
  const sl::BandedPrefixSums::Table tableTexels{ table->GetHandle(), static_cast<unsigned>(integer ? GL_RG_INTEGER : GL_RG),
    static_cast<unsigned>(integer ? GL_UNSIGNED_INT : GL_FLOAT), 2 };
  this->Bands.build(size, { tableTexels }, [&](int pass, int firstRow, int rows) {
    auto& program = this->Programs[{ integer, pass }];
    if (!program)
    {
      sl::ShaderDefines defines = { { "SAT_PRECISION_FLOAT_CENTRED", "0" }, { "SAT_PRECISION_INT32", "1" },
        { "SAT_PRECISION", integer ? "1" : "0" }, { "SAT_PASS", std::to_string(pass) } };
      program = std::make_unique<sl::ComputeProgram>(sl::assembleShader("sat/SatBuild.glsl", defines), "summed-area table");
    }
    program->use();
    program->setInt("shadowMapLinear", frame.shadowMapLinear->GetTextureUnit());
    program->setFloat("depthNear", frame.lightView.nearDepth);
    program->setFloat("depthFar", frame.lightView.farDepth);
    program->setFloat("fixedPointScale", fixedPointScale);
    program->setInt("mapSize", size);
    program->setInt("bandFirstRow", firstRow);
    program->setInt("bandRows", rows);
    // One invocation per row of the band (pass 0) or per column (pass 1).
    program->dispatch({ ((pass == 0 ? rows : size) + 63) / 64, 1 });
  });
  frame.shadowMapLinear->Deactivate();
  auto data = std::make_shared<sl::SummedAreaTableData>();
  data->table = table;
  data->integer = integer;
  data->fixedPointScale = fixedPointScale;
  data->bandBytes = this->Bands.bytes();
  frame.lightSpaceData[sl::summedAreaTableStructure().name] = data;
}

void vtkSLSatPass::ReleaseGraphicsResources(vtkWindow*)
{
  this->Programs.clear();
  this->Table = nullptr;
  this->Bands = sl::BandedPrefixSums();
}

void vtkSLSatPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
