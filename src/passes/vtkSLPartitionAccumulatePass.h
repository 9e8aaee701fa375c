// Stage "partition_accumulate": for views that partition the pixels (survey §4.3, lightspace/PartitionViews.h), run
// after the technique for each view: adds the view's technique targets into the frame's combined ones, weighted per
// pixel by FrameResources::viewSelection (shaders/multiview/PartitionAccumulate.glsl, one compute dispatch per buffer).
// Driven by vtkSLMultiViewPass, which sets the view index and the combined targets.
#pragma once

#include "gl/ComputeProgram.h"
#include "passes/vtkSLStagePass.h"

#include <vtkSmartPointer.h>

#include <map>
#include <memory>
#include <string>

class vtkTextureObject;

class vtkSLPartitionAccumulatePass : public vtkSLStagePass
{
public:
  static vtkSLPartitionAccumulatePass* New();
  vtkTypeMacro(vtkSLPartitionAccumulatePass, vtkSLStagePass);
  void PrintSelf(ostream& os, vtkIndent indent) override;
  const char* GetStageName() const override { return "partition_accumulate"; }
  void ReleaseGraphicsResources(vtkWindow* window) override;

  // View `index`; `combined` maps every technique output to its combined target.
  void SetView(int index, const std::map<std::string, vtkSmartPointer<vtkTextureObject>>* combined);

protected:
  vtkSLPartitionAccumulatePass();
  ~vtkSLPartitionAccumulatePass() override;
  void Execute(const vtkRenderState* state) override;

private:
  vtkSLPartitionAccumulatePass(const vtkSLPartitionAccumulatePass&) = delete;
  void operator=(const vtkSLPartitionAccumulatePass&) = delete;

  std::unique_ptr<sl::ComputeProgram> Program;
  int ViewIndex = 0;
  const std::map<std::string, vtkSmartPointer<vtkTextureObject>>* Combined = nullptr;
};
