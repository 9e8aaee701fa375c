#include "techniques/temporal/vtkSLTemporalPass.h"

#include "core/Error.h"
#include "passes/FrameResources.h"
#include "passes/PassUtilities.h"
#include "passes/ScopedRenderTarget.h"
#include "passes/ShadowMapRendering.h"
#include "passes/vtkSLGBufferPass.h"
#include "structures/shadowmap/ShadowMapStructure.h"
#include "techniques/temporal/TemporalTechnique.h"

#include <vtkObjectFactory.h>
#include <vtkOpenGLFramebufferObject.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkRenderState.h>
#include <vtkRenderer.h>
#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>

vtkStandardNewMacro(vtkSLTemporalPass);

vtkSLTemporalPass::vtkSLTemporalPass() = default;
vtkSLTemporalPass::~vtkSLTemporalPass() = default;

void vtkSLTemporalPass::AllocateHistory(vtkOpenGLRenderWindow* window)
{
  const sl::FrameResources& frame = *this->Frame;
  for (int set = 0; set < 2; ++set)
  {
    for (vtkSmartPointer<vtkTextureObject>* target : { &this->History[set], &this->Samples[set] })
    {
      if (!*target || (*target)->GetContext() != window || static_cast<int>((*target)->GetWidth()) != frame.width() ||
        static_cast<int>((*target)->GetHeight()) != frame.height())
      {
        *target = sl::makeFloatTarget(window, frame.width(), frame.height(), 4);
      }
    }
  }
}

void vtkSLTemporalPass::RenderJitteredShadowMap(vtkOpenGLRenderWindow* window)
{
  sl::FrameResources& frame = *this->Frame;
  const int size = frame.lightView.resolution;
  if (!this->MapLinear || this->MapLinear->GetContext() != window || static_cast<int>(this->MapLinear->GetWidth()) != size)
  {
    this->MapLinear = sl::makeFloatTarget(window, size, size, 1);
    this->MapDepth = sl::makeDepthTarget(window, size, size);
  }
  sl::renderShadowMap(window, this->MapFramebuffer, this->Drawer, *frame.gpuScene, frame.lightView,
    sl::shadowMapSettings(frame).secondDepth, this->MapLinear, this->MapDepth);
  frame.shadowMapLinear = this->MapLinear;
  frame.shadowMapDepth = this->MapDepth;
}

void vtkSLTemporalPass::RunFrame(vtkOpenGLRenderWindow* window, int frameIndex, const sl::CameraView& historyCamera)
{
  sl::FrameResources& frame = *this->Frame;
  const int written = frameIndex % 2;
  const int read = 1 - written;
  std::vector<vtkTextureObject*> targets = this->TechniqueTargets();
  targets.push_back(this->History[written]);
  targets.push_back(this->Samples[written]);
  const sl::ScopedRenderTarget target(window, this->TargetFramebuffer, targets);
  const std::string fragmentSource =
    sl::assembleShader(this->GetFragmentShaderPath(), this->TechniqueDefines(), this->ParameterDeclarations());
  vtkShaderProgram* program = this->Quad.ready(window, fragmentSource, frame.technique->name);
  std::vector<vtkTextureObject*> bound = this->SetCommonUniforms(program);
  bound.push_back(sl::bindTexture(program, "historyTarget", this->History[read]));
  bound.push_back(sl::bindTexture(program, "historySampleTarget", this->Samples[read]));
  program->SetUniformi("temporalFrameIndex", frameIndex);
  // A static camera: the history's camera is the frame's (reprojection is the identity, and the disocclusion test
  // compares the same depths).
  sl::setMatrix(program, "historyClipFromWorld", historyCamera.clipFromWorld);
  sl::setMatrix(program, "historyViewFromWorld", historyCamera.viewFromWorld);
  sl::setMatrix(program, "currentViewFromWorld", frame.camera.viewFromWorld);
  this->Quad.render();
  for (vtkTextureObject* texture : bound)
  {
    texture->Deactivate();
  }
}

void vtkSLTemporalPass::Execute(const vtkRenderState* state)
{
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(state->GetRenderer()->GetRenderWindow());
  sl::FrameResources& frame = *this->Frame;
  SL_CHECK_MSG(frame.hasLightView, "the temporal pass needs the shadow map's stages before it");
  const sl::TemporalSettings settings = sl::TemporalSettings::from(frame.parameters);
  const sl::LightView base = frame.lightView;
  this->AllocateHistory(window);
  if (settings.exportFrames)
  {
    this->FrameVisibility = sl::ImageF(frame.width(), frame.height(), settings.frames);
    this->FrameConfidence = sl::ImageF(frame.width(), frame.height(), settings.frames);
  }
  const bool movingCamera = settings.cameraStep != 0.0 && settings.frames > 1;
  if (movingCamera && !this->MovingCameraGBuffer)
  {
    this->MovingCameraGBuffer = vtkSmartPointer<vtkSLGBufferPass>::New();
  }
  sl::CameraView historyCamera = frame.camera;
  for (int k = 0; k < settings.frames; ++k)
  {
    if (k > 0)
    {
      frame.lightView = sl::jitteredLightView(base, sl::temporalJitterOffset(k));
      this->RenderJitteredShadowMap(window);
    }
    if (movingCamera)
    {
      // The light view stays the one focused on the scene camera's receivers (the last frame's).
      frame.camera = sl::temporalFrameCamera(*frame.scene, frame.camera.resolution, settings.cameraStep, k, settings.frames);
      this->MovingCameraGBuffer->SetFrame(&frame);
      this->MovingCameraGBuffer->Render(state);
    }
    this->RunFrame(window, k, historyCamera);
    historyCamera = frame.camera;
    if (settings.exportFrames)
    {
      const sl::ImageF samples = sl::readFloatTexture(this->Samples[k % 2], 4);
      for (std::size_t i = 0; i < samples.pixelCount(); ++i)
      {
        this->FrameVisibility.data[i * settings.frames + k] = samples.data[i * 4 + 1];
        this->FrameConfidence.data[i * settings.frames + k] = samples.data[i * 4 + 2];
      }
    }
  }
  if (movingCamera)
  {
    this->MovingCameraGBuffer->SetFrame(nullptr);
  }
  this->FramesRendered = settings.frames;
  this->LastSet = (settings.frames - 1) % 2;
}

std::vector<sl::NamedImage> vtkSLTemporalPass::CollectPassBuffers()
{
  SL_CHECK(this->Frame && this->History[this->LastSet]);
  const sl::TemporalSettings settings = sl::TemporalSettings::from(this->Frame->parameters);
  const sl::ImageF history = sl::readFloatTexture(this->History[this->LastSet], 4);
  const sl::ImageF samples = sl::readFloatTexture(this->Samples[this->LastSet], 4);
  std::vector<sl::NamedImage> buffers;
  const auto add = [&](const char* name, sl::ImageF image) {
    buffers.emplace_back();
    buffers.back().name = name;
    buffers.back().image = std::move(image);
  };
  add("history_visibility", history.channels(0, 1));
  add("history_weight", history.channels(1, 1));
  add("history_frames", history.channels(2, 1));
  add("confidence", history.channels(3, 1));
  add("history_depth", samples.channels(0, 1));
  add("sample_visibility", samples.channels(1, 1));
  add("sample_confidence", samples.channels(2, 1));
  // Flagged where a shadow test ran (history_frames > 0) and no frame's confidence reached the threshold; compared in
  // float, as the shader would.
  sl::ImageF unconverged(history.width, history.height, 1);
  const float threshold = static_cast<float>(settings.confidenceThreshold);
  for (std::size_t i = 0; i < unconverged.pixelCount(); ++i)
  {
    unconverged.data[i] = history.data[i * 4 + 2] > 0.0f && history.data[i * 4 + 3] < threshold ? 1.0f : 0.0f;
  }
  add("unconverged", std::move(unconverged));
  if (settings.exportFrames)
  {
    add("sample_visibility_frames", this->FrameVisibility);
    add("sample_confidence_frames", this->FrameConfidence);
  }
  return buffers;
}

std::map<std::string, double> vtkSLTemporalPass::CollectStatistics()
{
  return { { "temporal_shadow_map_renders", static_cast<double>(this->FramesRendered) } };
}

void vtkSLTemporalPass::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Quad.releaseGraphicsResources(window);
  this->TargetFramebuffer->ReleaseGraphicsResources(window);
  this->MapFramebuffer->ReleaseGraphicsResources(window);
  this->Drawer.releaseGraphicsResources(vtkOpenGLRenderWindow::SafeDownCast(window));
  if (this->MovingCameraGBuffer)
  {
    this->MovingCameraGBuffer->ReleaseGraphicsResources(window);
    this->MovingCameraGBuffer = nullptr;
  }
  this->MapLinear = nullptr;
  this->MapDepth = nullptr;
  for (int set = 0; set < 2; ++set)
  {
    this->History[set] = nullptr;
    this->Samples[set] = nullptr;
  }
  this->Superclass::ReleaseGraphicsResources(window);
}

void vtkSLTemporalPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FramesRendered: " << this->FramesRendered << "\n";
}
