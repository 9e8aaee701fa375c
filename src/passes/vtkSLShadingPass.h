// Stage 4: the shaded image from the G-buffer and the technique's visibility (Lambert + ambient, sRGB).
#pragma once

#include "passes/FullScreenQuad.h"
#include "passes/vtkSLStagePass.h"

#include <vtkNew.h>

#include <memory>

class vtkOpenGLFramebufferObject;

class vtkSLShadingPass : public vtkSLStagePass
{
public:
  static vtkSLShadingPass* New();
  vtkTypeMacro(vtkSLShadingPass, vtkSLStagePass);
  void PrintSelf(ostream& os, vtkIndent indent) override;
  const char* GetStageName() const override { return "shading"; }
  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkSLShadingPass();
  ~vtkSLShadingPass() override;
  void Execute(const vtkRenderState* state) override;

private:
  vtkSLShadingPass(const vtkSLShadingPass&) = delete;
  void operator=(const vtkSLShadingPass&) = delete;

  vtkNew<vtkOpenGLFramebufferObject> Framebuffer;
  sl::FullScreenQuad Quad;
};
