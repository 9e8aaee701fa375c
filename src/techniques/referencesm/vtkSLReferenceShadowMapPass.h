// The `reference-sm` technique's pass: for each of K light samples, focus (GpuReceivers), render a
// shadow map (renderShadowMap) and add the weighted hard test into an accumulation target; then resolve
// visibility and its standard error with the base class's full-screen shader.
#pragma once

#include "gl/GlResources.h"
#include "passes/FullScreenQuad.h"
#include "passes/GpuReceivers.h"
#include "techniques/vtkSLTechniquePass.h"

#include <vtkNew.h>
#include <vtkSmartPointer.h>

#include <memory>

class vtkOpenGLFramebufferObject;
class vtkTextureObject;

class vtkSLReferenceShadowMapPass : public vtkSLTechniquePass
{
public:
  static vtkSLReferenceShadowMapPass* New();
  vtkTypeMacro(vtkSLReferenceShadowMapPass, vtkSLTechniquePass);
  void PrintSelf(ostream& os, vtkIndent indent) override;
  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkSLReferenceShadowMapPass();
  ~vtkSLReferenceShadowMapPass() override;
  void Execute(const vtkRenderState* state) override;
  std::string GetFragmentShaderPath() const override { return "referencesm/ReferenceSmResolve.glsl"; }
  std::vector<vtkTextureObject*> SetTechniqueUniforms(vtkShaderProgram* program) override;

private:
  vtkSLReferenceShadowMapPass(const vtkSLReferenceShadowMapPass&) = delete;
  void operator=(const vtkSLReferenceShadowMapPass&) = delete;

  std::unique_ptr<sl::GpuReceivers> Receivers;
  vtkNew<vtkOpenGLFramebufferObject> MapFramebuffer;
  vtkNew<vtkOpenGLFramebufferObject> AccumulationFramebuffer;
  sl::MeshDrawer Drawer;
  sl::FullScreenQuad AccumulateQuad;
  vtkSmartPointer<vtkTextureObject> Accumulated;
  int SampleCount = 0;
};
