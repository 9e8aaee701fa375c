#include "passes/vtkSLMsaaResolvePass.h"

#include "core/Error.h"
#include "gl/GlResources.h"
#include "gl/ShaderLibrary.h"
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

#include <string>

vtkStandardNewMacro(vtkSLMsaaResolvePass);

vtkSLMsaaResolvePass::vtkSLMsaaResolvePass() = default;
vtkSLMsaaResolvePass::~vtkSLMsaaResolvePass() = default;

void vtkSLMsaaResolvePass::Execute(const vtkRenderState* state)
{
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(state->GetRenderer()->GetRenderWindow());
  sl::FrameResources& frame = *this->Frame;
  // One component per sample in an RGBA target: the resolve (and MultisampleSettings) supports 4 samples.
  SL_CHECK_MSG(frame.multisample.samples == 4, "the MSAA resolve takes 4 samples, not ", frame.multisample.samples);
  const int width = frame.width();
  const int height = frame.height();
  const vtkSmartPointer<vtkTextureObject> resolved = sl::makeFloatTarget(window, width, height, 1);
  frame.sampleVisibility = sl::makeFloatTarget(window, width, height, 4);
  frame.sampleDepth = sl::makeFloatTarget(window, width, height, 4);
  frame.distinctSamples = sl::makeFloatTarget(window, width, height, 1);
  frame.interpolatedSamples = sl::makeFloatTarget(window, width, height, 1);
  {
    const sl::ScopedRenderTarget target(window, this->Framebuffer,
      { resolved, frame.sampleVisibility, frame.sampleDepth, frame.distinctSamples, frame.interpolatedSamples });
    const sl::ShaderDefines defines = { { "MSAA_SAMPLES", std::to_string(frame.multisample.samples) } };
    vtkShaderProgram* program = this->Quad.ready(window, sl::assembleShader("msaa/MsaaResolve.glsl", defines), "msaa resolve");
    vtkTextureObject* bound[] = {
      sl::bindTexture(program, "pixelVisibility", frame.techniqueTargets.at("visibility")),
      sl::bindTexture(program, "gbufferPosition", frame.gbufferPosition),
      sl::bindTexture(program, "gbufferAlbedoDepth", frame.gbufferAlbedoDepth),
      sl::bindTexture(program, "multisamplePosition", frame.gbufferMsPosition),
      sl::bindTexture(program, "multisampleAlbedoDepth", frame.gbufferMsAlbedoDepth),
    };
    sl::setFloatIfUsed(program, "depthTolerance", frame.multisample.depthTolerance);
    this->Quad.render();
    for (vtkTextureObject* texture : bound)
    {
      texture->Deactivate();
    }
  }
  frame.pixelVisibility = frame.techniqueTargets.at("visibility");
  frame.techniqueTargets["visibility"] = resolved;
  sl::checkGlErrors("msaa_resolve");
}

void vtkSLMsaaResolvePass::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Quad.releaseGraphicsResources(window);
  this->Framebuffer->ReleaseGraphicsResources(window);
}

void vtkSLMsaaResolvePass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
