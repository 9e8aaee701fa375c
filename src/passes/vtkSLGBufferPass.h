// Stage 1: rasterises every scene object into the G-buffer (layout in FrameResources.h).
#pragma once

#include "passes/vtkSLStagePass.h"

#include <vtkNew.h>

class vtkOpenGLFramebufferObject;

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

  vtkNew<vtkOpenGLFramebufferObject> Framebuffer;
  sl::MeshDrawer Drawer;
};
