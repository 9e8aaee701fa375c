// Stage 1: rasterises every scene object into the G-buffer (layout in FrameResources.h). Multisampled frames
// (FrameResources::multisample) rasterise into multisampled targets, one fragment per pixel and primitive as
// Schwarz and Stamminger 2008 §7 assume (no sample shading: attributes at the pixel centre, §7), then copy
// sample 0 into the single-sampled targets (the paper's s_z, "always the first", §7) for every later pass.
#pragma once

#include "passes/FullScreenQuad.h"
#include "passes/vtkSLStagePass.h"

#include <vtkNew.h>

class vtkOpenGLFramebufferObject;
class vtkOpenGLRenderWindow;

class vtkSLGBufferPass : public vtkSLStagePass
{
public:
  static vtkSLGBufferPass* New();
  vtkTypeMacro(vtkSLGBufferPass, vtkSLStagePass);
  void PrintSelf(ostream& os, vtkIndent indent) override;
  const char* GetStageName() const override { return "gbuffer"; }
  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkSLGBufferPass();
  ~vtkSLGBufferPass() override;
  void Execute(const vtkRenderState* state) override;

private:
  vtkSLGBufferPass(const vtkSLGBufferPass&) = delete;
  void operator=(const vtkSLGBufferPass&) = delete;

  // Multisampled frames: sample 0 of the multisampled targets into the single-sampled ones (depth included).
  void CopyFirstSample(vtkOpenGLRenderWindow* window);

  vtkNew<vtkOpenGLFramebufferObject> Framebuffer;
  vtkNew<vtkOpenGLFramebufferObject> MultisampleFramebuffer;
  sl::MeshDrawer Drawer;
  sl::FullScreenQuad FirstSampleQuad;
};
