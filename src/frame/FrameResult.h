// What one frame produced, read back to the CPU: every buffer, the light-space exports, the shaded image, the
// timings and the technique's statistics. The pipeline (pipeline/ShadowRenderer.h) makes it; outputs
// (output/OutputWriter.h), metrics and the bench consume it without knowing the passes.
#pragma once

#include "core/Image.h"
#include "core/NamedImage.h"
#include "frame/TechniqueDescriptor.h"
#include "lightspace/AutomaticMapSize.h"
#include "lightspace/CameraView.h"
#include "lightspace/PartitionViews.h"
#include "lightspace/LightView.h"

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace sl
{

struct StageTiming
{
  std::string stage;
  double gpuMs = 0.0;
  double wallMs = 0.0;
};

// An object-space export of a technique that draws scene geometry (silhouette edges, shadow volumes, wedges),
// written as <name>.vtp beside light_space.vti, openable in ParaView.
struct NamedPolyData
{
  std::string name; // file stem: "silhouettes" -> silhouettes.vtp
  std::string doc;  // what the cells and their arrays are (stats.json "object_space")
  vtkSmartPointer<vtkPolyData> data;
};

struct FrameResult
{
  std::string technique;
  const TechniqueDescriptor* descriptor = nullptr; // the registry's entry for `technique`
  ParameterValues parameters;
  glm::ivec2 resolution{ 0 };
  CameraView camera;
  std::optional<LightView> lightView; // with views that partition the pixels, view 0's
  std::optional<AutomaticMapSize> automaticMapSize; // shadow_map_size = auto: how its size was chosen
  // Views that partition the pixels (survey §4.3, PartitionViews.h): cascades > 1 (§4.3.1), with their split depths.
  std::optional<PartitionSet> partitions;
  std::vector<NamedImage> buffers;    // per pixel: visibility, position, normal, depth, coverage, albedo, technique's
  std::vector<NamedImage> lightSpace; // per shadow-map texel, for the structures that were built
  std::vector<NamedPolyData> objectSpace; // geometry an object-space technique exports (vtkSLTechniquePass)
  std::vector<std::string> lightStructureNames; // the structures the technique reads (descriptor order)
  std::map<std::string, std::size_t> lightStructureGpuBytes; // by structure name, every structure that was built
  // By structure name, every structure whose build can be reused across frames (pipeline/StructureReuse.h): whether
  // this frame reused it (no run of its build stages executed), the GPU time its builds took in this frame (0 when
  // reused), and the GPU time of the run that built the results it now holds.
  struct LightStructureBuild
  {
    bool reused = false;
    double buildGpuMs = 0.0;
    double buildGpuMsWhenBuilt = 0.0;
  };
  std::map<std::string, LightStructureBuild> lightStructureBuilds;
  ImageU8 image;                      // shaded, RGB, row 0 at the bottom
  // The int32 summed-area table as stored (exact, for tests), when a technique built one in that precision.
  std::optional<Image<std::uint32_t>> integerSummedAreaTable;
  // The moment SAT's words as stored (exact, for tests), 8 per texel: the low words of its four sums, then the high.
  std::optional<Image<std::uint32_t>> momentSummedAreaTable;
  std::vector<StageTiming> stages;
  std::map<std::string, double> techniqueStatistics; // vtkSLTechniquePass::CollectStatistics
  double frameWallMs = 0.0;
  std::string glRenderer;
  std::string glVersion;
  std::string eglPlatform;
  int eglDeviceIndex = -1;   // among the hardware EGL devices; -1: none (surfaceless, default display)
  std::string eglDevice;     // EglContext::deviceDescription()
  // Multisampled frames (MultisampleSettings, RenderRequest::gbufferSamples): the G-buffer's sample positions within
  // the pixel, in [0, 1)^2 as GL reports them (glGetMultisamplefv); empty when single-sampled.
  std::vector<glm::dvec2> samplePositions;

  const NamedImage* find(const std::string& name) const;
  // The shadow map's size as rendered, given or chosen by shadow_map_size = auto (reference-sm's K maps have no
  // light view of their own, only the automatic choice); nullopt for a frame without a map.
  std::optional<int> shadowMapSize() const;
};

// Pixels whose value was cut short (BufferSpec::cutShortCode of the technique's categorical buffers): not exact.
struct CutShortPixels
{
  std::string buffer; // the categorical buffer that marks them, e.g. "packet_class"
  std::string label;  // the marking category's label
  std::size_t count = 0;
};
// The technique's cut-short marks in `frame`'s buffers; nullopt for a technique that declares none.
std::optional<CutShortPixels> cutShortPixels(const FrameResult& frame);

// Pixels a technique's continuous buffer flags (BufferSpec::flagAtOrAbove): one entry per such buffer of the frame.
struct FlaggedPixels
{
  std::string buffer;
  double threshold = 0.0;
  std::string warning; // BufferSpec::flagWarning
  std::size_t count = 0;
};
std::vector<FlaggedPixels> flaggedPixels(const FrameResult& frame);

// The buffers every technique's buffers.vti has, with their documentation (docs/outputs.md lists them).
const std::vector<BufferSpec>& commonBufferSpecs();
// The buffers of techniques with sub-lights (TechniqueDescriptor::hasSubLights): sublight_visibility.
const std::vector<BufferSpec>& subLightBufferSpecs();
// The buffers of multisampled frames (MultisampleSettings::samples > 1): msaa_distinct_samples,
// msaa_interpolated_samples, msaa_pixel_visibility, msaa_sample_depth, msaa_sample_visibility.
const std::vector<BufferSpec>& multisampleBufferSpecs();

} // namespace sl
