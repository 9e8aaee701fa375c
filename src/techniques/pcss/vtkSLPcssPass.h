// The `pcss` technique's pass: pcss/shaders/PcssVisibility.glsl with the light size, the blocker-search
// plane (the fitted near depth), the texel size in tangent units and the Poisson disk.
#pragma once

#include "techniques/vtkSLTechniquePass.h"

class vtkSLPcssPass : public vtkSLTechniquePass
{
public:
  static vtkSLPcssPass* New();
  vtkTypeMacro(vtkSLPcssPass, vtkSLTechniquePass);
  void PrintSelf(ostream& os, vtkIndent indent) override;

protected:
  vtkSLPcssPass() = default;
  ~vtkSLPcssPass() override = default;
  std::string GetFragmentShaderPath() const override { return "pcss/PcssVisibility.glsl"; }
  sl::ShaderDefines GetExtraDefines() const override;
  std::vector<vtkTextureObject*> SetTechniqueUniforms(vtkShaderProgram* program) override;

private:
  vtkSLPcssPass(const vtkSLPcssPass&) = delete;
  void operator=(const vtkSLPcssPass&) = delete;
};
