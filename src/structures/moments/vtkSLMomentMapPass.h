// The moment map's build (structures/moments/MomentMapStructure.h; vsm, esm): the shadow map's moments
// (structures/moments/shaders/MomentsFromDepth.glsl), prefiltered by a separable box blur of prefilter_texels
// (prefilter = blur) or mip-mapped (prefilter = mipmap); with prefilter_region = receivers, each of the three draws
// only over the tiles the next one reads (ReceiverTiles.h). Parameters read: MomentMapSettings.
#pragma once

#include "passes/FullScreenQuad.h"
#include "structures/moments/MomentPrefilter.h"
#include "passes/vtkSLStagePass.h"

#include <vtkNew.h>
#include <vtkSmartPointer.h>
#include <vtkTextureObject.h>

class vtkOpenGLFramebufferObject;

class vtkSLMomentMapPass : public vtkSLStagePass
{
public:
  static vtkSLMomentMapPass* New();
  vtkTypeMacro(vtkSLMomentMapPass, vtkSLStagePass);
  void PrintSelf(ostream& os, vtkIndent indent) override;
  const char* GetStageName() const override { return "moment_map"; }
  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkSLMomentMapPass();
  ~vtkSLMomentMapPass() override;
  void Execute(const vtkRenderState* state) override;

private:
  vtkSLMomentMapPass(const vtkSLMomentMapPass&) = delete;
  void operator=(const vtkSLMomentMapPass&) = delete;

  vtkNew<vtkOpenGLFramebufferObject> Framebuffer;
  sl::FullScreenQuad MomentsQuad;
  sl::FullScreenQuad BlurQuad;
  sl::ReceiverTileMarker TileMarker;
  // Kept from frame to frame while the map's size holds (sl::PrefilterTargets).
  vtkSmartPointer<vtkTextureObject> MomentsTarget;
  sl::PrefilterTargets BlurTargets;
};
