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
  program->SetUniformf("satDepthNear", static_cast<float>(frame.lightView.nearDepth));
  program->SetUniformf("satDepthFar", static_cast<float>(frame.lightView.farDepth));
  sl::setFloatIfUsed(program, "satFixedPointScale", frame.summedAreaTableFixedPointScale);
  return { sl::bindTexture(program, "satTable", frame.summedAreaTable) };
}

void vtkSLSavsmPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
