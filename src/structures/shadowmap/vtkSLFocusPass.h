// The shadow map's first stage (structures/shadowmap/ShadowMapStructure.h): fits the light frustum to the visible receivers and
// the casters clipped to it (survey §4.1, see lightspace/LightView.h). The receivers are reduced on the
// GPU (GpuReceivers: a compute shader, nine words read back); the casters are clipped on the CPU. Its
// own stage, so that stats.json separates this cost from rendering the map. Parameters it reads: ShadowMapSettings.
// With views that partition the pixels (lightspace/PartitionViews.h: cascades, survey §4.3.1; cube faces, survey §2)
// it fits every view at view 0 (fitCascades, fitCubeFaces), writes the per-pixel selection, and hands each view its
// fit. With fvsm (survey §4.3.3) it reads the G-buffer back at view 0 (the pre-pass), fits the quadtree's tiles
// (lightspace/FittedVirtualShadowMap.h fitFvsm) and writes the per-pixel tile selection.
#pragma once

#include "gl/ComputeProgram.h"
#include "lightspace/LightView.h"
#include "passes/GpuReceivers.h"
#include "passes/vtkSLStagePass.h"

#include <memory>
#include <vector>

namespace sl
{
struct ShadowMapSettings;
}

class vtkSLFocusPass : public vtkSLStagePass
{
public:
  static vtkSLFocusPass* New();
  vtkTypeMacro(vtkSLFocusPass, vtkSLStagePass);
  void PrintSelf(ostream& os, vtkIndent indent) override;
  const char* GetStageName() const override { return "focus"; }
  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkSLFocusPass();
  ~vtkSLFocusPass() override;
  void Execute(const vtkRenderState* state) override;

private:
  vtkSLFocusPass(const vtkSLFocusPass&) = delete;
  void operator=(const vtkSLFocusPass&) = delete;

  // Views that partition the pixels: the per-pixel selection (shaders/lightspace/PartitionSelection.glsl) into
  // FrameResources::viewSelection, with the uniforms of the set's kind.
  void WriteSelection(const vtkRenderState* state);
  // shadow_map_size = auto (lightspace/AutomaticMapSize.h): the largest size the GL and the frame's structures
  // allow, and the size chosen for `views` fitted at it (into FrameResources::automaticMapSize and focus.resolution).
  int LargestAutomaticSize(const sl::ShadowMapSettings& settings) const;
  void ChooseAutomaticSize(
    const std::vector<sl::LightView>& views, const sl::ShadowMapSettings& settings, sl::FocusSettings& focus);
  void SetCascadeUniforms();
  // fvsm: the tile selection (shaders/lightspace/FvsmSelection.glsl) into FrameResources::viewSelection.
  void WriteTileSelection(const vtkRenderState* state);

  std::unique_ptr<sl::GpuReceivers> Receivers; // compiled once, reused frame after frame
  std::unique_ptr<sl::ComputeProgram> Selection;
  std::unique_ptr<sl::ComputeProgram> TileSelection;
};
