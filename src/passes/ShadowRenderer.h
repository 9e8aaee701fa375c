// Renders one frame of a scene with one technique and returns every buffer, read back to the CPU.
//
// The frame is a vtkSequencePass on a vtkRenderer of an offscreen EGL window:
//   gbuffer -> [focus -> shadow_map, when the technique needs a shadow map] -> technique -> shading
// Only the light-space structures the technique's descriptor lists are built.
#pragma once

#include "core/Image.h"
#include "lightspace/CameraView.h"
#include "lightspace/LightView.h"
#include "scene/Scene.h"
#include "techniques/Technique.h"

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

struct StageTiming
{
  std::string stage;
  double gpuMs = 0.0;
  double wallMs = 0.0;
};

struct NamedImage
{
  std::string name;
  ImageF image;
  std::string unit;
  std::string doc;
  BufferKind kind = BufferKind::Continuous;
  std::vector<std::string> categoryLabels;
};

// The image called `name` in `images`, or nullptr.
const NamedImage* findNamed(const std::vector<NamedImage>& images, const std::string& name);

struct FrameResult
{
  std::string technique;
  ParameterValues parameters;
  glm::ivec2 resolution{ 0 };
  CameraView camera;
  std::optional<LightView> lightView;
  std::vector<NamedImage> buffers;    // per pixel: visibility, position, normal, depth, coverage, albedo, technique's
  std::vector<NamedImage> lightSpace; // per shadow-map texel, for the structures that were built
  ImageU8 image;                      // shaded, RGB, row 0 at the bottom
  // The int32 summed-area table as stored (exact, for tests), when a technique built one in that precision.
  std::optional<Image<std::uint32_t>> integerSummedAreaTable;
  std::vector<StageTiming> stages;
  std::map<std::string, double> techniqueStatistics; // vtkSLTechniquePass::CollectStatistics
  double frameWallMs = 0.0;
  std::string glRenderer;
  std::string glVersion;
  std::string eglPlatform;

  const NamedImage* find(const std::string& name) const;
};

// The buffers every technique's buffers.vti has, with their documentation (README lists them).
const std::vector<BufferSpec>& commonBufferSpecs();
// The buffers of techniques with sub-lights (TechniqueDescriptor::hasSubLights): sublight_visibility.
const std::vector<BufferSpec>& subLightBufferSpecs();

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
  std::vector<vtkSmartPointer<vtkSLStagePass>>& stagesFor(const TechniqueDescriptor& technique, bool gbufferOnly);

  vtkSmartPointer<vtkSLEglRenderWindow> window_;
  vtkSmartPointer<vtkRenderer> renderer_;
  std::map<std::string, std::vector<vtkSmartPointer<vtkSLStagePass>>> stagesByTechnique_;
  // Techniques with sub-lights: the pass that runs their light-space and technique stages per sub-light.
  std::map<std::string, vtkSmartPointer<vtkSLMultiViewPass>> multiViewByTechnique_;
};

} // namespace sl
