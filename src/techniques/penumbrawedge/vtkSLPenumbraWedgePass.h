// The `penumbra-wedge` technique's pass (PenumbraWedgeTechnique.h), on the object-space seam of `shadow-volume`:
//  1. volumes: the light centre's count, the shadow-volume pass's z-fail count (the hard shadow from the centre);
//  2. wedges: one screen polygon per centre-silhouette wedge (DcsGeometry.h, drawn by WedgeDrawer); each fragment
//     adds the wedge's signed share of the light (penumbrawedge/shaders/PenumbraWedgeArea.glsl) to an R32F occlusion
//     target and 1 to a covering count, by additive blending;
//  3. STSVs: for every perforated triangle its one or two soft textured shadow volumes (objectspace/StsvGeometry.h, built on
//     the CPU in double), drawn as the screen polygon of their closed mesh (the whole viewport when the mesh is
//     truncated); each fragment holding its point in the volume ORs the samples Eq. 1-5 hide into the pixel's mask
//     (R32UI array, image atomics; shaders/penumbrawedge/StsvSamples.glsl) and counts itself (covering, empty);
//  4. resolve: the base class's full-screen shader (PenumbraWedgeResolve.glsl).
#pragma once

#include "objectspace/DcsGeometry.h"
#include "gl/GlResources.h"
#include "objectspace/WedgeDrawer.h"
#include "objectspace/StsvDrawer.h"
#include "techniques/vtkSLShadowVolumePass.h"

#include <vtkNew.h>
#include <vtkSmartPointer.h>

#include <array>
#include <map>
#include <string>
#include <vector>

class vtkOpenGLFramebufferObject;
class vtkTextureObject;

class vtkSLPenumbraWedgePass : public vtkSLShadowVolumePass
{
public:
  static vtkSLPenumbraWedgePass* New();
  vtkTypeMacro(vtkSLPenumbraWedgePass, vtkSLShadowVolumePass);
  void PrintSelf(ostream& os, vtkIndent indent) override;
  void ReleaseGraphicsResources(vtkWindow* window) override;

  std::map<std::string, double> CollectStatistics() override;
  // silhouettes.vtp (the centre's, from shadow-volume) and wedges.vtp (the centre-silhouette wedges drawn).
  std::vector<sl::NamedPolyData> CollectObjectSpaceExports() override;
  // light_sample_mask: the STSVs' LS_buffer, N/16 components of 16 bits.
  std::vector<sl::NamedImage> CollectPassBuffers() override;

protected:
  vtkSLPenumbraWedgePass();
  ~vtkSLPenumbraWedgePass() override;
  void Execute(const vtkRenderState* state) override;
  std::string GetFragmentShaderPath() const override { return "penumbrawedge/PenumbraWedgeResolve.glsl"; }
  std::vector<PassShader> GetPassShaders() const override;
  std::vector<vtkTextureObject*> SetTechniqueUniforms(vtkShaderProgram* program) override;
  void AfterDraw() override;

private:
  vtkSLPenumbraWedgePass(const vtkSLPenumbraWedgePass&) = delete;
  void operator=(const vtkSLPenumbraWedgePass&) = delete;

  void DrawWedges(vtkOpenGLRenderWindow* window);
  void DrawStsvs(vtkOpenGLRenderWindow* window);
  int SampleCount() const;

  sl::DcsEdgeSet Wedges; // the centre silhouettes' wedges (statistics: of all potential silhouettes)
  std::size_t DrawnWedges = 0;
  double WedgeBuildMilliseconds = 0.0;
  sl::WedgeDrawer WedgeDrawer;
  vtkSmartPointer<vtkTextureObject> OcclusionDelta; // R32F, the wedges' summed signed shares
  vtkSmartPointer<vtkTextureObject> WedgesCovering; // R32F, wedges whose region holds the point
  vtkNew<vtkOpenGLFramebufferObject> WedgeFramebuffer;
  sl::StsvDrawer Stsvs;
  sl::UintArrayTexture Mask; // the LS_buffer: N/32 layers
  vtkSmartPointer<vtkTextureObject> StsvCovering;  // R32F
  vtkSmartPointer<vtkTextureObject> StsvEmptyHits; // R32F
  vtkNew<vtkOpenGLFramebufferObject> StsvFramebuffer;
  sl::StepTimestamps Steps{ { "volumes", "wedges", "stsv", "resolve" } };
};
