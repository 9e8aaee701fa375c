#include "techniques/MomentTechniquePass.h"
#include "techniques/MomentReference.h"

#include "passes/FrameResources.h"
#include "passes/PassUtilities.h"
#include "lightspace/ShadowMapMath.h"
#include "techniques/ShadowMapParameters.h"

#include <vtkObjectFactory.h>
#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>

#include <cmath>

vtkStandardNewMacro(vtkSLMomentTechniquePass);

std::vector<vtkTextureObject*> vtkSLMomentTechniquePass::SetTechniqueUniforms(vtkShaderProgram* program)
{
  const sl::FrameResources& frame = *this->Frame;
  const int width = sl::MomentPrefilterSettings::from(frame.parameters).texels;
  program->SetUniformi("kernelWidth", width);
  sl::setFloatIfUsed(program, "momentLod", std::log2(static_cast<double>(width)));
  sl::setFloatIfUsed(program, "depthNear", frame.lightView.nearDepth);
  sl::setFloatIfUsed(program, "depthFar", frame.lightView.farDepth);
  sl::setLeakBiasUniform(program);
  return {}; // the moment map itself is bound by its structure (structures/moments)
}

void vtkSLMomentTechniquePass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FragmentShader: " << this->ShaderPath << "\n";
}

std::function<vtkSmartPointer<vtkSLTechniquePass>()> sl::momentTechniquePass(std::string fragmentShaderPath)
{
  return [fragmentShaderPath] {
    auto pass = vtkSmartPointer<vtkSLMomentTechniquePass>::New();
    pass->SetFragmentShaderPath(fragmentShaderPath);
    return vtkSmartPointer<vtkSLTechniquePass>(pass);
  };
}

void sl::setLeakBiasUniform(vtkShaderProgram* program)
{
  if (program->IsUniformUsed("leakBiasTexels"))
  {
    const BiasSettings leakBias = defaultBiasSettings();
    setVector(program, "leakBiasTexels", { leakBias.constantTexels, leakBias.slopeTexels, leakBias.maxSlope });
  }
}
