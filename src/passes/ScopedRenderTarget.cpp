#include "passes/ScopedRenderTarget.h"

#include "core/Error.h"

#include <vtkOpenGLFramebufferObject.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkTextureObject.h>
#include <vtk_glew.h>

namespace sl
{

namespace
{

bool hasStencilBits(vtkTextureObject* texture)
{
  GLint stencilBits = 0;
  glGetTextureLevelParameteriv(texture->GetHandle(), 0, GL_TEXTURE_STENCIL_SIZE, &stencilBits);
  return stencilBits > 0;
}

} // namespace

ScopedRenderTarget::ScopedRenderTarget(vtkOpenGLRenderWindow* window, vtkOpenGLFramebufferObject* framebuffer,
  const std::vector<vtkTextureObject*>& colorTargets, vtkTextureObject* depthTarget)
  : state_(window->GetState())
  , framebuffer_(framebuffer)
  , colorCount_(static_cast<unsigned>(colorTargets.size()))
  , hasDepth_(depthTarget != nullptr)
  , hasStencil_(depthTarget && hasStencilBits(depthTarget))
  , viewport_(state_)
  , depthTest_(state_, GL_DEPTH_TEST)
  , cullFace_(state_, GL_CULL_FACE)
  , blend_(state_, GL_BLEND)
  , scissor_(state_, GL_SCISSOR_TEST)
  , depthFunc_(state_)
  , depthMask_(state_)
{
  SL_CHECK(!colorTargets.empty());
  state_->PushFramebufferBindings();
  framebuffer_->SetContext(window);
  framebuffer_->Bind();
  for (unsigned index = 0; index < colorCount_; ++index)
  {
    framebuffer_->AddColorAttachment(index, colorTargets[index]);
  }
  if (depthTarget)
  {
    framebuffer_->AddDepthAttachment(depthTarget);
    if (hasStencil_)
    {
      // VTK 9.1 attaches a depth texture to GL_DEPTH_ATTACHMENT only; a depth-stencil texture's stencil must be
      // attached too, or stencil tests see no stencil buffer (its target: multisampled G-buffers have one too).
      glFramebufferTexture2D(
        GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, depthTarget->GetTarget(), depthTarget->GetHandle(), 0);
    }
  }
  framebuffer_->ActivateDrawBuffers(colorCount_);
  if (!framebuffer_->CheckFrameBufferStatus(GL_FRAMEBUFFER))
  {
    framebuffer_->RemoveColorAttachments(colorCount_);
    state_->PopFramebufferBindings();
    throw GraphicsError("framebuffer is incomplete");
  }
  state_->vtkglViewport(0, 0, static_cast<int>(colorTargets[0]->GetWidth()), static_cast<int>(colorTargets[0]->GetHeight()));
  state_->vtkglDisable(GL_SCISSOR_TEST);
  state_->vtkglDisable(GL_BLEND);
  state_->vtkglDisable(GL_CULL_FACE); // surfaces are two-sided; facing is decided in shaders
  if (hasDepth_)
  {
    state_->vtkglEnable(GL_DEPTH_TEST);
    state_->vtkglDepthFunc(GL_LESS);
    state_->vtkglDepthMask(GL_TRUE);
  }
  else
  {
    state_->vtkglDisable(GL_DEPTH_TEST);
  }
}

ScopedRenderTarget::~ScopedRenderTarget()
{
  framebuffer_->RemoveColorAttachments(colorCount_);
  if (hasStencil_)
  {
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_TEXTURE_2D, 0, 0);
  }
  if (hasDepth_)
  {
    framebuffer_->RemoveDepthAttachment();
  }
  state_->PopFramebufferBindings();
}

void ScopedRenderTarget::clearColor(int index, float value) const
{
  const float values[4] = { value, value, value, value };
  glClearBufferfv(GL_COLOR, index, values);
}

void ScopedRenderTarget::clearDepth() const
{
  const float farthest = 1.0f;
  glClearBufferfv(GL_DEPTH, 0, &farthest);
}

void ScopedRenderTarget::clearStencil() const
{
  SL_CHECK_MSG(hasStencil_, "clearStencil on a target without stencil");
  const GLint zero = 0;
  glClearBufferiv(GL_STENCIL, 0, &zero);
}

} // namespace sl
