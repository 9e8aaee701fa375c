// The `gbp06` technique's pass: gbp06/shaders/Gbp06Visibility.glsl with the PCSS-family kernel uniforms and
// the min-max structure (passes/vtkSLHsmPass, N-buffers by default), which the hsm traversal walks as a quadtree.
#pragma once

#include "techniques/vtkSLTechniquePass.h"

class vtkSLGbp06Pass : public vtkSLTechniquePass
{
public:
  static vtkSLGbp06Pass* New();
  vtkTypeMacro(vtkSLGbp06Pass, vtkSLTechniquePass);
  void PrintSelf(ostream& os, vtkIndent indent) override;

protected:
  vtkSLGbp06Pass() = default;
  ~vtkSLGbp06Pass() override = default;
  std::string GetFragmentShaderPath() const override { return "gbp06/Gbp06Visibility.glsl"; }
  std::vector<vtkTextureObject*> SetTechniqueUniforms(vtkShaderProgram* program) override;

private:
  vtkSLGbp06Pass(const vtkSLGbp06Pass&) = delete;
  void operator=(const vtkSLGbp06Pass&) = delete;
};
