#include "structures/moments/vtkSLMomentMapPass.h"

#include "core/Error.h"
#include "gl/ShaderLibrary.h"
#include "structures/moments/MomentMapStructure.h"
#include "structures/moments/MomentPrefilter.h"
#include "passes/FrameResources.h"
#include "passes/PassUtilities.h"
#include "passes/ScopedRenderTarget.h"

#include <vtkObjectFactory.h>
#include <vtkOpenGLFramebufferObject.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkRenderState.h>
#include <vtkRenderer.h>
#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>
#include <vtk_glew.h>

vtkStandardNewMacro(vtkSLMomentMapPass);

vtkSLMomentMapPass::vtkSLMomentMapPass() = default;
vtkSLMomentMapPass::~vtkSLMomentMapPass() = default;

void vtkSLMomentMapPass::Execute(const vtkRenderState* state)
{
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(state->GetRenderer()->GetRenderWindow());
  sl::FrameResources& frame = *this->Frame;
  SL_CHECK_MSG(frame.hasLightView && frame.shadowMapLinear, "the shadow map must be built before its moments");
  const sl::MomentMapSettings settings = sl::momentMapSettings(frame);
  const int size = frame.lightView.resolution;
  const double exponent = settings.esmExponent;
  const bool mipmap = settings.mipmap;
  const int blurWidth = settings.blurTexels;

  // prefilter_region = receivers: each draw only over what the next one reads (ReceiverTiles.h).
  std::optional<sl::ReceiverPrefilterPlan> plan =
    this->TileMarker.planWhereItPays(window, frame, blurWidth, settings.receiversOnly);

  if (plan && plan->blur.sparse)
  {
    // Only the listed texels, their moments formed inline: no moments pass, no blur passes.
    auto data = std::make_shared<sl::MomentMapData>();
    data->moments = sl::sparseMomentsOfDepth(window, frame.shadowMapLinear, frame.lightView.nearDepth,
      frame.lightView.farDepth, exponent, blurWidth, plan->blur, this->BlurTargets);
    plan->sourceTiles = 0; // no moments pass
    data->region = plan;
    frame.lightSpaceData[sl::momentMapStructure().name] = data;
    return;
  }

  vtkSmartPointer<vtkTextureObject> moments = sl::reusedFloatTarget(window, this->MomentsTarget, size, size, 4);
  {
    const sl::ScopedRenderTarget target(window, this->Framebuffer, { moments });
    vtkShaderProgram* program =
      this->MomentsQuad.ready(window, sl::assembleShader("moments/MomentsFromDepth.glsl"), "moments");
    vtkTextureObject* bound = sl::bindTexture(program, "shadowMapLinear", frame.shadowMapLinear);
    program->SetUniformf("depthNear", static_cast<float>(frame.lightView.nearDepth));
    program->SetUniformf("depthFar", static_cast<float>(frame.lightView.farDepth));
    program->SetUniformf("esmExponent", static_cast<float>(exponent));
    sl::renderQuadOver(window, this->MomentsQuad, plan ? &plan->source : nullptr);
    bound->Deactivate();
  }
  moments = sl::prefilterMoments(window, this->Framebuffer, this->BlurQuad, moments, blurWidth, mipmap,
    plan ? &plan->blur : nullptr, &this->BlurTargets);
  auto data = std::make_shared<sl::MomentMapData>();
  data->moments = moments;
  data->mipmapped = mipmap;
  data->region = plan;
  frame.lightSpaceData[sl::momentMapStructure().name] = data;
}

void vtkSLMomentMapPass::ReleaseGraphicsResources(vtkWindow* window)
{
  this->MomentsQuad.releaseGraphicsResources(window);
  this->BlurQuad.releaseGraphicsResources(window);
  this->Framebuffer->ReleaseGraphicsResources(window);
  this->TileMarker.release();
  this->MomentsTarget = nullptr;
  this->BlurTargets = sl::PrefilterTargets{};
}

void vtkSLMomentMapPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
