#include "cli/XDisplay.h"

#include "core/Error.h"

#include <X11/Xlib.h>

#include <cstdlib>

namespace sl
{

XDisplay::XDisplay()
{
  const char* variable = std::getenv("DISPLAY");
  if (variable == nullptr || *variable == '\0')
  {
    throw GraphicsError("no display: DISPLAY is not set (shadowlab view opens a window; run it on a desktop, or "
                        "under xvfb-run)");
  }
  name_ = variable;
  Display* display = XOpenDisplay(nullptr);
  if (display == nullptr)
  {
    throw GraphicsError("no display: cannot open the X display '" + printable(name_) + "' (DISPLAY)");
  }
  int majorOpcode = 0;
  int eventBase = 0;
  int errorBase = 0;
  if (!XQueryExtension(display, "GLX", &majorOpcode, &eventBase, &errorBase))
  {
    XCloseDisplay(display);
    throw GraphicsError("no display: the X display '" + printable(name_) + "' has no GLX extension (OpenGL windows)");
  }
  display_ = display;
}

XDisplay::~XDisplay()
{
  XCloseDisplay(static_cast<Display*>(display_));
}

} // namespace sl
