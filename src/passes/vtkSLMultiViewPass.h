// Multi-view shadow maps (Yang et al. 2009 §5, Alg. 1 steps 2-8) for techniques with a `sublights` parameter:
// the square area light is split into S x S sub-lights, and the light-space stages (focus, shadow map, the
// structures the technique needs) and the technique run once per sub-light with that sub-light as the frame's
// light, each followed by vtkSLSubLightAccumulatePass. Afterwards the frame's technique targets are the
// combined ones and FrameResources::subLightVisibility holds each sub-light's visibility. With S = 1 the inner
// stages run once, as without this pass.
//
// Views that partition the pixels (survey §4.3, lightspace/PartitionViews.h: cascades; FrameResources::partitioned):
// the same inner stages run once per view with FrameResources::viewIndex set (the focus fits every view at view 0 and
// writes the per-pixel selection), each followed by vtkSLPartitionAccumulatePass, which blends the technique's targets
// by the selection instead of averaging them. When the focus fits no partition (one map is enough), view 0's run is
// the frame's, as without this pass.
//
// Not a timed stage itself: its inner stages report their times, summed over the sub-lights or views.
#pragma once

#include "passes/vtkSLStagePass.h"
#include "passes/vtkSLPartitionAccumulatePass.h"
#include "passes/vtkSLSubLightAccumulatePass.h"

#include <vtkRenderPass.h>
#include <vtkSmartPointer.h>

#include <vector>

class vtkSLMultiViewPass : public vtkRenderPass
{
public:
  static vtkSLMultiViewPass* New();
  vtkTypeMacro(vtkSLMultiViewPass, vtkRenderPass);
  void PrintSelf(ostream& os, vtkIndent indent) override;
  void Render(const vtkRenderState* state) override;
  void ReleaseGraphicsResources(vtkWindow* window) override;

  void SetFrame(sl::FrameResources* frame) { this->Frame = frame; }
  // The per-sub-light stages, in order, and the accumulation stage run after each.
  void SetStages(std::vector<vtkSLStagePass*> inner, vtkSLSubLightAccumulatePass* accumulate);
  // The per-view stages and the selection-weighted accumulation, for views that partition the pixels.
  void SetPartitionStages(std::vector<vtkSLStagePass*> inner, vtkSLPartitionAccumulatePass* accumulate);

protected:
  vtkSLMultiViewPass();
  ~vtkSLMultiViewPass() override;

private:
  vtkSLMultiViewPass(const vtkSLMultiViewPass&) = delete;
  void operator=(const vtkSLMultiViewPass&) = delete;

  sl::FrameResources* Frame = nullptr;
  std::vector<vtkSmartPointer<vtkSLStagePass>> Inner;
  vtkSmartPointer<vtkSLSubLightAccumulatePass> Accumulate;
  vtkSmartPointer<vtkSLPartitionAccumulatePass> PartitionAccumulate;

  void RenderPartition(const vtkRenderState* state);
};
