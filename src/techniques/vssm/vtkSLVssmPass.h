// The `vssm` technique's pass: vssm/shaders/VssmVisibility.glsl with the PCSS-family kernel uniforms, the
// summed-area table (passes/vtkSLSatPass) and the min-max HSM (passes/vtkSLHsmPass).
#pragma once

#include "techniques/vtkSLTechniquePass.h"

class vtkSLVssmPass : public vtkSLTechniquePass
{
public:
  static vtkSLVssmPass* New();
  vtkTypeMacro(vtkSLVssmPass, vtkSLTechniquePass);
  void PrintSelf(ostream& os, vtkIndent indent) override;

protected:
  vtkSLVssmPass() = default;
  ~vtkSLVssmPass() override = default;
  std::string GetFragmentShaderPath() const override { return "vssm/VssmVisibility.glsl"; }
  sl::ShaderDefines GetExtraDefines() const override;
  std::vector<vtkTextureObject*> SetTechniqueUniforms(vtkShaderProgram* program) override;

private:
  vtkSLVssmPass(const vtkSLVssmPass&) = delete;
  void operator=(const vtkSLVssmPass&) = delete;
};
