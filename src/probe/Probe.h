// `shadowlab probe` (issue 15): replay one pixel of a rendered frame on the technique's CPU twin with a recorder,
// and present what it recorded: probe.json (every quantity with unit and source), probe.vtm (world space,
// shadow-map space and the light plane as VTK data for ParaView) and probe.png (a figure). The probe command,
// the viewer (`shadowlab view`) and the lessons (`shadowlab lessons`) all go through these functions.
#pragma once

#include "core/Image.h"
#include "frame/FrameResult.h"
#include "frame/ProbeRecord.h"
#include "scene/Scene.h"

#include <nlohmann/json.hpp>
#include <vtkSmartPointer.h>

#include <glm/glm.hpp>

#include <string>

class vtkMultiBlockDataSet;

namespace sl
{

struct ProbeResult
{
  std::string technique;
  glm::ivec2 pixel{ 0 };     // image coordinates, row 0 at the bottom (as the buffers)
  int lightIndex = 0;
  ProbeOutcome outcome;      // the twin's visibility, tolerance, ambiguity
  double gpuVisibility = 0.0; // the frame's `visibility` at the pixel (multisampled: msaa_pixel_visibility)
  ProbeRecord record;

  double difference() const;
  // |GPU - twin| within the tolerance, or the pixel is ambiguous (outcome.ambiguity) or not evaluated by the twin
  // while the GPU agrees on the value.
  bool agrees() const;
};

// Validates the pixel (inside the image; a covered pixel, not background) and the technique (has a probe), then
// replays it. Throws InputError with one line naming --pixel or --technique.
ProbeResult probePixel(const FrameResult& frame, const Scene& scene, int lightIndex, glm::ivec2 pixel);

// The pixel whose centre's camera ray passes nearest to `world` among the covered pixels whose G-buffer
// position is within `tolerance` world units of it (`--pick world x,y,z`): the point must be visible. Throws
// InputError naming --pick otherwise.
glm::ivec2 pickPixel(const FrameResult& frame, const glm::dvec3& world, double tolerance);

// probe.json's content: the probe's header (technique, pixel, GPU and twin visibility, tolerance, ambiguity, the
// technique's parameters, light) and every record item with its unit and source.
nlohmann::json probeJson(const ProbeResult& probe, const FrameResult& frame, const Scene& scene);

// probe.vtm's content (probe/ProbeDataSet.cxx), every block in world units: "world" (light, receiver point and
// normal, segments to the light's corners or samples, the kernel's frustum), "shadow_map" (a crop of the map around
// the kernel as a vtkStructuredGrid with per-texel arrays read / compared / occluding / visited_level; rectangles
// of visited nodes and kernels; placed on the receiver's plane through the light view, texel coordinates in
// texel_uv), "light_plane" (back-projected polygons or micro-occluders clipped to the light, light samples).
vtkSmartPointer<vtkMultiBlockDataSet> probeDataSet(const ProbeResult& probe, const FrameResult& frame, const Scene& scene);

// probe.png (probe/ProbeFigure.cxx): panels drawn on a CPU canvas (vis/Canvas.h, text through VTK's FreeType
// renderer; no GL context needed, so the viewer can call it between frames): the image with the pixel marked, the shadow-map
// crop with kernel and traversal, the light plane with what covers it, a cross-section through the light centre
// and the receiver point, the algorithm's own diagrams (PCSS's similar triangles, the Chebyshev bound) and every
// recorded quantity over as many key-number pages as it takes; only panels with content (layout in
// probe/ProbeFigure.h, drawProbeFigure). RGB, row 0 at the bottom.
ImageU8 probeFigure(const ProbeResult& probe, const FrameResult& frame, const Scene& scene);

} // namespace sl
