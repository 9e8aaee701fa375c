#include "structures/shadowmap/vtkSLLightDepthPass.h"

#include "core/Error.h"
#include "structures/shadowmap/ShadowMapStructure.h"
#include "passes/FrameResources.h"
#include "passes/ShadowMapRendering.h"

#include <vtkObjectFactory.h>
#include <vtkOpenGLFramebufferObject.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkOpenGLState.h>
#include <vtkRenderState.h>
#include <vtkRenderer.h>
#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>
#include <vtk_glew.h>


vtkStandardNewMacro(vtkSLLightDepthPass);

vtkSLLightDepthPass::vtkSLLightDepthPass() = default;
vtkSLLightDepthPass::~vtkSLLightDepthPass() = default;

void vtkSLLightDepthPass::Execute(const vtkRenderState* state)
{
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(state->GetRenderer()->GetRenderWindow());
  sl::FrameResources& frame = *this->Frame;

  SL_CHECK_MSG(frame.hasLightView, "the focus stage must run before the shadow map");
  const sl::LightView& view = frame.lightView;

  // The previous frame's (or sub-light's) targets are reused when they have the map's size: the render
  // clears both, and fresh 2048^2 targets (2 x 16 MB) cost llvmpipe more wall time than drawing the casters.
  const unsigned size = static_cast<unsigned>(view.resolution);
  if (!this->LinearTarget || this->LinearTarget->GetContext() != window || this->LinearTarget->GetWidth() != size)
  {
    this->LinearTarget = sl::makeFloatTarget(window, view.resolution, view.resolution, 1);
    this->DepthTarget = sl::makeDepthTarget(window, view.resolution, view.resolution);
  }
  frame.shadowMapLinear = this->LinearTarget;
  frame.shadowMapDepth = this->DepthTarget;
  const bool secondDepth = sl::shadowMapSettings(frame).secondDepth;
  sl::renderShadowMap(window, this->Framebuffer, this->Drawer, *frame.gpuScene, view, secondDepth,
    frame.shadowMapLinear, frame.shadowMapDepth);
}

void vtkSLLightDepthPass::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Drawer.releaseGraphicsResources(vtkOpenGLRenderWindow::SafeDownCast(window));
  this->Framebuffer->ReleaseGraphicsResources(window);
  this->LinearTarget = nullptr;
  this->DepthTarget = nullptr;
}

void vtkSLLightDepthPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
