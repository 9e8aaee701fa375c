#include "structures/shadowmap/vtkSLFocusPass.h"

#include "structures/shadowmap/ShadowMapStructure.h"
#include "passes/FrameResources.h"

#include "core/Error.h"
#include "gl/GlResources.h"
#include "gl/ShaderLibrary.h"
#include "passes/PassUtilities.h"
#include "lightspace/AutomaticMapSize.h"
#include "lightspace/FittedVirtualShadowMap.h"

#include <vtkObjectFactory.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkRenderState.h>
#include <vtkRenderer.h>
#include <vtk_glew.h>
#include <vtkTextureObject.h>

#include <algorithm>
#include <cmath>

vtkStandardNewMacro(vtkSLFocusPass);

void vtkSLFocusPass::Execute(const vtkRenderState* state)
{
  sl::FrameResources& frame = *this->Frame;
  if (!this->Receivers)
  {
    this->Receivers = std::make_unique<sl::GpuReceivers>();
  }
  this->Receivers->setGBuffer(frame.gbufferPosition, frame.gbufferNormal);
  const sl::ShadowMapSettings settings = sl::shadowMapSettings(frame);
  sl::FocusSettings focus;
  focus.resolution = settings.resolution;
  focus.marginTexels = settings.marginTexels;
  focus.warp = settings.warp;
  focus.camera = &frame.camera;
  if (frame.technique->coversLightArea && frame.light->type == sl::LightType::Area)
  {
    focus.lightFootprintWidth = frame.light->size;
  }
  sl::adviseBeyondOneMap(frame, focus);
  if (!frame.partitioned || frame.viewIndex == 0)
  {
    frame.automaticMapSize.reset();
    if (settings.automaticResolution && !settings.fvsm.active())
    {
      // Fitted first at the largest allowed size (only the window's margin depends on it), then at the chosen one.
      focus.resolution = this->LargestAutomaticSize(settings);
    }
  }
  if (frame.partitioned && frame.viewIndex == 0)
  {
    // Views that partition the pixels (survey §4.3): every view is fitted at view 0, with the per-pixel selection the
    // accumulation blends by. Cube faces (survey §2) with cube_map=auto only where one map cannot cover the
    // receivers (the refusal's condition; two reductions to tell).
    const sl::Light& light = *frame.light;
    if (settings.fvsm.active())
    {
      // Survey §4.3.3: the pre-pass (the G-buffer read back: each receiver's query location and required
      // resolution), the quadtree and every tile's view.
      const sl::ImageF position = sl::readFloatTexture(frame.gbufferPosition, 4);
      const sl::ImageF normal = sl::readFloatTexture(frame.gbufferNormal, 4);
      auto fvsm = std::make_shared<sl::FittedVirtualShadowMap>(sl::fitFvsm(
        light, *frame.scene, *this->Receivers, focus, settings.fvsm, frame.camera, position, normal));
      sl::PartitionSet tiles;
      tiles.kind = sl::PartitionKind::FvsmTiles;
      tiles.views = fvsm->views;
      for (const sl::FvsmTile& tile : fvsm->quadtree.tiles)
      {
        tiles.ownerPlanes.push_back(sl::tileOwnerPlanes(fvsm->rootView, tile.rect));
      }
      tiles.ownerPlanes.resize(tiles.views.size()); // the root alone (no receiver) owns everything
      tiles.marginTexels = focus.marginTexels;
      tiles.fvsm = fvsm;
      frame.partitions = std::move(tiles);
      this->WriteTileSelection(state);
    }
    else if (settings.cascades.active())
    {
      frame.partitions = sl::fitCascades(light, *frame.scene, *this->Receivers, focus, settings.cascades);
    }
    else if (settings.cubeMap == sl::CubeMapMode::On ||
      (settings.cubeMap == sl::CubeMapMode::Auto && !sl::oneMapCovers(light, *frame.scene, *this->Receivers)))
    {
      frame.partitions = sl::fitCubeFaces(light, *frame.scene, *this->Receivers, focus);
    }
    if (frame.partitions && frame.partitions->kind != sl::PartitionKind::FvsmTiles)
    {
      if (settings.automaticResolution)
      {
        // Fitted again only at another size: the fit at the same size is the same set of views.
        const int fittedAt = focus.resolution;
        this->ChooseAutomaticSize(frame.partitions->views, settings, focus);
        if (focus.resolution != fittedAt)
        {
          const sl::PartitionKind kind = frame.partitions->kind;
          frame.partitions = kind == sl::PartitionKind::Cascades
            ? sl::fitCascades(light, *frame.scene, *this->Receivers, focus, settings.cascades)
            : sl::fitCubeFaces(light, *frame.scene, *this->Receivers, focus);
        }
      }
      this->WriteSelection(state);
    }
  }
  if (frame.partitions)
  {
    SL_CHECK(frame.viewIndex < frame.partitions->viewCount());
    frame.lightView = frame.partitions->views[static_cast<std::size_t>(frame.viewIndex)];
  }
  else
  {
    frame.lightView = sl::fitLightView(*frame.light, *frame.scene, *this->Receivers, focus);
    if (settings.automaticResolution && !settings.fvsm.active())
    {
      // Fitted again only at another size: the fit at the same size is the same view.
      const int fittedAt = focus.resolution;
      this->ChooseAutomaticSize({ frame.lightView }, settings, focus);
      if (focus.resolution != fittedAt)
      {
        frame.lightView = sl::fitLightView(*frame.light, *frame.scene, *this->Receivers, focus);
      }
    }
  }
  frame.hasLightView = true;
}

int vtkSLFocusPass::LargestAutomaticSize(const sl::ShadowMapSettings& settings) const
{
  const sl::FrameResources& frame = *this->Frame;
  GLint max2d = 0, max3d = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max2d);
  glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &max3d);
  const sl::ParameterSpec* spec = sl::findParameterSpec(sl::shadowMapStructure().parameters, "shadow_map_size");
  int largest = std::min({ static_cast<int>(spec->maxValue), static_cast<int>(max2d), sl::kAutomaticMapMaxSize,
    frame.technique->largestAutomaticMapSize });
  for (const sl::LightSpaceStructure* structure :
    sl::withBuildDependencies(frame.technique->structuresFor(frame.parameters)))
  {
    if (structure->largestMapSize)
    {
      largest = std::min(largest, structure->largestMapSize(frame.parameters, static_cast<int>(max3d)));
    }
  }
  const int size = sl::powerOfTwoAtMost(largest); // a power of two, as every automatic size is
  SL_CHECK_MSG(size > 2.0 * settings.marginTexels, "shadow_map_size=auto: the GL's largest map (", size,
    ") leaves no texel inside the filter's margin (", settings.marginTexels, ")");
  return size;
}

void vtkSLFocusPass::ChooseAutomaticSize(
  const std::vector<sl::LightView>& views, const sl::ShadowMapSettings& settings, sl::FocusSettings& focus)
{
  sl::FrameResources& frame = *this->Frame;
  // The G-buffer read back (a receiver's sampling error is the CPU's, lightspace/ShadowMapMath.h).
  const sl::ImageF position = sl::readFloatTexture(frame.gbufferPosition, 4);
  const sl::ImageF normal = sl::readFloatTexture(frame.gbufferNormal, 4);
  frame.automaticMapSize =
    sl::automaticMapSize(frame.camera, *frame.light, views, focus.marginTexels, position, normal, focus.resolution,
      settings.automaticTexelsPerPixelFor(*frame.light));
  focus.resolution = frame.automaticMapSize->size;
}

void vtkSLFocusPass::WriteSelection(const vtkRenderState* state)
{
  sl::FrameResources& frame = *this->Frame;
  const sl::PartitionSet& partitions = *frame.partitions;
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(state->GetRenderer()->GetRenderWindow());
  if (!this->Selection)
  {
    // The kinds' codes from the enum, so the GLSL cannot drift from it.
    sl::ShaderDefines defines = sl::commonDefines();
    defines.push_back({ "PARTITION_CASCADES", std::to_string(static_cast<int>(sl::PartitionKind::Cascades)) });
    defines.push_back({ "PARTITION_CUBE_FACES", std::to_string(static_cast<int>(sl::PartitionKind::CubeFaces)) });
    this->Selection = std::make_unique<sl::ComputeProgram>(
      sl::assembleShader("lightspace/PartitionSelection.glsl", defines), "partition selection");
  }
  if (!frame.viewSelection)
  {
    frame.viewSelection = sl::makeFloatTarget(window, frame.width(), frame.height(), 4);
  }
  const sl::ComputeProgram& program = *this->Selection;
  program.use();
  frame.gbufferPosition->Activate();
  frame.gbufferNormal->Activate();
  program.setInt("gbufferPosition", frame.gbufferPosition->GetTextureUnit());
  program.setInt("gbufferNormal", frame.gbufferNormal->GetTextureUnit());
  program.setInt("partitionKind", static_cast<int>(partitions.kind));
  program.setFloat("marginTexels", partitions.marginTexels);
  program.setInt("shadowMapSize", partitions.views.front().resolution);
  if (partitions.kind == sl::PartitionKind::Cascades)
  {
    this->SetCascadeUniforms();
  }
  else
  {
    program.setVector("lightCenterWs", partitions.lightCenterWs);
    for (int face = 0; face < sl::kCubeFaceCount; ++face)
    {
      const auto found = std::find(partitions.viewFaces.begin(), partitions.viewFaces.end(), face);
      const bool mapped = found != partitions.viewFaces.end();
      program.setInt(sl::format("faceView[", face, "]").c_str(),
        mapped ? static_cast<int>(found - partitions.viewFaces.begin()) : -1);
    }
  }
  glBindImageTexture(0, frame.viewSelection->GetHandle(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  program.dispatch({ (frame.width() + 7) / 8, (frame.height() + 7) / 8 });
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  frame.gbufferPosition->Deactivate();
  frame.gbufferNormal->Deactivate();
  sl::checkGlErrors("partition selection");
}

void vtkSLFocusPass::SetCascadeUniforms()
{
  const sl::FrameResources& frame = *this->Frame;
  const sl::PartitionSet& cascades = *frame.partitions;
  const sl::ComputeProgram& program = *this->Selection;
  program.setInt("cascadeCount", cascades.viewCount());
  const bool containment = cascades.cascadeSettings.selection == sl::CascadeSelection::Containment;
  program.setInt("selectByContainment", containment ? 1 : 0);
  program.setFloat("cascadeBlend", cascades.cascadeSettings.blend);
  const glm::dmat4& camera = frame.camera.viewFromWorld;
  program.setVectors("eyeDepthRow", { -glm::dvec4(camera[0][2], camera[1][2], camera[2][2], camera[3][2]) });
  std::vector<glm::dmat4> clipFromWorld, viewFromWorld;
  for (std::size_t k = 0; k < cascades.views.size(); ++k)
  {
    const sl::LightView& view = cascades.views[k];
    clipFromWorld.push_back(view.clipFromWorld);
    viewFromWorld.push_back(view.viewFromWorld);
    program.setFloat(sl::format("cascadeNearDepth[", k, "]").c_str(), view.nearDepth);
    program.setFloat(sl::format("cascadeFarDepth[", k, "]").c_str(), view.farDepth);
  }
  for (std::size_t i = 0; i < cascades.splits.size(); ++i)
  {
    // One uniform per split: a float array set four at a time is awkward.
    program.setFloat(sl::format("splitDepths[", i, "]").c_str(), cascades.splits[i]);
  }
  program.setMatrices("cascadeClipFromWorld", clipFromWorld);
  program.setMatrices("cascadeViewFromWorld", viewFromWorld);
}

void vtkSLFocusPass::WriteTileSelection(const vtkRenderState* state)
{
  sl::FrameResources& frame = *this->Frame;
  const sl::FittedVirtualShadowMap& fvsm = *frame.partitions->fvsm;
  const sl::FvsmQuadtree& tree = fvsm.quadtree;
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(state->GetRenderer()->GetRenderWindow());
  if (!this->TileSelection)
  {
    this->TileSelection = std::make_unique<sl::ComputeProgram>(
      sl::assembleShader("lightspace/FvsmSelection.glsl", sl::commonDefines()), "fvsm tile selection");
  }
  if (!frame.viewSelection)
  {
    frame.viewSelection = sl::makeFloatTarget(window, frame.width(), frame.height(), 4);
  }
  std::vector<float> tileOfCell(tree.tileOfCell.begin(), tree.tileOfCell.end());
  auto cells = vtkSmartPointer<vtkTextureObject>::New();
  cells->SetContext(window);
  cells->SetMinificationFilter(vtkTextureObject::Nearest);
  cells->SetMagnificationFilter(vtkTextureObject::Nearest);
  if (!cells->Create2DFromRaw(tree.gridSize, tree.gridSize, 1, VTK_FLOAT, tileOfCell.data()))
  {
    throw sl::GraphicsError("fvsm: cannot upload the tile-of-cell grid");
  }
  const sl::ComputeProgram& program = *this->TileSelection;
  program.use();
  frame.gbufferPosition->Activate();
  frame.gbufferNormal->Activate();
  cells->Activate();
  program.setInt("gbufferPosition", frame.gbufferPosition->GetTextureUnit());
  program.setInt("gbufferNormal", frame.gbufferNormal->GetTextureUnit());
  program.setInt("tileOfCell", cells->GetTextureUnit());
  program.setInt("gridSize", tree.gridSize);
  program.setMatrix("rootViewFromWorld", fvsm.rootView.viewFromWorld);
  program.setInt("lightIsPerspective", fvsm.rootView.projection == sl::LightProjection::Perspective ? 1 : 0);
  program.setVectors("rootRect", { tree.rootRect });
  glBindImageTexture(0, frame.viewSelection->GetHandle(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  program.dispatch({ (frame.width() + 7) / 8, (frame.height() + 7) / 8 });
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  cells->Deactivate();
  frame.gbufferPosition->Deactivate();
  frame.gbufferNormal->Deactivate();
  sl::checkGlErrors("fvsm tile selection");
}

vtkSLFocusPass::vtkSLFocusPass() = default;
vtkSLFocusPass::~vtkSLFocusPass() = default;

void vtkSLFocusPass::ReleaseGraphicsResources(vtkWindow*)
{
  this->Receivers.reset();
  this->Selection.reset();
  this->TileSelection.reset();
}

void vtkSLFocusPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  if (this->Frame && this->Frame->hasLightView)
  {
    os << indent << "ShadowMapSize: " << this->Frame->lightView.resolution << "\n";
    os << indent << "DepthRange: " << this->Frame->lightView.nearDepth << " .. " << this->Frame->lightView.farDepth << "\n";
  }
}
