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
  // common/HsmLayout.glsl is shared with the HSM build, which names its layout HSM_LAYOUT.
  const bool nBuffers = this->Frame->parameters.choice("hsm") == "nbuffers";
  defines.push_back({ "HSM_LAYOUT_MIPMAP", "0" });
  defines.push_back({ "HSM_LAYOUT_NBUFFERS", "1" });
  defines.push_back({ "HSM_LAYOUT", nBuffers ? "1" : "0" });
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
  sl::setIntIfUsed(program, "hsmMapSize", view.resolution);
  return { sl::bindSummedAreaTable(program, frame), sl::bindTexture(program, "hsmTexture", frame.hierarchicalShadowMap) };
}

void vtkSLVssmPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
