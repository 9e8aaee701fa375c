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
#include <vtkOpenGLShaderCache.h>
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

  auto data = std::make_shared<sl::FourierBasisData>();
  data->terms = settings.terms;
  data->mipmapped = settings.mipmap;
  // prefilter_region = receivers, as the moment map (structures/moments/README.md).
  data->region = this->TileMarker.planWhereItPays(window, frame, settings.blurTexels, settings.receiversOnly);
  if (data->region)
  {
    // The moment map's rule counts fetches alone; the basis decides by its own (its terms cost more than a fetch).
    if (sl::fourierSparseBlurIsCheaper(*data->region, settings.blurTexels, 2 * textures))
    {
      sl::planSparse(*data->region);
    }
    else
    {
      sl::planOverTiles(*data->region, settings.blurTexels);
    }
  }
  // The targets kept from frame to frame while the map's size holds: one per basis texture (its blurred one), the
  // blur's horizontal scratch shared by all.
  this->Sources.resize(static_cast<std::size_t>(2 * textures));
  this->Blurred.resize(static_cast<std::size_t>(2 * textures));
  std::vector<vtkSmartPointer<vtkTextureObject>> basis;
  if (data->region && data->region->blur.sparse)
  {
    // Only the listed texels, every texture's terms formed inline in one dispatch: no basis pass, no blur passes.
    if (!this->SparseProgram || this->SparseProgramTerms != settings.terms)
    {
      this->SparseProgram = std::make_unique<sl::ComputeProgram>(
        sl::assembleShader("fourier/FourierBasisSparseBlur.glsl", { { "FOURIER_TERMS", std::to_string(settings.terms) } }),
        "sparse Fourier basis blur");
      this->SparseProgramTerms = settings.terms;
    }
    sl::ComputeProgram& program = *this->SparseProgram;
    program.use();
    // In float, as the basis pass sets them (SetUniformf).
    program.setFloat("depthNear", static_cast<float>(frame.lightView.nearDepth));
    program.setFloat("depthFar", static_cast<float>(frame.lightView.farDepth));
    program.setFloat("depthRange", static_cast<float>(settings.depthRange));
    std::vector<vtkTextureObject*> targets;
    for (int i = 0; i < 2 * textures; ++i)
    {
      basis.push_back(sl::reusedFloatTarget(window, this->Blurred[static_cast<std::size_t>(i)], size, size, 4));
      targets.push_back(basis.back());
    }
    sl::blurReceiverTexels(program, frame.shadowMapLinear, targets, settings.blurTexels, data->region->blur);
    window->GetShaderCache()->ReleaseCurrentShader();
    data->region->sourceTiles = 0; // no basis pass
  }
  else
  {
    // One draw writes every texture: sine ones at locations 0 .. textures - 1, cosine ones after them.
    std::vector<vtkTextureObject*> targets;
    for (int i = 0; i < 2 * textures; ++i)
    {
      basis.push_back(sl::reusedFloatTarget(window, this->Sources[static_cast<std::size_t>(i)], size, size, 4));
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
      sl::renderQuadOver(window, this->BasisQuad, data->region ? &data->region->source : nullptr);
      bound->Deactivate();
    }
    for (std::size_t i = 0; i < basis.size(); ++i)
    {
      sl::PrefilterTargets kept{ this->Horizontal, this->Blurred[i], nullptr };
      basis[i] = sl::prefilterMoments(window, this->Framebuffer, this->BlurQuad, basis[i], settings.blurTexels,
        settings.mipmap, data->region ? &data->region->blur : nullptr, &kept);
      this->Horizontal = kept.horizontal;
      this->Blurred[i] = kept.blurred;
    }
  }
  data->sine.assign(basis.begin(), basis.begin() + textures);
  data->cosine.assign(basis.begin() + textures, basis.end());
  frame.lightSpaceData[sl::fourierBasisStructure().name] = data;
}

void vtkSLFourierBasisPass::ReleaseGraphicsResources(vtkWindow* window)
{
  this->BasisQuad.releaseGraphicsResources(window);
  this->BlurQuad.releaseGraphicsResources(window);
  this->Framebuffer->ReleaseGraphicsResources(window);
  this->TileMarker.release();
  this->SparseProgram.reset();
  this->Sources.clear();
  this->Blurred.clear();
  this->Horizontal = nullptr;
}

void vtkSLFourierBasisPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
