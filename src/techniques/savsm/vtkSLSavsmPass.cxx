#include "techniques/savsm/vtkSLSavsmPass.h"

#include "passes/FrameResources.h"
#include "passes/PassUtilities.h"
#include "techniques/SoftShadowSupport.h"

#include <vtkObjectFactory.h>
#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>

vtkStandardNewMacro(vtkSLSavsmPass);

sl::ShaderDefines vtkSLSavsmPass::GetExtraDefines() const
{
  return sl::poissonDiskDefines();
}

std::vector<vtkTextureObject*> vtkSLSavsmPass::SetTechniqueUniforms(vtkShaderProgram* program)
{
  const sl::FrameResources& frame = *this->Frame;
  sl::setSoftShadowUniforms(program, frame);
  return {}; // the summed-area table is bound by its structure (structures/sat)
}

void vtkSLSavsmPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
