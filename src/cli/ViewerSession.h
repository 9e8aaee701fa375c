// What `shadowlab view` shows and how its keys change it, without the window (cli/ViewerWindow.h draws it).
//
// The session holds the scene, the technique (the registry's order), each technique's parameter values, the
// light size, the frame the offscreen pipeline rendered for them, the buffer on show and the probed pixel. Every
// change re-renders the frame with ShadowRenderer (the same path as `shadowlab render`) and, when a pixel is
// probed, replays it on the new frame (probePixel, probeFigure). A change the pipeline refuses (InputError: a
// value the scene limits forbid, a technique that cannot render this light) is undone and rethrown, so the
// session always holds the last frame that rendered.
//
// OpenGL contexts: the pipeline renders into its own EGL context (gl/EglContext.h), exactly as `render` does,
// and the window draws with VTK's GLX context, in one process and one thread. Under glvnd only one window-system
// API may own a thread's current context at a time (measured with Mesa 22.3 on Xvfb: eglMakeCurrent fails with
// EGL_BAD_ACCESS while the window's GLX context is current, and glXMakeCurrent raises the X error BadAccess, which
// ends the process, while the pipeline's EGL context is). So every method here that renders first calls the
// releaseWindowContext hook (the window releases its GLX context), makes the pipeline's context current, and
// releases it again before returning, also when it throws; VTK's window makes its own context current again at
// its next Render(). GLEW's entry points are glvnd dispatch stubs that call into whichever context is current, so
// the one set of them (loaded by whichever of the two initialised last) serves both. This keeps the frames
// identical to `render`'s (same process, same pipeline) without copying buffers between processes; drawing the
// window without GL or running the pipeline in a child process would each have needed more machinery for no
// gain once the hand-over was measured to work.
#pragma once

#include "core/Image.h"
#include "frame/FrameResult.h"
#include "probe/Probe.h"
#include "scene/Scene.h"

#include <glm/glm.hpp>

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace sl
{

class ShadowRenderer;

struct ViewerStart
{
  std::string sceneFile;
  std::vector<std::string> sceneOverrides; // --scene-set, kept for the whole session
  std::string technique;
  std::vector<std::string> settings; // --set, for `technique`
  std::optional<glm::ivec2> resolution;
  int lightIndex = 0;
};

// The buffer on show drawn for the window: row 0 at the bottom; canvas pixel (x, y) with x < zoom * width and
// y < zoom * height shows image pixel (x / zoom, y / zoom), so the image keeps its place whatever the buffer.
struct ViewerCanvas
{
  ImageU8 rgb;
  int zoom = 1;
  glm::ivec2 imageSize{ 0 };
};

class ViewerSession
{
public:
  // Validates the technique, its settings and the scene; renders nothing. Throws InputError.
  explicit ViewerSession(const ViewerStart& start);
  ~ViewerSession();
  ViewerSession(const ViewerSession&) = delete;
  ViewerSession& operator=(const ViewerSession&) = delete;

  // Called before the pipeline's context is made current (see the file comment). Unset: nothing to release.
  void setReleaseWindowContext(std::function<void()> release) { releaseWindowContext_ = std::move(release); }

  // Creates the pipeline and renders the first frame. Throws InputError, GraphicsError.
  void renderFirstFrame();

  // The keys' actions. Each returns what happened in one line; InputError when the change cannot be rendered
  // (the session is then as it was).
  std::string cycleTechnique(int step);  // registry order, skipping techniques that cannot render this light
  std::string cycleBuffer(int step);     // image, visibility, then the technique's buffers
  std::string selectParameter(int step); // the technique's parameters, in its table's order (no file parameters)
  std::string stepParameter(int step);   // one step of the selected parameter (stepOf), clamped to its range
  std::string stepLightSize(int step);   // times or divided by kLightSizeFactor (area lights)
  std::string resetParameters();         // the technique's defaults (and --set) and the scene's light size
  std::string probeAt(glm::ivec2 pixel); // probePixel + probeFigure; InputError for a pixel it cannot probe
  std::string clearProbe();

  const ViewerCanvas& canvas() const { return canvas_; }
  // The canvas of every buffer of the current frame: the window sizes its image panel to hold the largest.
  std::vector<glm::ivec2> canvasSizesOfAllBuffers() const;
  // The image pixel a canvas pixel shows, or nullopt (key, title band).
  std::optional<glm::ivec2> imagePixelAt(glm::ivec2 canvasPixel) const;
  const ImageU8* probeFigureImage() const { return probeFigure_.empty() ? nullptr : &probeFigure_; }

  const std::string& technique() const;
  const std::string& buffer() const { return buffer_; }
  const Scene& scene() const { return scene_; } // with the session's light size
  // Status lines: technique, buffer, selected parameter and light size, probe.
  std::vector<std::string> statusLines() const;
  // The `shadowlab render` command that renders the frame on show.
  std::string renderCommand() const;

  static constexpr double kLightSizeFactor = 1.25;

private:
  struct Settings
  {
    std::size_t techniqueIndex = 0;
    std::map<std::string, ParameterValues> parameters; // by technique, created on first visit
    std::optional<double> lightSize;                   // override of the scene's light size
  };

  ParameterValues& parametersOf(Settings& settings, std::size_t techniqueIndex) const;
  std::vector<std::string> settingsOf(const ParameterValues& values) const; // key=value, the non-default ones
  std::vector<std::string> sceneOverridesOf(const Settings& settings) const;
  std::vector<const ParameterSpec*> adjustableParameters() const;
  std::vector<std::string> bufferNames() const;
  // Renders `next` (loads its scene, renders, re-probes); the session takes it only when that succeeds.
  void renderSettings(const Settings& next);
  void rebuildCanvas();
  ViewerCanvas drawBuffer(const std::string& name) const;
  std::string parameterText(const ParameterSpec& spec, const ParameterValues& values) const;
  // Replays probedPixel_ on the current frame; returns what it found.
  std::string reprobe();

  ViewerStart start_;
  ParameterValues startParameters_; // the defaults with --set, for resetParameters()
  std::size_t startTechniqueIndex_ = 0;
  std::function<void()> releaseWindowContext_;
  std::unique_ptr<ShadowRenderer> renderer_;
  Settings settings_;
  std::map<std::string, std::size_t> selectedParameter_; // by technique
  Scene scene_;
  FrameResult frame_;
  int zoom_ = 1;
  std::string buffer_ = "image";
  ViewerCanvas canvas_;
  std::optional<glm::ivec2> probedPixel_;
  std::optional<ProbeResult> probe_;
  ImageU8 probeFigure_;
  std::string probeStatus_;
};

} // namespace sl
