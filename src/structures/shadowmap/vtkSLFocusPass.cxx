#include "structures/shadowmap/vtkSLFocusPass.h"

#include "structures/shadowmap/ShadowMapStructure.h"
#include "passes/FrameResources.h"

#include <vtkObjectFactory.h>
#include <vtkTextureObject.h>

#include <cmath>

vtkStandardNewMacro(vtkSLFocusPass);

void vtkSLFocusPass::Execute(const vtkRenderState*)
{
  sl::FrameResources& frame = *this->Frame;
  if (!this->Receivers)
  {
    this->Receivers = std::make_unique<sl::GpuReceivers>();
  }
  this->Receivers->setGBuffer(frame.gbufferPosition, frame.gbufferNormal);
  const sl::ShadowMapSettings settings = sl::shadowMapSettings(frame);
  sl::FocusSettings focus;
  focus.resolution = settings.resolution;
  focus.marginTexels = settings.marginTexels;
  focus.warp = settings.warp;
  focus.camera = &frame.camera;
  if (frame.technique->coversLightArea && frame.light->type == sl::LightType::Area)
  {
    focus.lightFootprintWidth = frame.light->size;
  }
  frame.lightView = sl::fitLightView(*frame.light, *frame.scene, *this->Receivers, focus);
  frame.hasLightView = true;
}

vtkSLFocusPass::vtkSLFocusPass() = default;
vtkSLFocusPass::~vtkSLFocusPass() = default;

void vtkSLFocusPass::ReleaseGraphicsResources(vtkWindow*)
{
  this->Receivers.reset();
}

void vtkSLFocusPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  if (this->Frame && this->Frame->hasLightView)
  {
    os << indent << "ShadowMapSize: " << this->Frame->lightView.resolution << "\n";
    os << indent << "DepthRange: " << this->Frame->lightView.nearDepth << " .. " << this->Frame->lightView.farDepth << "\n";
  }
}
