#include "structures/shadowmap/vtkSLLightDepthPass.h"

#include "core/Error.h"
#include "structures/shadowmap/ShadowMapStructure.h"
#include "passes/FrameResources.h"
#include "passes/PassUtilities.h"
#include "passes/ScopedRenderTarget.h"
#include "passes/ShadowMapRendering.h"
#include "gl/ShaderLibrary.h"

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

  SL_CHECK_MSG(frame.hasLightView, "the focus stage must run before the shadow map");
  const sl::LightView& view = frame.lightView;

  // The previous frame's (or sub-light's) targets are reused when they have the map's size: the render
  // clears both, and fresh 2048^2 targets (2 x 16 MB) cost llvmpipe more wall time than drawing the casters.
  // Views that partition the pixels (PartitionViews.h) keep one pair each, for the export.
  const unsigned size = static_cast<unsigned>(view.resolution);
  const std::size_t index = frame.partitions ? static_cast<std::size_t>(frame.viewIndex) : 0;
  if (this->LinearTargets.size() <= index)
  {
    this->LinearTargets.resize(index + 1);
    this->DepthTargets.resize(index + 1);
  }
  vtkSmartPointer<vtkTextureObject>& linear = this->LinearTargets[index];
  if (!linear || linear->GetContext() != window || linear->GetWidth() != size)
  {
    linear = sl::makeFloatTarget(window, view.resolution, view.resolution, 1);
    this->DepthTargets[index] = sl::makeDepthTarget(window, view.resolution, view.resolution);
  }
  frame.shadowMapLinear = linear;
  frame.shadowMapDepth = this->DepthTargets[index];
  if (frame.partitions)
  {
    frame.viewShadowMapLinear.resize(static_cast<std::size_t>(frame.partitions->viewCount()));
    frame.viewShadowMapDepth.resize(static_cast<std::size_t>(frame.partitions->viewCount()));
    frame.viewShadowMapLinear[index] = frame.shadowMapLinear;
    frame.viewShadowMapDepth[index] = frame.shadowMapDepth;
  }
  const sl::ShadowMapSettings settings = sl::shadowMapSettings(frame);
  if (settings.depthLayer == sl::ShadowMapDepthLayer::PolygonId)
  {
    this->RenderPolygonIds(window);
    return;
  }
  if (settings.depthLayer == sl::ShadowMapDepthLayer::First)
  {
    if (index == 0)
    {
      frame.lightSpaceData.erase(sl::shadowMapStructure().name); // no layers of an earlier frame in this one's export
    }
    sl::renderShadowMap(window, this->Framebuffer, this->Drawer, *frame.gpuScene, view, settings.secondDepth,
      frame.shadowMapLinear, frame.shadowMapDepth);
    return;
  }
  this->RenderDepthLayers(window, settings, index);
}

void vtkSLLightDepthPass::RenderDepthLayers(
  vtkOpenGLRenderWindow* window, const sl::ShadowMapSettings& settings, std::size_t index)
{
  // Survey §5: the midpoint (Woo 1992) and dual (Weiskopf & Ertl 2003) maps store one depth combined from the nearest
  // and the second-nearest surface; the second by depth peeling, not by back faces, so open casters have one too.
  sl::FrameResources& frame = *this->Frame;
  const sl::LightView& view = frame.lightView;
  const unsigned size = static_cast<unsigned>(view.resolution);
  std::shared_ptr<sl::LightSpaceData>& entry = frame.lightSpaceData[sl::shadowMapStructure().name];
  if (index == 0 || !entry)
  {
    entry = std::make_shared<sl::ShadowMapLayersData>(); // the first view starts the frame's layers afresh
  }
  auto& layers = dynamic_cast<sl::ShadowMapLayersData&>(*entry);
  if (layers.first.size() <= index)
  {
    layers.first.resize(index + 1);
    layers.second.resize(index + 1);
  }
  if (!this->PeelDepth || this->PeelDepth->GetContext() != window || this->PeelDepth->GetWidth() != size)
  {
    this->PeelDepth = sl::makeDepthTarget(window, view.resolution, view.resolution);
  }
  // Fresh layer targets per frame: the frame's data keeps them for the export (2 x 4 bytes per texel).
  layers.first[index] = sl::makeFloatTarget(window, view.resolution, view.resolution, 1);
  layers.second[index] = sl::makeFloatTarget(window, view.resolution, view.resolution, 1);
  sl::renderShadowMap(
    window, this->Framebuffer, this->Drawer, *frame.gpuScene, view, false, layers.first[index], this->PeelDepth);
  sl::renderPeeledShadowMap(window, this->Framebuffer, this->Drawer, *frame.gpuScene, view, layers.first[index],
    layers.second[index], this->PeelDepth);

  const sl::ScopedRenderTarget target(window, this->Framebuffer, { frame.shadowMapLinear }, frame.shadowMapDepth);
  target.clearColor(0, static_cast<float>(2.0 * view.farDepth));
  target.clearDepth();
  // Every texel is written, a combined depth past the far plane too (the midpoint of a caster and an empty second
  // layer, 2 x far): its hardware depth clamps to 1 like an empty texel's, and the linear one keeps it.
  vtkOpenGLState::ScopedglDepthFunc depthFunc(window->GetState());
  window->GetState()->vtkglDepthFunc(GL_ALWAYS);
  sl::ShaderDefines defines = sl::commonDefines();
  defines.push_back({ "DEPTH_LAYER_MIDPOINT", "1" });
  defines.push_back({ "DEPTH_LAYER_DUAL", "2" });
  defines.push_back({ "DEPTH_LAYER", settings.depthLayer == sl::ShadowMapDepthLayer::Dual ? "2" : "1" });
  defines.push_back({ "WARPED_DEPTH", view.warp.active() ? "1" : "0" });
  vtkShaderProgram* program =
    this->CombineQuad.ready(window, sl::assembleShader("shadowmap/DepthLayerCombine.glsl", defines), "depth layers");
  vtkTextureObject* bound[] = {
    sl::bindTexture(program, "firstLayerLinear", layers.first[index]),
    sl::bindTexture(program, "secondLayerLinear", layers.second[index]),
  };
  program->SetUniformi("lightIsPerspective", view.projection == sl::LightProjection::Perspective ? 1 : 0);
  sl::setFloatIfUsed(program, "shadowTexelExtent",
    view.projection == sl::LightProjection::Perspective ? view.texelWorldSize(1.0) : view.texelWorldSize(0.0));
  sl::setFloatIfUsed(program, "dualMaxOffsetTexels", settings.dualMaxOffsetTexels);
  const glm::dmat4& projection = view.clipFromView;
  const float depthToClip[4] = { static_cast<float>(projection[2][2]), static_cast<float>(projection[3][2]),
    static_cast<float>(projection[2][3]), static_cast<float>(projection[3][3]) };
  if (program->IsUniformUsed("lightDepthToClip"))
  {
    program->SetUniform4f("lightDepthToClip", depthToClip);
  }
  if (view.warp.active())
  {
    program->SetUniformf("lightNearDepth", static_cast<float>(view.nearDepth));
    program->SetUniformf("lightFarDepth", static_cast<float>(view.farDepth));
  }
  this->CombineQuad.render();
  for (vtkTextureObject* texture : bound)
  {
    texture->Deactivate();
  }
}

namespace
{

// A 2-D R32UI target (nearest, clamped): polygon ids.
vtkSmartPointer<vtkTextureObject> makePolygonIdTarget(vtkOpenGLRenderWindow* window, int width, int height)
{
  auto texture = vtkSmartPointer<vtkTextureObject>::New();
  texture->SetContext(window);
  texture->SetInternalFormat(GL_R32UI);
  texture->SetFormat(GL_RED_INTEGER);
  texture->SetDataType(GL_UNSIGNED_INT);
  texture->SetMinificationFilter(vtkTextureObject::Nearest);
  texture->SetMagnificationFilter(vtkTextureObject::Nearest);
  texture->SetWrapS(vtkTextureObject::ClampToEdge);
  texture->SetWrapT(vtkTextureObject::ClampToEdge);
  if (!texture->Allocate2D(width, height, 1, VTK_UNSIGNED_INT))
  {
    throw sl::GraphicsError(sl::format("cannot allocate a ", width, "x", height, " polygon-id target"));
  }
  return texture;
}

} // namespace

void vtkSLLightDepthPass::RenderPolygonIds(vtkOpenGLRenderWindow* window)
{
  // Survey §5 (Hourcade & Nicolas 1985): the map stores the nearest triangle's id besides its depth, and the receivers
  // compare their own triangle's id, which the camera pass below renders as the G-buffer does.
  sl::FrameResources& frame = *this->Frame;
  if (frame.partitions)
  {
    // Cube faces (a point light one map cannot cover, cube_map=auto or on): the ids are one map's.
    throw sl::InputError("--set depth_layer=polygon_id: one map only, and this point light needs cube faces; use a "
                         "spot or area light, or another depth_layer");
  }
  const sl::LightView& view = frame.lightView;
  std::size_t triangles = 0;
  for (const sl::GpuMesh& mesh : frame.gpuScene->meshes())
  {
    triangles += mesh.indexCount / 3;
  }
  if (triangles >= (std::size_t(1) << 24))
  {
    throw sl::InputError(sl::format("--set depth_layer=polygon_id: the scene has ", triangles,
      " triangles; ids are exported as float, exact below 2^24 (16777216)"));
  }
  auto layers = std::make_shared<sl::ShadowMapLayersData>();
  layers->polygonIds = makePolygonIdTarget(window, view.resolution, view.resolution);
  layers->receiverPolygonIds = makePolygonIdTarget(window, frame.width(), frame.height());
  sl::renderPolygonIdShadowMap(window, this->Framebuffer, this->Drawer, *frame.gpuScene, view, frame.shadowMapLinear,
    frame.shadowMapDepth, layers->polygonIds);

  auto cameraDepth = sl::makeDepthTarget(window, frame.width(), frame.height());
  const GLuint none = 0;
  glClearTexImage(layers->receiverPolygonIds->GetHandle(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &none);
  {
    const sl::ScopedRenderTarget target(window, this->Framebuffer, { layers->receiverPolygonIds }, cameraDepth);
    target.clearDepth();
    vtkShaderProgram* program =
      sl::readyProgram(window, sl::assembleShader("gbuffer/GBufferVertex.glsl", sl::commonDefines()),
        sl::assembleShader("shadowmap/ReceiverPolygonId.glsl", sl::commonDefines()), "receiver polygon id");
    sl::setMatrix(program, "clipFromWorld", frame.camera.clipFromWorld);
    sl::setMatrix(program, "viewFromWorld", frame.camera.viewFromWorld);
    const float alphaTestOffset[2] = { static_cast<float>(frame.alphaTestOffset.x),
      static_cast<float>(frame.alphaTestOffset.y) };
    if (program->IsUniformUsed("alphaTestOffset"))
    {
      program->SetUniform2f("alphaTestOffset", alphaTestOffset);
    }
    // Casters with their ids, the others with 0, into one depth buffer: each pixel keeps its nearest surface's.
    program->SetUniformi("writePolygonIds", 1);
    this->Drawer.draw(program, *frame.gpuScene, [](const sl::SceneObject& object) { return object.castShadows; });
    program->SetUniformi("writePolygonIds", 0);
    this->Drawer.draw(program, *frame.gpuScene, [](const sl::SceneObject& object) { return !object.castShadows; });
  }
  frame.lightSpaceData[sl::shadowMapStructure().name] = layers;
}

void vtkSLLightDepthPass::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Drawer.releaseGraphicsResources(vtkOpenGLRenderWindow::SafeDownCast(window));
  this->CombineQuad.releaseGraphicsResources(window);
  this->PeelDepth = nullptr;
  this->Framebuffer->ReleaseGraphicsResources(window);
  this->LinearTargets.clear();
  this->DepthTargets.clear();
}

void vtkSLLightDepthPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
