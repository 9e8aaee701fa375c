// The `dcs` technique's pass (DcsTechnique.h): depth complexity sampling (Forest, Barthe & Paulin 2008, as used by
// Forest et al. 2009 §3.2) on the object-space seam of `shadow-volume`.
//  1. volumes: the reference sample's (the light centre's) count, the shadow-volume pass's z-fail count;
//  2. wedges: one screen polygon per potential-silhouette record (DcsGeometry.h), built on the CPU in double; each
//     fragment applies the per-sample update rule to its pixel's light-sample counters with image atomics
//     (dcs/shaders/DcsWedgeUpdate.glsl);
//  2b. STSVs: perforated casters (left out of steps 1 and 2, TechniqueDescriptor::perforatedCastersByStsv) through
//     their soft textured shadow volumes (objectspace/StsvDrawer.h): each fragment holding its point adds 1 to the counter of
//     every sample Eq. 1-5 hides (Forest et al. 2009 §3.2, shaders/stsv/StsvSamples.glsl with STSV_DCS_COUNTERS);
//  3. resolve: the base class's full-screen shader (dcs/shaders/DcsResolve.glsl) decodes the counters, checks their
//     range, and writes visibility and the instrumentation buffers, and the hidden-sample bit mask.
//
// Counters (the layout: DcsTechnique.h DcsCounterLayers). An R32UI 2-D array of N/4 + 3 layers: four 8-bit counters per
// word biased by 128 (no 8-bit stencil wrap: a counter holds the change relative to the centre, from -128 to +127),
// then two checksums and the covering count (shaders/dcs/DcsSampleCounters.glsl). Range check: packed words are summed
// modulo 2^32 in any order, so a word is exact whenever each of its final counters is in range; a counter out of range
// carries into its neighbour, which changes the decoded sum of changes by a multiple of 255 and the index-weighted sum
// differently. The resolve compares both with the sums the wedges added unpacked; a pixel that fails is marked
// counter_status = range exceeded (a cut-short mark: counted in stats.json, never passed off as exact). Memory: W H
// (N/4 + 3) 4 bytes of counters and W H ceil(N/32) 4 bytes of mask, reported as sample_buffer_bytes beside Forest et
// al. 2009's §5.1 formula.
#pragma once

#include "objectspace/DcsGeometry.h"
#include "objectspace/WedgeDrawer.h"
#include "objectspace/StsvDrawer.h"
#include "techniques/vtkSLShadowVolumePass.h"

#include <vtkNew.h>
#include <vtkSmartPointer.h>

#include <array>
#include <map>
#include <memory>
#include <string>
#include <vector>

class vtkOpenGLFramebufferObject;
class vtkPolyData;

class vtkSLDcsPass : public vtkSLShadowVolumePass
{
public:
  static vtkSLDcsPass* New();
  vtkTypeMacro(vtkSLDcsPass, vtkSLShadowVolumePass);
  void PrintSelf(ostream& os, vtkIndent indent) override;
  void ReleaseGraphicsResources(vtkWindow* window) override;

  std::map<std::string, double> CollectStatistics() override;
  // silhouettes.vtp (the centre's, from shadow-volume) and wedges.vtp (DcsWedgeExport.h).
  std::vector<sl::NamedPolyData> CollectObjectSpaceExports() override;
  // light_sample_mask, and sample_depth_complexity with export_sample_counts = 1.
  std::vector<sl::NamedImage> CollectPassBuffers() override;

protected:
  vtkSLDcsPass();
  ~vtkSLDcsPass() override;
  void Execute(const vtkRenderState* state) override;
  std::string GetFragmentShaderPath() const override { return "dcs/DcsResolve.glsl"; }
  // The counter layers of the frame's sample count (dcsCounterLayerShaderConstants).
  sl::ShaderDefines GetExtraDefines() const override;
  std::vector<PassShader> GetPassShaders() const override;
  std::vector<vtkTextureObject*> SetTechniqueUniforms(vtkShaderProgram* program) override;
  void AfterDraw() override;

private:
  vtkSLDcsPass(const vtkSLDcsPass&) = delete;
  void operator=(const vtkSLDcsPass&) = delete;

  void DrawWedges(vtkOpenGLRenderWindow* window);
  void DrawStsvs(vtkOpenGLRenderWindow* window);
  int SampleCount() const;

  sl::DcsEdgeSet Wedges;
  std::size_t DrawnWedges = 0;
  double WedgeBuildMilliseconds = 0.0;
  sl::UintArrayTexture Counters;
  sl::UintArrayTexture Mask;
  sl::WedgeDrawer WedgeDrawer;
  vtkNew<vtkOpenGLFramebufferObject> WedgeFramebuffer;
  sl::StsvDrawer Stsvs;
  sl::StepTimestamps Steps{ { "volumes", "wedges", "stsv", "resolve" } };
};
