// The power-moment map's build (structures/powermoments/PowerMomentMapStructure.h; msm): the four power moments of
// the normalised shadow-map depth (PowerMomentsFromDepth.glsl), prefiltered by the moment map's separable box blur
// (moments/BoxBlur.glsl) of prefilter_texels (prefilter = blur) or mip-mapped (prefilter = mipmap), only where the
// receivers read with prefilter_region = receivers (the moment map's plan: tiles, or the listed texels alone through
// PowerMomentsSparseBlur.glsl). Parameters read: PowerMomentMapSettings.
#pragma once

#include "gl/ComputeProgram.h"
#include "passes/FullScreenQuad.h"
#include "passes/vtkSLStagePass.h"
#include "structures/moments/MomentPrefilter.h"

#include <vtkNew.h>
#include <vtkSmartPointer.h>

#include <memory>

class vtkOpenGLFramebufferObject;

class vtkSLPowerMomentMapPass : public vtkSLStagePass
{
public:
  static vtkSLPowerMomentMapPass* New();
  vtkTypeMacro(vtkSLPowerMomentMapPass, vtkSLStagePass);
  void PrintSelf(ostream& os, vtkIndent indent) override;
  const char* GetStageName() const override { return "power_moment_map"; }
  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkSLPowerMomentMapPass();
  ~vtkSLPowerMomentMapPass() override;
  void Execute(const vtkRenderState* state) override;

private:
  vtkSLPowerMomentMapPass(const vtkSLPowerMomentMapPass&) = delete;
  void operator=(const vtkSLPowerMomentMapPass&) = delete;

  vtkNew<vtkOpenGLFramebufferObject> Framebuffer;
  sl::FullScreenQuad MomentsQuad;
  sl::FullScreenQuad BlurQuad;
  sl::ReceiverTileMarker TileMarker;
  std::unique_ptr<sl::ComputeProgram> SparseProgram;
  // Kept from frame to frame while the map's size holds (a fresh 2048^2 RGBA32F target costs llvmpipe tens of ms).
  vtkSmartPointer<vtkTextureObject> MomentsTarget;
  sl::PrefilterTargets BlurTargets;
};
