// The moment summed-area table's build (structures/momentsat/MomentSatStructure.h; msmsoft): the 64-bit summed-area
// table of the shadow map's four power moments, two compute passes (structures/momentsat/shaders/MomentSatBuild.glsl).
#pragma once

#include "gl/ComputeProgram.h"
#include "passes/vtkSLStagePass.h"

#include <vtkSmartPointer.h>
#include <vtkTextureObject.h>

#include <array>
#include <memory>

class vtkSLMomentSatPass : public vtkSLStagePass
{
public:
  static vtkSLMomentSatPass* New();
  vtkTypeMacro(vtkSLMomentSatPass, vtkSLStagePass);
  void PrintSelf(ostream& os, vtkIndent indent) override;
  const char* GetStageName() const override { return "moment_sat"; }
  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkSLMomentSatPass();
  ~vtkSLMomentSatPass() override;
  void Execute(const vtkRenderState* state) override;

private:
  vtkSLMomentSatPass(const vtkSLMomentSatPass&) = delete;
  void operator=(const vtkSLMomentSatPass&) = delete;

  // Compiled programs by pass (rows, columns).
  std::array<std::unique_ptr<sl::ComputeProgram>, 2> Programs;
  // The last tables built (low and high words), reused by the next frame when their size fits.
  vtkSmartPointer<vtkTextureObject> Low;
  vtkSmartPointer<vtkTextureObject> High;
};
