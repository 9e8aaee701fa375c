#include "techniques/penumbrawedge/vtkSLPenumbraWedgePass.h"

#include "core/Error.h"
#include "gl/GlResources.h"
#include "gl/ShaderLibrary.h"
#include "passes/FrameResources.h"
#include "passes/PassUtilities.h"
#include "passes/ScopedRenderTarget.h"
#include "objectspace/DcsWedgeExport.h"
#include "techniques/penumbrawedge/PenumbraWedgeGeometry.h"
#include "techniques/penumbrawedge/PenumbraWedgeTechnique.h"

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
#include <string>

vtkStandardNewMacro(vtkSLPenumbraWedgePass);

namespace
{

const char* const kPenumbraWedgeAreaShader = "penumbrawedge/PenumbraWedgeArea.glsl";

} // namespace

vtkSLPenumbraWedgePass::vtkSLPenumbraWedgePass() = default;
vtkSLPenumbraWedgePass::~vtkSLPenumbraWedgePass() = default;

void vtkSLPenumbraWedgePass::Execute(const vtkRenderState* state)
{
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(state->GetRenderer()->GetRenderWindow());
  this->Steps.mark(0);
  // Step 1: the centre's hard shadow (the shadow-volume pass).
  this->BuildAndCountVolumes(window);
  this->Steps.mark(1);
  // Step 2: the centre silhouettes' wedges, built on the CPU, blended into the occlusion.
  this->DrawWedges(window);
  sl::checkGlErrors("penumbra-wedge (wedges)");
  this->Steps.mark(2);
  // Step 3: the perforated casters' STSVs into the light-sample mask.
  this->DrawStsvs(window);
  sl::checkGlErrors("penumbra-wedge (STSVs)");
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  this->Steps.mark(3);
  // Step 4: the resolve, the base class's full-screen shader.
  this->vtkSLTechniquePass::Execute(state);
  glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
  this->Steps.mark(4);
  sl::checkGlErrors("penumbra-wedge (resolve)");
}

void vtkSLPenumbraWedgePass::DrawWedges(vtkOpenGLRenderWindow* window)
{
  const sl::FrameResources& frame = *this->Frame;
  const auto buildStart = std::chrono::steady_clock::now();
  const sl::DcsEdgeSet potential = sl::potentialSilhouetteWedges(*frame.weldedCasters, *frame.light);
  this->Wedges.statistics = potential.statistics;
  this->Wedges.wedges = sl::centreSilhouetteWedges(potential);
  this->DrawnWedges = this->WedgeDrawer.prepare(this->Wedges.wedges, frame);
  this->WedgeBuildMilliseconds =
    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - buildStart).count();

  this->OcclusionDelta = sl::makeFloatTarget(window, frame.width(), frame.height(), 1);
  this->WedgesCovering = sl::makeFloatTarget(window, frame.width(), frame.height(), 1);
  const sl::ShaderDefines defines = this->TechniqueDefines();
  vtkShaderProgram* program = sl::readyProgram(window, sl::assembleShader(sl::kWedgeVertexShaderPath, defines),
    sl::assembleShader(kPenumbraWedgeAreaShader, defines, this->ParameterDeclarations()),
    "penumbra-wedge wedges");
  std::vector<vtkTextureObject*> bound = this->SetCommonUniforms(program);
  this->SetReceiverOffsetUniforms(program);
  sl::setFloatIfUsed(program, "lightHalfSize", 0.5 * frame.light->size);

  const sl::ScopedRenderTarget target(window, this->WedgeFramebuffer, { this->OcclusionDelta, this->WedgesCovering });
  target.clearColor(0, 0.0f);
  target.clearColor(1, 0.0f);
  // Every wedge adds its share: one, one blending (float targets blend unclamped).
  vtkOpenGLState* glState = window->GetState();
  const vtkOpenGLState::ScopedglBlendFuncSeparate blendFunction(glState);
  glState->vtkglEnable(GL_BLEND);
  glState->vtkglBlendFuncSeparate(GL_ONE, GL_ONE, GL_ONE, GL_ONE);
  glBlendEquation(GL_FUNC_ADD);
  this->WedgeDrawer.drawCounted(program, *frame.light);
  glState->vtkglDisable(GL_BLEND);
  for (vtkTextureObject* texture : bound)
  {
    texture->Deactivate();
  }
}

std::vector<vtkSLTechniquePass::PassShader> vtkSLPenumbraWedgePass::GetPassShaders() const
{
  return { { kPenumbraWedgeAreaShader, {} }, { sl::kStsvSamplesShaderPath, {} } };
}

int vtkSLPenumbraWedgePass::SampleCount() const
{
  return sl::PenumbraWedgeSettings::from(this->Frame->parameters).lightSamples.count;
}

void vtkSLPenumbraWedgePass::DrawStsvs(vtkOpenGLRenderWindow* window)
{
  const sl::FrameResources& frame = *this->Frame;
  const int samples = this->SampleCount();
  this->Mask.allocate(frame.width(), frame.height(), (samples + 31) / 32);
  const GLuint zero = 0u;
  glClearTexImage(this->Mask.handle, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  this->StsvCovering = sl::makeFloatTarget(window, frame.width(), frame.height(), 1);
  this->StsvEmptyHits = sl::makeFloatTarget(window, frame.width(), frame.height(), 1);

  this->Stsvs.prepare(frame);

  const sl::ShaderDefines defines = this->TechniqueDefines();
  vtkShaderProgram* program = sl::readyProgram(window, sl::assembleShader(sl::kWedgeVertexShaderPath, defines),
    sl::assembleShader(sl::kStsvSamplesShaderPath, defines, this->ParameterDeclarations()), "penumbra-wedge STSVs");
  std::vector<vtkTextureObject*> bound = this->SetCommonUniforms(program);
  this->SetReceiverOffsetUniforms(program);
  sl::setIntIfUsed(program, "stsvOppositeSideCheck",
    sl::PenumbraWedgeSettings::from(frame.parameters).stsvTest == sl::StsvOcclusionTest::PaperAndOppositeSides ? 1 : 0);
  glBindImageTexture(1, this->Mask.handle, 0, GL_TRUE, 0, GL_READ_WRITE, GL_R32UI);

  const sl::ScopedRenderTarget target(window, this->StsvFramebuffer, { this->StsvCovering, this->StsvEmptyHits });
  target.clearColor(0, 0.0f);
  target.clearColor(1, 0.0f);
  vtkOpenGLState* glState = window->GetState();
  const vtkOpenGLState::ScopedglBlendFuncSeparate blendFunction(glState);
  glState->vtkglEnable(GL_BLEND);
  glState->vtkglBlendFuncSeparate(GL_ONE, GL_ONE, GL_ONE, GL_ONE);
  glBlendEquation(GL_FUNC_ADD);
  this->Stsvs.draw(program, frame);
  glState->vtkglDisable(GL_BLEND);
  glBindImageTexture(1, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
  for (vtkTextureObject* texture : bound)
  {
    texture->Deactivate();
  }
}

std::vector<vtkTextureObject*> vtkSLPenumbraWedgePass::SetTechniqueUniforms(vtkShaderProgram* program)
{
  glBindImageTexture(1, this->Mask.handle, 0, GL_TRUE, 0, GL_READ_ONLY, GL_R32UI);
  return { sl::bindTexture(program, "volumeCount", this->VolumeCount),
    sl::bindTexture(program, "occlusionDelta", this->OcclusionDelta),
    sl::bindTexture(program, "wedgesCovering", this->WedgesCovering),
    sl::bindTexture(program, "stsvCovering", this->StsvCovering),
    sl::bindTexture(program, "stsvEmptyHits", this->StsvEmptyHits) };
}

void vtkSLPenumbraWedgePass::AfterDraw()
{
  glBindImageTexture(1, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32UI);
}

std::vector<sl::NamedImage> vtkSLPenumbraWedgePass::CollectPassBuffers()
{
  return { { "light_sample_mask", this->Mask.readSampleMask(this->SampleCount()), "", "" },
    this->VolumeCountStatusImage() };
}

std::map<std::string, double> vtkSLPenumbraWedgePass::CollectStatistics()
{
  std::map<std::string, double> statistics = this->Superclass::CollectStatistics();
  const sl::DcsEdgeStatistics& s = this->Wedges.statistics;
  statistics["silhouette_edges_centre"] = static_cast<double>(s.centreSilhouetteEdges);
  statistics["potential_silhouette_edges"] = static_cast<double>(s.potentialSilhouetteEdges);
  statistics["wedges"] = static_cast<double>(this->Wedges.wedges.size());
  statistics["wedges_drawn"] = static_cast<double>(this->DrawnWedges);
  statistics["wedge_build_ms"] = this->WedgeBuildMilliseconds;
  statistics["wedge_fragments"] = static_cast<double>(this->WedgeDrawer.fragments());
  this->Stsvs.addStatistics(statistics);
  statistics["light_samples"] = this->SampleCount();
  this->Steps.addTo(statistics);
  return statistics;
}

std::vector<sl::NamedPolyData> vtkSLPenumbraWedgePass::CollectObjectSpaceExports()
{
  std::vector<sl::NamedPolyData> exports = this->Superclass::CollectObjectSpaceExports();
  exports.push_back({ "wedges",
    "each centre-silhouette wedge's two supporting faces (the planes through its edge touching the light) as quads; "
    "cell data wedge_id, caster_id, triangles, incident_triangles, centre_silhouette",
    sl::wedgePolyData(this->Wedges, *this->Frame->light, this->Frame->scene->bounds()) });
  this->Stsvs.addExport(exports);
  return exports;
}

void vtkSLPenumbraWedgePass::ReleaseGraphicsResources(vtkWindow* window)
{
  this->WedgeDrawer.releaseGraphicsResources();
  this->Stsvs.releaseGraphicsResources();
  this->Mask.release();
  this->StsvCovering = nullptr;
  this->StsvEmptyHits = nullptr;
  this->StsvFramebuffer->ReleaseGraphicsResources(window);
  this->OcclusionDelta = nullptr;
  this->WedgesCovering = nullptr;
  this->Steps.release();
  this->WedgeFramebuffer->ReleaseGraphicsResources(window);
  this->Superclass::ReleaseGraphicsResources(window);
}

void vtkSLPenumbraWedgePass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Centre-silhouette wedges: " << this->Wedges.wedges.size() << " (" << this->DrawnWedges << " drawn)\n";
}
