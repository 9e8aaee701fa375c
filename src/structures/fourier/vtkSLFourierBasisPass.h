// The Fourier basis images' build (structures/fourier/FourierBasisStructure.h; convsm): sin(c_k s z_n) and
// cos(c_k s z_n) (s = depth_range) of the shadow map (fourier/FourierBasis.glsl, all textures in one draw), each texture prefiltered by
// the moment map's separable box blur (moments/BoxBlur.glsl) of prefilter_texels (prefilter = blur) or mip-mapped
// (prefilter = mipmap), only where the receivers read with prefilter_region = receivers (the moment map's plan:
// tiles, or the listed texels alone through FourierBasisSparseBlur.glsl). Parameters read: FourierBasisSettings.
#pragma once

#include "gl/ComputeProgram.h"
#include "passes/FullScreenQuad.h"
#include "passes/vtkSLStagePass.h"
#include "structures/moments/MomentPrefilter.h"

#include <vtkNew.h>
#include <vtkSmartPointer.h>

#include <memory>
#include <vector>

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
  sl::ReceiverTileMarker TileMarker;
  std::unique_ptr<sl::ComputeProgram> SparseProgram;
  int SparseProgramTerms = 0;
  // Kept from frame to frame while the map's size holds (a fresh 2048^2 RGBA32F target costs llvmpipe tens of ms, and
  // 16 terms take 8 textures and their blurs): each texture's unfiltered and blurred target, one shared scratch.
  std::vector<vtkSmartPointer<vtkTextureObject>> Sources;
  std::vector<vtkSmartPointer<vtkTextureObject>> Blurred;
  vtkSmartPointer<vtkTextureObject> Horizontal;
};
