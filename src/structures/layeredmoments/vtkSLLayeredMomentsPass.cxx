#include "structures/layeredmoments/vtkSLLayeredMomentsPass.h"

#include "core/Error.h"
#include "gl/ShaderLibrary.h"
#include "passes/FrameResources.h"
#include "structures/layeredmoments/LayeredMomentsStructure.h"

#include <vtkObjectFactory.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkOpenGLShaderCache.h>
#include <vtkRenderState.h>
#include <vtkRenderer.h>
#include <vtkTextureObject.h>
#include <vtk_glew.h>

vtkStandardNewMacro(vtkSLLayeredMomentsPass);

vtkSLLayeredMomentsPass::vtkSLLayeredMomentsPass() = default;
vtkSLLayeredMomentsPass::~vtkSLLayeredMomentsPass() = default;

namespace
{

vtkSmartPointer<vtkTextureObject> makeLayeredMomentTexture(vtkOpenGLRenderWindow* window, int size, int layers)
{
  auto texture = vtkSmartPointer<vtkTextureObject>::New();
  texture->SetContext(window);
  texture->SetInternalFormat(GL_RG32F);
  texture->SetFormat(GL_RG);
  texture->SetDataType(GL_FLOAT);
  texture->SetMinificationFilter(vtkTextureObject::Nearest);
  texture->SetMagnificationFilter(vtkTextureObject::Nearest);
  texture->SetWrapS(vtkTextureObject::ClampToEdge);
  texture->SetWrapT(vtkTextureObject::ClampToEdge);
  texture->SetWrapR(vtkTextureObject::ClampToEdge);
  if (!texture->Allocate3D(size, size, layers, 2, VTK_FLOAT))
  {
    throw sl::GraphicsError(sl::format("cannot allocate the layered moment map (", size, "^2 x ", layers, " layers)"));
  }
  return texture;
}

} // namespace

void vtkSLLayeredMomentsPass::Execute(const vtkRenderState* state)
{
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(state->GetRenderer()->GetRenderWindow());
  sl::FrameResources& frame = *this->Frame;
  SL_CHECK_MSG(frame.hasLightView && frame.shadowMapLinear, "the shadow map must be built before its layered moments");
  const sl::LayeredMomentsSettings settings = sl::LayeredMomentsSettings::from(frame.parameters);
  const int size = frame.lightView.resolution;
  GLint max3dSize = 0;
  glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &max3dSize);
  if (size > max3dSize)
  {
    throw sl::InputError(sl::format("--set shadow_map_size=", size, ": the layered moments (layered_moments) need a ",
      size, "x", size, "x", settings.layers, " 3D texture and this GL allows ", max3dSize,
      " per side; use shadow_map_size <= ", max3dSize));
  }
  const double nearDepth = frame.lightView.nearDepth;
  const double farDepth = frame.lightView.farDepth;
  auto data = std::make_shared<sl::LayeredMomentsData>();
  data->layers = settings.layers;
  if (settings.placement == sl::LayerPlacement::Gaps)
  {
    // The depth histogram on the GPU (atomics), read back as 256 words; the boundaries are placed on the CPU.
    if (!this->HistogramProgram)
    {
      this->HistogramProgram = std::make_unique<sl::ComputeProgram>(
        sl::assembleShader("layeredmoments/LayeredMomentsHistogram.glsl",
          { { "LAYERED_HISTOGRAM_BINS", std::to_string(sl::layeredHistogramBins) } }),
        "layered moments (depth histogram)");
    }
    sl::StorageBuffer histogram(sl::layeredHistogramBins);
    histogram.upload(std::vector<std::uint32_t>(sl::layeredHistogramBins, 0));
    histogram.bind(0);
    frame.shadowMapLinear->Activate();
    this->HistogramProgram->use();
    this->HistogramProgram->setInt("shadowMapLinear", frame.shadowMapLinear->GetTextureUnit());
    this->HistogramProgram->setInt("mapSize", size);
    this->HistogramProgram->setFloat("depthNear", nearDepth);
    this->HistogramProgram->setFloat("depthFar", farDepth);
    this->HistogramProgram->dispatch({ (size + 7) / 8, (size + 7) / 8 });
    frame.shadowMapLinear->Deactivate();
    data->histogram = histogram.download();
    data->ends = sl::layeredGapEnds(data->histogram, settings.layers, nearDepth, farDepth);
  }
  else
  {
    data->ends = sl::layeredUniformEnds(settings.layers, nearDepth, farDepth);
  }
  const auto fits = [&](const vtkSmartPointer<vtkTextureObject>& texture) {
    return texture && texture->GetContext() == window && texture->GetWidth() == static_cast<unsigned>(size) &&
      texture->GetDepth() == static_cast<unsigned>(settings.layers);
  };
  if (!fits(this->MomentsTarget))
  {
    this->MomentsTarget = makeLayeredMomentTexture(window, size, settings.layers);
  }
  // prefilter_region = receivers, as the moment map: the blur over the receivers' tiles (the x pass over those grown
  // by the box's reach along y), or only at the texels they read (sparse), or the whole map.
  data->region = this->TileMarker.planWhereItPays(window, frame, settings.blurTexels, settings.receiversOnly);
  if (data->region)
  {
    sl::ReceiverPrefilterPlan& plan = *data->region;
    if (!sl::layeredSparseBlurFits(settings.blurTexels, settings.layers))
    {
      sl::planOverTiles(plan, settings.blurTexels);
    }
    plan.sourceTiles = 0; // the x pass warps the shadow map's depths itself: no pass of its own
  }
  if (data->region && data->region->blur.sparse)
  {
    this->BlurSparse(frame, *data, settings);
  }
  else
  {
    // The x pass's target, only for a blur over tiles (the sparse blur needs none).
    if (!fits(this->HorizontalTarget))
    {
      this->HorizontalTarget = makeLayeredMomentTexture(window, size, settings.layers);
    }
    this->BlurTiles(frame, *data, settings);
  }
  data->moments = this->MomentsTarget;
  frame.lightSpaceData[sl::layeredMomentsStructure().name] = data;
}

void vtkSLLayeredMomentsPass::BlurTiles(
  sl::FrameResources& frame, const sl::LayeredMomentsData& data, const sl::LayeredMomentsSettings& settings)
{
  const int size = frame.lightView.resolution;
  // Each pass's tiles as x | y << 16 words (LayeredMomentsBuild.glsl): the plan's rectangles (tile-aligned runs, or
  // the whole map where most tiles are read), so that the built texels are the plan's; every tile without a plan.
  const int tileTexels = data.region ? data.region->read.tileTexels() : sl::ReceiverTiles::tileTexelsFor(size);
  const auto tileWords = [&](const std::vector<sl::TileRect>* rects) {
    const std::vector<sl::TileRect> whole{ sl::TileRect{ 0, 0, size, size } };
    std::vector<std::uint32_t> words;
    for (const sl::TileRect& rect : rects ? *rects : whole)
    {
      for (int y = rect.y / tileTexels; y * tileTexels < rect.y + rect.height; ++y)
      {
        for (int x = rect.x / tileTexels; x * tileTexels < rect.x + rect.width; ++x)
        {
          words.push_back(static_cast<std::uint32_t>(x) | static_cast<std::uint32_t>(y) << 16);
        }
      }
    }
    return words;
  };
  // Without a blur (prefilter_texels = 1) the plan has no blur passes: both passes run over its source tiles, the ones
  // it marks built.
  const bool blurred = settings.blurTexels > 1;
  const std::vector<std::uint32_t> passTiles[2] = {
    tileWords(data.region ? (blurred ? &data.region->blur.horizontal : &data.region->source) : nullptr),
    tileWords(data.region ? (blurred ? &data.region->blur.vertical : &data.region->source) : nullptr),
  };
  // x pass into `horizontal` (warping each tap into the layer), y pass into the map; every layer in one dispatch.
  vtkTextureObject* targets[2] = { this->HorizontalTarget, this->MomentsTarget };
  for (int pass = 0; pass < 2; ++pass)
  {
    if (passTiles[pass].empty())
    {
      continue; // no receiver reads the map
    }
    auto& program = this->BlurPrograms[pass];
    if (!program)
    {
      program = std::make_unique<sl::ComputeProgram>(
        sl::assembleShader("layeredmoments/LayeredMomentsBuild.glsl", { { "LAYERED_BLUR_PASS", std::to_string(pass) } }),
        pass == 0 ? "layered moments (x)" : "layered moments (y)");
    }
    const sl::StorageBuffer tiles(passTiles[pass].size());
    tiles.upload(passTiles[pass]);
    tiles.bind(1);
    vtkTextureObject* source = pass == 0 ? frame.shadowMapLinear.Get() : targets[0];
    source->Activate();
    program->use();
    program->setInt(pass == 0 ? "shadowMapLinear" : "horizontal", source->GetTextureUnit());
    program->setInt("blurWidth", settings.blurTexels);
    program->setInt("mapSize", size);
    program->setInt("tileTexels", tileTexels);
    program->setInt("layeredLayers", data.layers);
    program->setFloats("layeredEnds", data.ends);
    glBindImageTexture(0, targets[pass]->GetHandle(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RG32F);
    program->dispatch(glm::ivec3(static_cast<int>(passTiles[pass].size()), 1, data.layers));
    // The y pass and the technique read these image writes through samplers.
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG32F);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, 0);
    source->Deactivate();
  }
}

void vtkSLLayeredMomentsPass::BlurSparse(
  sl::FrameResources& frame, const sl::LayeredMomentsData& data, const sl::LayeredMomentsSettings& settings)
{
  const sl::PrefilterRegion& region = data.region->blur;
  SL_CHECK_MSG(region.readTexelBuffer != nullptr, "the sparse layered blur needs the receivers' texel list");
  if (!this->SparseProgram)
  {
    this->SparseProgram = std::make_unique<sl::ComputeProgram>(
      sl::assembleShader("layeredmoments/LayeredMomentsSparseBlur.glsl"), "layered moments (sparse)");
  }
  sl::ComputeProgram& program = *this->SparseProgram;
  region.readTexelBuffer->bind(0);
  frame.shadowMapLinear->Activate();
  program.use();
  program.setInt("shadowMapLinear", frame.shadowMapLinear->GetTextureUnit());
  program.setInt("blurWidth", settings.blurTexels);
  program.setInt("mapSize", frame.lightView.resolution);
  program.setInt("readTexelCount", region.readTexelCount);
  program.setInt("layeredLayers", data.layers);
  program.setFloats("layeredEnds", data.ends);
  glBindImageTexture(0, this->MomentsTarget->GetHandle(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RG32F);
  program.dispatch(sl::listedTexelGroups(region.readTexelCount));
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG32F);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, 0);
  frame.shadowMapLinear->Deactivate();
}

void vtkSLLayeredMomentsPass::ReleaseGraphicsResources(vtkWindow*)
{
  this->BlurPrograms[0].reset();
  this->BlurPrograms[1].reset();
  this->HistogramProgram.reset();
  this->SparseProgram.reset();
  this->TileMarker.release();
  this->HorizontalTarget = nullptr;
  this->MomentsTarget = nullptr;
}

void vtkSLLayeredMomentsPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "BlurPrograms built: " << (this->BlurPrograms[0] != nullptr) << (this->BlurPrograms[1] != nullptr)
     << ", histogram " << (this->HistogramProgram != nullptr) << "\n";
}
