#include "passes/ShadowMapRendering.h"

#include "gl/ShaderLibrary.h"
#include "passes/PassUtilities.h"
#include "passes/ScopedRenderTarget.h"

#include <vtkOpenGLRenderWindow.h>
#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>
#include <vtk_glew.h>

namespace sl
{

namespace
{

void renderCasterDepth(vtkOpenGLRenderWindow* window, vtkOpenGLFramebufferObject* framebuffer, MeshDrawer& drawer,
  const GpuScene& scene, const LightView& view, bool secondDepth, vtkTextureObject* peelBehind,
  vtkTextureObject* linearDepth, vtkTextureObject* hardwareDepth, vtkTextureObject* polygonIds = nullptr)
{
  if (polygonIds)
  {
    const GLuint none = 0;
    glClearTexImage(polygonIds->GetHandle(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &none);
  }
  const ScopedRenderTarget target(window, framebuffer,
    polygonIds ? std::vector<vtkTextureObject*>{ linearDepth, polygonIds } : std::vector<vtkTextureObject*>{ linearDepth },
    hardwareDepth);
  // Texels no caster covers hold a depth beyond every receiver: they never shadow anything.
  target.clearColor(0, static_cast<float>(2.0 * view.farDepth));
  target.clearDepth();

  ShaderDefines defines = commonDefines();
  defines.push_back({ "CASTER_FACES_FRONT", "0" });
  defines.push_back({ "CASTER_FACES_BACK", "1" });
  defines.push_back({ "CASTER_FACES", secondDepth ? "1" : "0" });
  defines.push_back({ "WARPED_DEPTH", view.warp.active() ? "1" : "0" });
  defines.push_back({ "DEPTH_PEEL", peelBehind ? "1" : "0" });
  defines.push_back({ "POLYGON_ID", polygonIds ? "1" : "0" });
  vtkShaderProgram* program = readyProgram(window, assembleShader("lightspace/LightDepthVertex.glsl", defines),
    assembleShader("lightspace/LightDepthFragment.glsl", defines), "light depth");
  setMatrix(program, "lightClipFromWorld", view.clipFromWorld);
  setMatrix(program, "lightViewFromWorld", view.viewFromWorld);
  if (view.warp.active())
  {
    program->SetUniformf("lightNearDepth", static_cast<float>(view.nearDepth));
    program->SetUniformf("lightFarDepth", static_cast<float>(view.farDepth));
  }
  vtkTextureObject* bound = peelBehind ? bindTexture(program, "firstLayerLinear", peelBehind) : nullptr;
  drawer.draw(program, scene, [](const SceneObject& object) { return object.castShadows; });
  if (bound)
  {
    bound->Deactivate();
  }
}

} // namespace

void renderShadowMap(vtkOpenGLRenderWindow* window, vtkOpenGLFramebufferObject* framebuffer, MeshDrawer& drawer,
  const GpuScene& scene, const LightView& view, bool secondDepth, vtkTextureObject* linearDepth,
  vtkTextureObject* hardwareDepth)
{
  renderCasterDepth(window, framebuffer, drawer, scene, view, secondDepth, nullptr, linearDepth, hardwareDepth);
}

void renderPolygonIdShadowMap(vtkOpenGLRenderWindow* window, vtkOpenGLFramebufferObject* framebuffer, MeshDrawer& drawer,
  const GpuScene& scene, const LightView& view, vtkTextureObject* linearDepth, vtkTextureObject* hardwareDepth,
  vtkTextureObject* polygonIds)
{
  renderCasterDepth(window, framebuffer, drawer, scene, view, false, nullptr, linearDepth, hardwareDepth, polygonIds);
}

void renderPeeledShadowMap(vtkOpenGLRenderWindow* window, vtkOpenGLFramebufferObject* framebuffer, MeshDrawer& drawer,
  const GpuScene& scene, const LightView& view, vtkTextureObject* firstLayer, vtkTextureObject* linearDepth,
  vtkTextureObject* hardwareDepth)
{
  renderCasterDepth(window, framebuffer, drawer, scene, view, false, firstLayer, linearDepth, hardwareDepth);
}

} // namespace sl
