// The moment summed-area table's build (structures/momentsat/MomentSatStructure.h; msmsoft): the summed-area table of
// the shadow map's four power moments (64-bit or 32-bit sums), two compute passes per band of rows
// (structures/momentsat/shaders/MomentSatBuild.glsl, gl/BandedPrefixSums.h). Parameters read: moment_sat_precision,
// moment_sat_max_kernel_texels.
#pragma once

#include "gl/BandedPrefixSums.h"
#include "gl/ComputeProgram.h"
#include "passes/vtkSLStagePass.h"

#include <vtkSmartPointer.h>
#include <vtkTextureObject.h>

#include <map>
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

  // Compiled programs by (int64?, pass).
  std::map<std::pair<bool, int>, std::unique_ptr<sl::ComputeProgram>> Programs;
  // The last tables built (low and high words; int32 uses the low only), reused when their size fits.
  vtkSmartPointer<vtkTextureObject> Low;
  vtkSmartPointer<vtkTextureObject> High;
  // The band and carry buffers the tables are built in (gl/BandedPrefixSums.h), kept with them.
  sl::BandedPrefixSums Bands;
};
