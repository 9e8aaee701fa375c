// An offscreen OpenGL 4.5 core context through EGL, with no window system.
//
// Displays are tried in this order, and the first that yields a 4.5 core context wins:
//   1. the EGL device platform (EGL_EXT_platform_device) on a hardware device: the NVIDIA path;
//   2. Mesa's surfaceless platform (EGL_MESA_platform_surfaceless): llvmpipe here and in CI;
//   3. the default display.
// SHADOWLAB_EGL=device|surfaceless|default forces one. If none works, the constructor throws a
// GraphicsError listing what was tried and why each failed, in one line.
#pragma once

#include <memory>
#include <string>

namespace sl
{

class EglContext
{
public:
  EglContext();
  ~EglContext();
  EglContext(const EglContext&) = delete;
  EglContext& operator=(const EglContext&) = delete;

  void makeCurrent() const;
  bool isCurrent() const;
  const std::string& platformName() const { return platformName_; } // "device", "surfaceless", "default"

  struct Handles; // EGL display/surface/context; defined in the .cpp so EGL headers stay out of ours

private:
  std::unique_ptr<Handles> handles_;
  std::string platformName_;
};

} // namespace sl
