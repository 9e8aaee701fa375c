// An offscreen OpenGL 4.5 core context through EGL, with no window system.
//
// Displays are tried in this order, and the first that yields a 4.5 core context wins:
//   1. the EGL device platform (EGL_EXT_platform_device) on a hardware device: the NVIDIA path;
//   2. Mesa's surfaceless platform (EGL_MESA_platform_surfaceless): llvmpipe here and in CI;
//   3. the default display.
// SHADOWLAB_EGL=device|surfaceless|default forces one. Among several hardware devices, the one the batch system
// assigned (SLURM_STEP_GPUS, CUDA_VISIBLE_DEVICES) or SHADOWLAB_EGL_DEVICE names (gl/EglDeviceSelection.h). If none works, the constructor throws a
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
  // The hardware EGL device rendered on (index among them; -1 on the surfaceless or default display) and one line
  // naming it: index, DRM device file, EGL vendor, and what chose it (gl/EglDeviceSelection.h).
  int deviceIndex() const { return deviceIndex_; }
  const std::string& deviceDescription() const { return deviceDescription_; }

  struct Handles; // EGL display/surface/context; defined in the .cpp so EGL headers stay out of ours

private:
  std::unique_ptr<Handles> handles_;
  std::string platformName_;
  int deviceIndex_ = -1;
  std::string deviceDescription_;
};

} // namespace sl
