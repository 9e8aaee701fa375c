// Binds a framebuffer with the given colour (and optional depth or depth-stencil) targets for one pass, sets the viewport
// to their size and the raster state every ShadowLab pass starts from (no blending, no scissor, no face
// culling; depth test only when a depth target is given), and restores all of it on destruction, so a
// pass never leaves VTK's OpenGL state half-configured.
#pragma once

#include <vtkOpenGLState.h>

#include <vector>

class vtkOpenGLFramebufferObject;
class vtkOpenGLRenderWindow;
class vtkTextureObject;

namespace sl
{

class ScopedRenderTarget
{
public:
  ScopedRenderTarget(vtkOpenGLRenderWindow* window, vtkOpenGLFramebufferObject* framebuffer,
    const std::vector<vtkTextureObject*>& colorTargets, vtkTextureObject* depthTarget = nullptr);
  ~ScopedRenderTarget();
  ScopedRenderTarget(const ScopedRenderTarget&) = delete;
  ScopedRenderTarget& operator=(const ScopedRenderTarget&) = delete;

  // Clears colour attachment `index` to `value` (all components), the depth attachment to 1, or the stencil to 0.
  void clearColor(int index, float value) const;
  void clearDepth() const;
  void clearStencil() const;

private:
  vtkOpenGLState* state_;
  vtkOpenGLFramebufferObject* framebuffer_;
  unsigned colorCount_;
  bool hasDepth_;
  bool hasStencil_;
  vtkOpenGLState::ScopedglViewport viewport_;
  vtkOpenGLState::ScopedglEnableDisable depthTest_;
  vtkOpenGLState::ScopedglEnableDisable cullFace_;
  vtkOpenGLState::ScopedglEnableDisable blend_;
  vtkOpenGLState::ScopedglEnableDisable scissor_;
  vtkOpenGLState::ScopedglDepthFunc depthFunc_;
  vtkOpenGLState::ScopedglDepthMask depthMask_;
};

} // namespace sl
