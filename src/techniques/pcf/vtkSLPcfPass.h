// The `pcf` technique's visibility pass: pcf/shaders/PcfVisibility.glsl, plus the Poisson disk and, for
// filter = hardware_bilinear, a comparison sampler (GL_LINEAR, GL_COMPARE_REF_TO_TEXTURE, LEQUAL) bound
// over the shadow map's hardware depth.
#pragma once

#include "techniques/vtkSLTechniquePass.h"

class vtkSLPcfPass : public vtkSLTechniquePass
{
public:
  static vtkSLPcfPass* New();
  vtkTypeMacro(vtkSLPcfPass, vtkSLTechniquePass);
  void PrintSelf(ostream& os, vtkIndent indent) override;
  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkSLPcfPass() = default;
  ~vtkSLPcfPass() override;
  std::string GetFragmentShaderPath() const override { return "pcf/PcfVisibility.glsl"; }
  sl::ShaderDefines GetExtraDefines() const override;
  std::vector<vtkTextureObject*> SetTechniqueUniforms(vtkShaderProgram* program) override;
  void AfterDraw() override;

private:
  vtkSLPcfPass(const vtkSLPcfPass&) = delete;
  void operator=(const vtkSLPcfPass&) = delete;

  unsigned int CompareSampler = 0;
  int CompareUnit = -1;
};
