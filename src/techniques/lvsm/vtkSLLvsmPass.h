// The visibility pass of `lvsm`: lvsm/LvsmVisibility.glsl with the box width, and the bias the light-leak PCF
// compares with (`pcf`'s default, as vsm's). The layered moment map itself is bound by its structure
// (structures/layeredmoments).
#pragma once

#include "techniques/vtkSLTechniquePass.h"

class vtkSLLvsmPass : public vtkSLTechniquePass
{
public:
  static vtkSLLvsmPass* New();
  vtkTypeMacro(vtkSLLvsmPass, vtkSLTechniquePass);
  void PrintSelf(ostream& os, vtkIndent indent) override;

protected:
  vtkSLLvsmPass() = default;
  ~vtkSLLvsmPass() override = default;
  std::string GetFragmentShaderPath() const override { return "lvsm/LvsmVisibility.glsl"; }
  sl::ShaderDefines GetExtraDefines() const override;
  std::vector<vtkTextureObject*> SetTechniqueUniforms(vtkShaderProgram* program) override;

private:
  vtkSLLvsmPass(const vtkSLLvsmPass&) = delete;
  void operator=(const vtkSLLvsmPass&) = delete;
};
