#include "techniques/yfgl09/vtkSLYfgl09Pass.h"

#include "gl/GlResources.h"
#include "passes/FrameResources.h"
#include "passes/PassUtilities.h"
#include "passes/ScopedRenderTarget.h"
#include "techniques/SoftShadowSupport.h"
#include "techniques/yfgl09/Yfgl09Technique.h"

#include <vtkObjectFactory.h>
#include <vtkOpenGLFramebufferObject.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkRenderState.h>
#include <vtkRenderer.h>
#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>
#include <vtk_glew.h>

#include <algorithm>
#include <map>

vtkStandardNewMacro(vtkSLYfgl09Pass);

vtkSLYfgl09Pass::vtkSLYfgl09Pass() = default;
vtkSLYfgl09Pass::~vtkSLYfgl09Pass() = default;

std::vector<vtkTextureObject*> vtkSLYfgl09Pass::SetTechniqueUniforms(vtkShaderProgram* program)
{
  const sl::FrameResources& frame = *this->Frame;
  sl::setSoftShadowUniforms(program, frame);
  vtkTextureObject* visibility = frame.techniqueTargets.at("visibility");
  const int size[2] = { static_cast<int>(visibility->GetWidth()), static_cast<int>(visibility->GetHeight()) };
  program->SetUniform2i("imageSize", size);
  const sl::Yfgl09Settings settings = sl::Yfgl09Settings::from(frame.parameters);
  const int packetSize[2] = { settings.packetWidth, settings.packetHeight };
  program->SetUniform2i("packetSize", packetSize);
  // The packet size is a uniform, not a define: one program per pass serves every size. The dual-grid MSSM is
  // bound by its structure (structures/mssm).
  return {};
}

void vtkSLYfgl09Pass::DrawPass(vtkOpenGLRenderWindow* window, sl::FullScreenQuad& quad, bool packetPass)
{
  sl::ShaderDefines defines = this->TechniqueDefines();
  if (packetPass)
  {
    defines.push_back({ sl::yfgl09PacketPassFlag, "" });
  }
  const std::string source =
    sl::assembleShader(this->GetFragmentShaderPath(), defines, this->ParameterDeclarations());
  vtkShaderProgram* program = quad.ready(window, source, this->Frame->technique->name + (packetPass ? " (packets)" : " (pixels)"));
  std::vector<vtkTextureObject*> bound = this->SetCommonUniforms(program);
  const std::vector<vtkTextureObject*> extra = this->SetTechniqueUniforms(program);
  bound.insert(bound.end(), extra.begin(), extra.end());
  if (!packetPass)
  {
    bound.push_back(sl::bindTexture(program, "packetTexture", this->PacketTarget));
  }
  quad.render();
  for (vtkTextureObject* texture : bound)
  {
    texture->Deactivate();
  }
}

void vtkSLYfgl09Pass::Execute(const vtkRenderState* state)
{
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(state->GetRenderer()->GetRenderWindow());
  sl::FrameResources& frame = *this->Frame;
  const std::vector<vtkTextureObject*> targets = this->TechniqueTargets();
  const sl::Yfgl09Settings settings = sl::Yfgl09Settings::from(frame.parameters);
  const int packetWidth = settings.packetWidth;
  const int packetHeight = settings.packetHeight;
  const int packetColumns = (static_cast<int>(targets[0]->GetWidth()) + packetWidth - 1) / packetWidth;
  const int packetRows = (static_cast<int>(targets[0]->GetHeight()) + packetHeight - 1) / packetHeight;
  if (!this->PacketTarget || static_cast<int>(this->PacketTarget->GetWidth()) != packetColumns ||
    static_cast<int>(this->PacketTarget->GetHeight()) != packetRows)
  {
    this->PacketTarget = sl::makeFloatTarget(window, packetColumns, packetRows, 4);
  }

  // Pass 1 (Alg. 1 steps 5-7): one fragment per packet; its pixels go to the targets through image stores.
  {
    const sl::ScopedRenderTarget target(window, this->PacketFramebuffer, { this->PacketTarget });
    for (std::size_t binding = 0; binding < targets.size(); ++binding)
    {
      glBindImageTexture(static_cast<GLuint>(binding), targets[binding]->GetHandle(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
    }
    this->DrawPass(window, this->PacketQuad, true);
    for (std::size_t binding = 0; binding < targets.size(); ++binding)
    {
      glBindImageTexture(static_cast<GLuint>(binding), 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
    }
  }
  // The pixel pass reads the packet target and draws over the image-stored targets.
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  // Pass 2 (step 8): one fragment per pixel of the packets left to pixels; the others are discarded.
  {
    const sl::ScopedRenderTarget target(window, this->PixelFramebuffer, targets);
    this->DrawPass(window, this->PixelQuad, false);
  }
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
}

std::map<std::string, double> vtkSLYfgl09Pass::CollectStatistics()
{
  if (!this->PacketTarget)
  {
    return {};
  }
  const sl::ImageF packets = sl::readFloatTexture(this->PacketTarget, 4);
  // Packets by class (the packet target's x holds sl::PacketClass codes).
  using sl::PacketClass;
  std::map<PacketClass, double> counts;
  for (std::size_t i = 0; i < packets.pixelCount(); ++i)
  {
    const int code = std::clamp(static_cast<int>(packets.data[i * 4]), static_cast<int>(PacketClass::NotTested),
      static_cast<int>(PacketClass::OverBudget));
    ++counts[static_cast<PacketClass>(code)];
  }
  const double nonTrivial = counts[PacketClass::Coherent] + counts[PacketClass::NonCoherent] +
    counts[PacketClass::CaughtNull] + counts[PacketClass::OverBudget];
  // The median kernel width over the penumbra pixels, to compare coherence at matched kernel widths (the
  // paper's light sizes are in its own scene's units).
  const sl::FrameResources& frame = *this->Frame;
  const sl::ImageF kernels = sl::readFloatTexture(frame.techniqueTargets.at("kernel_texels"), 1);
  const sl::ImageF classes = sl::readFloatTexture(frame.techniqueTargets.at("packet_class"), 1);
  std::vector<float> penumbraKernels;
  for (std::size_t i = 0; i < kernels.pixelCount(); ++i)
  {
    if (classes.data[i] > static_cast<float>(PacketClass::Trivial))
    {
      penumbraKernels.push_back(kernels.data[i]);
    }
  }
  double medianKernel = 0.0;
  if (!penumbraKernels.empty())
  {
    auto middle = penumbraKernels.begin() + static_cast<std::ptrdiff_t>(penumbraKernels.size() / 2);
    std::nth_element(penumbraKernels.begin(), middle, penumbraKernels.end());
    medianKernel = *middle;
  }
  return {
    { "packets_non_trivial", nonTrivial },
    { "packets_coherent", counts[PacketClass::Coherent] },
    { "packets_predicted_non_coherent", counts[PacketClass::NonCoherent] },
    { "packets_caught_null", counts[PacketClass::CaughtNull] },
    { "packets_over_budget", counts[PacketClass::OverBudget] },
    { "coherent_packet_percent", nonTrivial > 0 ? 100.0 * counts[PacketClass::Coherent] / nonTrivial : 0.0 },
    { "median_penumbra_kernel_texels", medianKernel },
  };
}

void vtkSLYfgl09Pass::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Superclass::ReleaseGraphicsResources(window);
  this->PacketQuad.releaseGraphicsResources(window);
  this->PixelQuad.releaseGraphicsResources(window);
  this->PacketFramebuffer->ReleaseGraphicsResources(window);
  this->PixelFramebuffer->ReleaseGraphicsResources(window);
  this->PacketTarget = nullptr;
}

void vtkSLYfgl09Pass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "PacketTarget: " << (this->PacketTarget ? "allocated" : "(none)") << "\n";
}
