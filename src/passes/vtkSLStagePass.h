// Base of every ShadowLab render pass: one stage of the frame, timed on the GPU (timer query) and on
// the wall clock, with GL errors checked when it ends. Subclasses implement Execute().
#pragma once

#include "gl/GlResources.h"

#include <vtkRenderPass.h>

#include <memory>
#include <string>

namespace sl
{
struct FrameResources;
}

class vtkSLStagePass : public vtkRenderPass
{
public:
  vtkTypeMacro(vtkSLStagePass, vtkRenderPass);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  void Render(const vtkRenderState* state) final;

  void SetFrame(sl::FrameResources* frame) { this->Frame = frame; }
  // Stage name used in stats.json ("gbuffer", "shadow_map", "technique", "shading").
  virtual const char* GetStageName() const = 0;
  // Summed over the stage's runs since ResetTimer() (once per frame; once per sub-light for multi-view).
  double GetGpuMilliseconds() const { return this->Timer.gpuMilliseconds(); }
  double GetWallMilliseconds() const { return this->Timer.wallMilliseconds(); }
  void ResetTimer() { this->Timer.reset(); }

protected:
  vtkSLStagePass();
  ~vtkSLStagePass() override;
  virtual void Execute(const vtkRenderState* state) = 0;

  sl::FrameResources* Frame = nullptr;

private:
  vtkSLStagePass(const vtkSLStagePass&) = delete;
  void operator=(const vtkSLStagePass&) = delete;

  sl::StageTimer Timer;
};
