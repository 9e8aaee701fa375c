#include "techniques/vtkSLShadowVolumePass.h"

#include "core/Error.h"
#include "gl/GlResources.h"
#include "gl/ShaderLibrary.h"
#include "passes/FrameResources.h"
#include "passes/PassUtilities.h"
#include "passes/ScopedRenderTarget.h"
#include "objectspace/ShadowVolumeReference.h"
#include "techniques/VolumeCountStatus.h"
#include "objectspace/SilhouetteExport.h"

#include <vtkObjectFactory.h>
#include <vtkOpenGLBufferObject.h>
#include <vtkOpenGLFramebufferObject.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkOpenGLState.h>
#include <vtkOpenGLVertexArrayObject.h>
#include <vtkPolyData.h>
#include <vtkRenderState.h>
#include <vtkRenderer.h>
#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>
#include <vtk_glew.h>

#include <chrono>
#include <cmath>

vtkStandardNewMacro(vtkSLShadowVolumePass);

vtkSLShadowVolumePass::vtkSLShadowVolumePass() = default;
vtkSLShadowVolumePass::~vtkSLShadowVolumePass() = default;

namespace
{

// A GL capability VTK's state cache does not track (depth clamp, polygon offset): set for a scope, restored.
class ScopedCapability
{
public:
  ScopedCapability(GLenum capability, bool enable)
    : capability_(capability)
    , wasEnabled_(glIsEnabled(capability) == GL_TRUE)
  {
    enable ? glEnable(capability_) : glDisable(capability_);
  }
  ~ScopedCapability() { wasEnabled_ ? glEnable(capability_) : glDisable(capability_); }
  ScopedCapability(const ScopedCapability&) = delete;
  ScopedCapability& operator=(const ScopedCapability&) = delete;

private:
  GLenum capability_;
  bool wasEnabled_;
};

} // namespace

void vtkSLShadowVolumePass::Execute(const vtkRenderState* state)
{
  this->BuildAndCountVolumes(vtkOpenGLRenderWindow::SafeDownCast(state->GetRenderer()->GetRenderWindow()));
  // Step 3: the resolve, the base class's full-screen shader.
  this->Superclass::Execute(state);
}

void vtkSLShadowVolumePass::BuildAndCountVolumes(vtkOpenGLRenderWindow* window)
{
  const sl::FrameResources& frame = *this->Frame;

  // Step 1: the volumes, on the CPU.
  const auto buildStart = std::chrono::steady_clock::now();
  const sl::VolumeExtrusion extrusion = frame.scene->camera.projection == sl::Projection::Perspective
    ? sl::VolumeExtrusion::ToInfinity
    : sl::VolumeExtrusion::Finite;
  SL_CHECK_MSG(frame.weldedCasters, "shadow-volume: the pipeline welds the casters of a drawsSceneGeometry technique");
  const sl::ShadowVolumeGeometry geometry = sl::buildShadowVolumes(
    *frame.weldedCasters, sl::VolumeLight::from(*frame.light), extrusion, frame.scene->bounds());
  this->BuildMilliseconds =
    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - buildStart).count();
  this->Statistics = geometry.statistics;
  // The volumes holding the eye (the self-check, vtkSLShadowVolumePass.h): their winding number there, from the very
  // triangles drawn. Not an integer when the eye lies on a volume face; then every pixel is marked. Orthographic
  // views: 0, the whole line enters and leaves the finite volumes.
  this->EyeVolumeCount = 0.0;
  if (extrusion == sl::VolumeExtrusion::ToInfinity)
  {
    const double winding = sl::volumeWindingNumber(geometry, frame.scene->camera.position);
    this->EyeVolumeCount = std::abs(winding - std::round(winding)) < 1e-3 ? std::round(winding) : winding;
  }
  this->Silhouettes = sl::silhouettePolyData(geometry.silhouettes);

  // Step 2: z-fail count.
  this->CountVolumes(window, geometry);
  sl::checkGlErrors("shadow-volume (volume count)");
}

void vtkSLShadowVolumePass::CountVolumes(vtkOpenGLRenderWindow* window, const sl::ShadowVolumeGeometry& geometry)
{
  const sl::FrameResources& frame = *this->Frame;
  vtkTextureObject* depthStencil = frame.gbufferDepth;
  this->VolumeCount = sl::makeFloatTarget(window, frame.width(), frame.height(), 2);

  // The G-buffer's depth-stencil (FrameResources: GL_DEPTH32F_STENCIL8), attached as depth and stencil.
  const sl::ScopedRenderTarget target(window, this->CountFramebuffer, { this->VolumeCount }, depthStencil);
  vtkOpenGLState* glState = window->GetState();
  target.clearColor(0, 0.0f);
  glState->vtkglStencilMask(0xFF);
  target.clearStencil();
  if (geometry.vertices.empty())
  {
    return; // no caster faces the light: every count is 0
  }

  // Interleaved per vertex: homogeneous position, then its triangle's plane.
  std::vector<glm::vec4> interleaved;
  interleaved.reserve(2 * geometry.vertices.size());
  for (std::size_t vertex = 0; vertex < geometry.vertices.size(); ++vertex)
  {
    interleaved.push_back(geometry.vertices[vertex]);
    interleaved.push_back(geometry.planes[vertex / 3]);
  }
  if (!this->VolumeVertices)
  {
    this->VolumeVertices = vtkSmartPointer<vtkOpenGLBufferObject>::New();
    this->VolumeVertices->SetType(vtkOpenGLBufferObject::ArrayBuffer);
  }
  if (!this->VolumeVertices->Upload(interleaved, vtkOpenGLBufferObject::ArrayBuffer))
  {
    throw sl::GraphicsError("shadow-volume: cannot upload " + std::to_string(geometry.vertices.size()) +
      " volume vertices: " + this->VolumeVertices->GetError());
  }
  const sl::ShaderDefines defines = sl::commonDefines();
  vtkShaderProgram* program = sl::readyProgram(window, sl::assembleShader("shadowvolume/ShadowVolumeVertex.glsl", defines),
    sl::assembleShader("shadowvolume/ShadowVolumeCount.glsl", defines), "shadow-volume count");
  sl::setMatrix(program, "clipFromWorld", frame.camera.clipFromWorld);
  this->SetReceiverOffsetUniforms(program);
  const glm::vec3 eye(frame.scene->camera.position);
  const float eyePoint[4] = { eye.x, eye.y, eye.z,
    frame.scene->camera.projection == sl::Projection::Perspective ? 1.0f : 0.0f };
  program->SetUniform4f("eyePoint", eyePoint);
  const std::vector<vtkTextureObject*> gbuffer = { sl::bindTexture(program, "gbufferPosition", frame.gbufferPosition),
    sl::bindTexture(program, "gbufferNormal", frame.gbufferNormal) };
  if (this->VolumeArray)
  {
    this->VolumeArray->ReleaseGraphicsResources();
  }
  this->VolumeArray = vtkSmartPointer<vtkOpenGLVertexArrayObject>::New();
  this->VolumeArray->Bind();
  const int stride = 2 * sizeof(glm::vec4);
  this->VolumeArray->AddAttributeArray(program, this->VolumeVertices, "volumePositionIn", 0, stride, VTK_FLOAT, 4, false);
  this->VolumeArray->AddAttributeArray(
    program, this->VolumeVertices, "volumePlaneIn", sizeof(glm::vec4), stride, VTK_FLOAT, 4, false);

  // No depth test: the shader decides what lies behind the receiver. No clipping at the far plane either:
  // volumes reach infinity (depth clamp).
  glState->vtkglDepthMask(GL_FALSE);
  glState->vtkglDisable(GL_DEPTH_TEST);
  const ScopedCapability depthClamp(GL_DEPTH_CLAMP, true);
  // Two-sided stencil: leaving a volume behind the surface (back face) +1, entering it -1, wrapping.
  const vtkOpenGLState::ScopedglEnableDisable stencilTest(glState, GL_STENCIL_TEST);
  glState->vtkglEnable(GL_STENCIL_TEST);
  glState->vtkglStencilFunc(GL_ALWAYS, 0, 0xFF);
  glState->vtkglStencilOpSeparate(GL_BACK, GL_KEEP, GL_KEEP, GL_INCR_WRAP);
  glState->vtkglStencilOpSeparate(GL_FRONT, GL_KEEP, GL_KEEP, GL_DECR_WRAP);
  // The same count, exactly: +1 / -1 summed in the R32F target.
  const vtkOpenGLState::ScopedglBlendFuncSeparate blendFunc(glState);
  glState->vtkglEnable(GL_BLEND);
  glState->vtkglBlendFunc(GL_ONE, GL_ONE);
  glState->vtkglBlendEquation(GL_FUNC_ADD);
  const vtkOpenGLState::ScopedglColorMask colorMask(glState);
  glState->vtkglColorMask(GL_TRUE, GL_FALSE, GL_FALSE, GL_FALSE);
  glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(geometry.vertices.size()));

  // The self-check's sum (vtkSLShadowVolumePass.h): every face along the ray, in front of the point or behind it,
  // into the second component, without the stencil. Same triangles, same vertex shader: the same fragments.
  sl::ShaderDefines totalDefines = defines;
  totalDefines.emplace_back("VOLUME_TOTAL", "");
  vtkShaderProgram* totalProgram = sl::readyProgram(window,
    sl::assembleShader("shadowvolume/ShadowVolumeVertex.glsl", totalDefines),
    sl::assembleShader("shadowvolume/ShadowVolumeCount.glsl", totalDefines), "shadow-volume face sum");
  sl::setMatrix(totalProgram, "clipFromWorld", frame.camera.clipFromWorld);
  const std::vector<vtkTextureObject*> totalGbuffer = { sl::bindTexture(totalProgram, "gbufferPosition", frame.gbufferPosition),
    sl::bindTexture(totalProgram, "gbufferNormal", frame.gbufferNormal) };
  // Its own attribute location (the plane is not read there, so the linker may place the position elsewhere).
  this->VolumeArray->AddAttributeArray(
    totalProgram, this->VolumeVertices, "volumePositionIn", 0, stride, VTK_FLOAT, 4, false);
  glState->vtkglDisable(GL_STENCIL_TEST);
  glState->vtkglColorMask(GL_FALSE, GL_TRUE, GL_FALSE, GL_FALSE);
  glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(geometry.vertices.size()));
  for (vtkTextureObject* texture : totalGbuffer)
  {
    texture->Deactivate();
  }

  this->VolumeArray->Release();
  for (vtkTextureObject* texture : gbuffer)
  {
    texture->Deactivate();
  }
  glState->vtkglStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
  glState->vtkglStencilFunc(GL_ALWAYS, 0, 0xFF);
}

void vtkSLShadowVolumePass::SetReceiverOffsetUniforms(vtkShaderProgram* program) const
{
  const sl::FrameResources& frame = *this->Frame;
  const sl::CameraView& camera = frame.camera;
  sl::setCameraRayUniforms(program, camera);
  // receiver_offset as a fraction of the distance to the eye: the eye lies at s = -near / (far - near) on
  // every perspective ray N + s R, so the distance is (near / (far - near) + s) |R|. Orthographic: of the
  // scene's bounding radius, |R| = far - near.
  const double offset = sl::receiverOffsetOf(frame.parameters);
  const double range = camera.farDepth - camera.nearDepth;
  const bool perspective = frame.scene->camera.projection == sl::Projection::Perspective;
  program->SetUniformf("receiverOffsetS",
    static_cast<float>(perspective ? offset * camera.nearDepth / range : offset * frame.scene->bounds().radius() / range));
  program->SetUniformf("receiverOffsetPerS", static_cast<float>(perspective ? offset : 0.0));
}

sl::NamedImage vtkSLShadowVolumePass::VolumeCountStatusImage() const
{
  const sl::ImageF counts = sl::readFloatTexture(this->VolumeCount, 2);
  const sl::ImageF position = sl::readFloatTexture(this->Frame->gbufferPosition, 4);
  // An eye on a volume face (a winding number that is no integer) leaves nothing to compare with: every pixel marked.
  const bool eyeKnown = this->EyeVolumeCount == std::round(this->EyeVolumeCount);
  sl::ImageF status(counts.width, counts.height, 1, static_cast<float>(sl::VolumeCountStatus::Consistent));
  for (std::size_t pixel = 0; pixel < status.data.size(); ++pixel)
  {
    const float zFail = counts.data[2 * pixel];
    const float faceSum = counts.data[2 * pixel + 1];
    const bool covered = position.data[4 * pixel + 3] > 0.5f;
    if (covered && (zFail < -0.5f || !eyeKnown || std::abs(faceSum - this->EyeVolumeCount) >= 0.5))
    {
      status.data[pixel] = static_cast<float>(sl::VolumeCountStatus::Inconsistent);
    }
  }
  return { "volume_count_status", status, "", "" };
}

std::vector<sl::NamedImage> vtkSLShadowVolumePass::CollectPassBuffers()
{
  return { this->VolumeCountStatusImage() };
}

std::vector<vtkTextureObject*> vtkSLShadowVolumePass::SetTechniqueUniforms(vtkShaderProgram* program)
{
  vtkTextureObject* depthStencil = this->Frame->gbufferDepth;
  // Sample the stencil half of the depth-stencil texture (as an unsigned integer), not its depth.
  glTextureParameteri(depthStencil->GetHandle(), GL_DEPTH_STENCIL_TEXTURE_MODE, GL_STENCIL_INDEX);
  return { sl::bindTexture(program, "volumeCount", this->VolumeCount),
    sl::bindTexture(program, "volumeStencil", depthStencil) };
}

void vtkSLShadowVolumePass::AfterDraw()
{
  glTextureParameteri(this->Frame->gbufferDepth->GetHandle(), GL_DEPTH_STENCIL_TEXTURE_MODE, GL_DEPTH_COMPONENT);
}

std::map<std::string, double> vtkSLShadowVolumePass::CollectStatistics()
{
  const sl::ShadowVolumeStatistics& s = this->Statistics;
  return {
    { "caster_triangles", static_cast<double>(s.casterTriangles) },
    { "collapsed_triangles", static_cast<double>(s.collapsedTriangles) },
    { "flipped_triangles", static_cast<double>(s.flippedTriangles) },
    { "edge_on_triangles", static_cast<double>(s.edgeOnTriangles) },
    { "edges", static_cast<double>(s.edges) },
    { "boundary_edges", static_cast<double>(s.boundaryEdges) },
    { "non_manifold_edges", static_cast<double>(s.nonManifoldEdges) },
    { "inconsistent_edges", static_cast<double>(s.inconsistentEdges) },
    { "silhouette_edges", static_cast<double>(s.silhouetteEdges) },
    { "side_quads", static_cast<double>(s.sideQuads) },
    { "near_caps", static_cast<double>(s.nearCaps) },
    { "far_caps", static_cast<double>(s.farCaps) },
    { "volume_triangles", static_cast<double>(s.volumeTriangles()) },
    { "volume_build_ms", this->BuildMilliseconds },
    { "eye_volume_count", this->EyeVolumeCount },
  };
}

std::vector<sl::NamedPolyData> vtkSLShadowVolumePass::CollectObjectSpaceExports()
{
  if (!this->Silhouettes)
  {
    return {};
  }
  return { { "silhouettes",
    "silhouette edges as lines, running as the light-oriented triangles do; cell data caster_id (object index), "
    "multiplicity (side quads drawn), incident_triangles (1 boundary, 2 manifold, > 2 non-manifold)",
    this->Silhouettes } };
}

void vtkSLShadowVolumePass::ReleaseGraphicsResources(vtkWindow* window)
{
  if (this->VolumeArray)
  {
    this->VolumeArray->ReleaseGraphicsResources();
    this->VolumeArray = nullptr;
  }
  if (this->VolumeVertices)
  {
    this->VolumeVertices->ReleaseGraphicsResources();
    this->VolumeVertices = nullptr;
  }
  this->VolumeCount = nullptr;
  this->CountFramebuffer->ReleaseGraphicsResources(window);
  this->Superclass::ReleaseGraphicsResources(window);
}

void vtkSLShadowVolumePass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SilhouetteEdges: " << this->Statistics.silhouetteEdges << "\n";
  os << indent << "VolumeTriangles: " << this->Statistics.volumeTriangles() << "\n";
}
