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
  // Views that partition the pixels (PartitionViews.h) keep one pair each, for the export.
  const unsigned size = static_cast<unsigned>(view.resolution);
  const std::size_t index = frame.partitions ? static_cast<std::size_t>(frame.viewIndex) : 0;
  if (this->LinearTargets.size() <= index)
  {
    this->LinearTargets.resize(index + 1);
    this->DepthTargets.resize(index + 1);
  }
  vtkSmartPointer<vtkTextureObject>& linear = this->LinearTargets[index];
  if (!linear || linear->GetContext() != window || linear->GetWidth() != size)
  {
    linear = sl::makeFloatTarget(window, view.resolution, view.resolution, 1);
    this->DepthTargets[index] = sl::makeDepthTarget(window, view.resolution, view.resolution);
  }
  frame.shadowMapLinear = linear;
  frame.shadowMapDepth = this->DepthTargets[index];
  if (frame.partitions)
  {
    frame.viewShadowMapLinear.resize(static_cast<std::size_t>(frame.partitions->viewCount()));
    frame.viewShadowMapDepth.resize(static_cast<std::size_t>(frame.partitions->viewCount()));
    frame.viewShadowMapLinear[index] = frame.shadowMapLinear;
    frame.viewShadowMapDepth[index] = frame.shadowMapDepth;
  }
  const bool secondDepth = sl::shadowMapSettings(frame).secondDepth;
  sl::renderShadowMap(window, this->Framebuffer, this->Drawer, *frame.gpuScene, view, secondDepth,
    frame.shadowMapLinear, frame.shadowMapDepth);
}

void vtkSLLightDepthPass::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Drawer.releaseGraphicsResources(vtkOpenGLRenderWindow::SafeDownCast(window));
  this->Framebuffer->ReleaseGraphicsResources(window);
  this->LinearTargets.clear();
  this->DepthTargets.clear();
}

void vtkSLLightDepthPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
