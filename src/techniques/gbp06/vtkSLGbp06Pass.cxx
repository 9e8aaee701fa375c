#include "techniques/gbp06/vtkSLGbp06Pass.h"

#include "passes/FrameResources.h"
#include "techniques/SoftShadowSupport.h"

#include <vtkObjectFactory.h>
#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>

vtkStandardNewMacro(vtkSLGbp06Pass);

std::vector<vtkTextureObject*> vtkSLGbp06Pass::SetTechniqueUniforms(vtkShaderProgram* program)
{
  const sl::FrameResources& frame = *this->Frame;
  sl::setSoftShadowUniforms(program, frame);
  return {}; // the min-max structure is bound by its structure (structures/hsm)
}

void vtkSLGbp06Pass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
