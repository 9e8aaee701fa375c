#include "techniques/msmsoft/vtkSLMsmSoftPass.h"

#include "gl/GlResources.h"
#include "passes/FrameResources.h"
#include "techniques/SoftShadowSupport.h"

#include <vtkObjectFactory.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>
#include <vtk_glew.h>

vtkStandardNewMacro(vtkSLMsmSoftPass);

std::vector<vtkTextureObject*> vtkSLMsmSoftPass::SetTechniqueUniforms(vtkShaderProgram* program)
{
  const sl::FrameResources& frame = *this->Frame;
  sl::setSoftShadowUniforms(program, frame);
  program->SetUniformf("depthNear", static_cast<float>(frame.lightView.nearDepth));
  program->SetUniformf("depthFar", static_cast<float>(frame.lightView.farDepth));
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(frame.shadowMapLinear->GetContext());
  if (!this->FilterSupport || this->FilterSupport->GetContext() != window ||
    this->FilterSupport->GetWidth() != static_cast<unsigned>(frame.width()) ||
    this->FilterSupport->GetHeight() != static_cast<unsigned>(frame.height()))
  {
    this->FilterSupport = sl::makeFloatTarget(window, frame.width(), frame.height(), 4);
  }
  // Every pixel is stored by the shader; cleared anyway so that no earlier frame's value can survive.
  const float zero[4] = { 0.0f, 0.0f, 0.0f, 0.0f };
  glClearTexImage(this->FilterSupport->GetHandle(), 0, GL_RGBA, GL_FLOAT, zero);
  glBindImageTexture(0, this->FilterSupport->GetHandle(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  return {}; // the moment summed-area table is bound by its structure (structures/momentsat)
}

void vtkSLMsmSoftPass::AfterDraw()
{
  glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

std::vector<sl::NamedImage> vtkSLMsmSoftPass::CollectPassBuffers()
{
  if (!this->FilterSupport)
  {
    return {};
  }
  const sl::ImageF support = sl::readFloatTexture(this->FilterSupport, 4);
  return { { "support_depth_near", support.channels(0, 1), "", "" }, { "support_depth_far", support.channels(1, 1), "", "" },
    { "hankel_pivot", support.channels(2, 1), "", "" } };
}

void vtkSLMsmSoftPass::ReleaseGraphicsResources(vtkWindow* window)
{
  this->FilterSupport = nullptr;
  this->Superclass::ReleaseGraphicsResources(window);
}

void vtkSLMsmSoftPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
