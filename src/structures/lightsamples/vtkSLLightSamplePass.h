// The light-sample set's build (structures/lightsamples/LightSampleSetStructure.h; Forest et al. 2009 §4.1): constructs the
// named pattern on the CPU (lightspace/LightSampleSet.h) and uploads its N base points into an N x 1 RG32F
// texture, only when the settings (pattern, interleaving, N, seed) or the context change; otherwise the previous
// set and texture are handed to the frame again. One timed stage, "light_samples". Parameters read:
// light_samples, samples, sample_seed.
#pragma once

#include "lightspace/LightSampleSet.h"
#include "passes/vtkSLStagePass.h"

#include <vtkSmartPointer.h>
#include <vtkTextureObject.h>

#include <memory>

class vtkSLLightSamplePass : public vtkSLStagePass
{
public:
  static vtkSLLightSamplePass* New();
  vtkTypeMacro(vtkSLLightSamplePass, vtkSLStagePass);
  void PrintSelf(ostream& os, vtkIndent indent) override;
  const char* GetStageName() const override { return "light_samples"; }
  void ReleaseGraphicsResources(vtkWindow* window) override;
  // How many times the pass has constructed a set and uploaded it (tests: once per change of settings).
  int GetUploadCount() const { return this->UploadCount; }

protected:
  vtkSLLightSamplePass();
  ~vtkSLLightSamplePass() override;
  void Execute(const vtkRenderState* state) override;

private:
  vtkSLLightSamplePass(const vtkSLLightSamplePass&) = delete;
  void operator=(const vtkSLLightSamplePass&) = delete;

  std::shared_ptr<const sl::LightSampleSet> Samples; // the set the texture holds
  vtkSmartPointer<vtkTextureObject> BaseTexture;     // RG32F N x 1
  int UploadCount = 0;
};
