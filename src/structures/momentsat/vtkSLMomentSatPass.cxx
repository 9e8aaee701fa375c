#include "structures/momentsat/vtkSLMomentSatPass.h"

#include "core/Error.h"
#include "gl/BandedPrefixSums.h"
#include "gl/ShaderLibrary.h"
#include "lightspace/MomentSummedAreaTable.h"
#include "passes/FrameResources.h"
#include "structures/momentsat/MomentSatStructure.h"

#include <vtkObjectFactory.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkRenderState.h>
#include <vtkRenderer.h>
#include <vtkTextureObject.h>
#include <vtk_glew.h>

#include <vector>

vtkStandardNewMacro(vtkSLMomentSatPass);

vtkSLMomentSatPass::vtkSLMomentSatPass() = default;
vtkSLMomentSatPass::~vtkSLMomentSatPass() = default;

namespace
{

vtkSmartPointer<vtkTextureObject> momentSatWords(vtkOpenGLRenderWindow* window, int size)
{
  auto table = vtkSmartPointer<vtkTextureObject>::New();
  table->SetContext(window);
  table->SetInternalFormat(GL_RGBA32UI);
  table->SetFormat(GL_RGBA_INTEGER);
  table->SetDataType(GL_UNSIGNED_INT);
  table->SetMinificationFilter(vtkTextureObject::Nearest);
  table->SetMagnificationFilter(vtkTextureObject::Nearest);
  table->SetWrapS(vtkTextureObject::ClampToEdge);
  table->SetWrapT(vtkTextureObject::ClampToEdge);
  if (!table->Allocate2D(size, size, 4, VTK_UNSIGNED_INT))
  {
    throw sl::GraphicsError("cannot allocate the moment summed-area table");
  }
  return table;
}

} // namespace

void vtkSLMomentSatPass::Execute(const vtkRenderState* state)
{
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(state->GetRenderer()->GetRenderWindow());
  sl::FrameResources& frame = *this->Frame;
  SL_CHECK_MSG(frame.hasLightView && frame.shadowMapLinear, "the shadow map must be built before its moment SAT");
  const int size = frame.lightView.resolution;
  // Exact sums need every prefix sum below 2^64: at most 2^32 texels of at most 2^32 - 1 each.
  SL_CHECK_MSG(size <= sl::momentSatMaxMapSize, "the moment SAT holds exact sums up to a 65536^2 shadow map");
  const sl::MomentSatFormat format = sl::momentSatFormat(frame.parameters);
  // Reused when they fit: both passes overwrite every texel.
  if (!this->Low || this->Low->GetContext() != window || this->Low->GetWidth() != static_cast<unsigned>(size) ||
    this->Low->GetHeight() != static_cast<unsigned>(size))
  {
    this->Low = momentSatWords(window, size);
    this->High = nullptr;
  }
  if (format.wide && !this->High)
  {
    this->High = momentSatWords(window, size);
  }
  std::vector<sl::BandedPrefixSums::Table> tables{ { this->Low->GetHandle(), GL_RGBA_INTEGER, GL_UNSIGNED_INT, 4 } };
  if (format.wide)
  {
    tables.push_back({ this->High->GetHandle(), GL_RGBA_INTEGER, GL_UNSIGNED_INT, 4 });
  }
  frame.shadowMapLinear->Activate();
  this->Bands.build(size, tables, [&](int pass, int firstRow, int rows) {
    auto& program = this->Programs[{ format.wide, pass }];
    if (!program)
    {
      program = std::make_unique<sl::ComputeProgram>(sl::assembleShader("momentsat/MomentSatBuild.glsl",
                                                       { { "MOMENT_SAT_PASS", std::to_string(pass) },
                                                         { "MOMENT_SAT_WIDE", format.wide ? "1" : "0" } }),
        "moment summed-area table");
    }
    program->use();
    program->setInt("shadowMapLinear", frame.shadowMapLinear->GetTextureUnit());
    program->setFloat("depthNear", frame.lightView.nearDepth);
    program->setFloat("depthFar", frame.lightView.farDepth);
    program->setFloat("fixedPointScale", format.scale());
    program->setInt("mapSize", size);
    program->setInt("bandFirstRow", firstRow);
    program->setInt("bandRows", rows);
    // One invocation per row of the band (pass 0) or per column (pass 1).
    program->dispatch({ ((pass == 0 ? rows : size) + 63) / 64, 1 });
  });
  frame.shadowMapLinear->Deactivate();
  auto data = std::make_shared<sl::MomentSatData>();
  data->low = this->Low;
  data->high = format.wide ? this->High : nullptr;
  data->format = format;
  data->bandBytes = this->Bands.bytes();
  frame.lightSpaceData[sl::momentSatStructure().name] = data;
}

void vtkSLMomentSatPass::ReleaseGraphicsResources(vtkWindow*)
{
  this->Programs.clear();
  this->Low = nullptr;
  this->High = nullptr;
  this->Bands = sl::BandedPrefixSums();
}

void vtkSLMomentSatPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Stage: " << this->GetStageName() << "\n";
}
