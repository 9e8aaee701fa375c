#include "techniques/hard/vtkSLHardShadowPass.h"

#include <vtkObjectFactory.h>

vtkStandardNewMacro(vtkSLHardShadowPass);

void vtkSLHardShadowPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
