#include "passes/vtkSLGBufferPass.h"

#include "core/Error.h"
#include "gl/GlResources.h"
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

vtkStandardNewMacro(vtkSLGBufferPass);

vtkSLGBufferPass::vtkSLGBufferPass() = default;
vtkSLGBufferPass::~vtkSLGBufferPass() = default;

void vtkSLGBufferPass::Execute(const vtkRenderState* state)
{
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(state->GetRenderer()->GetRenderWindow());
  sl::FrameResources& frame = *this->Frame;
  const int width = frame.width();
  const int height = frame.height();

  frame.gbufferPosition = sl::makeFloatTarget(window, width, height, 4);
  frame.gbufferNormal = sl::makeFloatTarget(window, width, height, 4);
  frame.gbufferAlbedoDepth = sl::makeFloatTarget(window, width, height, 4);
  // Depth-stencil: object-space techniques (TechniqueDescriptor::drawsSceneGeometry) test against this depth and
  // write stencil into it.
  frame.gbufferDepth = sl::makeDepthStencilTarget(window, width, height);
  const int samples = frame.multisample.samples;
  if (samples > 1)
  {
    frame.gbufferMsPosition = sl::makeMultisampleFloatTarget(window, width, height, 4, samples);
    frame.gbufferMsNormal = sl::makeMultisampleFloatTarget(window, width, height, 4, samples);
    frame.gbufferMsAlbedoDepth = sl::makeMultisampleFloatTarget(window, width, height, 4, samples);
    frame.gbufferMsDepth = sl::makeMultisampleDepthStencilTarget(window, width, height, samples);
    sl::checkGlErrors("gbuffer DEBUG alloc");
  }

  {
    const bool multisampled = samples > 1;
    const sl::ScopedRenderTarget target(window, multisampled ? this->MultisampleFramebuffer : this->Framebuffer,
      multisampled ? std::vector<vtkTextureObject*>{ frame.gbufferMsPosition, frame.gbufferMsNormal, frame.gbufferMsAlbedoDepth }
                   : std::vector<vtkTextureObject*>{ frame.gbufferPosition, frame.gbufferNormal, frame.gbufferAlbedoDepth },
      multisampled ? frame.gbufferMsDepth : frame.gbufferDepth);
    for (int attachment = 0; attachment < 3; ++attachment)
    {
      target.clearColor(attachment, 0.0f); // w = 0 marks uncovered pixels
    }
    target.clearDepth();
    target.clearStencil();
    sl::checkGlErrors("gbuffer DEBUG clear");

    const std::string vertexSource = sl::assembleShader("gbuffer/GBufferVertex.glsl", sl::commonDefines());
    const std::string fragmentSource = sl::assembleShader("gbuffer/GBufferFragment.glsl", sl::commonDefines());
    vtkShaderProgram* program = sl::readyProgram(window, vertexSource, fragmentSource, "gbuffer");
    sl::setMatrix(program, "clipFromWorld", frame.camera.clipFromWorld);
    sl::setMatrix(program, "viewFromWorld", frame.camera.viewFromWorld);
    const float alphaTestOffset[2] = { static_cast<float>(frame.alphaTestOffset.x),
      static_cast<float>(frame.alphaTestOffset.y) };
    program->SetUniform2f("alphaTestOffset", alphaTestOffset);
    // One fragment per pixel and primitive, replicated to the samples it covers (SS08 §7), whatever the
    // driver's default (nothing in ShadowLab or VTK enables sample shading; GL_MULTISAMPLE is on by default).
    glDisable(GL_SAMPLE_SHADING);
    this->Drawer.draw(program, *frame.gpuScene, [](const sl::SceneObject&) { return true; });
    sl::checkGlErrors("gbuffer DEBUG draw");
    if (multisampled)
    {
      frame.samplePositions.clear();
      for (int sample = 0; sample < samples; ++sample)
      {
        GLfloat position[2] = { 0.0f, 0.0f };
        glGetMultisamplefv(GL_SAMPLE_POSITION, static_cast<GLuint>(sample), position);
        frame.samplePositions.emplace_back(position[0], position[1]);
      }
    }
  }
  if (samples > 1)
  {
    this->CopyFirstSample(window);
  }
  sl::checkGlErrors("gbuffer");
}

void vtkSLGBufferPass::CopyFirstSample(vtkOpenGLRenderWindow* window)
{
  sl::FrameResources& frame = *this->Frame;
  const sl::ScopedRenderTarget target(window, this->Framebuffer,
    { frame.gbufferPosition, frame.gbufferNormal, frame.gbufferAlbedoDepth }, frame.gbufferDepth);
  for (int attachment = 0; attachment < 3; ++attachment)
  {
    target.clearColor(attachment, 0.0f);
  }
  target.clearDepth();
  target.clearStencil();
  vtkShaderProgram* program = this->FirstSampleQuad.ready(
    window, sl::assembleShader("gbuffer/GBufferFirstSample.glsl", sl::commonDefines()), "gbuffer first sample");
  vtkTextureObject* bound[] = {
    sl::bindTexture(program, "multisamplePosition", frame.gbufferMsPosition),
    sl::bindTexture(program, "multisampleNormal", frame.gbufferMsNormal),
    sl::bindTexture(program, "multisampleAlbedoDepth", frame.gbufferMsAlbedoDepth),
    sl::bindTexture(program, "multisampleDepth", frame.gbufferMsDepth),
  };
  this->FirstSampleQuad.render();
  for (vtkTextureObject* texture : bound)
  {
    texture->Deactivate();
  }
}

void vtkSLGBufferPass::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Drawer.releaseGraphicsResources(vtkOpenGLRenderWindow::SafeDownCast(window));
  this->Framebuffer->ReleaseGraphicsResources(window);
  this->MultisampleFramebuffer->ReleaseGraphicsResources(window);
  this->FirstSampleQuad.releaseGraphicsResources(window);
}

void vtkSLGBufferPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
