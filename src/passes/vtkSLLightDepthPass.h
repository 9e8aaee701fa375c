// Stage 2 (when the technique needs a shadow map): focuses the light frustum on the visible receivers
// (survey §4.1, see lightspace/LightView.h) and renders the casters' linear and hardware depth from the
// light. Parameters it reads from the technique: shadow_map_size, caster_faces, and the kernel margin
// the technique declares (kernel_texels / 2 + 1 when present).
#pragma once

#include "passes/vtkSLStagePass.h"

#include <vtkNew.h>

class vtkOpenGLFramebufferObject;

class vtkSLLightDepthPass : public vtkSLStagePass
{
public:
  static vtkSLLightDepthPass* New();
  vtkTypeMacro(vtkSLLightDepthPass, vtkSLStagePass);
  void PrintSelf(ostream& os, vtkIndent indent) override;
  const char* GetStageName() const override { return "shadow_map"; }
  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkSLLightDepthPass();
  ~vtkSLLightDepthPass() override;
  void Execute(const vtkRenderState* state) override;

private:
  vtkSLLightDepthPass(const vtkSLLightDepthPass&) = delete;
  void operator=(const vtkSLLightDepthPass&) = delete;

  vtkNew<vtkOpenGLFramebufferObject> Framebuffer;
  sl::MeshDrawer Drawer;
};
