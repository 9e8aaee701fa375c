#include "structures/momentsat/vtkSLMomentSatPass.h"

#include "core/Error.h"
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
  glBindImageTexture(0, this->Low->GetHandle(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32UI);
  if (format.wide)
  {
    glBindImageTexture(1, this->High->GetHandle(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32UI);
  }
  frame.shadowMapLinear->Activate();
  for (int pass = 0; pass < 2; ++pass)
  {
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
    // One invocation per row (pass 0) or column (pass 1); the image writes of pass 0 must be visible to pass 1.
    program->dispatch({ (size + 63) / 64, 1 });
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  }
  frame.shadowMapLinear->Deactivate();
  glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32UI);
  glBindImageTexture(1, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32UI);
  auto data = std::make_shared<sl::MomentSatData>();
  data->low = this->Low;
  data->high = format.wide ? this->High : nullptr;
  data->format = format;
  frame.lightSpaceData[sl::momentSatStructure().name] = data;
}

void vtkSLMomentSatPass::ReleaseGraphicsResources(vtkWindow*)
{
  this->Programs.clear();
  this->Low = nullptr;
  this->High = nullptr;
}

void vtkSLMomentSatPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Stage: " << this->GetStageName() << "\n";
}
