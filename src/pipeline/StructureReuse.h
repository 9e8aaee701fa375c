// Reuse of a light-space structure's build across frames (issue 33): a build stage is skipped when everything it
// reads is unchanged since the run that built it, and its results are put back into the frame instead.
//
// The key is everything a build reads, compared exactly (bytes of the doubles, not a tolerance): the fitted light
// view of this view (all matrices, window, depth range, resolution, warp), the view index and whether views partition
// the pixels, the light (the sub-light, inside the multi-view loop), the camera (a build may read the G-buffer), a
// hash of the scene's geometry and materials, the parameters the structure and every structure it is built from
// declare, the technique's LightSpaceRequest (the filter margin and the moment exponent a moment map reads from the
// technique), and the version of the content of every structure it is built from. The focus stage is never skipped:
// it depends on the camera and fits the light view the key holds.
//
// One remembered build per stage: a build pass keeps one set of textures and overwrites it at its next build, so an
// earlier build's results are gone once another ran. Consecutive runs with equal keys (frames of a still scene,
// bench repeats, sub-lights whose structure does not depend on the sub-light) reuse; anything else rebuilds.
#pragma once

#include "passes/FrameResources.h"
#include "passes/vtkSLStagePass.h"

#include <cstdint>
#include <optional>
#include <string>

namespace sl
{

struct LightSpaceStructure;
struct Scene;

// A 64-bit hash of everything of the scene a light-space build may read besides the light and the camera: each
// object's mesh (positions, normals, uvs, indices), its shadow flags and alpha texture. Computed once per frame.
std::uint64_t sceneGeometryHash(const Scene& scene);

// The key of `structure`'s build in `frame` at its current view (see above); a byte string compared exactly.
std::string structureBuildKey(const FrameResources& frame, const LightSpaceStructure& structure);

// The reuse of one build stage of `structure` (vtkSLStagePass::SetReuse).
class StructureBuildReuse : public StageReuse
{
public:
  explicit StructureBuildReuse(const LightSpaceStructure& structure);

  bool restore(FrameResources& frame) override;
  void remember(FrameResources& frame, double gpuMilliseconds) override;
  void forget() override;

  const LightSpaceStructure& structure() const { return structure_; }
  // The GPU time of the run that built the remembered results (ms); 0 when nothing is remembered.
  double buildGpuMillisecondsWhenBuilt() const { return remembered_ ? remembered_->buildGpuMilliseconds : 0.0; }

private:
  // What the build left in the frame: the shadow map's targets (the shadow map's build), the structure's
  // LightSpaceData (absent when the build erased it) and the version of its content.
  struct Remembered
  {
    std::string key;
    std::uint64_t version = 0;
    double buildGpuMilliseconds = 0.0;
    vtkSmartPointer<vtkTextureObject> shadowMapLinear;
    vtkSmartPointer<vtkTextureObject> shadowMapDepth;
    std::shared_ptr<LightSpaceData> data;
  };

  const LightSpaceStructure& structure_;
  bool isShadowMap_ = false;
  std::string pendingKey_; // computed in restore, for remember after the build
  std::optional<Remembered> remembered_;
};

} // namespace sl
