#include "structures/fourier/vtkSLFourierBasisPass.h"

#include "core/Error.h"
#include "gl/GlResources.h"
#include "gl/ShaderLibrary.h"
#include "passes/FrameResources.h"
#include "passes/PassUtilities.h"
#include "passes/ScopedRenderTarget.h"
#include "structures/fourier/FourierBasisStructure.h"
#include "structures/moments/MomentPrefilter.h"

#include <vtkObjectFactory.h>
#include <vtkOpenGLFramebufferObject.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkRenderState.h>
#include <vtkRenderer.h>
#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>
#include <vtk_glew.h>

#include <string>

vtkStandardNewMacro(vtkSLFourierBasisPass);

vtkSLFourierBasisPass::vtkSLFourierBasisPass() = default;
vtkSLFourierBasisPass::~vtkSLFourierBasisPass() = default;

void vtkSLFourierBasisPass::Execute(const vtkRenderState* state)
{
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(state->GetRenderer()->GetRenderWindow());
  sl::FrameResources& frame = *this->Frame;
  SL_CHECK_MSG(frame.hasLightView && frame.shadowMapLinear, "the shadow map must be built before its Fourier basis");
  const sl::FourierBasisSettings settings = sl::FourierBasisSettings::from(frame.parameters);
  const int size = frame.lightView.resolution;
  const int textures = settings.terms / sl::fourierTermsPerTexture;

  // One draw writes every texture: sine ones at locations 0 .. textures - 1, cosine ones after them.
  std::vector<vtkSmartPointer<vtkTextureObject>> basis;
  std::vector<vtkTextureObject*> targets;
  for (int i = 0; i < 2 * textures; ++i)
  {
    basis.push_back(sl::makeFloatTarget(window, size, size, 4));
    targets.push_back(basis.back());
  }
  {
    const sl::ScopedRenderTarget target(window, this->Framebuffer, targets);
    vtkShaderProgram* program = this->BasisQuad.ready(window,
      sl::assembleShader("fourier/FourierBasis.glsl", { { "FOURIER_TERMS", std::to_string(settings.terms) } }),
      "fourier basis");
    vtkTextureObject* bound = sl::bindTexture(program, "shadowMapLinear", frame.shadowMapLinear);
    program->SetUniformf("depthNear", static_cast<float>(frame.lightView.nearDepth));
    program->SetUniformf("depthFar", static_cast<float>(frame.lightView.farDepth));
    program->SetUniformf("depthRange", static_cast<float>(settings.depthRange));
    this->BasisQuad.render();
    bound->Deactivate();
  }
  for (vtkSmartPointer<vtkTextureObject>& texture : basis)
  {
    texture = sl::prefilterMoments(window, this->Framebuffer, this->BlurQuad, texture, settings.blurTexels, settings.mipmap);
  }
  auto data = std::make_shared<sl::FourierBasisData>();
  data->sine.assign(basis.begin(), basis.begin() + textures);
  data->cosine.assign(basis.begin() + textures, basis.end());
  data->terms = settings.terms;
  data->mipmapped = settings.mipmap;
  frame.lightSpaceData[sl::fourierBasisStructure().name] = data;
}

void vtkSLFourierBasisPass::ReleaseGraphicsResources(vtkWindow* window)
{
  this->BasisQuad.releaseGraphicsResources(window);
  this->BlurQuad.releaseGraphicsResources(window);
  this->Framebuffer->ReleaseGraphicsResources(window);
}

void vtkSLFourierBasisPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
