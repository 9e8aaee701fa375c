#include "gl/EglContext.h"

#include "core/Error.h"
#include "gl/EglDeviceSelection.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstdlib>
#include <cstring>
#include <vector>

namespace sl
{

struct EglContext::Handles
{
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLSurface surface = EGL_NO_SURFACE;
  EGLContext context = EGL_NO_CONTEXT;

  void release()
  {
    if (display == EGL_NO_DISPLAY)
    {
      return;
    }
    eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (context != EGL_NO_CONTEXT)
    {
      eglDestroyContext(display, context);
    }
    if (surface != EGL_NO_SURFACE)
    {
      eglDestroySurface(display, surface);
    }
    eglTerminate(display);
    *this = Handles();
  }
};

namespace
{

std::string eglErrorName(EGLint error)
{
  switch (error)
  {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE: return "EGL_BAD_SURFACE";
    default: return format("EGL error 0x", std::hex, error);
  }
}

bool hasExtension(const char* extensions, const char* name)
{
  if (!extensions)
  {
    return false;
  }
  const std::size_t length = std::strlen(name);
  for (const char* at = std::strstr(extensions, name); at; at = std::strstr(at + 1, name))
  {
    const bool startsWord = at == extensions || at[-1] == ' ';
    const bool endsWord = at[length] == ' ' || at[length] == '\0';
    if (startsWord && endsWord)
    {
      return true;
    }
  }
  return false;
}

// Initialises `display` and creates a 4.5 core context on it: with a small pbuffer when a config
// offers one (VTK's generic window expects a default framebuffer to exist), else surfaceless.
// Returns "" on success, or why it failed.
std::string createContext(EGLDisplay display, EglContext::Handles& handles)
{
  if (display == EGL_NO_DISPLAY)
  {
    return "no display";
  }
  EGLint major = 0;
  EGLint minor = 0;
  if (!eglInitialize(display, &major, &minor))
  {
    return "eglInitialize: " + eglErrorName(eglGetError());
  }
  handles.display = display;
  if (!eglBindAPI(EGL_OPENGL_API))
  {
    return "eglBindAPI(OpenGL): " + eglErrorName(eglGetError());
  }
  const EGLint pbufferConfig[] = { EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8,
    EGL_BLUE_SIZE, 8, EGL_ALPHA_SIZE, 8, EGL_DEPTH_SIZE, 24, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE };
  const EGLint anyConfig[] = { EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE };
  EGLConfig config = nullptr;
  EGLint configCount = 0;
  bool pbuffer = eglChooseConfig(display, pbufferConfig, &config, 1, &configCount) && configCount > 0;
  if (!pbuffer)
  {
    if (!hasExtension(eglQueryString(display, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context"))
    {
      return "no pbuffer config and no EGL_KHR_surfaceless_context";
    }
    if (!eglChooseConfig(display, anyConfig, &config, 1, &configCount) || configCount == 0)
    {
      return "no OpenGL-renderable config";
    }
  }
  const EGLint contextAttributes[] = { EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
    EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE };
  handles.context = eglCreateContext(display, config, EGL_NO_CONTEXT, contextAttributes);
  if (handles.context == EGL_NO_CONTEXT)
  {
    return "no OpenGL 4.5 core context (" + eglErrorName(eglGetError()) + ")";
  }
  if (pbuffer)
  {
    const EGLint pbufferSize[] = { EGL_WIDTH, 16, EGL_HEIGHT, 16, EGL_NONE };
    handles.surface = eglCreatePbufferSurface(display, config, pbufferSize);
    if (handles.surface == EGL_NO_SURFACE)
    {
      return "eglCreatePbufferSurface: " + eglErrorName(eglGetError());
    }
  }
  if (!eglMakeCurrent(display, handles.surface, handles.surface, handles.context))
  {
    return "eglMakeCurrent: " + eglErrorName(eglGetError());
  }
  return {};
}

template <typename Function>
Function eglFunction(const char* name)
{
  return reinterpret_cast<Function>(eglGetProcAddress(name));
}

} // namespace

EglContext::EglContext()
  : handles_(std::make_unique<Handles>())
{
  const char* forced = std::getenv("SHADOWLAB_EGL");
  const std::string only = forced ? forced : "";
  if (!only.empty() && only != "device" && only != "surfaceless" && only != "default")
  {
    throw GraphicsError(format("SHADOWLAB_EGL='", only, "': expected device, surfaceless or default"));
  }
  const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  const auto getPlatformDisplay =
    eglFunction<PFNEGLGETPLATFORMDISPLAYEXTPROC>("eglGetPlatformDisplayEXT");
  std::vector<std::string> failures;

  const auto attempt = [&](const std::string& name, EGLDisplay display) {
    const std::string why = createContext(display, *handles_);
    if (why.empty())
    {
      platformName_ = name;
      return true;
    }
    handles_->release();
    failures.push_back(name + ": " + why);
    return false;
  };

  // 1. EGL device platform, hardware devices only (Mesa's software device is covered by 2.).
  if (only.empty() || only == "device")
  {
    const auto queryDevices = eglFunction<PFNEGLQUERYDEVICESEXTPROC>("eglQueryDevicesEXT");
    const auto queryDeviceString = eglFunction<PFNEGLQUERYDEVICESTRINGEXTPROC>("eglQueryDeviceStringEXT");
    if (!getPlatformDisplay || !queryDevices || !hasExtension(clientExtensions, "EGL_EXT_platform_device"))
    {
      failures.push_back("device: EGL_EXT_platform_device not available");
    }
    else
    {
      EGLDeviceEXT devices[16];
      EGLint deviceCount = 0;
      queryDevices(16, devices, &deviceCount);
      std::vector<EGLDeviceEXT> hardware;
      for (EGLint i = 0; i < deviceCount; ++i)
      {
        const char* deviceExtensions = queryDeviceString ? queryDeviceString(devices[i], EGL_EXTENSIONS) : nullptr;
        if (!hasExtension(deviceExtensions, "EGL_MESA_device_software"))
        {
          hardware.push_back(devices[i]);
        }
      }
      const EglDeviceSelection selection = selectEglDevice(eglDeviceEnvironment(), static_cast<int>(hardware.size()));
      // An assigned device only: another GPU would be another job's.
      for (std::size_t k = 0; k < hardware.size() && platformName_.empty(); ++k)
      {
        const std::size_t i = selection.assigned ? static_cast<std::size_t>(selection.index) : k;
        if (i < hardware.size() && attempt("device", getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, hardware[i], nullptr)))
        {
          const char* deviceExtensions = queryDeviceString(hardware[i], EGL_EXTENSIONS);
          const char* drmFile = hasExtension(deviceExtensions, "EGL_EXT_device_drm")
            ? queryDeviceString(hardware[i], EGL_DRM_DEVICE_FILE_EXT)
            : nullptr;
          const char* vendor = eglQueryString(handles_->display, EGL_VENDOR);
          deviceIndex_ = static_cast<int>(i);
          deviceDescription_ = format("EGL device ", i, " of ", hardware.size(), " (",
            drmFile ? drmFile : "no DRM file",
            ", ", vendor ? vendor : "unknown vendor", "), chosen by ", selection.source);
        }
        if (selection.assigned)
        {
          break;
        }
      }
      if (hardware.empty())
      {
        failures.push_back(format("device: no hardware EGL device among ", deviceCount));
      }
    }
  }
  // 2. Mesa surfaceless.
  if (platformName_.empty() && (only.empty() || only == "surfaceless"))
  {
    if (!getPlatformDisplay || !hasExtension(clientExtensions, "EGL_MESA_platform_surfaceless"))
    {
      failures.push_back("surfaceless: EGL_MESA_platform_surfaceless not available");
    }
    else
    {
      attempt("surfaceless", getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr));
    }
  }
  // 3. Default display.
  if (platformName_.empty() && (only.empty() || only == "default"))
  {
    attempt("default", eglGetDisplay(EGL_DEFAULT_DISPLAY));
  }
  if (!platformName_.empty() && deviceIndex_ < 0)
  {
    const char* vendor = eglQueryString(handles_->display, EGL_VENDOR);
    const EglDeviceEnvironment environment = eglDeviceEnvironment();
    const bool assigned = !environment.explicitDevice.empty() || !environment.slurmStepGpus.empty() ||
      !environment.slurmJobGpus.empty() || !environment.cudaVisibleDevices.empty();
    deviceDescription_ = format(platformName_, " display (", vendor ? vendor : "unknown vendor",
      "), no hardware EGL device",
      assigned ? " (the GPU assignment in the environment does not apply)" : "");
  }
  if (platformName_.empty())
  {
    std::string tried;
    for (const std::string& failure : failures)
    {
      tried += (tried.empty() ? "" : "; ") + failure;
    }
    throw GraphicsError("no usable EGL display for an OpenGL 4.5 core context (tried " + tried + ")");
  }
}

EglContext::~EglContext()
{
  handles_->release();
}

void EglContext::makeCurrent() const
{
  if (!eglMakeCurrent(handles_->display, handles_->surface, handles_->surface, handles_->context))
  {
    throw GraphicsError("eglMakeCurrent failed: " + eglErrorName(eglGetError()));
  }
}

bool EglContext::isCurrent() const
{
  return handles_->context != EGL_NO_CONTEXT && eglGetCurrentContext() == handles_->context;
}

} // namespace sl
