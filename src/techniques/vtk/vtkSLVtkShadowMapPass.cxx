#include "techniques/vtk/vtkSLVtkShadowMapPass.h"

#include "core/Error.h"
#include "gl/GlResources.h"
#include "passes/FrameResources.h"
#include "passes/PassUtilities.h"
#include "passes/ScopedRenderTarget.h"
#include "techniques/vtk/VtkTechnique.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCameraPass.h>
#include <vtkCellArray.h>
#include <vtkFloatArray.h>
#include <vtkLight.h>
#include <vtkLightsPass.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkOpaquePass.h>
#include <vtkOpenGLFramebufferObject.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkOpenGLState.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderPassCollection.h>
#include <vtkRenderState.h>
#include <vtkRenderer.h>
#include <vtkSequencePass.h>
#include <vtkShadowMapBakerPass.h>
#include <vtkShadowMapPass.h>
#include <vtkTextureObject.h>
#include <vtk_glew.h>

#include <algorithm>
#include <cmath>

vtkStandardNewMacro(vtkSLVtkShadowMapPass);

vtkSLVtkShadowMapPass::vtkSLVtkShadowMapPass() = default;
vtkSLVtkShadowMapPass::~vtkSLVtkShadowMapPass() = default;

namespace
{

vtkSmartPointer<vtkPolyData> toPolyData(const sl::TriangleMesh& mesh)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToFloat();
  vtkNew<vtkFloatArray> normals;
  normals->SetNumberOfComponents(3);
  normals->SetName("Normals");
  for (std::size_t v = 0; v < mesh.positions.size(); ++v)
  {
    points->InsertNextPoint(mesh.positions[v].x, mesh.positions[v].y, mesh.positions[v].z);
    normals->InsertNextTuple3(mesh.normals[v].x, mesh.normals[v].y, mesh.normals[v].z);
  }
  vtkNew<vtkCellArray> triangles;
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
  {
    const vtkIdType ids[3] = { mesh.indices[3 * t], mesh.indices[3 * t + 1], mesh.indices[3 * t + 2] };
    triangles->InsertNextCell(3, ids);
  }
  auto polyData = vtkSmartPointer<vtkPolyData>::New();
  polyData->SetPoints(points);
  polyData->SetPolys(triangles);
  polyData->GetPointData()->SetNormals(normals);
  return polyData;
}

// Half-angle (degrees) of the cone from `apex` along `axis` that contains the box, for VTK's spot frustum.
double coneCovering(const glm::dvec3& apex, const glm::dvec3& axis, const sl::Bounds& bounds)
{
  double widest = 0.0;
  for (int corner = 0; corner < 8; ++corner)
  {
    const glm::dvec3 p((corner & 1) ? bounds.max.x : bounds.min.x, (corner & 2) ? bounds.max.y : bounds.min.y,
      (corner & 4) ? bounds.max.z : bounds.min.z);
    const glm::dvec3 toCorner = p - apex;
    const double length = glm::length(toCorner);
    if (length > 1e-12)
    {
      widest = std::max(widest, std::acos(std::clamp(glm::dot(axis, toCorner / length), -1.0, 1.0)));
    }
  }
  return glm::degrees(widest);
}

} // namespace

void vtkSLVtkShadowMapPass::BuildVtkScene(vtkRenderWindow* window)
{
  const sl::FrameResources& frame = *this->Frame;
  const sl::Scene& scene = *frame.scene;
  this->VtkRenderer = vtkSmartPointer<vtkRenderer>::New();
  // Not added to the window (the window is rendering our pipeline right now): we drive its passes.
  this->VtkRenderer->SetRenderWindow(window);
  this->VtkRenderer->SetAutomaticLightCreation(false);
  this->VtkRenderer->SetBackground(0.0, 0.0, 0.0);
  this->VtkRenderer->SetTwoSidedLighting(true);
  this->Actors.clear();
  for (const sl::SceneObject& object : scene.objects)
  {
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(toPolyData(object.mesh));
    auto actor = vtkSmartPointer<vtkActor>::New();
    actor->SetMapper(mapper);
    vtkProperty* property = actor->GetProperty();
    property->SetColor(1.0, 1.0, 1.0);
    property->SetAmbient(0.0);
    property->SetDiffuse(1.0);
    property->SetSpecular(0.0);
    property->SetInterpolationToPhong();
    property->BackfaceCullingOff();
    this->VtkRenderer->AddActor(actor);
    this->Actors.push_back(actor);
  }

  const sl::Camera& sceneCamera = scene.camera;
  vtkCamera* camera = this->VtkRenderer->GetActiveCamera();
  camera->SetPosition(sceneCamera.position.x, sceneCamera.position.y, sceneCamera.position.z);
  camera->SetFocalPoint(sceneCamera.focalPoint.x, sceneCamera.focalPoint.y, sceneCamera.focalPoint.z);
  camera->SetViewUp(sceneCamera.viewUp.x, sceneCamera.viewUp.y, sceneCamera.viewUp.z);
  camera->SetParallelProjection(sceneCamera.projection == sl::Projection::Orthographic);
  camera->SetViewAngle(sceneCamera.viewAngleDeg);
  camera->SetParallelScale(sceneCamera.parallelScale);
  camera->SetClippingRange(frame.camera.nearDepth, frame.camera.farDepth);

  const sl::Light& light = *frame.light;
  const sl::Bounds bounds = scene.bounds();
  vtkNew<vtkLight> vtkLightSource;
  vtkLightSource->SetLightTypeToSceneLight();
  vtkLightSource->SetColor(1.0, 1.0, 1.0);
  vtkLightSource->SetIntensity(1.0);
  if (light.type == sl::LightType::Directional)
  {
    const glm::dvec3 target = bounds.center();
    const glm::dvec3 from = target - light.direction * (2.0 * bounds.radius() + 1.0);
    vtkLightSource->SetPositional(false);
    vtkLightSource->SetPosition(from.x, from.y, from.z);
    vtkLightSource->SetFocalPoint(target.x, target.y, target.z);
  }
  else
  {
    // VTK's baker needs a positional light with a cone under 90 degrees: it uses the cone as its frustum.
    const glm::dvec3 axis = light.type == sl::LightType::Point ? glm::normalize(bounds.center() - light.center)
                                                                : light.normal;
    const double cone = light.type == sl::LightType::Spot ? light.coneAngleDeg
                                                          : coneCovering(light.center, axis, bounds) + 1.0;
    const glm::dvec3 focal = light.center + axis;
    vtkLightSource->SetPositional(true);
    vtkLightSource->SetPosition(light.center.x, light.center.y, light.center.z);
    vtkLightSource->SetFocalPoint(focal.x, focal.y, focal.z);
    vtkLightSource->SetConeAngle(std::min(cone, 89.0));
    vtkLightSource->SetExponent(0.0); // no spot falloff (it would cancel in the ratio anyway)
  }
  this->VtkRenderer->AddLight(vtkLightSource);
}

void vtkSLVtkShadowMapPass::RenderVtk(vtkRenderPass* pass, vtkTextureObject* target, vtkRenderWindow* window)
{
  auto* openGLWindow = vtkOpenGLRenderWindow::SafeDownCast(window);
  vtkNew<vtkOpenGLFramebufferObject> framebuffer;
  const auto depth = sl::makeDepthTarget(openGLWindow, this->Frame->width(), this->Frame->height());
  const sl::ScopedRenderTarget renderTarget(openGLWindow, framebuffer, { target }, depth);
  std::vector<vtkProp*> props(this->Actors.begin(), this->Actors.end());
  vtkRenderState renderState(this->VtkRenderer);
  renderState.SetPropArrayAndCount(props.data(), static_cast<int>(props.size()));
  renderState.SetFrameBuffer(framebuffer);
  pass->Render(&renderState);
}

void vtkSLVtkShadowMapPass::Execute(const vtkRenderState* state)
{
  vtkRenderWindow* window = state->GetRenderer()->GetRenderWindow();
  auto* openGLWindow = vtkOpenGLRenderWindow::SafeDownCast(window);
  this->BuildVtkScene(window);
  this->Shadowed = sl::makeFloatTarget(openGLWindow, this->Frame->width(), this->Frame->height(), 4);
  this->Unshadowed = sl::makeFloatTarget(openGLWindow, this->Frame->width(), this->Frame->height(), 4);

  // VTK's documented shadow pipeline: camera -> [baker, shadow map pass(lights + opaque)].
  vtkNew<vtkShadowMapPass> shadows;
  shadows->GetShadowMapBakerPass()->SetResolution(
    static_cast<unsigned int>(sl::VtkSettings::from(this->Frame->parameters).shadowMapSize));
  vtkNew<vtkRenderPassCollection> shadowPasses;
  shadowPasses->AddItem(shadows->GetShadowMapBakerPass());
  shadowPasses->AddItem(shadows);
  vtkNew<vtkSequencePass> shadowSequence;
  shadowSequence->SetPasses(shadowPasses);
  vtkNew<vtkCameraPass> shadowCamera;
  shadowCamera->SetDelegatePass(shadowSequence);

  vtkNew<vtkLightsPass> lights;
  vtkNew<vtkOpaquePass> opaque;
  vtkNew<vtkRenderPassCollection> plainPasses;
  plainPasses->AddItem(lights);
  plainPasses->AddItem(opaque);
  vtkNew<vtkSequencePass> plainSequence;
  plainSequence->SetPasses(plainPasses);
  vtkNew<vtkCameraPass> plainCamera;
  plainCamera->SetDelegatePass(plainSequence);

  this->RenderVtk(shadowCamera, this->Shadowed, window);
  this->RenderVtk(plainCamera, this->Unshadowed, window);
  sl::checkGlErrors("vtk technique (VTK passes)");

  this->Superclass::Execute(state); // the ratio shader

  shadowCamera->ReleaseGraphicsResources(window);
  plainCamera->ReleaseGraphicsResources(window);
  for (const auto& actor : this->Actors)
  {
    actor->ReleaseGraphicsResources(window);
  }
}

std::vector<vtkTextureObject*> vtkSLVtkShadowMapPass::SetTechniqueUniforms(vtkShaderProgram* program)
{
  return { sl::bindTexture(program, "vtkShadowedRadiance", this->Shadowed),
    sl::bindTexture(program, "vtkUnshadowedRadiance", this->Unshadowed) };
}

void vtkSLVtkShadowMapPass::ReleaseGraphicsResources(vtkWindow* window)
{
  if (this->VtkRenderer)
  {
    for (const auto& actor : this->Actors)
    {
      actor->ReleaseGraphicsResources(window);
    }
    this->VtkRenderer->SetRenderWindow(nullptr);
    this->VtkRenderer = nullptr;
  }
  this->Actors.clear();
  this->Shadowed = nullptr;
  this->Unshadowed = nullptr;
  this->Superclass::ReleaseGraphicsResources(window);
}

void vtkSLVtkShadowMapPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
