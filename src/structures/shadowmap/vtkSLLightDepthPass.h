// Stage 2b (when the technique needs a shadow map): renders the casters' linear and hardware depth from
// the light view the focus stage fitted. Parameter it reads: caster_faces (first- or second-depth).
#pragma once

#include "passes/vtkSLStagePass.h"

#include <vtkNew.h>
#include <vtkSmartPointer.h>
#include <vtkTextureObject.h>

#include <vector>

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
  // The last targets rendered, reused by the next frame (or sub-light) when the map size fits; one pair per view for
  // views that partition the pixels (cascades).
  std::vector<vtkSmartPointer<vtkTextureObject>> LinearTargets;
  std::vector<vtkSmartPointer<vtkTextureObject>> DepthTargets;
};
