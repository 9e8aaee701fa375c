// Stage 2e (techniques that need LightStructure::HierarchicalShadowMap, vssm and gbp07, or
// LightStructure::DualMultiScaleShadowMap, yfgl09): the min-max hierarchical shadow map of VSSM (Alg. 1 L4,
// §6.1) or the dual-grid MSSM of Yang et al. 2009 (§4.2), one compute dispatch per level
// (shaders/hsm/HsmBuild.glsl). Parameter read: hsm (mipmap | nbuffers). Layouts:
// src/lightspace/HierarchicalShadowMap.h.
#pragma once

#include "gl/ComputeProgram.h"
#include "gl/ShaderLibrary.h"
#include "lightspace/HierarchicalShadowMap.h"
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

  // The layout this frame builds: the dual-grid MSSM for techniques that need it, else the `hsm` parameter.
  static sl::HsmLayout LayoutFor(const sl::FrameResources& frame);
  // HSM_LAYOUT and HSM_LAYOUT_* for common/HsmLayout.glsl (the build and the lookups).
  static sl::ShaderDefines LayoutDefines(sl::HsmLayout layout);
  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkSLHsmPass();
  ~vtkSLHsmPass() override;
  void Execute(const vtkRenderState* state) override;

private:
  vtkSLHsmPass(const vtkSLHsmPass&) = delete;
  void operator=(const vtkSLHsmPass&) = delete;

  std::map<sl::HsmLayout, std::unique_ptr<sl::ComputeProgram>> Programs;
};
