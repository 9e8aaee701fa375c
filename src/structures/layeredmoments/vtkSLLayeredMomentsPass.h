// The layered moment map's build (structures/layeredmoments/LayeredMomentsStructure.h; lvsm): for each depth layer,
// the shadow map's depths warped into the layer and their squares (Lauritzen & McCool 2008), box-blurred over
// prefilter_texels by two compute passes (x, then y) of layeredmoments/LayeredMomentsBuild.glsl, over the tiles the
// receivers read (prefilter_region = receivers; ReceiverTileMarker) or the whole map; with layer_placement=gaps,
// first the shadow map's depth histogram (LayeredMomentsHistogram.glsl) that places the layers.
#pragma once

#include "gl/ComputeProgram.h"
#include "passes/vtkSLStagePass.h"
#include "structures/moments/MomentPrefilter.h"

#include <vtkSmartPointer.h>

#include <memory>

class vtkTextureObject;
namespace sl
{
struct FrameResources;
struct LayeredMomentsData;
struct LayeredMomentsSettings;
}

class vtkSLLayeredMomentsPass : public vtkSLStagePass
{
public:
  static vtkSLLayeredMomentsPass* New();
  vtkTypeMacro(vtkSLLayeredMomentsPass, vtkSLStagePass);
  void PrintSelf(ostream& os, vtkIndent indent) override;
  const char* GetStageName() const override { return "layered_moments"; }
  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkSLLayeredMomentsPass();
  ~vtkSLLayeredMomentsPass() override;
  void Execute(const vtkRenderState* state) override;

private:
  vtkSLLayeredMomentsPass(const vtkSLLayeredMomentsPass&) = delete;
  void operator=(const vtkSLLayeredMomentsPass&) = delete;
  // The separable blur over the plan's tiles (every tile without a region), and the sparse one at its listed texels.
  void BlurTiles(sl::FrameResources& frame, const sl::LayeredMomentsData& data, const sl::LayeredMomentsSettings& settings);
  void BlurSparse(sl::FrameResources& frame, const sl::LayeredMomentsData& data, const sl::LayeredMomentsSettings& settings);

  std::unique_ptr<sl::ComputeProgram> BlurPrograms[2]; // x (warping), y
  std::unique_ptr<sl::ComputeProgram> HistogramProgram; // layer_placement=gaps: the depth histogram
  std::unique_ptr<sl::ComputeProgram> SparseProgram;    // prefilter_region = receivers, sparse
  sl::ReceiverTileMarker TileMarker;
  // The x pass's target and the map, kept from frame to frame (and sub-light to sub-light) while the map's size and
  // layer count hold: two fresh 2048^2 x 4 RG32F textures cost llvmpipe more than a receivers-only build.
  vtkSmartPointer<vtkTextureObject> HorizontalTarget;
  vtkSmartPointer<vtkTextureObject> MomentsTarget;
};
