#include "passes/vtkSLGBufferPass.h"

#include "core/Error.h"
#include "gl/ShaderLibrary.h"
#include "passes/FrameResources.h"
#include "passes/PassUtilities.h"
#include "passes/ScopedRenderTarget.h"

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
  // Depth-stencil: object-space techniques (TechniqueDescriptor::drawsSceneGeometry) test against this depth and
  // write stencil into it.
  frame.gbufferDepth = sl::makeDepthStencilTarget(window, width, height);

  const sl::ScopedRenderTarget target(window, this->Framebuffer,
    { frame.gbufferPosition, frame.gbufferNormal, frame.gbufferAlbedoDepth }, frame.gbufferDepth);
  for (int attachment = 0; attachment < 3; ++attachment)
  {
    target.clearColor(attachment, 0.0f); // w = 0 marks uncovered pixels
  }
  target.clearDepth();
  target.clearStencil();

  const std::string vertexSource = sl::assembleShader("gbuffer/GBufferVertex.glsl", sl::commonDefines());
  const std::string fragmentSource = sl::assembleShader("gbuffer/GBufferFragment.glsl", sl::commonDefines());
  vtkShaderProgram* program = sl::readyProgram(window, vertexSource, fragmentSource, "gbuffer");
  sl::setMatrix(program, "clipFromWorld", frame.camera.clipFromWorld);
  sl::setMatrix(program, "viewFromWorld", frame.camera.viewFromWorld);
  this->Drawer.draw(program, *frame.gpuScene, [](const sl::SceneObject&) { return true; });

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
