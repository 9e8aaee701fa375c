// The X display `shadowlab view` opens its window on, checked before any window or frame exists: DISPLAY must be
// set, the X server must accept the connection and offer GLX (VTK 9.1 on Debian draws its windows with
// vtkXOpenGLRenderWindow, which aborts the process when it finds no display). Xlib's headers stay in the .cpp
// (their macros, None, Status, Bool, clash with VTK's and the standard library's names).
#pragma once

#include <string>

namespace sl
{

class XDisplay
{
public:
  // Throws GraphicsError, one line saying why there is no usable display.
  XDisplay();
  ~XDisplay(); // closes the connection: after every window on it is gone
  XDisplay(const XDisplay&) = delete;
  XDisplay& operator=(const XDisplay&) = delete;

  void* handle() const { return display_; } // Display*, for vtkRenderWindow::SetDisplayId
  const std::string& name() const { return name_; }

private:
  void* display_ = nullptr;
  std::string name_;
};

} // namespace sl
