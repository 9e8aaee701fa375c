#include "passes/FullScreenQuad.h"

#include "core/Error.h"
#include "gl/ShaderLibrary.h"

#include <vtkOpenGLQuadHelper.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkOpenGLShaderCache.h>
#include <vtkShader.h>
#include <vtkShaderProgram.h>

namespace sl
{

FullScreenQuad::FullScreenQuad() = default;
FullScreenQuad::~FullScreenQuad() = default;

vtkShaderProgram* FullScreenQuad::ready(
  vtkOpenGLRenderWindow* window, const std::string& fragmentSource, const std::string& label)
{
  if (!quad_ || fragmentSource != fragmentSource_)
  {
    const std::string vertexSource = assembleShader("common/FullScreenVertex.glsl");
    quad_ = std::make_unique<vtkOpenGLQuadHelper>(window, vertexSource.c_str(), fragmentSource.c_str(), "");
    fragmentSource_ = fragmentSource;
  }
  vtkShaderProgram* program = quad_->Program;
  if (!program || !program->GetCompiled())
  {
    // The compiler's or linker's own words, when VTK kept them (its log goes to the captured output window).
    std::string log = program ? program->GetError() : std::string();
    if (log.empty() && program && program->GetFragmentShader())
    {
      log = program->GetFragmentShader()->GetError();
    }
    throw GraphicsError("cannot build the shader program '" + label + "'" + (log.empty() ? std::string(" (run with SHADOWLAB_VTK_LOG=full to see the GLSL compiler log)") : ": " + log));
  }
  window->GetShaderCache()->ReadyShaderProgram(program);
  return program;
}

void FullScreenQuad::render()
{
  SL_CHECK(quad_);
  quad_->Render();
}

void FullScreenQuad::releaseGraphicsResources(vtkWindow* window)
{
  if (quad_)
  {
    quad_->ReleaseGraphicsResources(window);
    quad_.reset();
  }
  fragmentSource_.clear();
}

} // namespace sl
