#include "structures/moments/MomentPrefilter.h"

#include "core/Error.h"
#include "gl/ComputeProgram.h"
#include "gl/GlResources.h"
#include "gl/ShaderLibrary.h"
#include "passes/FrameResources.h"
#include "passes/FullScreenQuad.h"
#include "passes/PassUtilities.h"
#include "passes/ScopedRenderTarget.h"

#include <vtkOpenGLFramebufferObject.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkOpenGLShaderCache.h>
#include <vtkOpenGLState.h>
#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>
#include <vtk_glew.h>

#include <algorithm>

namespace sl
{

vtkTextureObject* reusedFloatTarget(vtkOpenGLRenderWindow* window, vtkSmartPointer<vtkTextureObject>& slot, int width,
  int height, int components)
{
  if (!(slot && slot->GetContext() == window && slot->GetWidth() == static_cast<unsigned>(width) &&
        slot->GetHeight() == static_cast<unsigned>(height) && slot->GetComponents() == components))
  {
    slot = makeFloatTarget(window, width, height, components);
  }
  slot->SetMinificationFilter(vtkTextureObject::Nearest);
  slot->SetMagnificationFilter(vtkTextureObject::Nearest);
  return slot;
}

glm::ivec2 listedTexelGroups(int listedItems)
{
  const int groups = (listedItems + 63) / 64;
  const int groupsX = std::max(1, std::min(groups, 1024));
  return { groupsX, (groups + groupsX - 1) / groupsX };
}

void blurReceiverTexels(ComputeProgram& program, vtkTextureObject* source,
  const std::vector<vtkTextureObject*>& targets, int blurTexels, const PrefilterRegion& region)
{
  SL_CHECK_MSG(region.readTexelBuffer != nullptr, "the sparse blur needs the receivers' texel list");
  region.readTexelBuffer->bind(0);
  for (std::size_t unit = 0; unit < targets.size(); ++unit)
  {
    SL_CHECK_MSG(targets[unit]->GetComponents() == 4, "the sparse blur writes RGBA32F");
    glBindImageTexture(static_cast<GLuint>(unit), targets[unit]->GetHandle(), 0, GL_FALSE, 0, GL_WRITE_ONLY,
      GL_RGBA32F);
  }
  source->Activate();
  program.use();
  program.setInt("source", source->GetTextureUnit());
  program.setInt("blurWidth", blurTexels);
  program.setInt("readTexelCount", region.readTexelCount);
  // One invocation per pixel's footprint: the list holds four entries per pixel (shaders/ReceiverTiles.glsl).
  SL_CHECK_MSG(region.readTexelCount % 4 == 0, "the receivers' texel list holds four entries per pixel");
  program.dispatch(listedTexelGroups(region.readTexelCount / 4));
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  source->Deactivate();
  for (std::size_t unit = 0; unit < targets.size(); ++unit)
  {
    glBindImageTexture(static_cast<GLuint>(unit), 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  }
}

vtkSmartPointer<vtkTextureObject> prefilterMoments(vtkOpenGLRenderWindow* window, vtkOpenGLFramebufferObject* framebuffer,
  FullScreenQuad& blurQuad, vtkSmartPointer<vtkTextureObject> texture, int blurTexels, bool mipmap,
  const PrefilterRegion* region, PrefilterTargets* targets)
{
  SL_CHECK_MSG(!(region && region->sparse), "a sparse region is blurred by sparseMomentsOfDepth");
  if (blurTexels > 1)
  {
    const int width = texture->GetWidth();
    const int height = texture->GetHeight();
    const int components = texture->GetComponents();
    PrefilterTargets fresh;
    PrefilterTargets& kept = targets ? *targets : fresh;
    vtkSmartPointer<vtkTextureObject> horizontal =
      reusedFloatTarget(window, kept.horizontal, width, height, components);
    vtkSmartPointer<vtkTextureObject> blurred = reusedFloatTarget(window, kept.blurred, width, height, components);
    const int directions[2][2] = { { 1, 0 }, { 0, 1 } };
    vtkTextureObject* sources[2] = { texture, horizontal };
    vtkTextureObject* passTargets[2] = { horizontal, blurred };
    const std::vector<TileRect>* passRegions[2] = { region ? &region->horizontal : nullptr,
      region ? &region->vertical : nullptr };
    for (int pass = 0; pass < 2; ++pass)
    {
      const ScopedRenderTarget target(window, framebuffer, { passTargets[pass] });
      vtkShaderProgram* program = blurQuad.ready(window, assembleShader("moments/BoxBlur.glsl"), "box blur");
      vtkTextureObject* bound = bindTexture(program, "source", sources[pass]);
      program->SetUniform2i("direction", directions[pass]);
      program->SetUniformi("blurWidth", blurTexels);
      renderQuadOver(window, blurQuad, passRegions[pass]);
      bound->Deactivate();
    }
    texture = blurred;
  }
  if (mipmap)
  {
    glGenerateTextureMipmap(texture->GetHandle());
    texture->SetMinificationFilter(vtkTextureObject::LinearMipmapLinear);
    texture->SetMagnificationFilter(vtkTextureObject::Linear);
  }
  return texture;
}

vtkSmartPointer<vtkTextureObject> sparseMomentsOfDepth(vtkOpenGLRenderWindow* window, vtkTextureObject* shadowMapLinear,
  double depthNear, double depthFar, double esmExponent, int blurTexels, const PrefilterRegion& region,
  PrefilterTargets& targets)
{
  SL_CHECK_MSG(region.sparse && blurTexels > 1, "sparseMomentsOfDepth: a sparse region and a blur");
  if (!targets.sparseProgram)
  {
    targets.sparseProgram =
      std::make_unique<ComputeProgram>(assembleShader("moments/SparseMomentsBlur.glsl"), "sparse moment blur");
  }
  const int size = static_cast<int>(shadowMapLinear->GetWidth());
  vtkSmartPointer<vtkTextureObject> blurred = reusedFloatTarget(window, targets.blurred, size, size, 4);
  ComputeProgram& program = *targets.sparseProgram;
  program.use();
  // In float, as the moments pass sets them (SetUniformf).
  program.setFloat("depthNear", static_cast<float>(depthNear));
  program.setFloat("depthFar", static_cast<float>(depthFar));
  program.setFloat("esmExponent", static_cast<float>(esmExponent));
  blurReceiverTexels(program, shadowMapLinear, { blurred }, blurTexels, region);
  window->GetShaderCache()->ReleaseCurrentShader();
  return blurred;
}

void renderQuadOver(vtkOpenGLRenderWindow* window, FullScreenQuad& quad, const std::vector<TileRect>* rects)
{
  if (!rects)
  {
    quad.render();
    return;
  }
  // The same fragments as the whole-target draw, each computed alike, only fewer of them: the texels drawn are bit
  // for bit those of the whole draw.
  vtkOpenGLState* state = window->GetState();
  const vtkOpenGLState::ScopedglScissor scissor(state);
  const vtkOpenGLState::ScopedglEnableDisable scissorTest(state, GL_SCISSOR_TEST);
  state->vtkglEnable(GL_SCISSOR_TEST);
  for (const TileRect& rect : *rects)
  {
    state->vtkglScissor(rect.x, rect.y, rect.width, rect.height);
    quad.render();
  }
}

ReceiverTileMarker::ReceiverTileMarker() = default;
ReceiverTileMarker::~ReceiverTileMarker() = default;

ReceiverTiles ReceiverTileMarker::mark(const FrameResources& frame, int tileTexels, bool listTexels,
  std::vector<std::uint32_t>& readTexels)
{
  SL_CHECK_MSG(frame.gbufferPosition && frame.gbufferNormal, "the G-buffer must be rendered before the receiver tiles");
  const int mapSize = frame.lightView.resolution;
  ReceiverTiles tiles(mapSize, tileTexels);
  const int tilesPerSide = tiles.tilesPerSide();
  if (!program_)
  {
    program_ = std::make_unique<ComputeProgram>(assembleShader("moments/ReceiverTiles.glsl"), "receiver tiles");
  }
  // One word per tile and one for "the whole map" (shaders/ReceiverTiles.glsl).
  StorageBuffer flags(static_cast<std::size_t>(tilesPerSide) * static_cast<std::size_t>(tilesPerSide) + 1);
  flags.clear();
  flags.bind(0);
  // Up to 2 x 2 texels per pixel (shaders/ReceiverTiles.glsl's half-texel margin), after the count; none when the
  // list cannot pay (a map with fewer texels than that to blur).
  const std::size_t pixels = static_cast<std::size_t>(frame.width()) * static_cast<std::size_t>(frame.height());
  const std::size_t capacity = listTexels ? 4 * pixels : 0;
  if (!readTexels_ || readTexels_->words() != capacity + 1)
  {
    readTexels_ = std::make_unique<StorageBuffer>(capacity + 1);
  }
  readTexels_->clear();
  readTexels_->bind(1);
  frame.gbufferPosition->Activate();
  frame.gbufferNormal->Activate();
  program_->use();
  program_->setInt("gbufferPosition", frame.gbufferPosition->GetTextureUnit());
  program_->setInt("gbufferNormal", frame.gbufferNormal->GetTextureUnit());
  program_->setMatrix("lightClipFromWorld", frame.lightView.clipFromWorld);
  program_->setInt("shadowMapSize", mapSize);
  program_->setInt("tileTexels", tileTexels);
  program_->setInt("tilesPerSide", tilesPerSide);
  program_->setInt("readTexelCapacity", static_cast<int>(capacity));
  const Light& light = *frame.light;
  const bool behindLightReads =
    light.type == LightType::Point || (light.type == LightType::Spot && light.coneAngleDeg >= 90.0);
  program_->setInt("behindLightReads", behindLightReads ? 1 : 0);
  program_->dispatch({ (frame.width() + 7) / 8, (frame.height() + 7) / 8 });
  frame.gbufferNormal->Deactivate();
  frame.gbufferPosition->Deactivate();
  const std::vector<std::uint32_t> flagWords = flags.download();
  tiles.markFromFlags(flagWords);
  readTexels.clear();
  const bool wholeMap = flagWords.back() != 0;
  const std::vector<std::uint32_t> listed = listTexels ? readTexels_->download() : std::vector<std::uint32_t>{ 0 };
  if (listTexels && !wholeMap && listed[0] <= capacity)
  {
    readTexels.assign(listed.begin() + 1, listed.begin() + 1 + listed[0]);
  }
  return tiles;
}

ReceiverPrefilterPlan ReceiverTileMarker::plan(
  vtkOpenGLRenderWindow* window, const FrameResources& frame, int blurTexels)
{
  std::vector<std::uint32_t> readTexels;
  const int mapSize = frame.lightView.resolution;
  const bool listTexels =
    receiverTexelListCanPay(static_cast<long long>(frame.width()) * frame.height(), mapSize, blurTexels);
  const ReceiverTiles read = mark(frame, ReceiverTiles::tileTexelsFor(mapSize), listTexels, readTexels);
  window->GetShaderCache()->ReleaseCurrentShader();
  ReceiverPrefilterPlan plan = planReceiverPrefilter(read, blurTexels, std::move(readTexels));
  plan.blur.readTexelBuffer = readTexels_.get();
  return plan;
}

std::optional<ReceiverPrefilterPlan> ReceiverTileMarker::planWhereItPays(
  vtkOpenGLRenderWindow* window, const FrameResources& frame, int blurTexels, bool receiversOnly)
{
  if (!receiversOnly ||
    !receiverRegionCanPay(static_cast<long long>(frame.width()) * frame.height(), frame.lightView.resolution))
  {
    return std::nullopt;
  }
  return plan(window, frame, blurTexels);
}

void ReceiverTileMarker::release()
{
  program_.reset();
  readTexels_.reset();
}

} // namespace sl
