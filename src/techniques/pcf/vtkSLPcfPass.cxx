#include "techniques/pcf/vtkSLPcfPass.h"

#include "passes/FrameResources.h"
#include "passes/PassUtilities.h"
#include "techniques/SoftShadowSupport.h"
#include "techniques/pcf/PcfTechnique.h"

#include <vtkObjectFactory.h>
#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>
#include <vtk_glew.h>

vtkStandardNewMacro(vtkSLPcfPass);

vtkSLPcfPass::~vtkSLPcfPass() = default;

sl::ShaderDefines vtkSLPcfPass::GetExtraDefines() const
{
  return sl::poissonDiskDefines();
}

std::vector<vtkTextureObject*> vtkSLPcfPass::SetTechniqueUniforms(vtkShaderProgram* program)
{
  sl::FrameResources& frame = *this->Frame;
  std::vector<vtkTextureObject*> bound;
  sl::setPoissonDiskUniform(program);
  if (program->IsUniformUsed("shadowMapCompare"))
  {
    if (this->CompareSampler == 0)
    {
      glCreateSamplers(1, &this->CompareSampler);
      glSamplerParameteri(this->CompareSampler, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
      glSamplerParameteri(this->CompareSampler, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
      glSamplerParameteri(this->CompareSampler, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
      glSamplerParameteri(this->CompareSampler, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
      glSamplerParameteri(this->CompareSampler, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
      glSamplerParameteri(this->CompareSampler, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    }
    bound.push_back(sl::bindTexture(program, "shadowMapCompare", frame.shadowMapDepth));
    this->CompareUnit = frame.shadowMapDepth->GetTextureUnit();
    glBindSampler(static_cast<GLuint>(this->CompareUnit), this->CompareSampler);
  }
  return bound;
}

void vtkSLPcfPass::AfterDraw()
{
  if (this->CompareUnit >= 0)
  {
    glBindSampler(static_cast<GLuint>(this->CompareUnit), 0);
    this->CompareUnit = -1;
  }
}

void vtkSLPcfPass::ReleaseGraphicsResources(vtkWindow* window)
{
  if (this->CompareSampler != 0)
  {
    glDeleteSamplers(1, &this->CompareSampler);
    this->CompareSampler = 0;
  }
  this->Superclass::ReleaseGraphicsResources(window);
}

void vtkSLPcfPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
