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

namespace sl
{

vtkSmartPointer<vtkTextureObject> prefilterMoments(vtkOpenGLRenderWindow* window, vtkOpenGLFramebufferObject* framebuffer,
  FullScreenQuad& blurQuad, vtkSmartPointer<vtkTextureObject> texture, int blurTexels, bool mipmap,
  const PrefilterRegion* region)
{
  if (blurTexels > 1)
  {
    const int width = texture->GetWidth();
    const int height = texture->GetHeight();
    const int components = texture->GetComponents();
    auto horizontal = makeFloatTarget(window, width, height, components);
    auto blurred = makeFloatTarget(window, width, height, components);
    const int directions[2][2] = { { 1, 0 }, { 0, 1 } };
    vtkTextureObject* sources[2] = { texture, horizontal };
    vtkTextureObject* targets[2] = { horizontal, blurred };
    const std::vector<TileRect>* passRegions[2] = { region ? &region->horizontal : nullptr,
      region ? &region->vertical : nullptr };
    for (int pass = 0; pass < 2; ++pass)
    {
      const ScopedRenderTarget target(window, framebuffer, { targets[pass] });
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

ReceiverTiles ReceiverTileMarker::mark(const FrameResources& frame, int tileTexels)
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
  frame.gbufferPosition->Activate();
  frame.gbufferNormal->Activate();
  program_->use();
  program_->setInt("gbufferPosition", frame.gbufferPosition->GetTextureUnit());
  program_->setInt("gbufferNormal", frame.gbufferNormal->GetTextureUnit());
  program_->setMatrix("lightClipFromWorld", frame.lightView.clipFromWorld);
  program_->setInt("shadowMapSize", mapSize);
  program_->setInt("tileTexels", tileTexels);
  program_->setInt("tilesPerSide", tilesPerSide);
  const Light& light = *frame.light;
  const bool behindLightReads =
    light.type == LightType::Point || (light.type == LightType::Spot && light.coneAngleDeg >= 90.0);
  program_->setInt("behindLightReads", behindLightReads ? 1 : 0);
  program_->dispatch({ (frame.width() + 7) / 8, (frame.height() + 7) / 8 });
  frame.gbufferNormal->Deactivate();
  frame.gbufferPosition->Deactivate();
  tiles.markFromFlags(flags.download());
  return tiles;
}

ReceiverPrefilterPlan ReceiverTileMarker::plan(vtkOpenGLRenderWindow* window, const FrameResources& frame, int blurTexels)
{
  const ReceiverTiles read = mark(frame, ReceiverTiles::tileTexelsFor(frame.lightView.resolution));
  window->GetShaderCache()->ReleaseCurrentShader();
  return planReceiverPrefilter(read, blurTexels);
}

void ReceiverTileMarker::release()
{
  program_.reset();
}

} // namespace sl
