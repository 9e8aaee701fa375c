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

// Lets a stage skip its work when the results it would compute are still in place from an earlier run (a light-space
// structure's build whose inputs are unchanged: pipeline/StructureReuse.h). The pipeline attaches one per skippable
// stage; a stage without one always runs.
class StageReuse
{
public:
  virtual ~StageReuse() = default;
  // Before the stage's work: true when the earlier results were put back into `frame` (the work is skipped). On false
  // the earlier results are forgotten, since the work about to run may overwrite the textures they live in.
  virtual bool restore(FrameResources& frame) = 0;
  // After the stage's work: its results are in `frame`; `gpuMilliseconds` is what the work took.
  virtual void remember(FrameResources& frame, double gpuMilliseconds) = 0;
  // Drops the remembered results (the next run does the work).
  virtual void forget() = 0;
};
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
  void ResetTimer()
  {
    this->Timer.reset();
    this->ExecutedRuns = 0;
    this->ReusedRuns = 0;
  }
  // Light-space builds: the reuse that may skip Execute (nullptr: always executes), and how many runs since
  // ResetTimer() executed and how many were skipped because their results were still in place.
  void SetReuse(std::shared_ptr<sl::StageReuse> reuse) { this->Reuse = std::move(reuse); }
  sl::StageReuse* GetReuse() const { return this->Reuse.get(); }
  int GetExecutedRuns() const { return this->ExecutedRuns; }
  int GetReusedRuns() const { return this->ReusedRuns; }

protected:
  vtkSLStagePass();
  ~vtkSLStagePass() override;
  virtual void Execute(const vtkRenderState* state) = 0;

  sl::FrameResources* Frame = nullptr;

private:
  vtkSLStagePass(const vtkSLStagePass&) = delete;
  void operator=(const vtkSLStagePass&) = delete;

  sl::StageTimer Timer;
  std::shared_ptr<sl::StageReuse> Reuse;
  int ExecutedRuns = 0;
  int ReusedRuns = 0;
};
