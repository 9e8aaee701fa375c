// A vtkGenericOpenGLRenderWindow driven by an offscreen EGL context (no X, no Xvfb, no OSMesa).
//
// Debian's VTK 9.1 is built for GLX. Its OpenGLInitContext() calls glewInit(), which in a GLX build of
// GLEW first loads the core GL entry points (this works under EGL: glvnd dispatches to the current
// context) and then initialises GLX, which fails with GLEW_ERROR_NO_GLX_DISPLAY because an EGL context
// has no X display. VTK would report that as "GLEW could not be initialized" although every GL entry
// point it needs is loaded. This class does VTK's context initialisation itself: it accepts exactly
// that GLX-only failure, verifies the context really is OpenGL >= 4.5 core with the entry points loaded,
// and throws a GraphicsError with the real reason otherwise. Users never see the false error.
#pragma once

#include "gl/EglContext.h"

#include <vtkGenericOpenGLRenderWindow.h>

#include <memory>
#include <string>

class vtkSLEglRenderWindow : public vtkGenericOpenGLRenderWindow
{
public:
  static vtkSLEglRenderWindow* New();
  vtkTypeMacro(vtkSLEglRenderWindow, vtkGenericOpenGLRenderWindow);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  // Creates the EGL context and initialises VTK's OpenGL state on it. Throws sl::GraphicsError.
  void InitializeOffscreen(int width, int height);

  void MakeCurrent() override;
  bool IsCurrent() override;
  int SupportsOpenGL() override { return 1; }
  vtkTypeBool IsDirect() override { return 1; }

  // "llvmpipe (LLVM 15.0.6, 256 bits)", "NVIDIA H100 ..." (GL_RENDERER), and GL_VERSION.
  const std::string& GetRendererString() const { return this->RendererString; }
  const std::string& GetVersionString() const { return this->VersionString; }
  const sl::EglContext* GetEglContext() const { return this->Context.get(); }

protected:
  vtkSLEglRenderWindow();
  ~vtkSLEglRenderWindow() override;
  void OpenGLInitContext() override;

private:
  vtkSLEglRenderWindow(const vtkSLEglRenderWindow&) = delete;
  void operator=(const vtkSLEglRenderWindow&) = delete;

  std::unique_ptr<sl::EglContext> Context;
  std::string RendererString;
  std::string VersionString;
};
