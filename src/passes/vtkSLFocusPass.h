// Stage 2a (when the technique needs a shadow map): fits the light frustum to the visible receivers and
// the casters clipped to it (survey §4.1, see lightspace/LightView.h). It reads the G-buffer's position
// and normal back to the CPU (kept for the outputs) and runs the fit there; its own stage so that
// stats.json separates this cost from rendering the map. Parameters it reads: shadow_map_size, and the
// technique's kernel_texels when declared (margin = ceil(kernel / 2) + 1 texels).
#pragma once

#include "passes/vtkSLStagePass.h"

class vtkSLFocusPass : public vtkSLStagePass
{
public:
  static vtkSLFocusPass* New();
  vtkTypeMacro(vtkSLFocusPass, vtkSLStagePass);
  void PrintSelf(ostream& os, vtkIndent indent) override;
  const char* GetStageName() const override { return "focus"; }

protected:
  vtkSLFocusPass() = default;
  ~vtkSLFocusPass() override = default;
  void Execute(const vtkRenderState* state) override;

private:
  vtkSLFocusPass(const vtkSLFocusPass&) = delete;
  void operator=(const vtkSLFocusPass&) = delete;
};
