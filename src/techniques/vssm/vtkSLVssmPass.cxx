#include "techniques/vssm/vtkSLVssmPass.h"

#include "structures/sat/SatStructure.h"
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
  return sl::poissonDiskDefines();
}

std::vector<vtkTextureObject*> vtkSLVssmPass::SetTechniqueUniforms(vtkShaderProgram* program)
{
  const sl::FrameResources& frame = *this->Frame;
  sl::setSoftShadowUniforms(program, frame);
  program->SetUniformf("sceneRadius", static_cast<float>(frame.scene->bounds().radius()));
  const sl::LightView& view = frame.lightView;
  program->SetUniformf("satHalfStep",
    static_cast<float>(sl::vssmSatHalfStep(sl::summedAreaTableData(frame).integer, view.resolution, view.nearDepth, view.farDepth)));
  return {}; // the summed-area table and the HSM are bound by their structures (structures/sat, structures/hsm)
}

void vtkSLVssmPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
