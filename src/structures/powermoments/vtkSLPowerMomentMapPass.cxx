#include "structures/powermoments/vtkSLPowerMomentMapPass.h"

#include "core/Error.h"
#include "gl/ShaderLibrary.h"
#include "passes/FrameResources.h"
#include "passes/PassUtilities.h"
#include "passes/ScopedRenderTarget.h"
#include "structures/powermoments/PowerMomentMapStructure.h"
#include "structures/moments/MomentPrefilter.h"

#include <vtkObjectFactory.h>
#include <vtkOpenGLFramebufferObject.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkOpenGLShaderCache.h>
#include <vtkRenderState.h>
#include <vtkRenderer.h>
#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>
#include <vtk_glew.h>

vtkStandardNewMacro(vtkSLPowerMomentMapPass);

vtkSLPowerMomentMapPass::vtkSLPowerMomentMapPass() = default;
vtkSLPowerMomentMapPass::~vtkSLPowerMomentMapPass() = default;

void vtkSLPowerMomentMapPass::Execute(const vtkRenderState* state)
{
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(state->GetRenderer()->GetRenderWindow());
  sl::FrameResources& frame = *this->Frame;
  SL_CHECK_MSG(frame.hasLightView && frame.shadowMapLinear, "the shadow map must be built before its power moments");
  const sl::PowerMomentMapSettings settings = sl::PowerMomentMapSettings::from(frame.parameters);
  const int size = frame.lightView.resolution;

  auto data = std::make_shared<sl::PowerMomentMapData>();
  data->mipmapped = settings.mipmap;
  // prefilter_region = receivers, as the moment map (structures/moments/README.md).
  data->region = this->TileMarker.planWhereItPays(window, frame, settings.blurTexels, settings.receiversOnly);
  if (data->region && data->region->blur.sparse)
  {
    // Only the listed texels, their power moments formed inline: no moments pass, no blur passes.
    if (!this->SparseProgram)
    {
      this->SparseProgram = std::make_unique<sl::ComputeProgram>(
        sl::assembleShader("powermoments/PowerMomentsSparseBlur.glsl"), "sparse power-moment blur");
    }
    this->SparseProgram->use();
    // In float, as the moments pass sets them (SetUniformf).
    this->SparseProgram->setFloat("depthNear", static_cast<float>(frame.lightView.nearDepth));
    this->SparseProgram->setFloat("depthFar", static_cast<float>(frame.lightView.farDepth));
    data->moments = sl::reusedFloatTarget(window, this->BlurTargets.blurred, size, size, 4);
    sl::blurReceiverTexels(
      *this->SparseProgram, frame.shadowMapLinear, { data->moments }, settings.blurTexels, data->region->blur);
    window->GetShaderCache()->ReleaseCurrentShader();
    data->region->sourceTiles = 0; // no moments pass
    frame.lightSpaceData[sl::powerMomentMapStructure().name] = data;
    return;
  }
  vtkSmartPointer<vtkTextureObject> moments = sl::reusedFloatTarget(window, this->MomentsTarget, size, size, 4);
  {
    const sl::ScopedRenderTarget target(window, this->Framebuffer, { moments });
    vtkShaderProgram* program = this->MomentsQuad.ready(
      window, sl::assembleShader("powermoments/PowerMomentsFromDepth.glsl"), "power moments");
    vtkTextureObject* bound = sl::bindTexture(program, "shadowMapLinear", frame.shadowMapLinear);
    program->SetUniformf("depthNear", static_cast<float>(frame.lightView.nearDepth));
    program->SetUniformf("depthFar", static_cast<float>(frame.lightView.farDepth));
    sl::renderQuadOver(window, this->MomentsQuad, data->region ? &data->region->source : nullptr);
    bound->Deactivate();
  }
  // The moment map's prefilter: the same texels as vsm's and esm's.
  data->moments = sl::prefilterMoments(window, this->Framebuffer, this->BlurQuad, moments, settings.blurTexels,
    settings.mipmap, data->region ? &data->region->blur : nullptr, &this->BlurTargets);
  frame.lightSpaceData[sl::powerMomentMapStructure().name] = data;
}

void vtkSLPowerMomentMapPass::ReleaseGraphicsResources(vtkWindow* window)
{
  this->MomentsQuad.releaseGraphicsResources(window);
  this->BlurQuad.releaseGraphicsResources(window);
  this->Framebuffer->ReleaseGraphicsResources(window);
  this->TileMarker.release();
  this->SparseProgram.reset();
  this->MomentsTarget = nullptr;
  this->BlurTargets = sl::PrefilterTargets{};
}

void vtkSLPowerMomentMapPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Stage: " << this->GetStageName() << "\n";
}
