// The `savsm` technique's pass: savsm/shaders/SavsmVisibility.glsl with the PCSS-family uniforms and the
// summed-area table (passes/vtkSLSatPass).
#pragma once

#include "techniques/vtkSLTechniquePass.h"

class vtkSLSavsmPass : public vtkSLTechniquePass
{
public:
  static vtkSLSavsmPass* New();
  vtkTypeMacro(vtkSLSavsmPass, vtkSLTechniquePass);
  void PrintSelf(ostream& os, vtkIndent indent) override;

protected:
  vtkSLSavsmPass() = default;
  ~vtkSLSavsmPass() override = default;
  std::string GetFragmentShaderPath() const override { return "savsm/SavsmVisibility.glsl"; }
  sl::ShaderDefines GetExtraDefines() const override;
  std::vector<vtkTextureObject*> SetTechniqueUniforms(vtkShaderProgram* program) override;

private:
  vtkSLSavsmPass(const vtkSLSavsmPass&) = delete;
  void operator=(const vtkSLSavsmPass&) = delete;
};
