#include "passes/vtkSLLightDepthPass.h"

#include "core/Error.h"
#include "gl/ShaderLibrary.h"
#include "passes/FrameResources.h"
#include "passes/PassUtilities.h"
#include "passes/ScopedRenderTarget.h"

#include <vtkObjectFactory.h>
#include <vtkOpenGLFramebufferObject.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkOpenGLState.h>
#include <vtkRenderState.h>
#include <vtkRenderer.h>
#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>
#include <vtk_glew.h>


vtkStandardNewMacro(vtkSLLightDepthPass);

vtkSLLightDepthPass::vtkSLLightDepthPass() = default;
vtkSLLightDepthPass::~vtkSLLightDepthPass() = default;

void vtkSLLightDepthPass::Execute(const vtkRenderState* state)
{
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(state->GetRenderer()->GetRenderWindow());
  sl::FrameResources& frame = *this->Frame;
  const sl::ParameterValues& parameters = frame.parameters;

  SL_CHECK_MSG(frame.hasLightView, "the focus stage must run before the shadow map");
  const sl::LightView& view = frame.lightView;

  frame.shadowMapLinear = sl::makeFloatTarget(window, view.resolution, view.resolution, 1);
  frame.shadowMapDepth = sl::makeDepthTarget(window, view.resolution, view.resolution);

  const sl::ScopedRenderTarget target(window, this->Framebuffer, { frame.shadowMapLinear }, frame.shadowMapDepth);
  // Texels no caster covers hold a depth beyond every receiver: they never shadow anything.
  target.clearColor(0, static_cast<float>(2.0 * view.farDepth));
  target.clearDepth();

  sl::ShaderDefines defines = sl::commonDefines();
  defines.push_back({ "CASTER_FACES_FRONT", "0" });
  defines.push_back({ "CASTER_FACES_BACK", "1" });
  const bool secondDepth =
    frame.technique->findParameter("caster_faces") && parameters.choice("caster_faces") == "back";
  defines.push_back({ "CASTER_FACES", secondDepth ? "1" : "0" });
  vtkShaderProgram* program = sl::readyProgram(window, sl::assembleShader("lightspace/LightDepthVertex.glsl", defines),
    sl::assembleShader("lightspace/LightDepthFragment.glsl", defines), "light depth");
  sl::setMatrix(program, "lightClipFromWorld", view.clipFromWorld);
  sl::setMatrix(program, "lightViewFromWorld", view.viewFromWorld);
  this->Drawer.draw(program, *frame.gpuScene, [](const sl::SceneObject& object) { return object.castShadows; });

}

void vtkSLLightDepthPass::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Drawer.releaseGraphicsResources(vtkOpenGLRenderWindow::SafeDownCast(window));
  this->Framebuffer->ReleaseGraphicsResources(window);
}

void vtkSLLightDepthPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
