// The visibility pass of `lvsm`: lvsm/LvsmVisibility.glsl with the box width, and the bias the light-leak PCF
// compares with (`pcf`'s default, as vsm's). The layered moment map itself is bound by its structure
// (structures/layeredmoments); the layers' ends it used go to stats.json (layer_end_<i>), which the twin reads.
#pragma once

#include "techniques/vtkSLTechniquePass.h"

#include <vector>

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
  std::map<std::string, double> CollectStatistics() override;

private:
  vtkSLLvsmPass(const vtkSLLvsmPass&) = delete;
  void operator=(const vtkSLLvsmPass&) = delete;

  std::vector<double> LayerEnds; // of the last frame drawn (the layered moment map's)
};
