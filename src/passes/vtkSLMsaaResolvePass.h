// The custom multisample resolve of Schwarz and Stamminger 2008 §7 (shaders/msaa/MsaaResolve.glsl, CPU twin
// techniques/MsaaResolve.h), for frames whose technique asks for multisampling (TechniqueDescriptor::multisampleFor):
// runs after the technique (which evaluated visibility once per pixel, from the G-buffer's first sample) and before
// the shading. It gives every covered sample a visibility (the pixel's, or a 4-neighbour's where the sample's depth
// deviates from the first sample's by more than tau), replaces the frame's `visibility` by their mean and fills the
// multisample buffers (FrameResult.h, multisampleBufferSpecs).
#pragma once

#include "passes/FullScreenQuad.h"
#include "passes/vtkSLStagePass.h"

#include <vtkNew.h>

class vtkOpenGLFramebufferObject;

class vtkSLMsaaResolvePass : public vtkSLStagePass
{
public:
  static vtkSLMsaaResolvePass* New();
  vtkTypeMacro(vtkSLMsaaResolvePass, vtkSLStagePass);
  void PrintSelf(ostream& os, vtkIndent indent) override;
  const char* GetStageName() const override { return "msaa_resolve"; }
  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkSLMsaaResolvePass();
  ~vtkSLMsaaResolvePass() override;
  void Execute(const vtkRenderState* state) override;

private:
  vtkSLMsaaResolvePass(const vtkSLMsaaResolvePass&) = delete;
  void operator=(const vtkSLMsaaResolvePass&) = delete;

  vtkNew<vtkOpenGLFramebufferObject> Framebuffer;
  sl::FullScreenQuad Quad;
};
