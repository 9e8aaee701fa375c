#include "structures/microrect/vtkSLMicrorectPass.h"

#include "core/Error.h"
#include "core/Image.h"
#include "gl/ShaderLibrary.h"
#include "lightspace/HierarchicalShadowMap.h"
#include "structures/microrect/MicrorectStructure.h"
#include "passes/FrameResources.h"

#include <vtkObjectFactory.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkRenderState.h>
#include <vtkRenderer.h>
#include <vtk_glew.h>

vtkStandardNewMacro(vtkSLMicrorectPass);

vtkSLMicrorectPass::vtkSLMicrorectPass() = default;
vtkSLMicrorectPass::~vtkSLMicrorectPass() = default;

namespace
{

// Extents are level-0 texel coordinates in RGBA16UI.
static_assert(sl::kMaxImageSide <= 65536, "microrect extents are stored as 16-bit texel coordinates");

vtkSmartPointer<vtkTextureObject> makeTexture(vtkOpenGLRenderWindow* window, int size, unsigned internalFormat,
  unsigned format, unsigned dataType, int components, int vtkType)
{
  auto texture = vtkSmartPointer<vtkTextureObject>::New();
  texture->SetContext(window);
  texture->SetInternalFormat(internalFormat);
  texture->SetFormat(format);
  texture->SetDataType(dataType);
  // Integer textures must not be filtered; the float atlas is read texel by texel too.
  texture->SetMinificationFilter(vtkTextureObject::Nearest);
  texture->SetMagnificationFilter(vtkTextureObject::Nearest);
  texture->SetWrapS(vtkTextureObject::ClampToEdge);
  texture->SetWrapT(vtkTextureObject::ClampToEdge);
  if (!texture->Allocate2D(size, size, components, vtkType))
  {
    throw sl::GraphicsError(sl::format("cannot allocate a ", size, "^2 microrect texture"));
  }
  return texture;
}

} // namespace

void vtkSLMicrorectPass::Execute(const vtkRenderState* state)
{
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(state->GetRenderer()->GetRenderWindow());
  sl::FrameResources& frame = *this->Frame;
  SL_CHECK_MSG(frame.hasLightView && frame.shadowMapLinear, "the shadow map must be built before the microrects");
  const int size = frame.lightView.resolution;
  const int levels = sl::hsmLevelCount(size);

  // The previous frame's textures are reused when the map size is the same: each level's dispatches rewrite the
  // same texels, and the atlases' unused texels stay 0.
  const bool fits = this->ExtentTexture && this->ExtentTexture->GetContext() == window && this->TextureMapSize == size;
  if (!fits)
  {
    this->ExtentTexture = makeTexture(window, size, GL_RGBA16UI, GL_RGBA_INTEGER, GL_UNSIGNED_SHORT, 4, VTK_UNSIGNED_SHORT);
    this->DepthTexture = makeTexture(window, size, GL_R32F, GL_RED, GL_FLOAT, 1, VTK_FLOAT);
    this->ClaimTexture = makeTexture(window, sl::hsmLevelSize(sl::HsmLayout::MipMap, size, 1), GL_R8UI,
      GL_RED_INTEGER, GL_UNSIGNED_BYTE, 1, VTK_UNSIGNED_CHAR);
    // The atlases' unused texels are exported: make them 0, not undefined (no level ever writes them).
    const GLushort zeroExtent[4] = { 0, 0, 0, 0 };
    const float zeroDepth = 0.0f;
    glClearTexImage(this->ExtentTexture->GetHandle(), 0, GL_RGBA_INTEGER, GL_UNSIGNED_SHORT, zeroExtent);
    glClearTexImage(this->DepthTexture->GetHandle(), 0, GL_RED, GL_FLOAT, &zeroDepth);
    this->TextureMapSize = size;
  }
  if (!this->FirstPass)
  {
    this->FirstPass = std::make_unique<sl::ComputeProgram>(
      sl::assembleShader("microrect/MicrorectBuild.glsl", sl::microrectBuildDefines(1)), "microrects, pass 1");
    this->SecondPass = std::make_unique<sl::ComputeProgram>(
      sl::assembleShader("microrect/MicrorectBuild.glsl", sl::microrectBuildDefines(2)), "microrects, pass 2");
  }

  glBindImageTexture(0, this->ExtentTexture->GetHandle(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA16UI);
  glBindImageTexture(1, this->DepthTexture->GetHandle(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32F);
  glBindImageTexture(2, this->ClaimTexture->GetHandle(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R8UI);
  // Level - 1 is read through the lookup's samplers (level 0: the shadow map), level by level after the
  // barrier that makes the previous level's image writes visible to texel fetches.
  frame.shadowMapLinear->Activate();
  this->ExtentTexture->Activate();
  this->DepthTexture->Activate();
  for (const sl::ComputeProgram* program : { this->FirstPass.get(), this->SecondPass.get() })
  {
    program->setInt("shadowMapLinear", frame.shadowMapLinear->GetTextureUnit());
    program->setInt("microrectExtentTexture", this->ExtentTexture->GetTextureUnit());
    program->setInt("microrectDepthTexture", this->DepthTexture->GetTextureUnit());
    program->setInt("microrectMapSize", size);
  }
  for (int level = 1; level <= levels; ++level)
  {
    const int levelSize = sl::hsmLevelSize(sl::HsmLayout::MipMap, size, level);
    const glm::ivec2 groups((levelSize + 7) / 8, (levelSize + 7) / 8);
    this->FirstPass->use();
    this->FirstPass->setInt("level", level);
    this->FirstPass->dispatch(groups);
    // Pass 2 reads pass 1's partial microrects and claims.
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    this->SecondPass->use();
    this->SecondPass->setInt("level", level);
    this->SecondPass->dispatch(groups);
    // The next level reads this one through texel fetches.
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  }
  this->DepthTexture->Deactivate();
  this->ExtentTexture->Deactivate();
  frame.shadowMapLinear->Deactivate();
  for (GLuint unit = 0; unit < 3; ++unit)
  {
    glBindImageTexture(unit, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32F);
  }

  auto data = std::make_shared<sl::MicrorectData>();
  data->extentTexture = this->ExtentTexture;
  data->depthTexture = this->DepthTexture;
  data->claimTexture = this->ClaimTexture;
  data->mapSize = size;
  frame.lightSpaceData[sl::microrectStructure().name] = data;
}

void vtkSLMicrorectPass::ReleaseGraphicsResources(vtkWindow*)
{
  this->FirstPass.reset();
  this->SecondPass.reset();
  this->ExtentTexture = nullptr;
  this->DepthTexture = nullptr;
  this->ClaimTexture = nullptr;
  this->TextureMapSize = 0;
}

void vtkSLMicrorectPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "TextureMapSize: " << this->TextureMapSize << "\n";
}
