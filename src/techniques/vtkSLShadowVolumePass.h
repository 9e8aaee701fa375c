// The `shadow-volume` technique's pass (ShadowVolumeTechnique.h): builds the volumes on the CPU, counts
// them per pixel with z-fail stencil in the G-buffer's depth-stencil, then runs the base class's full-screen
// resolve (shadowvolume/ShadowVolumeResolve.glsl).
//
// Why "behind the visible point" is decided from each volume triangle's plane and the G-buffer's position,
// not by the depth test against the G-buffer's depth. The count near a volume face is only as good as the
// depth the face is rasterised at, and a tessellated caster's silhouette edges are a fraction of a pixel
// long: extruded to infinity they make sliver triangles whose rasterised depth plane is tilted by the
// fixed-point snapping of their two close corners. Measured on llvmpipe at 160x160 with GL_GEQUAL against the
// G-buffer's depth: depth_complexity_center disagreed with the CPU crossing count on 52 of the bunny's 17164
// covered pixels (0.3 %), pixels where a side quad crosses the camera ray within 1e-4 of the distance to the
// point; with the plane test, on none of them, nor on any pixel of the other datasets. The plane test also
// makes the point the G-buffer's own position (the one the CPU twin is given), and receiver_offset replaces
// the equality a caster's own near cap would need with the depth test (bit-identical depths, which a near cap
// wound the other way round does not even get on llvmpipe: it came out in front along whole rows).
// The depth-stencil's depth is therefore not tested here, only its stencil written.
//
// The count checked against itself (buffer volume_count_status, a cut-short mark). The volume triangles are drawn a
// second time without the depth decision, summing every face's +1/-1 along the camera ray into VolumeCount's second
// component. Along the ray from the eye the faces sum to the number of volumes holding the eye (EyeVolumeCount, the
// CPU's winding number there; 0 for orthographic views, whose finite volumes the whole line enters and leaves), so a
// face lost or doubled by rasterisation makes it differ. A z-fail count below 0 is impossible too. Either marks the
// pixel inconsistent. A face put on the wrong side of the point (a grazing view of the point's own surface) escapes
// the first test and is marked only when it drives the count below 0.
#pragma once

#include "techniques/vtkSLTechniquePass.h"
#include "scene/WeldedMesh.h"
#include "objectspace/ShadowVolumeGeometry.h"

#include <vtkNew.h>
#include <vtkSmartPointer.h>

#include <map>
#include <string>
#include <vector>

class vtkOpenGLBufferObject;
class vtkOpenGLFramebufferObject;
class vtkOpenGLRenderWindow;
class vtkOpenGLVertexArrayObject;
class vtkPolyData;
class vtkTextureObject;

class vtkSLShadowVolumePass : public vtkSLTechniquePass
{
public:
  static vtkSLShadowVolumePass* New();
  vtkTypeMacro(vtkSLShadowVolumePass, vtkSLTechniquePass);
  void PrintSelf(ostream& os, vtkIndent indent) override;
  void ReleaseGraphicsResources(vtkWindow* window) override;

  std::map<std::string, double> CollectStatistics() override;
  // The last frame's silhouette edges (SilhouetteExport.h), written as silhouettes.vtp.
  std::vector<sl::NamedPolyData> CollectObjectSpaceExports() override;
  // volume_count_status (VolumeCountStatusImage).
  std::vector<sl::NamedImage> CollectPassBuffers() override;

protected:
  vtkSLShadowVolumePass();
  ~vtkSLShadowVolumePass() override;
  void Execute(const vtkRenderState* state) override;
  std::string GetFragmentShaderPath() const override { return "shadowvolume/ShadowVolumeResolve.glsl"; }
  std::vector<vtkTextureObject*> SetTechniqueUniforms(vtkShaderProgram* program) override;
  void AfterDraw() override;

  // Steps 1 and 2 (ShadowVolumeTechnique.h): the volumes from the light's centre, built on the CPU, and their z-fail
  // count into VolumeCount and the G-buffer's stencil. Technique `dcs` takes its reference sample's count from here.
  void BuildAndCountVolumes(vtkOpenGLRenderWindow* window);
  // The camera-ray uniforms and receiverOffsetS / receiverOffsetPerS (parameter receiver_offset) of a shader that
  // finds the counted point as shadowvolume/ShadowVolumeCount.glsl does.
  void SetReceiverOffsetUniforms(vtkShaderProgram* program) const;

  // The buffer volume_count_status (the self-check above) from VolumeCount and the G-buffer's coverage; dcs and
  // penumbra-wedge add it to their own pass buffers.
  sl::NamedImage VolumeCountStatusImage() const;

  // RG32F: x the exact z-fail count, y the signed sum of every volume face along the ray (the self-check above).
  vtkSmartPointer<vtkTextureObject> VolumeCount;
  double EyeVolumeCount = 0.0; // volumes holding the eye (0 for orthographic views), for the self-check
  sl::ShadowVolumeStatistics Statistics;
  double BuildMilliseconds = 0.0;
  vtkSmartPointer<vtkPolyData> Silhouettes;

private:
  vtkSLShadowVolumePass(const vtkSLShadowVolumePass&) = delete;
  void operator=(const vtkSLShadowVolumePass&) = delete;

  void CountVolumes(vtkOpenGLRenderWindow* window, const sl::ShadowVolumeGeometry& geometry);

  vtkSmartPointer<vtkOpenGLBufferObject> VolumeVertices;
  vtkSmartPointer<vtkOpenGLVertexArrayObject> VolumeArray;
  vtkNew<vtkOpenGLFramebufferObject> CountFramebuffer;
};
