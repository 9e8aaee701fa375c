// Stage "sublight_accumulate" of multi-view shadow maps (Yang et al. 2009 §5), run after the technique for
// each sub-light: adds the sub-light's technique targets into the frame's combined ones by each buffer's
// SubLightCombine (shaders/multiview/SubLightAccumulate.glsl, one compute dispatch per buffer). Driven by
// vtkSLMultiViewPass, which sets the sub-light index and the combined targets.
#pragma once

#include "gl/ComputeProgram.h"
#include "passes/vtkSLStagePass.h"

#include <vtkSmartPointer.h>

#include <map>
#include <memory>
#include <string>

class vtkTextureObject;

class vtkSLSubLightAccumulatePass : public vtkSLStagePass
{
public:
  static vtkSLSubLightAccumulatePass* New();
  vtkTypeMacro(vtkSLSubLightAccumulatePass, vtkSLStagePass);
  void PrintSelf(ostream& os, vtkIndent indent) override;
  const char* GetStageName() const override { return "sublight_accumulate"; }
  void ReleaseGraphicsResources(vtkWindow* window) override;

  // Sub-light `index` of `count`; `combined` maps every technique output to its combined target.
  void SetSubLight(int index, int count, const std::map<std::string, vtkSmartPointer<vtkTextureObject>>* combined);

protected:
  vtkSLSubLightAccumulatePass();
  ~vtkSLSubLightAccumulatePass() override;
  void Execute(const vtkRenderState* state) override;

private:
  vtkSLSubLightAccumulatePass(const vtkSLSubLightAccumulatePass&) = delete;
  void operator=(const vtkSLSubLightAccumulatePass&) = delete;

  std::unique_ptr<sl::ComputeProgram> Program;
  int SubLightIndex = 0;
  int SubLightCount = 1;
  const std::map<std::string, vtkSmartPointer<vtkTextureObject>>* Combined = nullptr;
};
