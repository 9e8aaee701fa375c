// The Fourier basis images' build (structures/fourier/FourierBasisStructure.h; convsm): sin(c_k s z_n) and
// cos(c_k s z_n) (s = depth_range) of the shadow map (fourier/FourierBasis.glsl, all textures in one draw), each texture prefiltered by
// the moment map's separable box blur (moments/BoxBlur.glsl) of prefilter_texels (prefilter = blur) or mip-mapped
// (prefilter = mipmap). Parameters read: FourierBasisSettings.
#pragma once

#include "passes/FullScreenQuad.h"
#include "passes/vtkSLStagePass.h"

#include <vtkNew.h>

class vtkOpenGLFramebufferObject;

class vtkSLFourierBasisPass : public vtkSLStagePass
{
public:
  static vtkSLFourierBasisPass* New();
  vtkTypeMacro(vtkSLFourierBasisPass, vtkSLStagePass);
  void PrintSelf(ostream& os, vtkIndent indent) override;
  const char* GetStageName() const override { return "fourier_basis"; }
  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkSLFourierBasisPass();
  ~vtkSLFourierBasisPass() override;
  void Execute(const vtkRenderState* state) override;

private:
  vtkSLFourierBasisPass(const vtkSLFourierBasisPass&) = delete;
  void operator=(const vtkSLFourierBasisPass&) = delete;

  vtkNew<vtkOpenGLFramebufferObject> Framebuffer;
  sl::FullScreenQuad BasisQuad;
  sl::FullScreenQuad BlurQuad;
};
