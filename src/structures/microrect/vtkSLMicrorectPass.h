// The microrects' build (structures/microrect/MicrorectStructure.h; Schwarz & Stamminger 2008 §5.2): for each
// level 1..L two compute dispatches, pass 1 and pass 2 of structures/microrect/shaders/MicrorectBuild.glsl, with memory
// barriers between them; one timed stage, "microrects". No parameters. Definition and CPU twin:
// src/lightspace/Microrects.h.
#pragma once

#include "gl/ComputeProgram.h"
#include "passes/vtkSLStagePass.h"

#include <vtkSmartPointer.h>
#include <vtkTextureObject.h>

#include <memory>

class vtkSLMicrorectPass : public vtkSLStagePass
{
public:
  static vtkSLMicrorectPass* New();
  vtkTypeMacro(vtkSLMicrorectPass, vtkSLStagePass);
  void PrintSelf(ostream& os, vtkIndent indent) override;
  const char* GetStageName() const override { return "microrects"; }
  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkSLMicrorectPass();
  ~vtkSLMicrorectPass() override;
  void Execute(const vtkRenderState* state) override;

private:
  vtkSLMicrorectPass(const vtkSLMicrorectPass&) = delete;
  void operator=(const vtkSLMicrorectPass&) = delete;

  std::unique_ptr<sl::ComputeProgram> FirstPass;
  std::unique_ptr<sl::ComputeProgram> SecondPass;
  // The last frame's textures, reused when the map size fits: every level's dispatches rewrite the same texels.
  vtkSmartPointer<vtkTextureObject> ExtentTexture; // RGBA16UI N x N atlas
  vtkSmartPointer<vtkTextureObject> DepthTexture;  // R32F N x N atlas
  vtkSmartPointer<vtkTextureObject> ClaimTexture;  // R8UI ceil(N / 2)^2, pass 1's claims of the level being built
  int TextureMapSize = 0;
};
