// The layered moment map's build (structures/layeredmoments/LayeredMomentsStructure.h; lvsm): for each depth layer,
// the shadow map's depths warped into the layer and their squares (Lauritzen & McCool 2008), box-blurred over
// prefilter_texels by two compute passes (x, then y) of layeredmoments/LayeredMomentsBuild.glsl; with
// layer_placement=gaps, first the shadow map's depth histogram (LayeredMomentsHistogram.glsl) that places the layers.
#pragma once

#include "gl/ComputeProgram.h"
#include "passes/vtkSLStagePass.h"

#include <memory>

class vtkTextureObject;

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

  std::unique_ptr<sl::ComputeProgram> BlurPrograms[2]; // x (warping), y
  std::unique_ptr<sl::ComputeProgram> HistogramProgram; // layer_placement=gaps: the depth histogram
};
