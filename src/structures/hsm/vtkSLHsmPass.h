// The min-max hierarchical shadow map's build (structures/hsm/HsmStructure.h; vssm, gbp06, gbp07) or, with
// SetDualGrid(true), the dual-grid MSSM's (structures/mssm/DualMssmStructure.h; yfgl09): one compute dispatch per
// level (structures/hsm/shaders/HsmBuild.glsl; VSSM Alg. 1 L4, §6.1; Yang et al. 2009 §4.2), and for hsm=ysm the Y shadow
// map's MSSM part after the mip-map levels, one more dispatch per level (structures/hsm/shaders/YsmMssmBuild.glsl; SS08
// §6), timed in the same stage. Parameters read:
// HierarchicalShadowMapSettings (not for the dual grid). Layouts: src/lightspace/HierarchicalShadowMap.h.
#pragma once

#include "gl/ComputeProgram.h"
#include "gl/ShaderLibrary.h"
#include "lightspace/HierarchicalShadowMap.h"
#include "passes/vtkSLStagePass.h"

#include <vtkSmartPointer.h>
#include <vtkTextureObject.h>

#include <map>
#include <memory>

class vtkOpenGLRenderWindow;

class vtkSLHsmPass : public vtkSLStagePass
{
public:
  static vtkSLHsmPass* New();
  vtkTypeMacro(vtkSLHsmPass, vtkSLStagePass);
  void PrintSelf(ostream& os, vtkIndent indent) override;
  const char* GetStageName() const override { return "hierarchical_shadow_map"; }

  // Builds the dual-grid MSSM instead of the hierarchical shadow map of the `hsm` parameter.
  void SetDualGrid(bool dualGrid) { this->DualGrid = dualGrid; }
  // HSM_LAYOUT and HSM_LAYOUT_* for common/HsmLayout.glsl (the build and the lookups).
  // Invocations per axis that build `level` of `layout` (HsmBuild.glsl): one per texel for the mip-map and the dual
  // grid's level 0, one per 2 x 2 texels sharing their finer squares for the N-buffers and the dual grid's levels.
  static int LevelInvocations(sl::HsmLayout layout, int mapSize, int level);
  static sl::ShaderDefines LayoutDefines(sl::HsmLayout layout);
  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkSLHsmPass();
  ~vtkSLHsmPass() override;
  void Execute(const vtkRenderState* state) override;
  // The YSM's MSSM part from the mip-map `atlas` just built; returns its texture.
  vtkTextureObject* BuildYsmMssmPart(vtkOpenGLRenderWindow* window, sl::FrameResources& frame, vtkTextureObject* atlas);

private:
  vtkSLHsmPass(const vtkSLHsmPass&) = delete;
  void operator=(const vtkSLHsmPass&) = delete;

  std::map<sl::HsmLayout, std::unique_ptr<sl::ComputeProgram>> Programs;
  bool DualGrid = false;
  // The last texture built, reused by the next frame when its layout, map size and layers (levels built) fit.
  vtkSmartPointer<vtkTextureObject> Texture;
  sl::HsmLayout TextureLayout = sl::HsmLayout::MipMap;
  int TextureMapSize = 0;
  int TextureLayers = 0;
  // The YSM's MSSM part and its build, likewise reused.
  std::unique_ptr<sl::ComputeProgram> MssmPartProgram;
  vtkSmartPointer<vtkTextureObject> MssmPartTexture;
  int MssmPartMapSize = 0;
};
