#include "gl/vtkSLEglRenderWindow.h"

#include "core/Error.h"

#include <vtkObjectFactory.h>
#include <vtkOpenGLState.h>
#include <vtk_glew.h>

vtkStandardNewMacro(vtkSLEglRenderWindow);

vtkSLEglRenderWindow::vtkSLEglRenderWindow()
{
  // We read our results from our own framebuffers; copying VTK's frame to the 16x16 pbuffer is waste.
  this->SetFrameBlitModeToNoBlit();
  this->SetShowWindow(false);
  this->SetUseOffScreenBuffers(true);
  this->SetMultiSamples(0);
}

vtkSLEglRenderWindow::~vtkSLEglRenderWindow()
{
  if (this->Context)
  {
    // VTK frees its GL objects in Finalize(); the context must be current for that.
    this->Context->makeCurrent();
    this->Finalize();
  }
}

void vtkSLEglRenderWindow::InitializeOffscreen(int width, int height)
{
  this->Context = std::make_unique<sl::EglContext>();
  this->SetSize(width, height);
  this->SetReadyForRendering(true);
  this->SetIsCurrent(true);
  this->OpenGLInit(); // calls our OpenGLInitContext()
}

void vtkSLEglRenderWindow::MakeCurrent()
{
  if (this->Context)
  {
    this->Context->makeCurrent();
  }
}

bool vtkSLEglRenderWindow::IsCurrent()
{
  return this->Context && this->Context->isCurrent();
}

void vtkSLEglRenderWindow::OpenGLInitContext()
{
  if (this->Initialized)
  {
    return;
  }
  this->MakeCurrent();
  this->ContextCreationTime.Modified();
  const GLenum glewResult = glewInit();
  // GLEW_ERROR_NO_GLX_DISPLAY comes from glxewInit(), after the core entry points were loaded.
  if (glewResult != GLEW_OK && glewResult != GLEW_ERROR_NO_GLX_DISPLAY)
  {
    throw sl::GraphicsError(sl::format("cannot load OpenGL entry points: ",
      reinterpret_cast<const char*>(glewGetErrorString(glewResult))));
  }
  const auto* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  GLint major = 0;
  GLint minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  if (!version || major * 10 + minor < 45 || !GLEW_VERSION_4_5 || glCreateShader == nullptr ||
    glDispatchCompute == nullptr || glGetTextureImage == nullptr)
  {
    throw sl::GraphicsError(sl::format("OpenGL 4.5 core is required, the EGL context offers '",
      version ? version : "nothing", "'"));
  }
  this->VersionString = version;
  this->RendererString = renderer ? renderer : "unknown";
  this->GlewInitValid = true;
  this->Initialized = true;

  GLfloat lineWidthRange[2] = { 1.0f, 1.0f };
  glGetFloatv(GL_ALIASED_LINE_WIDTH_RANGE, lineWidthRange);
  this->MaximumHardwareLineWidth = lineWidthRange[1];
  while (glGetError() != GL_NO_ERROR)
  {
  }
}

void vtkSLEglRenderWindow::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "EGL platform: " << (this->Context ? this->Context->platformName() : "none") << "\n";
  os << indent << "Renderer: " << this->RendererString << "\n";
  os << indent << "Version: " << this->VersionString << "\n";
}
