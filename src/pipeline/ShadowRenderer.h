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

  vtkSLEglRenderWindow* window() const { return window_; }

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
};

} // namespace sl
