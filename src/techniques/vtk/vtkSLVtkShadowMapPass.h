// The `vtk` technique's pass: renders the scene through VTK's vtkCameraPass + vtkShadowMapPass (and a
// plain vtkLightsPass + vtkOpaquePass for the unshadowed reference) into two float targets, then runs the
// full-screen ratio shader of the base class. See VtkTechnique.h.
#pragma once

#include "techniques/vtkSLTechniquePass.h"

#include <vtkSmartPointer.h>

#include <vector>

class vtkActor;
class vtkRenderer;
class vtkRenderWindow;
class vtkTextureObject;

class vtkSLVtkShadowMapPass : public vtkSLTechniquePass
{
public:
  static vtkSLVtkShadowMapPass* New();
  vtkTypeMacro(vtkSLVtkShadowMapPass, vtkSLTechniquePass);
  void PrintSelf(ostream& os, vtkIndent indent) override;
  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkSLVtkShadowMapPass();
  ~vtkSLVtkShadowMapPass() override;
  void Execute(const vtkRenderState* state) override;
  std::string GetFragmentShaderPath() const override { return "vtk/VtkVisibilityRatio.glsl"; }
  std::vector<vtkTextureObject*> SetTechniqueUniforms(vtkShaderProgram* program) override;

private:
  vtkSLVtkShadowMapPass(const vtkSLVtkShadowMapPass&) = delete;
  void operator=(const vtkSLVtkShadowMapPass&) = delete;

  void BuildVtkScene(vtkRenderWindow* window);
  void RenderVtk(vtkRenderPass* pass, vtkTextureObject* target, vtkRenderWindow* window);

  vtkSmartPointer<vtkRenderer> VtkRenderer;
  std::vector<vtkSmartPointer<vtkActor>> Actors;
  vtkSmartPointer<vtkTextureObject> Shadowed;
  vtkSmartPointer<vtkTextureObject> Unshadowed;
};
