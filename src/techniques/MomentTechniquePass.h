// The visibility pass of the prefiltered-map techniques (vsm, esm, msm, convsm): their full-screen shader with the
// prefiltered map (structures/moments/MomentPrefilter), its mip level, the box width, the depth range and the bias
// the light-leak PCF compares with (`pcf`'s default).
#pragma once

#include "techniques/vtkSLTechniquePass.h"

#include <functional>
#include <string>

class vtkSLMomentTechniquePass : public vtkSLTechniquePass
{
public:
  static vtkSLMomentTechniquePass* New();
  vtkTypeMacro(vtkSLMomentTechniquePass, vtkSLTechniquePass);
  void PrintSelf(ostream& os, vtkIndent indent) override;
  void SetFragmentShaderPath(const std::string& path) { this->ShaderPath = path; }

protected:
  vtkSLMomentTechniquePass() = default;
  ~vtkSLMomentTechniquePass() override = default;
  std::string GetFragmentShaderPath() const override { return this->ShaderPath; }
  std::vector<vtkTextureObject*> SetTechniqueUniforms(vtkShaderProgram* program) override;

private:
  vtkSLMomentTechniquePass(const vtkSLMomentTechniquePass&) = delete;
  void operator=(const vtkSLMomentTechniquePass&) = delete;

  std::string ShaderPath;
};

namespace sl
{

// Sets common/LeakPcf.glsl's leakBiasTexels (pcf's default bias) when the program uses it.
void setLeakBiasUniform(vtkShaderProgram* program);

// A descriptor's createPass for a technique this pass draws with its full-screen shader `fragmentShaderPath`.
std::function<vtkSmartPointer<vtkSLTechniquePass>()> momentTechniquePass(std::string fragmentShaderPath);

} // namespace sl
