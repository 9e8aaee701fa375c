#include "passes/vtkSLShadingPass.h"

#include "core/Error.h"
#include "gl/ShaderLibrary.h"
#include "passes/FrameResources.h"
#include "passes/PassUtilities.h"

#include <vtkObjectFactory.h>
#include <vtkOpenGLFramebufferObject.h>
#include <vtkOpenGLQuadHelper.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkOpenGLShaderCache.h>
#include <vtkOpenGLState.h>
#include <vtkRenderState.h>
#include <vtkRenderer.h>
#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>
#include <vtk_glew.h>

vtkStandardNewMacro(vtkSLShadingPass);

vtkSLShadingPass::vtkSLShadingPass() = default;
vtkSLShadingPass::~vtkSLShadingPass() = default;

void vtkSLShadingPass::Execute(const vtkRenderState* state)
{
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(state->GetRenderer()->GetRenderWindow());
  sl::FrameResources& frame = *this->Frame;
  frame.shadedImage = sl::makeColorTarget(window, frame.width(), frame.height());

  vtkOpenGLState* glState = window->GetState();
  vtkOpenGLState::ScopedglViewport viewportSaver(glState);
  vtkOpenGLState::ScopedglEnableDisable depthTestSaver(glState, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable blendSaver(glState, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable scissorSaver(glState, GL_SCISSOR_TEST);
  glState->PushFramebufferBindings();
  this->Framebuffer->SetContext(window);
  this->Framebuffer->Bind();
  this->Framebuffer->AddColorAttachment(0, frame.shadedImage);
  this->Framebuffer->ActivateDrawBuffers(1);
  glState->vtkglViewport(0, 0, frame.width(), frame.height());
  glState->vtkglDisable(GL_DEPTH_TEST);
  glState->vtkglDisable(GL_BLEND);
  glState->vtkglDisable(GL_SCISSOR_TEST);

  if (!this->Quad)
  {
    const std::string vertexSource = sl::assembleShader("common/FullScreenVertex.glsl");
    const std::string fragmentSource = sl::assembleShader("shading/ShadingFragment.glsl", sl::commonDefines());
    this->Quad = std::make_unique<vtkOpenGLQuadHelper>(window, vertexSource.c_str(), fragmentSource.c_str(), "");
  }
  vtkShaderProgram* program = this->Quad->Program;
  if (!program || !program->GetCompiled())
  {
    throw sl::GraphicsError("cannot build the shading shader (GLSL log above)");
  }
  window->GetShaderCache()->ReadyShaderProgram(program);
  vtkTextureObject* bound[] = {
    sl::bindTexture(program, "gbufferPosition", frame.gbufferPosition),
    sl::bindTexture(program, "gbufferNormal", frame.gbufferNormal),
    sl::bindTexture(program, "gbufferAlbedoDepth", frame.gbufferAlbedoDepth),
    sl::bindTexture(program, "visibilityTexture", frame.techniqueTargets.at("visibility")),
  };
  sl::setLightUniforms(program, *frame.light);
  sl::setFloatIfUsed(program, "lightIntensity", frame.light->intensity);
  if (program->IsUniformUsed("backgroundColor"))
  {
    sl::setVector(program, "backgroundColor", glm::dvec3(0.32, 0.34, 0.38));
  }
  this->Quad->Render();
  for (vtkTextureObject* texture : bound)
  {
    texture->Deactivate();
  }
  this->Framebuffer->RemoveColorAttachments(1);
  glState->PopFramebufferBindings();
}

void vtkSLShadingPass::ReleaseGraphicsResources(vtkWindow* window)
{
  if (this->Quad)
  {
    this->Quad->ReleaseGraphicsResources(window);
    this->Quad.reset();
  }
  this->Framebuffer->ReleaseGraphicsResources(window);
}

void vtkSLShadingPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
