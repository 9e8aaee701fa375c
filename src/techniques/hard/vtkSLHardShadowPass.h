// The `hard` technique's visibility pass: the full-screen shader hard/shaders/HardVisibility.glsl.
#pragma once

#include "techniques/vtkSLTechniquePass.h"

class vtkSLHardShadowPass : public vtkSLTechniquePass
{
public:
  static vtkSLHardShadowPass* New();
  vtkTypeMacro(vtkSLHardShadowPass, vtkSLTechniquePass);
  void PrintSelf(ostream& os, vtkIndent indent) override;

protected:
  vtkSLHardShadowPass() = default;
  ~vtkSLHardShadowPass() override = default;
  std::string GetFragmentShaderPath() const override { return "hard/HardVisibility.glsl"; }

private:
  vtkSLHardShadowPass(const vtkSLHardShadowPass&) = delete;
  void operator=(const vtkSLHardShadowPass&) = delete;
};
