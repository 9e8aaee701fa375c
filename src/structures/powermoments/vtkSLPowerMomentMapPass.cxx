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

  auto moments = sl::makeFloatTarget(window, size, size, 4);
  {
    const sl::ScopedRenderTarget target(window, this->Framebuffer, { moments });
    vtkShaderProgram* program = this->MomentsQuad.ready(
      window, sl::assembleShader("powermoments/PowerMomentsFromDepth.glsl"), "power moments");
    vtkTextureObject* bound = sl::bindTexture(program, "shadowMapLinear", frame.shadowMapLinear);
    program->SetUniformf("depthNear", static_cast<float>(frame.lightView.nearDepth));
    program->SetUniformf("depthFar", static_cast<float>(frame.lightView.farDepth));
    this->MomentsQuad.render();
    bound->Deactivate();
  }
  // The moment map's prefilter: the same texels as vsm's and esm's.
  moments = sl::prefilterMoments(window, this->Framebuffer, this->BlurQuad, moments, settings.blurTexels, settings.mipmap);
  auto data = std::make_shared<sl::PowerMomentMapData>();
  data->moments = moments;
  data->mipmapped = settings.mipmap;
  frame.lightSpaceData[sl::powerMomentMapStructure().name] = data;
}

void vtkSLPowerMomentMapPass::ReleaseGraphicsResources(vtkWindow* window)
{
  this->MomentsQuad.releaseGraphicsResources(window);
  this->BlurQuad.releaseGraphicsResources(window);
  this->Framebuffer->ReleaseGraphicsResources(window);
}

void vtkSLPowerMomentMapPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Stage: " << this->GetStageName() << "\n";
}
