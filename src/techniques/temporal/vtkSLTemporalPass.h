// The `temporal` technique's pass (TemporalTechnique.h): the frame loop of temporal reprojection (survey §4.6). For
// each of the K frames it shifts the frame's light view by the frame's sub-texel offset, renders the shadow map again
// (frame 0 uses the one the shadow-map stage rendered, unshifted), and runs temporal/shaders/TemporalVisibility.glsl,
// which reads the previous frame's history targets and writes this frame's. The history is two RGBA32F targets of
// this pass, in two sets that alternate; the pipeline's targets (visibility, depth_bias) hold the last frame's. The
// frame's light view and shadow map end as the last frame's, so the exported map and light view are the ones the
// last frame's lookups used. The technique stage's times therefore include K - 1 shadow-map renders. With camera_step
// > 0 each frame also renders its own G-buffer from its camera (temporalFrameCamera), the last one the scene's.
#pragma once

#include "gl/GlResources.h"
#include "lightspace/CameraView.h"
#include "passes/FullScreenQuad.h"
#include "techniques/vtkSLTechniquePass.h"

#include <vtkNew.h>
#include <vtkSmartPointer.h>

#include <map>
#include <string>
#include <vector>

class vtkOpenGLFramebufferObject;
class vtkSLGBufferPass;
class vtkTextureObject;

class vtkSLTemporalPass : public vtkSLTechniquePass
{
public:
  static vtkSLTemporalPass* New();
  vtkTypeMacro(vtkSLTemporalPass, vtkSLTechniquePass);
  void PrintSelf(ostream& os, vtkIndent indent) override;
  void ReleaseGraphicsResources(vtkWindow* window) override;
  std::vector<sl::NamedImage> CollectPassBuffers() override;
  std::map<std::string, double> CollectStatistics() override;

protected:
  vtkSLTemporalPass();
  ~vtkSLTemporalPass() override;
  void Execute(const vtkRenderState* state) override;
  std::string GetFragmentShaderPath() const override { return "temporal/TemporalVisibility.glsl"; }

private:
  vtkSLTemporalPass(const vtkSLTemporalPass&) = delete;
  void operator=(const vtkSLTemporalPass&) = delete;

  // The two sets of history targets, (re)made when the image size changes.
  void AllocateHistory(vtkOpenGLRenderWindow* window);
  // Renders the shadow map of the frame's (jittered) light view into this pass's own map targets.
  void RenderJitteredShadowMap(vtkOpenGLRenderWindow* window);
  // One frame of the history update: reads set (frameIndex + 1) % 2, writes set frameIndex % 2.
  void RunFrame(vtkOpenGLRenderWindow* window, int frameIndex, const sl::CameraView& historyCamera);

  vtkNew<vtkOpenGLFramebufferObject> TargetFramebuffer;
  vtkNew<vtkOpenGLFramebufferObject> MapFramebuffer;
  sl::FullScreenQuad Quad;
  sl::MeshDrawer Drawer;
  // camera_step > 0: renders each frame's G-buffer from that frame's camera.
  vtkSmartPointer<vtkSLGBufferPass> MovingCameraGBuffer;
  vtkSmartPointer<vtkTextureObject> MapLinear;
  vtkSmartPointer<vtkTextureObject> MapDepth;
  // RGBA32F: history_visibility, history_weight, history_frames, confidence; and history_depth, sample_visibility,
  // sample_confidence.
  vtkSmartPointer<vtkTextureObject> History[2];
  vtkSmartPointer<vtkTextureObject> Samples[2];
  int LastSet = 0;
  // export_frames=on: each frame's sample_visibility and sample_confidence, one component per frame.
  sl::ImageF FrameVisibility;
  sl::ImageF FrameConfidence;
  int FramesRendered = 0;
};
