// A full-screen quad (vtkOpenGLQuadHelper) whose program is built from an embedded fragment shader and
// rebuilt only when that shader's assembled source changes (a different technique variant).
#pragma once

#include <memory>
#include <string>

class vtkOpenGLQuadHelper;
class vtkOpenGLRenderWindow;
class vtkShaderProgram;
class vtkWindow;

namespace sl
{

class FullScreenQuad
{
public:
  FullScreenQuad();
  ~FullScreenQuad();
  // Builds (or reuses) the program and binds it. Throws GraphicsError naming `label` on failure.
  vtkShaderProgram* ready(vtkOpenGLRenderWindow* window, const std::string& fragmentSource, const std::string& label);
  void render();
  void releaseGraphicsResources(vtkWindow* window);

private:
  std::unique_ptr<vtkOpenGLQuadHelper> quad_;
  std::string fragmentSource_;
};

} // namespace sl
