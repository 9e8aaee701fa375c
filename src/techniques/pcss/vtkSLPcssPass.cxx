#include "techniques/pcss/vtkSLPcssPass.h"

#include "passes/FrameResources.h"
#include "techniques/SoftShadowSupport.h"

#include <vtkObjectFactory.h>
#include <vtkShaderProgram.h>

vtkStandardNewMacro(vtkSLPcssPass);

sl::ShaderDefines vtkSLPcssPass::GetExtraDefines() const
{
  return sl::poissonDiskDefines();
}

std::vector<vtkTextureObject*> vtkSLPcssPass::SetTechniqueUniforms(vtkShaderProgram* program)
{
  sl::setSoftShadowUniforms(program, *this->Frame);
  return {};
}

void vtkSLPcssPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
