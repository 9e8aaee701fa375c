// Stage 2e (techniques that need LightStructure::HierarchicalShadowMap: vssm): the min-max hierarchical
// shadow map of VSSM (Alg. 1 L4, §6.1), one compute dispatch per level (shaders/hsm/HsmBuild.glsl).
// Parameter read: hsm (mipmap | nbuffers). Layouts: src/lightspace/HierarchicalShadowMap.h.
#pragma once

#include "gl/ComputeProgram.h"
#include "passes/vtkSLStagePass.h"

#include <map>
#include <memory>

class vtkSLHsmPass : public vtkSLStagePass
{
public:
  static vtkSLHsmPass* New();
  vtkTypeMacro(vtkSLHsmPass, vtkSLStagePass);
  void PrintSelf(ostream& os, vtkIndent indent) override;
  const char* GetStageName() const override { return "hierarchical_shadow_map"; }
  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkSLHsmPass();
  ~vtkSLHsmPass() override;
  void Execute(const vtkRenderState* state) override;

private:
  vtkSLHsmPass(const vtkSLHsmPass&) = delete;
  void operator=(const vtkSLHsmPass&) = delete;

  std::map<bool, std::unique_ptr<sl::ComputeProgram>> Programs; // by N-buffers?
};
