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
    // clip.z = -P22 d + P32, clip.w = -P23 d + P33 for linear depth d (z_view = -d).
    const glm::dmat4& projection = frame.lightView.clipFromView;
    const float depthToClip[4] = { static_cast<float>(projection[2][2]), static_cast<float>(projection[3][2]),
      static_cast<float>(projection[2][3]), static_cast<float>(projection[3][3]) };
    program->SetUniform4f("lightDepthToClip", depthToClip);
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
