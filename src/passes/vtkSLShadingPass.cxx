#include "passes/vtkSLShadingPass.h"

#include "core/Error.h"
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
#include <vtk_glew.h>

#include <string>
#include <vector>

vtkStandardNewMacro(vtkSLShadingPass);

vtkSLShadingPass::vtkSLShadingPass() = default;
vtkSLShadingPass::~vtkSLShadingPass() = default;

void vtkSLShadingPass::Execute(const vtkRenderState* state)
{
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(state->GetRenderer()->GetRenderWindow());
  sl::FrameResources& frame = *this->Frame;
  frame.shadedImage = sl::makeColorTarget(window, frame.width(), frame.height());

  const sl::ScopedRenderTarget target(window, this->Framebuffer, { frame.shadedImage });
  const bool multisampled = frame.multisample.samples > 1;
  sl::ShaderDefines defines = sl::commonDefines();
  if (multisampled)
  {
    defines.emplace_back("MSAA_SAMPLES", std::to_string(frame.multisample.samples));
  }
  vtkShaderProgram* program =
    this->Quad.ready(window, sl::assembleShader("shading/ShadingFragment.glsl", defines), "shading");
  std::vector<vtkTextureObject*> bound = {
    sl::bindTexture(program, "gbufferPosition", frame.gbufferPosition),
    sl::bindTexture(program, "gbufferNormal", frame.gbufferNormal),
    sl::bindTexture(program, "gbufferAlbedoDepth", frame.gbufferAlbedoDepth),
    sl::bindTexture(program, "visibilityTexture", frame.techniqueTargets.at("visibility")),
  };
  if (multisampled)
  {
    bound.push_back(sl::bindTexture(program, "multisamplePosition", frame.gbufferMsPosition));
    bound.push_back(sl::bindTexture(program, "multisampleNormal", frame.gbufferMsNormal));
    bound.push_back(sl::bindTexture(program, "multisampleAlbedoDepth", frame.gbufferMsAlbedoDepth));
    bound.push_back(sl::bindTexture(program, "sampleVisibility", frame.sampleVisibility));
  }
  sl::setLightUniforms(program, *frame.light);
  sl::setFloatIfUsed(program, "lightIntensity", frame.light->intensity);
  if (program->IsUniformUsed("backgroundColor"))
  {
    sl::setVector(program, "backgroundColor", glm::dvec3(0.32, 0.34, 0.38));
  }
  this->Quad.render();
  for (vtkTextureObject* texture : bound)
  {
    texture->Deactivate();
  }
}

void vtkSLShadingPass::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Quad.releaseGraphicsResources(window);
  this->Framebuffer->ReleaseGraphicsResources(window);
}

void vtkSLShadingPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
