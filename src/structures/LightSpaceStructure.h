// A light-space structure, described in one place: the shadow map, the moment map, the summed-area table, the
// min-max hierarchical shadow map (mip-map or N-buffers), the dual-grid MSSM, microrects and light sample sets. Each
// lives in its own folder under src/structures/ (build pass, typed settings, export, binding, build shaders), which
// its structure.cmake registers (cmake/Structures.cmake generates the registry in build order; src/structures/README.md).
//
// A technique lists the structures it needs (TechniqueDescriptor::lightStructures); the pipeline builds each of
// them, and what they are built from, once per frame (once per sub-light for multi-view), exports them in
// light_space.vti, reports their GPU memory in stats.json, and binds them to the technique's shader
// (vtkSLTechniquePass), so a technique pass never binds a structure itself.
//
// Layering: the CPU mirrors in src/lightspace/ are the `lightspace` area (below the passes); the structures'
// GPU parts in the sub-folders are the `structures` area, above `passes` and below `techniques`.
#pragma once

#include "core/NamedImage.h"
#include "core/Parameters.h"
#include "gl/ShaderLibrary.h"
#include "passes/FrameResources.h"
#include "passes/vtkSLStagePass.h"

#include <vtkSmartPointer.h>

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

class vtkShaderProgram;
class vtkTextureObject;

namespace sl
{

struct FrameResult;

struct LightSpaceStructure
{
  std::string name; // "summed_area_table": stats.json light_structures, `shadowlab list`
  std::string doc;  // one line, cites the paper
  // Structures its build reads; the pipeline builds them first (the shadow map for every other one).
  std::vector<const LightSpaceStructure*> builtFrom;
  // The parameters its build reads (through its typed settings, never by name in a shared pass). A technique
  // that needs the structure declares each of them, with the same choices and a range inside this one
  // (LightSpaceStructureTest checks).
  std::vector<ParameterSpec> parameters;
  // Parameters another structure declares (a name belongs to one structure) that its build reads too, such as the
  // moment map's prefilter_texels and prefilter_region for the layered moments: they key its reuse across frames.
  std::vector<std::string> sharedParameters;
  // Its build, one timed stage per pass (the pass's GetStageName() names the stage in stats.json).
  std::function<std::vector<vtkSmartPointer<vtkSLStagePass>>()> createBuildPasses;
  // Its arrays in light_space.vti, read back after the frame; `result` receives anything else it exports.
  std::function<std::vector<NamedImage>(const FrameResources& frame, FrameResult& result)> exportImages;
  // The GPU memory it holds once built (bytes), stats.json light_structure_gpu_bytes.
  std::function<std::size_t(const FrameResources& frame)> gpuBytes;
  // Defines its GLSL lookup needs in a technique's shader (may be empty), and its textures and uniforms;
  // bind returns the textures to deactivate after drawing.
  std::function<ShaderDefines(const FrameResources& frame)> shaderDefines;
  std::function<std::vector<vtkTextureObject*>(vtkShaderProgram* program, const FrameResources& frame)> bind;
  // The largest shadow-map size its build accepts on a GL whose 3D textures are at most max3dTextureSize per side (a
  // structure stored as a 3D texture as wide as the map); unset: no limit of its own. shadow_map_size = auto stays
  // within it; an explicit size beyond it is refused by the build, which names the limit.
  std::function<int(const ParameterValues& values, int max3dTextureSize)> largestMapSize;
};

// Every structure, in build order (a structure after those it is built from): its folder's structure.cmake ORDER.
const std::vector<const LightSpaceStructure*>& lightSpaceStructureRegistry();

// `needed` and every structure they are built from, each once, in registry (build) order.
std::vector<const LightSpaceStructure*> withBuildDependencies(const std::vector<const LightSpaceStructure*>& needed);

// GPU bytes of a 2-D or 3-D texture of `bytesPerTexel`, with its mip chain when `mipmapped`.
std::size_t textureBytes(vtkTextureObject* texture, std::size_t bytesPerTexel, bool mipmapped = false);

} // namespace sl
