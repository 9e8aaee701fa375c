#include "techniques/vssm/vtkSLVssmPass.h"

#include "passes/FrameResources.h"
#include "passes/PassUtilities.h"
#include "techniques/SoftShadowSupport.h"
#include "techniques/vssm/VssmTechnique.h"

#include <vtkObjectFactory.h>
#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>

vtkStandardNewMacro(vtkSLVssmPass);

sl::ShaderDefines vtkSLVssmPass::GetExtraDefines() const
{
  sl::ShaderDefines defines = sl::poissonDiskDefines();
  const sl::ShaderDefines hsm = sl::hsmLayoutDefines(*this->Frame);
  defines.insert(defines.end(), hsm.begin(), hsm.end());
  return defines;
}

std::vector<vtkTextureObject*> vtkSLVssmPass::SetTechniqueUniforms(vtkShaderProgram* program)
{
  const sl::FrameResources& frame = *this->Frame;
  sl::setSoftShadowUniforms(program, frame);
  program->SetUniformf("sceneRadius", static_cast<float>(frame.scene->bounds().radius()));
  const sl::LightView& view = frame.lightView;
  program->SetUniformf("satHalfStep",
    static_cast<float>(sl::vssmSatHalfStep(frame.summedAreaTableIsInteger, view.resolution, view.nearDepth, view.farDepth)));
  return { sl::bindSummedAreaTable(program, frame), sl::bindHierarchicalShadowMap(program, frame) };
}

void vtkSLVssmPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
