#include "pipeline/ShadowRenderer.h"

#include "frame/Approximations.h"
#include "pipeline/StructureReuse.h"

#include "techniques/Registry.h"

#include "core/Error.h"
#include "gl/vtkSLEglRenderWindow.h"
#include "structures/LightSpaceStructure.h"
#include "structures/shadowmap/ShadowMapStructure.h"
#include "structures/shadowmap/vtkSLFocusPass.h"
#include "passes/FrameResources.h"
#include "passes/vtkSLGBufferPass.h"
#include "passes/vtkSLMsaaResolvePass.h"
#include "passes/vtkSLMultiViewPass.h"
#include "passes/vtkSLSubLightAccumulatePass.h"
#include "passes/vtkSLShadingPass.h"
#include "techniques/vtkSLTechniquePass.h"

#include <vtkNew.h>
#include <vtkOpenGLShaderCache.h>
#include <vtkRenderPassCollection.h>
#include <vtkRenderer.h>
#include <vtkSequencePass.h>
#include <vtkTextureObject.h>

#include <algorithm>
#include <chrono>

namespace sl
{

ShadowRenderer::ShadowRenderer()
  : window_(vtkSmartPointer<vtkSLEglRenderWindow>::New())
  , renderer_(vtkSmartPointer<vtkRenderer>::New())
{
  window_->InitializeOffscreen(64, 64);
  window_->AddRenderer(renderer_);
}

ShadowRenderer::~ShadowRenderer()
{
  window_->MakeCurrent();
  renderer_->SetPass(nullptr);
  forgetLightSpaceBuilds(); // their textures released while the context is current, with the stages' own
  for (auto& [name, stages] : stagesByTechnique_)
  {
    for (const auto& stage : stages)
    {
      stage->ReleaseGraphicsResources(window_);
    }
  }
}

// The stages of a technique depend on its settings where it needs a structure only for some
// (TechniqueDescriptor::structureNeeded): one stage list per technique and set of structures.
std::string ShadowRenderer::stageKey(const FrameResources& frame)
{
  std::string key = frame.technique->name;
  for (const LightSpaceStructure* structure : frame.technique->structuresFor(frame.parameters))
  {
    key += "|" + structure->name;
  }
  if (frame.multisample.samples > 1)
  {
    key += "|msaa"; // the resolve stage
  }
  if (frame.partitioned)
  {
    key += "|views"; // the multi-view loop over views that partition the pixels
  }
  return key;
}

std::vector<vtkSmartPointer<vtkSLStagePass>>& ShadowRenderer::stagesFor(const FrameResources& frame, bool gbufferOnly)
{
  const TechniqueDescriptor& technique = *frame.technique;
  if (gbufferOnly)
  {
    auto& stages = stagesByTechnique_[""]; // no technique name is empty
    if (stages.empty())
    {
      stages.push_back(vtkSmartPointer<vtkSLGBufferPass>::New());
    }
    return stages;
  }
  const std::string key = stageKey(frame);
  auto& stages = stagesByTechnique_[key];
  if (stages.empty())
  {
    // Only the light-space structures this technique needs, and what they are built from, each once.
    stages.push_back(vtkSmartPointer<vtkSLGBufferPass>::New());
    for (const LightSpaceStructure* structure : withBuildDependencies(technique.structuresFor(frame.parameters)))
    {
      for (const auto& pass : structure->createBuildPasses())
      {
        // Every build stage may be skipped while its inputs are unchanged, except the focus: it depends on the
        // camera, and fits the light view the other stages' keys hold.
        if (!vtkSLFocusPass::SafeDownCast(pass))
        {
          auto reuse = std::make_shared<StructureBuildReuse>(*structure);
          pass->SetReuse(reuse);
          structureReuses_.push_back(reuse);
        }
        stages.push_back(pass);
      }
    }
    stages.push_back(technique.createPass());
    if (frame.partitioned)
    {
      // Views that partition the pixels (survey §4.3, PartitionViews.h): everything between the G-buffer and the
      // shading runs per view, blended by the focus's per-pixel selection.
      SL_CHECK_MSG(!technique.hasSubLights(), "partitioned shadow maps with sub-lights are not supported");
      auto accumulate = vtkSmartPointer<vtkSLPartitionAccumulatePass>::New();
      auto multiView = vtkSmartPointer<vtkSLMultiViewPass>::New();
      multiView->SetPartitionStages(std::vector<vtkSLStagePass*>(stages.begin() + 1, stages.end()), accumulate);
      multiViewByTechnique_[key] = multiView;
      stages.push_back(accumulate);
    }
    else if (technique.hasSubLights())
    {
      // Multi-view (Yang et al. 2009 §5): everything between the G-buffer and the shading runs per sub-light.
      auto accumulate = vtkSmartPointer<vtkSLSubLightAccumulatePass>::New();
      auto multiView = vtkSmartPointer<vtkSLMultiViewPass>::New();
      multiView->SetStages(std::vector<vtkSLStagePass*>(stages.begin() + 1, stages.end()), accumulate);
      multiViewByTechnique_[key] = multiView;
      stages.push_back(accumulate);
    }
    if (frame.multisample.samples > 1)
    {
      SL_CHECK_MSG(!technique.hasSubLights() && !frame.partitioned,
        "multisampling with sub-lights or partitioned shadow maps is not supported");
      stages.push_back(vtkSmartPointer<vtkSLMsaaResolvePass>::New());
    }
    stages.push_back(vtkSmartPointer<vtkSLShadingPass>::New());
  }
  return stages;
}

namespace
{

// The request's light, or an InputError naming it and, for a light the technique does not support, what the
// technique takes instead (from the descriptor, so the message stays right when a technique's support changes).
const Light& requestedLight(const Scene& scene, const RenderRequest& request, const TechniqueDescriptor& technique)
{
  if (request.lightIndex < 0 || request.lightIndex >= static_cast<int>(scene.lights.size()))
  {
    throw InputError(format("--light ", request.lightIndex, ": the scene has ", scene.lights.size(), " light(s)"));
  }
  const Light& light = scene.lights[static_cast<std::size_t>(request.lightIndex)];
  if (technique.supports(light))
  {
    return light;
  }
  std::string supported;
  for (const LightType type : technique.supportedLights)
  {
    supported += supported.empty() ? "" : ", ";
    if (type == LightType::Area && technique.supportedAreaShapes.size() == 1)
    {
      supported += format(lightShapeName(technique.supportedAreaShapes.front()), " ");
    }
    supported += format(lightTypeName(type), " lights");
  }
  const std::string kind =
    light.type == LightType::Area ? format(lightShapeName(light.shape), " area") : lightTypeName(light.type);
  throw InputError(format(scene.file.empty() ? "" : scene.file.string() + ": ", "lights[", request.lightIndex,
    "]: technique '", technique.name, "' does not support this ", kind, " light; it supports ",
    supported.empty() ? "no light" : supported));
}

// The frame's inputs: scene, light, technique, parameters (defaults, then --set) and the camera. No GL.
void setFrameInputs(FrameResources& frame, const Scene& scene, const RenderRequest& request,
  const TechniqueDescriptor& technique)
{
  frame.scene = &scene;
  frame.light = &requestedLight(scene, request, technique);
  frame.technique = &technique;
  frame.parameters = technique.defaultParameters();
  for (const std::string& assignment : request.settings)
  {
    frame.parameters.set(assignment);
  }
  if (technique.needs(shadowMapStructure()))
  {
    // Its InputError before any GL, rather than inside the focus pass.
    frame.partitioned = shadowMapSettings(frame).mayPartition(*frame.light);
  }
  for (const TechniqueDescriptor& other : techniqueRegistry())
  {
    if (other.findParameter("cube_map"))
    {
      frame.cubeMapTechniques += (frame.cubeMapTechniques.empty() ? "" : ", ") + other.name;
    }
  }
  const glm::ivec2 resolution = request.resolution.value_or(scene.camera.resolution);
  if (resolution.x <= 0 || resolution.y <= 0 || resolution.x > kMaxImageSide || resolution.y > kMaxImageSide)
  {
    throw InputError(format("--resolution ", resolution.x, "x", resolution.y, ": each side must be in 1..", kMaxImageSide));
  }
  frame.camera = makeCameraView(scene.camera, scene.bounds(), resolution, scene.objectBounds());
  if (request.pixelOffset != glm::dvec2(0.0))
  {
    frame.camera = offsetCameraView(frame.camera, request.pixelOffset);
    frame.alphaTestOffset = -request.pixelOffset;
  }
  if (request.gbufferOnly)
  {
    if (request.gbufferSamples != 1 && request.gbufferSamples != 4)
    {
      throw InputError(format("--msaa ", request.gbufferSamples, ": expected 1 or 4"));
    }
    frame.multisample.samples = request.gbufferSamples;
  }
  else
  {
    frame.multisample = technique.multisampleFor(frame.parameters);
  }
}

// 1 where the pixel reaches a shadow test (shaders/common/ShadowReceiver.glsl: covered, receiving, lightCanReach),
// else 0: what tells the heat maps that a 0 in depth_margin is no margin. Decided again here in double precision
// from the float G-buffer, so a pixel whose facing test lies within float rounding of 0 may be decided the other
// way than the shader did (lightReachMargin < 1e-5; grazing pixels only).
ImageF shadowTestedPixels(const Light& light, const ImageF& position, const ImageF& normal)
{
  ImageF tested(position.width, position.height, 1, 0.0f);
  for (int y = 0; y < position.height; ++y)
  {
    for (int x = 0; x < position.width; ++x)
    {
      const bool covered = position.at(x, y, 3) > 0.5f;
      const bool receives = normal.at(x, y, 3) > 0.5f;
      const glm::dvec3 pWs(position.at(x, y, 0), position.at(x, y, 1), position.at(x, y, 2));
      const glm::dvec3 nWs(normal.at(x, y, 0), normal.at(x, y, 1), normal.at(x, y, 2));
      tested.at(x, y, 0) = covered && receives && lightCanReach(light, pWs, nWs) ? 1.0f : 0.0f;
    }
  }
  return tested;
}

// The per-pixel buffers: the common ones (G-buffer, visibility), the technique's, and the sub-lights'.
void readBackBuffers(const FrameResources& frame, const RenderRequest& request, FrameResult& result)
{
  const ImageF position = readFloatTexture(frame.gbufferPosition, 4);
  const ImageF normal = readFloatTexture(frame.gbufferNormal, 4);
  const ImageF albedoDepth = readFloatTexture(frame.gbufferAlbedoDepth, 4);
  const auto& common = commonBufferSpecs();
  const auto commonBuffer = [&](const std::string& name, ImageF image) {
    const auto spec = std::find_if(common.begin(), common.end(), [&](const BufferSpec& s) { return s.name == name; });
    result.buffers.push_back({ name, std::move(image), spec->unit, spec->doc, spec->kind, spec->categoryLabels, spec->domain });
  };
  if (!request.gbufferOnly)
  {
    commonBuffer("visibility", readFloatTexture(frame.techniqueTargets.at("visibility"), 1));
  }
  commonBuffer("position", position.channels(0, 3));
  commonBuffer("normal", normal.channels(0, 3));
  commonBuffer("depth", albedoDepth.channels(3, 1));
  commonBuffer("coverage", position.channels(3, 1));
  commonBuffer("albedo", albedoDepth.channels(0, 3));
  commonBuffer("receives_shadows", normal.channels(3, 1));
  commonBuffer("shadow_tested", shadowTestedPixels(*frame.light, position, normal));
  if (request.gbufferOnly)
  {
    return;
  }
  if (frame.multisample.samples > 1)
  {
    const auto multisampleBuffer = [&](const std::string& name, vtkTextureObject* texture, int components) {
      const auto& specs = multisampleBufferSpecs();
      const auto spec = std::find_if(specs.begin(), specs.end(), [&](const BufferSpec& s) { return s.name == name; });
      result.buffers.push_back(
        { name, readFloatTexture(texture, components), spec->unit, spec->doc, spec->kind, spec->categoryLabels, spec->domain });
    };
    multisampleBuffer("msaa_distinct_samples", frame.distinctSamples, 1);
    multisampleBuffer("msaa_interpolated_samples", frame.interpolatedSamples, 1);
    multisampleBuffer("msaa_pixel_visibility", frame.pixelVisibility, 1);
    multisampleBuffer("msaa_sample_depth", frame.sampleDepth, frame.multisample.samples);
    multisampleBuffer("msaa_sample_visibility", frame.sampleVisibility, frame.multisample.samples);
  }
  for (const BufferSpec& spec : frame.technique->buffers)
  {
    if (!spec.fromPass)
    {
      result.buffers.push_back({ spec.name, readFloatTexture(frame.techniqueTargets.at(spec.name), 1), spec.unit,
        spec.doc, spec.kind, spec.categoryLabels, spec.domain });
    }
  }
  if (!frame.subLightVisibility.empty())
  {
    const int count = static_cast<int>(frame.subLightVisibility.size());
    ImageF subLights(frame.width(), frame.height(), count);
    for (int k = 0; k < count; ++k)
    {
      const ImageF one = readFloatTexture(frame.subLightVisibility[static_cast<std::size_t>(k)], 1);
      for (std::size_t i = 0; i < one.pixelCount(); ++i)
      {
        subLights.data[i * count + k] = one.data[i];
      }
    }
    const BufferSpec& spec = subLightBufferSpecs().front();
    result.buffers.push_back({ spec.name, std::move(subLights), spec.unit, spec.doc, spec.kind, spec.categoryLabels, spec.domain });
  }
}

// Each light-space structure the frame built, in build order: its light_space.vti arrays and its GPU memory.
void readBackLightSpace(const FrameResources& frame, FrameResult& result)
{
  const TechniqueDescriptor& technique = *frame.technique;
  const std::vector<const LightSpaceStructure*> needed = technique.structuresFor(frame.parameters);
  for (const LightSpaceStructure* structure : needed)
  {
    result.lightStructureNames.push_back(structure->name);
  }
  for (const LightSpaceStructure* structure : withBuildDependencies(needed))
  {
    std::vector<NamedImage> images = structure->exportImages(frame, result);
    result.lightSpace.insert(
      result.lightSpace.end(), std::make_move_iterator(images.begin()), std::make_move_iterator(images.end()));
    result.lightStructureGpuBytes[structure->name] = structure->gpuBytes(frame);
  }
}

// The MSAA resolve's counts for stats.json and bench's columns (SS08 §7: "usually the vast majority of pixels require
// only a single visibility determination", §7).
void addMultisampleStatistics(FrameResult& result)
{
  const ImageF& distinct = result.find("msaa_distinct_samples")->image;
  const ImageF& interpolated = result.find("msaa_interpolated_samples")->image;
  double pixelsWithDistinct = 0.0;
  double interpolatedSamples = 0.0;
  for (std::size_t i = 0; i < distinct.data.size(); ++i)
  {
    pixelsWithDistinct += distinct.data[i] > 0.0f ? 1.0 : 0.0;
    interpolatedSamples += interpolated.data[i];
  }
  result.techniqueStatistics["msaa_pixels_with_distinct_samples"] = pixelsWithDistinct;
  result.techniqueStatistics["msaa_interpolated_samples"] = interpolatedSamples;
}

} // namespace

vtkSLMultiViewPass* ShadowRenderer::multiViewFor(const FrameResources& frame, bool gbufferOnly)
{
  const auto found = gbufferOnly ? multiViewByTechnique_.end() : multiViewByTechnique_.find(stageKey(frame));
  return found == multiViewByTechnique_.end() ? nullptr : found->second.Get();
}

void ShadowRenderer::allocateFrameTargets(FrameResources& frame, const Scene& scene, bool gbufferOnly)
{
  window_->MakeCurrent();
  window_->SetSize(frame.width(), frame.height());
  frame.gpuScene = std::make_unique<GpuScene>(window_, scene);
  if (gbufferOnly)
  {
    return;
  }
  if (frame.technique->drawsSceneGeometry)
  {
    frame.weldedCasters =
      std::make_shared<const std::vector<WeldedMesh>>(weldCasters(scene, frame.technique->perforatedCastersByStsv));
  }
  for (const std::string& output : frame.technique->outputNames())
  {
    frame.techniqueTargets[output] = makeFloatTarget(window_, frame.width(), frame.height(), 1);
  }
}

double ShadowRenderer::renderStages(FrameResources& frame, bool gbufferOnly)
{
  const auto& stages = stagesFor(frame, gbufferOnly);
  vtkSLMultiViewPass* multiView = multiViewFor(frame, gbufferOnly);
  vtkNew<vtkRenderPassCollection> collection;
  for (const auto& stage : stages)
  {
    stage->SetFrame(&frame);
    stage->ResetTimer();
  }
  if (multiView)
  {
    multiView->SetFrame(&frame);
    collection->AddItem(stages.front()); // gbuffer
    collection->AddItem(multiView);      // per sub-light: focus .. technique, accumulation
    collection->AddItem(stages.back());  // shading
  }
  else
  {
    for (const auto& stage : stages)
    {
      collection->AddItem(stage);
    }
  }
  vtkNew<vtkSequencePass> sequence;
  sequence->SetPasses(collection);
  renderer_->SetPass(sequence);

  const auto frameStart = std::chrono::steady_clock::now();
  window_->Render();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - frameStart).count();
}

void ShadowRenderer::forgetLightSpaceBuilds()
{
  for (const auto& reuse : structureReuses_)
  {
    reuse->forget();
  }
}

void ShadowRenderer::collectStageResults(const FrameResources& frame, bool gbufferOnly, FrameResult& result)
{
  std::map<std::string, int> executedBuildRuns;
  std::map<std::string, int> reusedBuildRuns;
  for (const auto& stage : stagesFor(frame, gbufferOnly))
  {
    result.stages.push_back({ stage->GetStageName(), stage->GetGpuMilliseconds(), stage->GetWallMilliseconds() });
    if (const auto* reuse = dynamic_cast<const StructureBuildReuse*>(stage->GetReuse()))
    {
      const std::string& name = reuse->structure().name;
      FrameResult::LightStructureBuild& build = result.lightStructureBuilds[name];
      executedBuildRuns[name] += stage->GetExecutedRuns();
      reusedBuildRuns[name] += stage->GetReusedRuns();
      build.buildGpuMs += stage->GetGpuMilliseconds();
      build.buildGpuMsWhenBuilt += reuse->buildGpuMillisecondsWhenBuilt();
      // Reused: every run of its build stages this frame (each sub-light's) was skipped.
      build.reused = executedBuildRuns[name] == 0 && reusedBuildRuns[name] > 0;
    }
    if (auto* techniquePass = vtkSLTechniquePass::SafeDownCast(stage))
    {
      result.techniqueStatistics = techniquePass->CollectStatistics();
      result.objectSpace = techniquePass->CollectObjectSpaceExports();
    }
  }
  result.technique = frame.technique->name;
  result.descriptor = frame.technique;
  result.parameters = frame.parameters;
  result.resolution = frame.camera.resolution;
  result.camera = frame.camera;
  if (frame.hasLightView)
  {
    result.lightView = frame.partitions ? frame.partitions->views.front() : frame.lightView;
    result.partitions = frame.partitions;
  }
  result.automaticMapSize = frame.automaticMapSize;
  result.glRenderer = window_->GetRendererString();
  result.glVersion = window_->GetVersionString();
  result.eglPlatform = window_->GetEglContext()->platformName();
  result.eglDeviceIndex = window_->GetEglContext()->deviceIndex();
  result.eglDevice = window_->GetEglContext()->deviceDescription();
  result.samplePositions = frame.samplePositions;
}

void ShadowRenderer::appendPassBuffers(const FrameResources& frame, FrameResult& result)
{
  for (const auto& stage : stagesFor(frame, false))
  {
    if (auto* techniquePass = vtkSLTechniquePass::SafeDownCast(stage))
    {
      std::vector<NamedImage> passBuffers = techniquePass->CollectPassBuffers();
      for (const BufferSpec& spec : frame.technique->buffers)
      {
        if (!spec.fromPass)
        {
          continue;
        }
        const auto found = std::find_if(
          passBuffers.begin(), passBuffers.end(), [&](const NamedImage& image) { return image.name == spec.name; });
        if (found == passBuffers.end())
        {
          continue; // not asked for by this frame's parameters
        }
        SL_CHECK(found->image.width == frame.width() && found->image.height == frame.height());
        result.buffers.push_back({ spec.name, std::move(found->image), spec.unit, spec.doc, spec.kind, spec.categoryLabels, spec.domain });
      }
    }
  }
}

void ShadowRenderer::releaseFrame(FrameResources& frame, bool gbufferOnly)
{
  renderer_->SetPass(nullptr);
  for (const auto& stage : stagesFor(frame, gbufferOnly))
  {
    stage->SetFrame(nullptr); // the frame's resources end here
  }
  if (vtkSLMultiViewPass* multiView = multiViewFor(frame, gbufferOnly))
  {
    multiView->SetFrame(nullptr);
  }
  frame.gpuScene->releaseGraphicsResources(window_);
}

FrameResult ShadowRenderer::render(const Scene& scene, const RenderRequest& request)
{
  FrameResources frame;
  setFrameInputs(frame, scene, request, findTechnique(request.technique));
  if (!request.gbufferOnly)
  {
    frame.sceneGeometryHash = sceneGeometryHash(scene); // part of every light-space build's key
  }
  allocateFrameTargets(frame, scene, request.gbufferOnly);

  FrameResult result;
  try
  {
    result.frameWallMs = renderStages(frame, request.gbufferOnly);
  }
  catch (...)
  {
    // A stage that refuses its settings mid-frame (e.g. ss08's budget_map=image without budget_image) must not
    // leave the passes holding this frame: the renderer's next frame would use them (found by the differential
    // test, issue 27: the next render crashed). VTK's window also still believes it is rendering (its InRender flag,
    // which makes every later Render() return at once, so the next frame's G-buffer was never drawn).
    window_->ClearInRenderStatus();
    // A refusal inside a stage that ran a compute program (the focus's receiver reduction: a point light one map
    // cannot cover) leaves that program bound behind VTK's shader cache, which still believes its last program is:
    // the next frame's G-buffer draw would skip binding it (GL_INVALID_OPERATION).
    window_->GetShaderCache()->ReleaseCurrentShader();
    releaseFrame(frame, request.gbufferOnly);
    throw;
  }
  collectStageResults(frame, request.gbufferOnly, result);
  readBackBuffers(frame, request, result);
  if (!request.gbufferOnly)
  {
    appendPassBuffers(frame, result);
    readBackLightSpace(frame, result);
    // Counted beside the technique's own statistics so that stats.json and bench's columns carry it.
    if (const std::optional<CutShortPixels> cutShort = cutShortPixels(result))
    {
      result.techniqueStatistics["cut_short_pixels"] = static_cast<double>(cutShort->count);
    }
    for (const FlaggedPixels& flagged : flaggedPixels(result))
    {
      result.techniqueStatistics[flagged.buffer + "_flagged_pixels"] = static_cast<double>(flagged.count);
    }
    if (frame.multisample.samples > 1)
    {
      addMultisampleStatistics(result);
    }
    // Where the technique's declared approximations apply (AccuracyContract), published and counted like the
    // cut-short pixels.
    result.buffers.push_back(approximationBuffer(result, scene, request.lightIndex));
    result.techniqueStatistics["approximate_pixels"] = static_cast<double>(approximatePixels(result).count);
  }
  if (frame.shadedImage)
  {
    result.image = readColorTexture(frame.shadedImage);
  }
  releaseFrame(frame, request.gbufferOnly);
  return result;
}

std::vector<FrameResult> ShadowRenderer::renderSampleGBuffers(const Scene& scene, RenderRequest request, int samples)
{
  request.gbufferOnly = true;
  request.gbufferSamples = samples;
  request.pixelOffset = glm::dvec2(0.0);
  const FrameResult multisampled = render(scene, request);
  if (samples == 1)
  {
    return { multisampled };
  }
  std::vector<FrameResult> perSample;
  request.gbufferSamples = 1;
  for (const glm::dvec2& position : multisampled.samplePositions)
  {
    request.pixelOffset = position - glm::dvec2(0.5);
    perSample.push_back(render(scene, request));
  }
  return perSample;
}

} // namespace sl
