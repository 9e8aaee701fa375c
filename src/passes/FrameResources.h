// Everything the passes of one frame share: inputs (scene, light, technique, camera), the targets each
// stage writes, and the light view fitted for this frame. The pipeline owns it; passes hold a pointer.
//
// G-buffer layout (all RGBA32F, cleared to 0, so w = 0 marks an uncovered pixel):
//   gbufferPosition   xyz = pWs (world position),            w = coverage (1 where a surface is seen)
//   gbufferNormal     xyz = nWs (unit, facing the camera),   w = 1 if the surface receives shadows
//   gbufferAlbedoDepth xyz = albedo,                          w = view depth (linear, along the camera axis)
#pragma once

#include "gl/GlResources.h"
#include "lightspace/CameraView.h"
#include "lightspace/HierarchicalShadowMap.h"
#include "lightspace/LightView.h"
#include "scene/WeldedMesh.h"
#include "scene/Scene.h"
#include "frame/TechniqueDescriptor.h"

#include <vtkSmartPointer.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

class vtkTextureObject;

namespace sl
{

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

  // Light-space stage (only when the technique needs the shadow map).
  bool hasLightView = false;
  LightView lightView;
  vtkSmartPointer<vtkTextureObject> shadowMapLinear; // R32F, linear depth along the light axis
  vtkSmartPointer<vtkTextureObject> shadowMapDepth;  // D32F, window depth (for hardware compare)
  // Moment-map stage: RGBA32F (z, z^2, exp(c z_n), 1), box-blurred (mip-mapped when prefilter = mipmap).
  vtkSmartPointer<vtkTextureObject> momentMap;
  // Summed-area-table stage: RG32F (centred z, z^2) or RG32UI (16-bit fixed-point z_n, z_n^2), see
  // shaders/sat/SatBuild.glsl.
  vtkSmartPointer<vtkTextureObject> summedAreaTable;
  bool summedAreaTableIsInteger = false;
  double summedAreaTableFixedPointScale = 0.0; // int32: 2^b - 1 (vtkSLSatPass picks b)
  // Hierarchical-shadow-map stage: RG32F (min, max) of levels 1..L, a mip-map atlas (N x N) or N-buffers
  // (N x N x L, layer k - 1 = level k), or the dual-grid MSSM ((N + 1)^2 x (L + 1), layer k = level k); see
  // src/lightspace/HierarchicalShadowMap.h.
  vtkSmartPointer<vtkTextureObject> hierarchicalShadowMap;
  HsmLayout hierarchicalShadowMapLayout = HsmLayout::MipMap;

  // Technique stage: "visibility" plus each buffer the descriptor publishes, all R32F. With sub-lights, the
  // combined targets once vtkSLMultiViewPass has run.
  std::map<std::string, vtkSmartPointer<vtkTextureObject>> techniqueTargets;
  // Multi-view (techniques with `sublights`): each sub-light's visibility, row by row over the S x S grid.
  std::vector<vtkSmartPointer<vtkTextureObject>> subLightVisibility;

  // Shading stage.
  vtkSmartPointer<vtkTextureObject> shadedImage; // RGBA8

  int width() const { return camera.resolution.x; }
  int height() const { return camera.resolution.y; }
};

} // namespace sl
