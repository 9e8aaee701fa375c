#include "techniques/gbp07/vtkSLGbp07Pass.h"

#include "passes/FrameResources.h"
#include "techniques/SoftShadowSupport.h"

#include <vtkObjectFactory.h>
#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>

vtkStandardNewMacro(vtkSLGbp07Pass);

sl::ShaderDefines vtkSLGbp07Pass::GetExtraDefines() const
{
  return sl::hsmLayoutDefines(*this->Frame);
}

std::vector<vtkTextureObject*> vtkSLGbp07Pass::SetTechniqueUniforms(vtkShaderProgram* program)
{
  const sl::FrameResources& frame = *this->Frame;
  sl::setSoftShadowUniforms(program, frame);
  return { sl::bindHierarchicalShadowMap(program, frame) };
}

void vtkSLGbp07Pass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
