#include "techniques/dcs/vtkSLDcsPass.h"

#include "core/Error.h"
#include "core/Progress.h"
#include "gl/GlResources.h"
#include "gl/ShaderLibrary.h"
#include "passes/FrameResources.h"
#include "passes/PassUtilities.h"
#include "passes/ScopedRenderTarget.h"
#include "techniques/dcs/DcsTechnique.h"
#include "objectspace/DcsWedgeExport.h"

#include <vtkObjectFactory.h>
#include <vtkOpenGLFramebufferObject.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkOpenGLState.h>
#include <vtkPolyData.h>
#include <vtkRenderState.h>
#include <vtkRenderer.h>
#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>
#include <vtk_glew.h>

#include <chrono>

vtkStandardNewMacro(vtkSLDcsPass);

vtkSLDcsPass::vtkSLDcsPass() = default;
vtkSLDcsPass::~vtkSLDcsPass() = default;

int vtkSLDcsPass::SampleCount() const
{
  return sl::DcsSettings::from(this->Frame->parameters).lightSamples.count;
}

namespace
{

const char* const kDcsWedgeUpdateShader = "dcs/DcsWedgeUpdate.glsl";
const char* const kStsvCountersFlag = "STSV_DCS_COUNTERS";

} // namespace

sl::ShaderDefines vtkSLDcsPass::GetExtraDefines() const
{
  sl::ShaderDefines defines;
  for (const sl::ShaderConstant& constant : sl::dcsCounterLayerShaderConstants(this->SampleCount()))
  {
    defines.emplace_back(constant.name, std::to_string(constant.value));
  }
  return defines;
}

std::vector<vtkSLTechniquePass::PassShader> vtkSLDcsPass::GetPassShaders() const
{
  return { { kDcsWedgeUpdateShader, {} }, { sl::kStsvSamplesShaderPath, { kStsvCountersFlag } } };
}

void vtkSLDcsPass::Execute(const vtkRenderState* state)
{
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(state->GetRenderer()->GetRenderWindow());
  const sl::FrameResources& frame = *this->Frame;
  this->Steps.mark(0);

  // Step 1: the centre's count (the shadow-volume pass).
  this->BuildAndCountVolumes(window);
  this->Steps.mark(1);

  // Step 2: the wedges, built on the CPU, drawn into the sample counters.
  const int samples = this->SampleCount();
  const sl::DcsCounterLayers layers(samples);
  this->Counters.allocate(frame.width(), frame.height(), layers.total());
  this->Mask.allocate(frame.width(), frame.height(), (samples + 31) / 32);
  const GLuint bias = sl::DcsCounterLayers::replicated(sl::kDcsCounterBias);
  const GLuint zero = 0u;
  glClearTexSubImage(this->Counters.handle, 0, 0, 0, 0, frame.width(), frame.height(), layers.sampleCounterLayers,
    GL_RED_INTEGER, GL_UNSIGNED_INT, &bias);
  glClearTexSubImage(this->Counters.handle, 0, 0, 0, layers.sampleCounterLayers, frame.width(), frame.height(),
    layers.total() - layers.sampleCounterLayers, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  this->DrawWedges(window);
  sl::checkGlErrors("dcs (wedges)");
  this->Steps.mark(2);
  // Step 2b: the perforated casters' STSVs add 1 to the counters of the samples they hide (Forest et al. 2009 §3.2, STSV_DCS).
  this->DrawStsvs(window);
  sl::checkGlErrors("dcs (STSVs)");
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  this->Steps.mark(3);

  // Step 3: the resolve, the base class's full-screen shader.
  this->vtkSLTechniquePass::Execute(state);
  glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  this->Steps.mark(4);
  sl::checkGlErrors("dcs (resolve)");
}

void vtkSLDcsPass::DrawWedges(vtkOpenGLRenderWindow* window)
{
  const sl::FrameResources& frame = *this->Frame;
  const auto buildStart = std::chrono::steady_clock::now();
  this->Wedges = sl::potentialSilhouetteWedges(*frame.weldedCasters, *frame.light);
  this->DrawnWedges = this->WedgeDrawer.prepare(this->Wedges.wedges, frame);
  this->WedgeBuildMilliseconds =
    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - buildStart).count();

  const sl::ShaderDefines defines = this->TechniqueDefines();
  vtkShaderProgram* program = sl::readyProgram(window, sl::assembleShader(sl::kWedgeVertexShaderPath, defines),
    sl::assembleShader(kDcsWedgeUpdateShader, defines, this->ParameterDeclarations()), "dcs wedges");
  std::vector<vtkTextureObject*> bound = this->SetCommonUniforms(program);
  this->SetReceiverOffsetUniforms(program);
  glBindImageTexture(0, this->Counters.handle, 0, GL_TRUE, 0, GL_READ_WRITE, GL_R32UI);

  // The counters are written through the image; the colour target only gives the draw a framebuffer.
  const sl::ScopedRenderTarget target(window, this->WedgeFramebuffer, { this->VolumeCount });
  vtkOpenGLState* glState = window->GetState();
  const vtkOpenGLState::ScopedglColorMask colorMask(glState);
  glState->vtkglColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  if (sl::progressStream() == nullptr)
  {
    this->WedgeDrawer.drawCounted(program, *frame.light); // one draw: bench's children and tests
  }
  else
  {
    // A 1 M triangle mesh draws its wedges for minutes: the draw in chunks, with an estimate after the first and
    // progress when the whole is expected to be long (core/Progress.h).
    constexpr std::size_t kChunks = 16;
    std::size_t triangles = 0;
    for (const sl::GpuMesh& mesh : frame.gpuScene->meshes())
    {
      triangles += mesh.indexCount / 3;
    }
    sl::Progress progress("dcs",
      sl::format(triangles, " triangles, ", this->DrawnWedges, " wedges at ", frame.width(), "x", frame.height(),
        " with N = ", this->SampleCount()),
      "wedge chunk", kChunks);
    if (progress.needsSync(0))
    {
      glFinish(); // the first chunk's time without the volumes still queued
    }
    progress.begin();
    this->WedgeDrawer.drawCounted(program, *frame.light, kChunks, [&progress](std::size_t done) {
      if (progress.needsSync(done))
      {
        glFinish(); // the clock measures the wedges drawn, not the commands queued
      }
      progress.step(done);
    });
    progress.finish();
  }

  glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
  for (vtkTextureObject* texture : bound)
  {
    texture->Deactivate();
  }
}

void vtkSLDcsPass::DrawStsvs(vtkOpenGLRenderWindow* window)
{
  const sl::FrameResources& frame = *this->Frame;
  this->Stsvs.prepare(frame);
  sl::ShaderDefines defines = this->TechniqueDefines();
  defines.emplace_back(kStsvCountersFlag, "");
  vtkShaderProgram* program = sl::readyProgram(window, sl::assembleShader(sl::kWedgeVertexShaderPath, defines),
    sl::assembleShader(sl::kStsvSamplesShaderPath, defines, this->ParameterDeclarations()), "dcs STSVs");
  std::vector<vtkTextureObject*> bound = this->SetCommonUniforms(program);
  this->SetReceiverOffsetUniforms(program);
  sl::setIntIfUsed(program, "stsvOppositeSideCheck",
    sl::DcsSettings::from(frame.parameters).stsvTest == sl::StsvOcclusionTest::PaperAndOppositeSides ? 1 : 0);
  glBindImageTexture(0, this->Counters.handle, 0, GL_TRUE, 0, GL_READ_WRITE, GL_R32UI);
  // As for the wedges: the counters are written through the image.
  const sl::ScopedRenderTarget target(window, this->WedgeFramebuffer, { this->VolumeCount });
  vtkOpenGLState* glState = window->GetState();
  const vtkOpenGLState::ScopedglColorMask colorMask(glState);
  glState->vtkglColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  this->Stsvs.draw(program, frame);
  glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
  for (vtkTextureObject* texture : bound)
  {
    texture->Deactivate();
  }
}

std::vector<vtkTextureObject*> vtkSLDcsPass::SetTechniqueUniforms(vtkShaderProgram* program)
{
  glBindImageTexture(0, this->Counters.handle, 0, GL_TRUE, 0, GL_READ_ONLY, GL_R32UI);
  glBindImageTexture(1, this->Mask.handle, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R32UI);
  return { sl::bindTexture(program, "volumeCount", this->VolumeCount) };
}

void vtkSLDcsPass::AfterDraw()
{
  glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32UI);
  glBindImageTexture(1, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32UI);
}

std::map<std::string, double> vtkSLDcsPass::CollectStatistics()
{
  std::map<std::string, double> statistics = this->Superclass::CollectStatistics();
  const sl::DcsEdgeStatistics& s = this->Wedges.statistics;
  statistics["silhouette_edges_centre"] = static_cast<double>(s.centreSilhouetteEdges);
  statistics["potential_silhouette_edges"] = static_cast<double>(s.potentialSilhouetteEdges);
  statistics["edges_at_light_plane"] = static_cast<double>(s.edgesAtLightPlane);
  statistics["wedges"] = static_cast<double>(s.wedges);
  statistics["wedges_drawn"] = static_cast<double>(this->DrawnWedges);
  statistics["wedge_build_ms"] = this->WedgeBuildMilliseconds;
  statistics["wedge_fragments"] = static_cast<double>(this->WedgeDrawer.fragments());
  this->Stsvs.addStatistics(statistics);
  const std::size_t pixels = static_cast<std::size_t>(this->Counters.width) * this->Counters.height;
  statistics["sample_buffer_bytes"] = static_cast<double>(4 * pixels * (this->Counters.layers + this->Mask.layers));
  // Forest et al. 2009 §5.1: N x W x H x 1 bit of LS_buffer plus the N x 16-bit sample pattern.
  const int samples = this->SampleCount();
  statistics["paper_sample_buffer_bytes"] = static_cast<double>(samples) * pixels / 8.0 + 2.0 * samples;
  statistics["light_samples"] = samples;
  this->Steps.addTo(statistics);
  return statistics;
}

std::vector<sl::NamedPolyData> vtkSLDcsPass::CollectObjectSpaceExports()
{
  std::vector<sl::NamedPolyData> exports = this->Superclass::CollectObjectSpaceExports();
  // Built here, once per frame whose results are collected, not inside the timed pass.
  exports.push_back({ "wedges",
    "each wedge's two supporting faces (the planes through its edge touching the light) as quads; cell data wedge_id, "
    "caster_id, triangles (of the edge in this record), incident_triangles, centre_silhouette",
    sl::wedgePolyData(this->Wedges, *this->Frame->light, this->Frame->scene->bounds()) });
  this->Stsvs.addExport(exports);
  return exports;
}

std::vector<sl::NamedImage> vtkSLDcsPass::CollectPassBuffers()
{
  const sl::FrameResources& frame = *this->Frame;
  const int samples = this->SampleCount();
  const int width = frame.width();
  const int height = frame.height();
  const std::size_t pixels = static_cast<std::size_t>(width) * height;
  std::vector<sl::NamedImage> buffers;

  buffers.push_back({ "light_sample_mask", this->Mask.readSampleMask(samples), "", "" });
  buffers.push_back(this->VolumeCountStatusImage());

  if (sl::DcsSettings::from(frame.parameters).exportSampleCounts)
  {
    const std::vector<std::uint32_t> counterWords = this->Counters.read();
    const sl::ImageF centre = sl::readFloatTexture(this->VolumeCount, 1);
    sl::ImageF counts(width, height, samples);
    for (std::size_t pixel = 0; pixel < pixels; ++pixel)
    {
      for (int index = 0; index < samples; ++index)
      {
        constexpr int kPerLayer = sl::DcsCounterLayers::kCountersPerLayer;
        const std::uint32_t word = counterWords[static_cast<std::size_t>(index / kPerLayer) * pixels + pixel];
        const int field = sl::DcsCounterLayers::kCounterBits * (index % kPerLayer);
        const int change = static_cast<int>((word >> field) & sl::DcsCounterLayers::kCounterMask) - sl::kDcsCounterBias;
        counts.data[pixel * samples + index] = centre.data[pixel] + static_cast<float>(change);
      }
    }
    buffers.push_back({ "sample_depth_complexity", std::move(counts), "", "" });
  }
  return buffers;
}

void vtkSLDcsPass::ReleaseGraphicsResources(vtkWindow* window)
{
  this->WedgeDrawer.releaseGraphicsResources();
  this->Stsvs.releaseGraphicsResources();
  this->Counters.release();
  this->Mask.release();
  this->Steps.release();
  this->WedgeFramebuffer->ReleaseGraphicsResources(window);
  this->Superclass::ReleaseGraphicsResources(window);
}

void vtkSLDcsPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Wedges: " << this->Wedges.wedges.size() << " (" << this->DrawnWedges << " drawn)\n";
}
