// The `gbp07` technique's pass: gbp07/shaders/Gbp07Visibility.glsl with the PCSS-family kernel uniforms and
// the min-max structure (passes/vtkSLHsmPass, N-buffers = the MSSM by default).
#pragma once

#include "techniques/vtkSLTechniquePass.h"

class vtkSLGbp07Pass : public vtkSLTechniquePass
{
public:
  static vtkSLGbp07Pass* New();
  vtkTypeMacro(vtkSLGbp07Pass, vtkSLTechniquePass);
  void PrintSelf(ostream& os, vtkIndent indent) override;

protected:
  vtkSLGbp07Pass() = default;
  ~vtkSLGbp07Pass() override = default;
  std::string GetFragmentShaderPath() const override { return "gbp07/Gbp07Visibility.glsl"; }
  std::vector<vtkTextureObject*> SetTechniqueUniforms(vtkShaderProgram* program) override;

private:
  vtkSLGbp07Pass(const vtkSLGbp07Pass&) = delete;
  void operator=(const vtkSLGbp07Pass&) = delete;
};
