#include "passes/FullScreenQuad.h"

#include "core/Error.h"
#include "gl/ShaderLibrary.h"

#include <vtkOpenGLQuadHelper.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkOpenGLShaderCache.h>
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
    throw GraphicsError("cannot build the shader program '" + label + "' (the GLSL compiler log is above)");
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
