#include "techniques/gbp07/vtkSLGbp07Pass.h"

#include "passes/FrameResources.h"
#include "techniques/SoftShadowSupport.h"

#include <vtkObjectFactory.h>
#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>

vtkStandardNewMacro(vtkSLGbp07Pass);

std::vector<vtkTextureObject*> vtkSLGbp07Pass::SetTechniqueUniforms(vtkShaderProgram* program)
{
  const sl::FrameResources& frame = *this->Frame;
  sl::setSoftShadowUniforms(program, frame);
  return {}; // the min-max structure is bound by its structure (structures/hsm)
}

void vtkSLGbp07Pass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
