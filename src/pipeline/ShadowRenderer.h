// Renders one frame of a scene with one technique and returns every buffer, read back to the CPU.
//
// The frame is a vtkSequencePass on a vtkRenderer of an offscreen EGL window:
//   gbuffer -> [focus -> shadow_map, when the technique needs a shadow map] -> technique -> shading
// Only the light-space structures the technique's descriptor lists are built.
#pragma once

#include "frame/FrameResult.h"
#include "scene/Scene.h"

#include <vtkSmartPointer.h>

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "gl/vtkSLEglRenderWindow.h"
#include "passes/vtkSLMultiViewPass.h"
#include "passes/vtkSLStagePass.h"
#include <vtkRenderer.h>

namespace sl
{

struct FrameResources;

struct RenderRequest
{
  std::string technique = "hard";
  std::vector<std::string> settings;   // "key=value", as given to --set
  std::optional<glm::ivec2> resolution; // overrides the scene camera's
  int lightIndex = 0;                   // which of the scene's lights casts the shadows
  // Only the G-buffer stage: buffers position, normal, depth, coverage, albedo, receives_shadows (no
  // visibility, no image). The ray-traced reference shades exactly these surface points.
  bool gbufferOnly = false;
  // G-buffer-only frames: render the G-buffer this many times multisampled (1 or 4) and report the sample positions
  // (FrameResult::samplePositions); the buffers then hold sample 0. Technique frames take their technique's
  // (TechniqueDescriptor::multisampleFor) and ignore this.
  int gbufferSamples = 1;
  // Shifts the camera so that pixel (x, y) sees window position (x + 0.5 + pixelOffset.x, y + 0.5 + pixelOffset.y):
  // the ray-traced reference's multisample mode traces each sample position this way (one G-buffer per sample).
  glm::dvec2 pixelOffset{ 0.0 };
};

class ShadowRenderer
{
public:
  ShadowRenderer(); // creates the EGL context; throws GraphicsError naming what was tried
  ~ShadowRenderer();
  ShadowRenderer(const ShadowRenderer&) = delete;
  ShadowRenderer& operator=(const ShadowRenderer&) = delete;

  // Throws InputError for bad requests (unknown technique/parameter, out-of-range value, unsupported light).
  FrameResult render(const Scene& scene, const RenderRequest& request);
  // The ray-traced reference's multisample mode: G-buffer-only frames of `request` (gbufferOnly is implied), one per
  // sample of a `samples`x multisampled G-buffer, each seen through that sample's position as GL reports it (the
  // camera shifted by position - 0.5: pixelOffset), so that frame s's pixel (x, y) holds the surface sample s of the
  // multisampled frame covers; an alpha texture is tested at the pixel centre (FrameResources::alphaTestOffset), as that
  // frame's one fragment per pixel tests it for all its samples. samples = 1: the one ordinary G-buffer.
  std::vector<FrameResult> renderSampleGBuffers(const Scene& scene, RenderRequest request, int samples);

  vtkSLEglRenderWindow* window() const { return window_; }
  // Forgets every remembered light-space build, so that the next frame builds every structure (bench's cold repeats).
  // Frames otherwise reuse a build whose inputs are unchanged (pipeline/StructureReuse.h).
  void forgetLightSpaceBuilds();

private:
  // The stage passes of each technique, built on first use and kept: their programs, framebuffers and
  // VAOs are reused frame after frame (warm frames are what benchmarks time).
  std::vector<vtkSmartPointer<vtkSLStagePass>>& stagesFor(const FrameResources& frame, bool gbufferOnly);
  static std::string stageKey(const FrameResources& frame);
  // The multi-view pass of a technique with sub-lights (nullptr otherwise, and for G-buffer-only frames).
  vtkSLMultiViewPass* multiViewFor(const FrameResources& frame, bool gbufferOnly);
  // The steps of render(), in order.
  void allocateFrameTargets(FrameResources& frame, const Scene& scene, bool gbufferOnly); // GPU scene, targets
  double renderStages(FrameResources& frame, bool gbufferOnly); // returns the frame's wall time (ms)
  void collectStageResults(const FrameResources& frame, bool gbufferOnly, FrameResult& result); // timings, stats
  // The technique's BufferSpec::fromPass buffers, from its pass (vtkSLTechniquePass::CollectPassBuffers).
  void appendPassBuffers(const FrameResources& frame, FrameResult& result);
  void releaseFrame(FrameResources& frame, bool gbufferOnly);

  vtkSmartPointer<vtkSLEglRenderWindow> window_;
  vtkSmartPointer<vtkRenderer> renderer_;
  std::map<std::string, std::vector<vtkSmartPointer<vtkSLStagePass>>> stagesByTechnique_;
  // Techniques with sub-lights: the pass that runs their light-space and technique stages per sub-light.
  std::map<std::string, vtkSmartPointer<vtkSLMultiViewPass>> multiViewByTechnique_;
  // The reuse attached to every light-space build stage of every stage list (forgetLightSpaceBuilds).
  std::vector<std::shared_ptr<StageReuse>> structureReuses_;
};

} // namespace sl
