// Everything the passes of one frame share: inputs (scene, light, technique, camera), the targets each
// stage writes, and the light view fitted for this frame. The pipeline owns it; passes hold a pointer.
//
// G-buffer layout (all RGBA32F, cleared to 0, so w = 0 marks an uncovered pixel):
//   gbufferPosition   xyz = pWs (world position),            w = coverage (1 where a surface is seen)
//   gbufferNormal     xyz = nWs (unit, facing the camera),   w = 1 if the surface receives shadows
//   gbufferAlbedoDepth xyz = albedo,                          w = view depth (linear, along the camera axis)
#pragma once

#include "core/Error.h"
#include "gl/GlResources.h"
#include "lightspace/AutomaticMapSize.h"
#include "lightspace/CameraView.h"
#include "lightspace/PartitionViews.h"
#include "lightspace/LightView.h"
#include "scene/WeldedMesh.h"
#include "scene/Scene.h"
#include "frame/TechniqueDescriptor.h"

#include <vtkSmartPointer.h>

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

class vtkTextureObject;

namespace sl
{

// What a light-space structure's build leaves in the frame; each structure derives its own.
struct LightSpaceData
{
  virtual ~LightSpaceData() = default;
};

struct FrameResources
{
  // Inputs.
  const Scene* scene = nullptr;
  const Light* light = nullptr;
  const TechniqueDescriptor* technique = nullptr;
  ParameterValues parameters;
  CameraView camera;
  std::unique_ptr<GpuScene> gpuScene;
  // The casters with welded connectivity, in scene order; only for techniques that draw scene geometry
  // (TechniqueDescriptor::drawsSceneGeometry), welded once per frame before the timed stages.
  std::shared_ptr<const std::vector<WeldedMesh>> weldedCasters;

  // G-buffer stage.
  vtkSmartPointer<vtkTextureObject> gbufferPosition;
  vtkSmartPointer<vtkTextureObject> gbufferNormal;
  vtkSmartPointer<vtkTextureObject> gbufferAlbedoDepth;
  vtkSmartPointer<vtkTextureObject> gbufferDepth; // GL_DEPTH32F_STENCIL8, stencil cleared to 0
  // Multisampled frames (TechniqueDescriptor::multisampleFor, RenderRequest::gbufferSamples): the G-buffer rendered
  // gbufferSamples x multisampled, one fragment per pixel and primitive (attributes at the pixel centre, extrapolating
  // the primitive: SS08 §7), into these targets; the single-sampled ones above then hold sample 0.
  MultisampleSettings multisample;
  vtkSmartPointer<vtkTextureObject> gbufferMsPosition;
  vtkSmartPointer<vtkTextureObject> gbufferMsNormal;
  vtkSmartPointer<vtkTextureObject> gbufferMsAlbedoDepth;
  vtkSmartPointer<vtkTextureObject> gbufferMsDepth;
  std::vector<glm::dvec2> samplePositions; // in the pixel, [0, 1)^2 (glGetMultisamplefv)
  // Where the G-buffer's alpha test reads an alpha texture, in pixels from the fragment's own position. A multisampled
  // G-buffer runs one fragment per pixel and primitive, so its alpha test decides at the pixel centre for every sample;
  // the reference's per-sample frames (RenderRequest::pixelOffset) are shifted by the sample's offset and test at
  // -pixelOffset to decide as it does.
  glm::dvec2 alphaTestOffset{ 0.0 };
  // The MSAA resolve's outputs (passes/vtkSLMsaaResolvePass.h): the technique's visibility before it, then RGBA32F,
  // one component per sample, and the counts.
  vtkSmartPointer<vtkTextureObject> pixelVisibility;
  vtkSmartPointer<vtkTextureObject> sampleVisibility;
  vtkSmartPointer<vtkTextureObject> sampleDepth;
  vtkSmartPointer<vtkTextureObject> distinctSamples;     // R32F
  vtkSmartPointer<vtkTextureObject> interpolatedSamples; // R32F

  // The shadow map (structures/shadowmap), the structure every other one is built from (only when the technique
  // needs it).
  bool hasLightView = false;
  LightView lightView;
  // shadow_map_size = auto: how the focus stage chose the size (lightspace/AutomaticMapSize.h).
  std::optional<AutomaticMapSize> automaticMapSize;
  vtkSmartPointer<vtkTextureObject> shadowMapLinear; // R32F, linear depth along the light axis
  vtkSmartPointer<vtkTextureObject> shadowMapDepth;  // D32F, window depth (for hardware compare)
  // Views that partition the pixels (survey §4.3, lightspace/PartitionViews.h; vtkSLMultiViewPass): whether the stages
  // run in that loop (decided before GL, from the parameters and the light), the view the inner stages run for now,
  // every view's fit (the focus fits all at view 0; none when it finds one map enough), each view's maps (the light
  // depth pass keeps them for the export), and the per-pixel selection (RGBA32F: primary view, secondary view,
  // primary's weight, 0).
  bool partitioned = false;
  // The techniques with cube shadow maps (survey §2: those that list cube_map), for the refusal of a point light one
  // map cannot cover ("hard, pcf").
  std::string cubeMapTechniques;
  int viewIndex = 0;
  std::optional<PartitionSet> partitions;
  std::vector<vtkSmartPointer<vtkTextureObject>> viewShadowMapLinear;
  std::vector<vtkSmartPointer<vtkTextureObject>> viewShadowMapDepth;
  vtkSmartPointer<vtkTextureObject> viewSelection;
  // The other light-space structures (structures/LightSpaceStructure.h), by structure name: what each one's
  // build left for its binding and export (e.g. structures/sat/SatStructure.h's SummedAreaTableData).
  std::map<std::string, std::shared_ptr<LightSpaceData>> lightSpaceData;
  // Reuse of light-space builds across frames (pipeline/StructureReuse.h): a hash of the scene's geometry and
  // materials, computed once per frame before the stages, and the version of each structure's content in this frame
  // (a new number at every build, kept when reused), which the key of every structure built from it includes.
  std::uint64_t sceneGeometryHash = 0;
  std::map<std::string, std::uint64_t> structureVersions;

  // Technique stage: "visibility" plus each buffer the descriptor publishes, all R32F. With sub-lights, the
  // combined targets once vtkSLMultiViewPass has run.
  std::map<std::string, vtkSmartPointer<vtkTextureObject>> techniqueTargets;
  // Multi-view (techniques with `sublights`): each sub-light's visibility, row by row over the S x S grid.
  std::vector<vtkSmartPointer<vtkTextureObject>> subLightVisibility;

  // Shading stage.
  vtkSmartPointer<vtkTextureObject> shadedImage; // RGBA8

  int width() const { return camera.resolution.x; }
  // The data the structure `name` left in this frame (SL_CHECKs it was built, with that type).
  template <class Data>
  const Data& structureData(const std::string& name) const
  {
    const auto found = lightSpaceData.find(name);
    SL_CHECK_MSG(found != lightSpaceData.end(), "light-space structure ", name, " was not built");
    const auto* data = dynamic_cast<const Data*>(found->second.get());
    SL_CHECK_MSG(data, "light-space structure ", name, " holds another type of data");
    return *data;
  }
  int height() const { return camera.resolution.y; }
};

} // namespace sl
