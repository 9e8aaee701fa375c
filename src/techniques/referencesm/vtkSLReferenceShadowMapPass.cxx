#include "techniques/referencesm/vtkSLReferenceShadowMapPass.h"
#include "techniques/referencesm/ReferenceSmTechnique.h"

#include "core/Error.h"
#include "lightspace/LightSamples.h"
#include "passes/FrameResources.h"
#include "passes/PassUtilities.h"
#include "structures/shadowmap/ShadowMapStructure.h"
#include "core/Progress.h"
#include "passes/ScopedRenderTarget.h"
#include "passes/ShadowMapRendering.h"

#include <vtkObjectFactory.h>
#include <vtkOpenGLFramebufferObject.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkOpenGLState.h>
#include <vtkRenderState.h>
#include <vtkRenderer.h>
#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>
#include <vtk_glew.h>

#include <algorithm>

vtkStandardNewMacro(vtkSLReferenceShadowMapPass);

vtkSLReferenceShadowMapPass::vtkSLReferenceShadowMapPass() = default;
vtkSLReferenceShadowMapPass::~vtkSLReferenceShadowMapPass() = default;

void vtkSLReferenceShadowMapPass::Execute(const vtkRenderState* state)
{
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(state->GetRenderer()->GetRenderWindow());
  sl::FrameResources& frame = *this->Frame;
  const sl::ReferenceSmSettings settings = sl::ReferenceSmSettings::from(frame.parameters);
  const sl::Light& light = *frame.light;

  // Directional lights have no position to sample: one orthographic map, as `hard`.
  std::vector<glm::dvec3> samples = sl::lightSamplePoints(light, settings.samples, settings.seed);
  const bool directional = light.type == sl::LightType::Directional;
  const int sampleCount = directional ? 1 : static_cast<int>(samples.size());
  this->SampleCount = sampleCount;

  if (!this->Receivers)
  {
    this->Receivers = std::make_unique<sl::GpuReceivers>();
  }
  this->Receivers->setGBuffer(frame.gbufferPosition, frame.gbufferNormal);
  sl::FocusSettings focus;
  focus.resolution = settings.shadowMap.resolution;
  focus.marginTexels = settings.shadowMap.marginTexels;
  sl::adviseBeyondOneMap(frame, focus);
  if (settings.shadowMap.automaticResolution)
  {
    // shadow_map_size = auto: one size for the K maps, the one the light's centre's map would get (AutomaticMapSize.h).
    focus.resolution = std::min(sl::kAutomaticMapMaxSize, frame.technique->largestAutomaticMapSize);
    const sl::LightView centre = sl::fitLightView(light, *frame.scene, *this->Receivers, focus);
    frame.automaticMapSize = sl::automaticMapSize(frame.camera, light, { centre }, focus.marginTexels,
      sl::readFloatTexture(frame.gbufferPosition, 4), sl::readFloatTexture(frame.gbufferNormal, 4), focus.resolution,
      settings.shadowMap.automaticTexelsPerPixelFor(light));
    focus.resolution = frame.automaticMapSize->size;
  }
  const bool secondDepth = settings.shadowMap.secondDepth;
  const auto linearDepth = sl::makeFloatTarget(window, focus.resolution, focus.resolution, 1);
  const auto hardwareDepth = sl::makeDepthTarget(window, focus.resolution, focus.resolution);
  this->Accumulated = sl::makeFloatTarget(window, frame.width(), frame.height(), 2); // visibility, edge
  {
    const sl::ScopedRenderTarget clearTarget(window, this->AccumulationFramebuffer, { this->Accumulated });
    clearTarget.clearColor(0, 0.0f);
  }

  const sl::Light* originalLight = frame.light;
  const std::string accumulateSource = sl::assembleShader(
    "referencesm/ReferenceSmAccumulate.glsl", this->TechniqueDefines(), this->ParameterDeclarations());
  // A 2-million-triangle mesh at K = 64 maps runs for minutes: an estimate and progress after the first map when
  // the whole is expected to be long (core/Progress.h; silent and never waiting for the GPU without a stream).
  std::size_t triangles = 0;
  for (const sl::GpuMesh& mesh : frame.gpuScene->meshes())
  {
    triangles += mesh.indexCount / 3;
  }
  sl::Progress progress("reference-sm", sl::format(triangles, " triangles x ", sampleCount, " maps"), "map",
    static_cast<std::size_t>(sampleCount));
  if (progress.needsSync(0))
  {
    glFinish(); // the first map's time without the G-buffer still queued
  }
  progress.begin();
  for (int k = 0; k < sampleCount; ++k)
  {
    // A point light at the sample, with the area light's orientation (the one-sided plane, the axis).
    sl::Light sampleLight = light;
    if (!directional)
    {
      sampleLight.center = samples[static_cast<std::size_t>(k)];
    }
    frame.light = &sampleLight;
    frame.lightView = sl::fitLightView(sampleLight, *frame.scene, *this->Receivers, focus);
    frame.hasLightView = true;
    sl::renderShadowMap(
      window, this->MapFramebuffer, this->Drawer, *frame.gpuScene, frame.lightView, secondDepth, linearDepth, hardwareDepth);
    frame.shadowMapLinear = linearDepth;

    const sl::ScopedRenderTarget target(window, this->AccumulationFramebuffer, { this->Accumulated });
    vtkOpenGLState* glState = window->GetState();
    vtkOpenGLState::ScopedglBlendFuncSeparate blendSaver(glState);
    glState->vtkglEnable(GL_BLEND);
    glState->vtkglBlendFunc(GL_ONE, GL_ONE);
    vtkShaderProgram* program = this->AccumulateQuad.ready(window, accumulateSource, "reference-sm accumulate");
    std::vector<vtkTextureObject*> bound = this->SetCommonUniforms(program);
    // This sample's map, bound as the shadow-map structure binds the pipeline's (the technique lists none: its K
    // maps are internal).
    const std::vector<vtkTextureObject*> shadowMap = sl::shadowMapStructure().bind(program, frame);
    bound.insert(bound.end(), shadowMap.begin(), shadowMap.end());
    program->SetUniformf("sampleWeight", static_cast<float>(1.0 / sampleCount));
    this->AccumulateQuad.render();
    for (vtkTextureObject* texture : bound)
    {
      texture->Deactivate();
    }
    if (progress.needsSync(static_cast<std::size_t>(k) + 1))
    {
      glFinish(); // the clock measures the maps drawn, not the commands queued
    }
    progress.step(static_cast<std::size_t>(k) + 1);
  }
  progress.finish();
  frame.light = originalLight;
  // The per-sample light views are internal; the frame exports no light-space structure.
  frame.hasLightView = false;
  frame.shadowMapLinear = nullptr;

  this->Superclass::Execute(state); // resolve
}

std::vector<vtkTextureObject*> vtkSLReferenceShadowMapPass::SetTechniqueUniforms(vtkShaderProgram* program)
{
  program->SetUniformi("sampleCount", this->SampleCount);
  return { sl::bindTexture(program, "accumulatedVisibility", this->Accumulated) };
}

void vtkSLReferenceShadowMapPass::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Receivers.reset();
  this->Drawer.releaseGraphicsResources(vtkOpenGLRenderWindow::SafeDownCast(window));
  this->AccumulateQuad.releaseGraphicsResources(window);
  this->MapFramebuffer->ReleaseGraphicsResources(window);
  this->AccumulationFramebuffer->ReleaseGraphicsResources(window);
  this->Accumulated = nullptr;
  this->Superclass::ReleaseGraphicsResources(window);
}

void vtkSLReferenceShadowMapPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SampleCount: " << this->SampleCount << "\n";
}
