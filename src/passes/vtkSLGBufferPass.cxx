#include "passes/vtkSLGBufferPass.h"

#include "core/Error.h"
#include "gl/ShaderLibrary.h"
#include "passes/FrameResources.h"
#include "passes/PassUtilities.h"

#include <vtkObjectFactory.h>
#include <vtkOpenGLFramebufferObject.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkOpenGLState.h>
#include <vtkRenderState.h>
#include <vtkRenderer.h>
#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>
#include <vtk_glew.h>

vtkStandardNewMacro(vtkSLGBufferPass);

vtkSLGBufferPass::vtkSLGBufferPass() = default;
vtkSLGBufferPass::~vtkSLGBufferPass() = default;

void vtkSLGBufferPass::Execute(const vtkRenderState* state)
{
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(state->GetRenderer()->GetRenderWindow());
  sl::FrameResources& frame = *this->Frame;
  const int width = frame.width();
  const int height = frame.height();

  frame.gbufferPosition = sl::makeFloatTarget(window, width, height, 4);
  frame.gbufferNormal = sl::makeFloatTarget(window, width, height, 4);
  frame.gbufferAlbedoDepth = sl::makeFloatTarget(window, width, height, 4);
  frame.gbufferDepth = sl::makeDepthTarget(window, width, height);

  vtkOpenGLState* glState = window->GetState();
  vtkOpenGLState::ScopedglViewport viewportSaver(glState);
  vtkOpenGLState::ScopedglEnableDisable depthTestSaver(glState, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable cullSaver(glState, GL_CULL_FACE);
  vtkOpenGLState::ScopedglEnableDisable blendSaver(glState, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable scissorSaver(glState, GL_SCISSOR_TEST);
  vtkOpenGLState::ScopedglDepthFunc depthFuncSaver(glState);
  vtkOpenGLState::ScopedglDepthMask depthMaskSaver(glState);
  glState->PushFramebufferBindings();

  this->Framebuffer->SetContext(window);
  this->Framebuffer->Bind();
  this->Framebuffer->AddColorAttachment(0, frame.gbufferPosition);
  this->Framebuffer->AddColorAttachment(1, frame.gbufferNormal);
  this->Framebuffer->AddColorAttachment(2, frame.gbufferAlbedoDepth);
  this->Framebuffer->AddDepthAttachment(frame.gbufferDepth);
  this->Framebuffer->ActivateDrawBuffers(3);
  if (!this->Framebuffer->CheckFrameBufferStatus(GL_FRAMEBUFFER))
  {
    throw sl::GraphicsError("G-buffer framebuffer is incomplete");
  }

  glState->vtkglViewport(0, 0, width, height);
  glState->vtkglDisable(GL_SCISSOR_TEST);
  glState->vtkglDisable(GL_BLEND);
  glState->vtkglDisable(GL_CULL_FACE); // two-sided surfaces
  glState->vtkglEnable(GL_DEPTH_TEST);
  glState->vtkglDepthFunc(GL_LESS);
  glState->vtkglDepthMask(GL_TRUE);
  const float zeros[4] = { 0.0f, 0.0f, 0.0f, 0.0f };
  for (int attachment = 0; attachment < 3; ++attachment)
  {
    glClearBufferfv(GL_COLOR, attachment, zeros);
  }
  const float farthest = 1.0f;
  glClearBufferfv(GL_DEPTH, 0, &farthest);

  const std::string vertexSource = sl::assembleShader("gbuffer/GBufferVertex.glsl", sl::commonDefines());
  const std::string fragmentSource = sl::assembleShader("gbuffer/GBufferFragment.glsl", sl::commonDefines());
  vtkShaderProgram* program = sl::readyProgram(window, vertexSource, fragmentSource, "gbuffer");
  sl::setMatrix(program, "clipFromWorld", frame.camera.clipFromWorld);
  sl::setMatrix(program, "viewFromWorld", frame.camera.viewFromWorld);
  this->Drawer.draw(program, *frame.gpuScene, [](const sl::SceneObject&) { return true; });

  this->Framebuffer->RemoveColorAttachments(3);
  this->Framebuffer->RemoveDepthAttachment();
  glState->PopFramebufferBindings();
}

void vtkSLGBufferPass::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Drawer.releaseGraphicsResources(vtkOpenGLRenderWindow::SafeDownCast(window));
  this->Framebuffer->ReleaseGraphicsResources(window);
}

void vtkSLGBufferPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
