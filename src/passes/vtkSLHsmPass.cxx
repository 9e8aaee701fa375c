#include "passes/vtkSLHsmPass.h"

#include "core/Error.h"
#include "gl/ShaderLibrary.h"
#include "lightspace/HierarchicalShadowMap.h"
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
  const bool nBuffers = frame.parameters.choice("hsm") == "nbuffers";
  const int size = frame.lightView.resolution;
  const int levels = sl::hsmLevelCount(size);

  if (nBuffers)
  {
    GLint max3dSize = 0;
    glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &max3dSize);
    if (size > max3dSize)
    {
      throw sl::InputError(sl::format("hsm=nbuffers: a ", size, "^2 shadow map needs a ", size, "x", size, "x", levels,
        " 3D texture and this GL allows ", max3dSize, " per side; use hsm=mipmap or shadow_map_size <= ", max3dSize));
    }
  }
  // Mip-map: levels 1..L in one N x N atlas; N-buffers: level k in layer k - 1 of an N x N x L texture.
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
  const bool allocated = nBuffers ? hsm->Allocate3D(size, size, std::max(levels, 1), 2, VTK_FLOAT)
                                  : hsm->Allocate2D(size, size, 2, VTK_FLOAT);
  if (!allocated)
  {
    throw sl::GraphicsError(sl::format("cannot allocate the hierarchical shadow map (", size, "^2, ",
      nBuffers ? "N-buffers" : "mip-map", ")"));
  }
  if (!nBuffers)
  {
    // The atlas's unused texels are exported: make them 0, not undefined.
    const float zero[2] = { 0.0f, 0.0f };
    glClearTexImage(hsm->GetHandle(), 0, GL_RG, GL_FLOAT, zero);
  }
  auto& program = this->Programs[nBuffers];
  if (!program)
  {
    const sl::ShaderDefines defines = { { "HSM_LAYOUT_MIPMAP", "0" }, { "HSM_LAYOUT_NBUFFERS", "1" },
      { "HSM_LAYOUT", nBuffers ? "1" : "0" } };
    program = std::make_unique<sl::ComputeProgram>(sl::assembleShader("hsm/HsmBuild.glsl", defines), "hierarchical shadow map");
  }
  glBindImageTexture(0, hsm->GetHandle(), 0, nBuffers ? GL_TRUE : GL_FALSE, 0, GL_READ_WRITE, GL_RG32F);
  frame.shadowMapLinear->Activate();
  program->use();
  program->setInt("shadowMapLinear", frame.shadowMapLinear->GetTextureUnit());
  program->setInt("hsmMapSize", size);
  for (int level = 1; level <= levels; ++level)
  {
    program->setInt("level", level);
    const int levelSize = sl::hsmLevelSize(nBuffers ? sl::HsmLayout::NBuffers : sl::HsmLayout::MipMap, size, level);
    program->dispatch({ (levelSize + 7) / 8, (levelSize + 7) / 8 });
    // Level k + 1 reads level k's image writes.
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  }
  frame.shadowMapLinear->Deactivate();
  glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RG32F);
  frame.hierarchicalShadowMap = hsm;
  frame.hierarchicalShadowMapIsNBuffers = nBuffers;
}

void vtkSLHsmPass::ReleaseGraphicsResources(vtkWindow*)
{
  this->Programs.clear();
}

void vtkSLHsmPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
