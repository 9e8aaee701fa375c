#include "techniques/pcss/vtkSLPcssPass.h"

#include "passes/FrameResources.h"
#include "techniques/SamplingPatterns.h"

#include <vtkObjectFactory.h>
#include <vtkShaderProgram.h>

vtkStandardNewMacro(vtkSLPcssPass);

sl::ShaderDefines vtkSLPcssPass::GetExtraDefines() const
{
  return { { "MAX_POISSON_SAMPLES", std::to_string(sl::maxPoissonSamples) } };
}

std::vector<vtkTextureObject*> vtkSLPcssPass::SetTechniqueUniforms(vtkShaderProgram* program)
{
  const sl::FrameResources& frame = *this->Frame;
  const sl::LightView& view = frame.lightView;
  const double lightSize = frame.light->type == sl::LightType::Area ? frame.light->size : 0.0;
  program->SetUniformf("lightSizeWorld", static_cast<float>(lightSize));
  program->SetUniformf("lightNearDepth", static_cast<float>(view.nearDepth));
  const float texelTangent[2] = { static_cast<float>((view.window.y - view.window.x) / view.resolution),
    static_cast<float>((view.window.w - view.window.z) / view.resolution) };
  program->SetUniform2f("shadowTexelTangent", texelTangent);
  const float windowMin[2] = { static_cast<float>(view.window.x), static_cast<float>(view.window.z) };
  program->SetUniform2f("shadowWindowMin", windowMin);
  if (program->IsUniformUsed("poissonDisk"))
  {
    program->SetUniform2fv("poissonDisk", sl::maxPoissonSamples, sl::poissonDiskFloats().data());
  }
  return {};
}

void vtkSLPcssPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
