#include "structures/hsm/vtkSLHsmPass.h"

#include "core/Error.h"
#include "gl/ShaderLibrary.h"
#include "lightspace/HierarchicalShadowMap.h"
#include "structures/hsm/HsmStructure.h"
#include "structures/mssm/DualMssmStructure.h"
#include "passes/FrameResources.h"

#include <vtkObjectFactory.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkRenderState.h>
#include <vtkRenderer.h>
#include <vtkTextureObject.h>
#include <vtk_glew.h>

vtkStandardNewMacro(vtkSLHsmPass);

vtkSLHsmPass::vtkSLHsmPass() = default;
vtkSLHsmPass::~vtkSLHsmPass() = default;

void vtkSLHsmPass::Execute(const vtkRenderState* state)
{
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(state->GetRenderer()->GetRenderWindow());
  sl::FrameResources& frame = *this->Frame;
  SL_CHECK_MSG(frame.hasLightView && frame.shadowMapLinear, "the shadow map must be built before its HSM");
  const sl::HsmLayout layout =
    this->DualGrid ? sl::HsmLayout::DualMssm : sl::hierarchicalShadowMapSettings(frame.parameters).layout;
  // The YSM's mip-map part is the mip-map HSM itself (texture, program, dispatches); its MSSM part follows.
  const sl::HsmLayout stored = layout == sl::HsmLayout::Ysm ? sl::HsmLayout::MipMap : layout;
  const bool nBuffers = layout == sl::HsmLayout::NBuffers;
  const bool dual = layout == sl::HsmLayout::DualMssm;
  const int size = frame.lightView.resolution;
  const int levelCount = dual ? sl::dualMssmLevelCount(size) : sl::hsmLevelCount(size);
  // The N-buffers and the dual grid stop at the level of the frame's widest query (issue 33); every other layout
  // builds all its levels.
  const int levels = sl::minMaxTopLevel(layout, frame);
  const int textureSize = sl::hsmLevelSize(layout, size, 1);
  const int layers = dual ? levels + 1 : std::max(levels, 1);

  if (nBuffers || dual)
  {
    GLint max3dSize = 0;
    glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &max3dSize);
    if (textureSize > max3dSize || layers > max3dSize)
    {
      throw sl::InputError(sl::format(dual ? "the dual-grid MSSM" : "hsm=nbuffers", ": a ", size, "^2 shadow map needs a ",
        textureSize, "x", textureSize, "x", layers, " 3D texture and this GL allows ", max3dSize,
        " per side; use shadow_map_size <= ", dual ? max3dSize - 1 : max3dSize, nBuffers ? " or hsm=mipmap" : ""));
    }
  }
  // Mip-map: levels 1..L in one N x N atlas; N-buffers: level k in layer k - 1 of an N x N x L texture;
  // dual-grid MSSM: level k in layer k of an (N + 1)^2 x (L + 1) texture.
  // The texture of the previous frame (or sub-light) is reused when it has the same layout and size: every
  // level's dispatch rewrites the same texels each time, and a fresh 2048^2 atlas (32 MB, cleared) costs
  // llvmpipe more wall time than the build itself.
  const bool fits = this->Texture && this->Texture->GetContext() == window && this->TextureLayout == stored &&
    this->TextureMapSize == size && this->TextureLayers == layers;
  if (!fits)
  {
    auto hsm = vtkSmartPointer<vtkTextureObject>::New();
    hsm->SetContext(window);
    hsm->SetInternalFormat(GL_RG32F);
    hsm->SetFormat(GL_RG);
    hsm->SetDataType(GL_FLOAT);
    hsm->SetMinificationFilter(vtkTextureObject::Nearest);
    hsm->SetMagnificationFilter(vtkTextureObject::Nearest);
    hsm->SetWrapS(vtkTextureObject::ClampToEdge);
    hsm->SetWrapT(vtkTextureObject::ClampToEdge);
    hsm->SetWrapR(vtkTextureObject::ClampToEdge);
    const bool allocated = nBuffers || dual ? hsm->Allocate3D(textureSize, textureSize, layers, 2, VTK_FLOAT)
                                            : hsm->Allocate2D(size, size, 2, VTK_FLOAT);
    if (!allocated)
    {
      throw sl::GraphicsError(sl::format("cannot allocate the hierarchical shadow map (", size, "^2, ",
        dual ? "dual-grid MSSM" : nBuffers ? "N-buffers" : "mip-map", ")"));
    }
    if (stored == sl::HsmLayout::MipMap)
    {
      // The atlas's unused texels are exported: make them 0, not undefined (no level ever writes them).
      const float zero[2] = { 0.0f, 0.0f };
      glClearTexImage(hsm->GetHandle(), 0, GL_RG, GL_FLOAT, zero);
    }
    this->Texture = hsm;
    this->TextureLayout = stored;
    this->TextureMapSize = size;
    this->TextureLayers = layers;
  }
  vtkTextureObject* hsm = this->Texture;
  auto& program = this->Programs[stored];
  if (!program)
  {
    program = std::make_unique<sl::ComputeProgram>(
      sl::assembleShader("hsm/HsmBuild.glsl", LayoutDefines(stored)), "hierarchical shadow map");
  }
  glBindImageTexture(0, hsm->GetHandle(), 0, nBuffers || dual ? GL_TRUE : GL_FALSE, 0, GL_READ_WRITE, GL_RG32F);
  frame.shadowMapLinear->Activate();
  program->use();
  program->setInt("shadowMapLinear", frame.shadowMapLinear->GetTextureUnit());
  program->setInt("hsmMapSize", size);
  // Samples outside the map never occlude, like the map's empty texels (ShadowMapRendering.h).
  program->setFloat("outsideDepth", 2.0 * frame.lightView.farDepth);
  for (int level = dual ? 0 : 1; level <= levels; ++level)
  {
    program->setInt("level", level);
    const int invocations = LevelInvocations(stored, size, level);
    program->dispatch({ (invocations + 7) / 8, (invocations + 7) / 8 });
    // Level k + 1 reads level k's image writes.
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  }
  frame.shadowMapLinear->Deactivate();
  glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RG32F);
  auto data = std::make_shared<sl::MinMaxDepthData>();
  data->texture = hsm;
  data->layout = layout;
  data->topLevel = levels;
  data->levelCount = levelCount;
  if (layout == sl::HsmLayout::Ysm)
  {
    data->ysmBaseLevel = sl::ysmBaseLevel(size);
    data->mssmPart = this->BuildYsmMssmPart(window, frame, hsm);
  }
  frame.lightSpaceData[this->DualGrid ? sl::dualMssmStructure().name : sl::hierarchicalShadowMapStructure().name] = data;
}

vtkTextureObject* vtkSLHsmPass::BuildYsmMssmPart(vtkOpenGLRenderWindow* window, sl::FrameResources& frame,
  vtkTextureObject* atlas)
{
  // SS08 §6: N-buffers over the M x M nodes of HSM level b, level j in layer j - 1 (level 0 is
  // that HSM level, read from the atlas just built). Reused across frames like the atlas.
  const int size = frame.lightView.resolution;
  const int partSize = sl::ysmMssmPartSize(size);
  const int partLevels = sl::ysmMssmPartLevelCount(size);
  const int layers = std::max(partLevels, 1);
  if (!(this->MssmPartTexture && this->MssmPartTexture->GetContext() == window && this->MssmPartMapSize == size))
  {
    GLint max3dSize = 0;
    glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &max3dSize);
    if (partSize > max3dSize)
    {
      throw sl::InputError(sl::format("hsm=ysm: a ", size, "^2 shadow map needs a ", partSize, "x", partSize, "x", layers,
        " 3D texture for the MSSM part and this GL allows ", max3dSize, " per side; use hsm=mipmap"));
    }
    auto part = vtkSmartPointer<vtkTextureObject>::New();
    part->SetContext(window);
    part->SetInternalFormat(GL_RG32F);
    part->SetFormat(GL_RG);
    part->SetDataType(GL_FLOAT);
    part->SetMinificationFilter(vtkTextureObject::Nearest);
    part->SetMagnificationFilter(vtkTextureObject::Nearest);
    part->SetWrapS(vtkTextureObject::ClampToEdge);
    part->SetWrapT(vtkTextureObject::ClampToEdge);
    part->SetWrapR(vtkTextureObject::ClampToEdge);
    if (!part->Allocate3D(partSize, partSize, layers, 2, VTK_FLOAT))
    {
      throw sl::GraphicsError(sl::format("cannot allocate the Y shadow map's MSSM part (", partSize, "^2 x ", layers, ")"));
    }
    this->MssmPartTexture = part;
    this->MssmPartMapSize = size;
  }
  if (!this->MssmPartProgram)
  {
    this->MssmPartProgram = std::make_unique<sl::ComputeProgram>(
      sl::assembleShader("hsm/YsmMssmBuild.glsl", LayoutDefines(sl::HsmLayout::Ysm)), "Y shadow map MSSM part");
  }
  sl::ComputeProgram& program = *this->MssmPartProgram;
  glBindImageTexture(0, this->MssmPartTexture->GetHandle(), 0, GL_TRUE, 0, GL_READ_WRITE, GL_RG32F);
  frame.shadowMapLinear->Activate();
  atlas->Activate();
  program.use();
  program.setInt("shadowMapLinear", frame.shadowMapLinear->GetTextureUnit());
  program.setInt("hsmAtlas", atlas->GetTextureUnit());
  program.setInt("hsmMapSize", size);
  program.setInt("ysmBaseLevel", sl::ysmBaseLevel(size));
  for (int level = 1; level <= partLevels; ++level)
  {
    program.setInt("level", level);
    program.dispatch({ (partSize + 7) / 8, (partSize + 7) / 8 });
    // Level j + 1 reads level j's image writes.
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  }
  atlas->Deactivate();
  frame.shadowMapLinear->Deactivate();
  glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RG32F);
  return this->MssmPartTexture;
}

int vtkSLHsmPass::LevelInvocations(sl::HsmLayout layout, int mapSize, int level)
{
  const int levelSize = sl::hsmLevelSize(layout, mapSize, level);
  if (layout == sl::HsmLayout::MipMap || level == 0)
  {
    return levelSize;
  }
  // One invocation per 2 x 2 texels (x, y) + 2^(level-1) {0, 1}^2 (HsmBuild.glsl): per axis, stride invocations per
  // block of 2 stride texels.
  const int stride = 1 << (level - 1);
  return (levelSize + 2 * stride - 1) / (2 * stride) * stride;
}

sl::ShaderDefines vtkSLHsmPass::LayoutDefines(sl::HsmLayout layout)
{
  const char* value = layout == sl::HsmLayout::NBuffers ? "1"
    : layout == sl::HsmLayout::DualMssm                 ? "2"
    : layout == sl::HsmLayout::Ysm                      ? "3"
                                                        : "0";
  return { { "HSM_LAYOUT_MIPMAP", "0" }, { "HSM_LAYOUT_NBUFFERS", "1" }, { "HSM_LAYOUT_DUAL", "2" },
    { "HSM_LAYOUT_YSM", "3" }, { "HSM_LAYOUT", value } };
}

void vtkSLHsmPass::ReleaseGraphicsResources(vtkWindow*)
{
  this->Programs.clear();
  this->Texture = nullptr;
  this->MssmPartProgram.reset();
  this->MssmPartTexture = nullptr;
}

void vtkSLHsmPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "DualGrid: " << this->DualGrid << "\n";
}
