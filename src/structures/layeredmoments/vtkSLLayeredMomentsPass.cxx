#include "structures/layeredmoments/vtkSLLayeredMomentsPass.h"

#include "core/Error.h"
#include "gl/ShaderLibrary.h"
#include "passes/FrameResources.h"
#include "structures/layeredmoments/LayeredMomentsStructure.h"

#include <vtkObjectFactory.h>
#include <vtkOpenGLRenderWindow.h>
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
  // x pass into `horizontal` (warping each tap into the layer), y pass into `moments`.
  vtkSmartPointer<vtkTextureObject> horizontal = makeLayeredMomentTexture(window, size, settings.layers);
  vtkSmartPointer<vtkTextureObject> moments = makeLayeredMomentTexture(window, size, settings.layers);
  vtkTextureObject* targets[2] = { horizontal, moments };
  for (int pass = 0; pass < 2; ++pass)
  {
    auto& program = this->BlurPrograms[pass];
    if (!program)
    {
      program = std::make_unique<sl::ComputeProgram>(
        sl::assembleShader("layeredmoments/LayeredMomentsBuild.glsl", { { "LAYERED_BLUR_PASS", std::to_string(pass) } }),
        pass == 0 ? "layered moments (x)" : "layered moments (y)");
    }
    vtkTextureObject* source = pass == 0 ? frame.shadowMapLinear.Get() : horizontal.Get();
    source->Activate();
    program->use();
    program->setInt(pass == 0 ? "shadowMapLinear" : "horizontal", source->GetTextureUnit());
    program->setInt("blurWidth", settings.blurTexels);
    program->setInt("mapSize", size);
    glBindImageTexture(0, targets[pass]->GetHandle(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RG32F);
    for (int layer = 0; layer < settings.layers; ++layer)
    {
      program->setInt("layer", layer);
      program->setFloat("layerNearEnd", data->ends[static_cast<std::size_t>(layer)]);
      program->setFloat("layerFarEnd", data->ends[static_cast<std::size_t>(layer) + 1]);
      program->dispatch({ (size + 7) / 8, (size + 7) / 8 });
    }
    // The y pass and the technique read these image writes through samplers.
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG32F);
    source->Deactivate();
  }
  data->moments = moments;
  frame.lightSpaceData[sl::layeredMomentsStructure().name] = data;
}

void vtkSLLayeredMomentsPass::ReleaseGraphicsResources(vtkWindow*)
{
  this->BlurPrograms[0].reset();
  this->BlurPrograms[1].reset();
  this->HistogramProgram.reset();
}

void vtkSLLayeredMomentsPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "BlurPrograms built: " << (this->BlurPrograms[0] != nullptr) << (this->BlurPrograms[1] != nullptr)
     << ", histogram " << (this->HistogramProgram != nullptr) << "\n";
}
