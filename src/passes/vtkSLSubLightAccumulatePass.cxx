#include "passes/vtkSLSubLightAccumulatePass.h"

#include "core/Error.h"
#include "gl/ShaderLibrary.h"
#include "passes/FrameResources.h"

#include <vtkObjectFactory.h>
#include <vtkTextureObject.h>
#include <vtk_glew.h>

vtkStandardNewMacro(vtkSLSubLightAccumulatePass);

vtkSLSubLightAccumulatePass::vtkSLSubLightAccumulatePass() = default;
vtkSLSubLightAccumulatePass::~vtkSLSubLightAccumulatePass() = default;

void vtkSLSubLightAccumulatePass::SetSubLight(
  int index, int count, const std::map<std::string, vtkSmartPointer<vtkTextureObject>>* combined)
{
  this->SubLightIndex = index;
  this->SubLightCount = count;
  this->Combined = combined;
}

void vtkSLSubLightAccumulatePass::Execute(const vtkRenderState*)
{
  const sl::FrameResources& frame = *this->Frame;
  SL_CHECK_MSG(this->Combined, "sublight_accumulate runs inside the multi-view pass");
  if (!this->Program)
  {
    this->Program = std::make_unique<sl::ComputeProgram>(sl::assembleShader("multiview/SubLightAccumulate.glsl", {}), "sub-light accumulation");
  }
  this->Program->use();
  this->Program->setInt("imageWidth", frame.width());
  this->Program->setInt("imageHeight", frame.height());
  this->Program->setInt("firstSubLight", this->SubLightIndex == 0 ? 1 : 0);
  std::map<std::string, sl::SubLightCombine> combineRules = { { "visibility", sl::SubLightCombine::Mean } };
  std::map<std::string, int> cutShortCodes;
  for (const sl::BufferSpec& buffer : frame.technique->buffers)
  {
    combineRules[buffer.name] = buffer.subLightCombine;
    cutShortCodes[buffer.name] = buffer.cutShortCode;
  }
  for (const std::string& output : frame.technique->outputNames())
  {
    const sl::SubLightCombine rule = combineRules.at(output);
    const double weight = rule == sl::SubLightCombine::Mean ? 1.0 / this->SubLightCount : rule == sl::SubLightCombine::Sum ? 1.0 : 0.0;
    this->Program->setFloat("weight", weight);
    this->Program->setFloat("cutShortCode", static_cast<float>(cutShortCodes.count(output) ? cutShortCodes.at(output) : -1));
    glBindImageTexture(0, frame.techniqueTargets.at(output)->GetHandle(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32F);
    glBindImageTexture(1, this->Combined->at(output)->GetHandle(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32F);
    this->Program->dispatch({ (frame.width() + 7) / 8, (frame.height() + 7) / 8 });
  }
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
  glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32F);
  glBindImageTexture(1, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32F);
}

void vtkSLSubLightAccumulatePass::ReleaseGraphicsResources(vtkWindow*)
{
  this->Program.reset();
}

void vtkSLSubLightAccumulatePass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SubLight: " << this->SubLightIndex << " of " << this->SubLightCount << "\n";
}
