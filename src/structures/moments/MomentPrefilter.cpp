#include "structures/moments/MomentPrefilter.h"

#include "gl/GlResources.h"
#include "gl/ShaderLibrary.h"
#include "passes/FullScreenQuad.h"
#include "passes/PassUtilities.h"
#include "passes/ScopedRenderTarget.h"

#include <vtkOpenGLFramebufferObject.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>
#include <vtk_glew.h>

namespace sl
{

vtkSmartPointer<vtkTextureObject> prefilterMoments(vtkOpenGLRenderWindow* window, vtkOpenGLFramebufferObject* framebuffer,
  FullScreenQuad& blurQuad, vtkSmartPointer<vtkTextureObject> texture, int blurTexels, bool mipmap)
{
  if (blurTexels > 1)
  {
    const int width = texture->GetWidth();
    const int height = texture->GetHeight();
    const int components = texture->GetComponents();
    auto horizontal = makeFloatTarget(window, width, height, components);
    auto blurred = makeFloatTarget(window, width, height, components);
    const int directions[2][2] = { { 1, 0 }, { 0, 1 } };
    vtkTextureObject* sources[2] = { texture, horizontal };
    vtkTextureObject* targets[2] = { horizontal, blurred };
    for (int pass = 0; pass < 2; ++pass)
    {
      const ScopedRenderTarget target(window, framebuffer, { targets[pass] });
      vtkShaderProgram* program = blurQuad.ready(window, assembleShader("moments/BoxBlur.glsl"), "box blur");
      vtkTextureObject* bound = bindTexture(program, "source", sources[pass]);
      program->SetUniform2i("direction", directions[pass]);
      program->SetUniformi("blurWidth", blurTexels);
      blurQuad.render();
      bound->Deactivate();
    }
    texture = blurred;
  }
  if (mipmap)
  {
    glGenerateTextureMipmap(texture->GetHandle());
    texture->SetMinificationFilter(vtkTextureObject::LinearMipmapLinear);
    texture->SetMagnificationFilter(vtkTextureObject::Linear);
  }
  return texture;
}

} // namespace sl
