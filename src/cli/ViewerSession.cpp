#include "cli/ViewerSession.h"

#include "cli/Commands.h"
#include "core/Error.h"
#include "pipeline/ShadowRenderer.h"
#include "vis/NumberText.h"
#include "probe/ProbeFigure.h"
#include "techniques/Registry.h"
#include "vis/BufferHeatMap.h"
#include "vis/Canvas.h"
#include "vis/HeatMap.h"

#include <EGL/egl.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace sl
{
namespace
{

// The image is drawn `zoom` canvas pixels per image pixel, so that a small frame is still big enough to click
// on: the largest integer zoom that keeps the image within this many pixels per side (at least 1).
constexpr int kTargetImageSidePx = 256;

// Numbers as the user would type them back (--set, --scene-set): up to 12 significant digits, no trailing zeros.
std::string numberText(double value)
{
  std::ostringstream text;
  text << std::setprecision(12) << value;
  return text.str();
}

std::size_t techniqueIndexOf(const std::string& name)
{
  const std::vector<TechniqueDescriptor>& registry = techniqueRegistry();
  const TechniqueDescriptor& technique = findTechnique(name); // InputError listing the techniques
  return static_cast<std::size_t>(&technique - registry.data());
}

// A step of 1, 2 or 5 times a power of ten: the largest such at most `span` / 20 (a real parameter's step).
double niceStep(double span)
{
  const double rough = span / 20.0;
  const double decade = std::pow(10.0, std::floor(std::log10(rough)));
  for (const double factor : { 5.0, 2.0, 1.0 })
  {
    if (factor * decade <= rough)
    {
      return factor * decade;
    }
  }
  return decade;
}

// One step of a parameter from `value`, within its range: an enumeration's next choice (wrapping), an integer
// +/- 1, or doubled / halved when its range spans more than 64 (shadow-map sizes, tap budgets), a real value to
// the next multiple of niceStep(range).
double steppedValue(const ParameterSpec& spec, double value, int step)
{
  if (!spec.choices.empty())
  {
    const int count = static_cast<int>(spec.choices.size());
    return static_cast<double>(((static_cast<int>(std::lround(value)) + step) % count + count) % count);
  }
  double next = value;
  if (spec.integer)
  {
    if (spec.maxValue - spec.minValue <= 64.0)
    {
      next = value + step;
    }
    else
    {
      next = step > 0 ? std::max(value + 1.0, std::round(value * 2.0)) : std::round(value / 2.0);
    }
  }
  else
  {
    const double stepSize = niceStep(spec.maxValue - spec.minValue);
    // The next multiple of the step (a value between multiples goes to the nearer one in the step's direction).
    const double steps = value / stepSize;
    next = step > 0 ? (std::floor(steps + 1e-9) + 1.0) * stepSize : (std::ceil(steps - 1e-9) - 1.0) * stepSize;
  }
  return std::clamp(next, spec.minValue, spec.maxValue);
}

// Nearest-neighbour enlargement by an integer factor: each pixel becomes a zoom x zoom block.
template <typename T>
Image<T> enlarged(const Image<T>& image, int zoom)
{
  Image<T> result(image.width * zoom, image.height * zoom, image.components);
  for (int y = 0; y < result.height; ++y)
  {
    for (int x = 0; x < result.width; ++x)
    {
      for (int c = 0; c < image.components; ++c)
      {
        result.at(x, y, c) = image.at(x / zoom, y / zoom, c);
      }
    }
  }
  return result;
}

// Releases whatever EGL context is current on this thread (the pipeline's): the X window's GLX context can then
// be made current (see ViewerSession.h).
void releaseEglContext()
{
  const EGLDisplay display = eglGetCurrentDisplay();
  if (display != EGL_NO_DISPLAY)
  {
    eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  }
}

} // namespace

ViewerSession::ViewerSession(const ViewerStart& start)
  : start_(start)
{
  startTechniqueIndex_ = techniqueIndexOf(start.technique);
  checkSettings(techniqueRegistry()[startTechniqueIndex_], start.settings);
  startParameters_ = techniqueRegistry()[startTechniqueIndex_].defaultParameters();
  for (const std::string& assignment : start.settings)
  {
    startParameters_.set(assignment);
  }
  scene_ = loadScene(start.sceneFile, start.sceneOverrides);
  if (start.lightIndex < 0 || start.lightIndex >= static_cast<int>(scene_.lights.size()))
  {
    throw InputError(format("--light ", start.lightIndex, ": the scene has ", scene_.lights.size(), " light(s)"));
  }
  settings_.techniqueIndex = startTechniqueIndex_;
  settings_.parameters.emplace(techniqueRegistry()[startTechniqueIndex_].name, startParameters_);
  const glm::ivec2 size = start.resolution ? *start.resolution : scene_.camera.resolution;
  zoom_ = std::max(1, kTargetImageSidePx / std::max(size.x, size.y));
}

ViewerSession::~ViewerSession()
{
  if (renderer_)
  {
    // The pipeline frees its GL objects in its own context.
    if (releaseWindowContext_)
    {
      releaseWindowContext_();
    }
    try
    {
      renderer_->window()->MakeCurrent();
    }
    catch (const GraphicsError&)
    {
      // Nothing to free the GL objects in: the process is ending with the pipeline's context gone.
    }
    renderer_.reset();
    releaseEglContext();
  }
}

const std::string& ViewerSession::technique() const
{
  return techniqueRegistry()[settings_.techniqueIndex].name;
}

ParameterValues& ViewerSession::parametersOf(Settings& settings, std::size_t techniqueIndex) const
{
  const TechniqueDescriptor& descriptor = techniqueRegistry()[techniqueIndex];
  auto found = settings.parameters.find(descriptor.name);
  if (found == settings.parameters.end())
  {
    found = settings.parameters.emplace(descriptor.name, descriptor.defaultParameters()).first;
  }
  return found->second;
}

std::vector<std::string> ViewerSession::settingsOf(const ParameterValues& values) const
{
  std::vector<std::string> assignments;
  for (const ParameterSpec& spec : values.specs())
  {
    if (spec.file)
    {
      if (!values.file(spec.name).empty())
      {
        assignments.push_back(spec.name + "=" + values.file(spec.name));
      }
      continue;
    }
    if (values.get(spec.name) == spec.defaultValue)
    {
      continue;
    }
    assignments.push_back(spec.name + "=" +
      (values.automatic(spec.name) ? spec.automatic
          : spec.choices.empty()   ? numberText(values.get(spec.name))
                                   : values.choice(spec.name)));
  }
  return assignments;
}

std::vector<std::string> ViewerSession::sceneOverridesOf(const Settings& settings) const
{
  std::vector<std::string> overrides = start_.sceneOverrides;
  if (settings.lightSize)
  {
    overrides.push_back(format("/lights/", start_.lightIndex, "/size=", numberText(*settings.lightSize)));
  }
  return overrides;
}

std::vector<const ParameterSpec*> ViewerSession::adjustableParameters() const
{
  std::vector<const ParameterSpec*> specs;
  for (const ParameterSpec& spec : techniqueRegistry()[settings_.techniqueIndex].parameters)
  {
    if (!spec.file)
    {
      specs.push_back(&spec);
    }
  }
  return specs;
}

std::vector<std::string> ViewerSession::bufferNames() const
{
  std::vector<std::string> names = { "image", "visibility" };
  for (const BufferSpec& spec : frame_.descriptor->buffers)
  {
    const NamedImage* buffer = frame_.find(spec.name);
    if (buffer && buffer->image.components == 1)
    {
      names.push_back(spec.name);
    }
  }
  return names;
}

void ViewerSession::renderFirstFrame()
{
  SL_CHECK(!renderer_);
  if (releaseWindowContext_)
  {
    releaseWindowContext_();
  }
  struct ReleaseOnExit
  {
    ~ReleaseOnExit() { releaseEglContext(); }
  } release;
  renderer_ = std::make_unique<ShadowRenderer>();
  RenderRequest request;
  request.technique = technique();
  request.settings = settingsOf(startParameters_);
  request.resolution = start_.resolution;
  request.lightIndex = start_.lightIndex;
  frame_ = renderer_->render(scene_, request);
  rebuildCanvas();
}

void ViewerSession::renderSettings(const Settings& next)
{
  SL_CHECK(renderer_);
  Settings candidate = next;
  const TechniqueDescriptor& descriptor = techniqueRegistry()[candidate.techniqueIndex];
  Scene scene = loadScene(start_.sceneFile, sceneOverridesOf(candidate));
  RenderRequest request;
  request.technique = descriptor.name;
  request.settings = settingsOf(parametersOf(candidate, candidate.techniqueIndex));
  request.resolution = start_.resolution;
  request.lightIndex = start_.lightIndex;
  if (releaseWindowContext_)
  {
    releaseWindowContext_();
  }
  struct ReleaseOnExit
  {
    ~ReleaseOnExit() { releaseEglContext(); }
  } release;
  renderer_->window()->MakeCurrent();
  FrameResult frame = renderer_->render(scene, request);
  // Taken: from here on nothing throws an InputError for this change.
  settings_ = std::move(candidate);
  scene_ = std::move(scene);
  frame_ = std::move(frame);
  const std::vector<std::string> names = bufferNames();
  if (std::find(names.begin(), names.end(), buffer_) == names.end())
  {
    buffer_ = "visibility";
  }
  reprobe();
  rebuildCanvas();
}

std::string ViewerSession::cycleTechnique(int step)
{
  const std::vector<TechniqueDescriptor>& registry = techniqueRegistry();
  const Light& light = scene_.lights[static_cast<std::size_t>(start_.lightIndex)];
  const std::size_t count = registry.size();
  std::size_t index = settings_.techniqueIndex;
  // Techniques that cannot render this frame are passed over (and named), so that one of them never blocks the
  // way round the registry.
  std::string skipped;
  for (std::size_t tried = 1; tried < count; ++tried)
  {
    index = (index + (step > 0 ? 1 : count - 1)) % count;
    std::string why = "cannot render this light";
    if (registry[index].supports(light))
    {
      Settings next = settings_;
      next.techniqueIndex = index;
      try
      {
        renderSettings(next);
        return "technique " + registry[index].name + " (" + registry[index].title + ")" +
          (skipped.empty() ? std::string() : "; passed over " + skipped);
      }
      catch (const InputError& error)
      {
        why = error.what();
      }
    }
    skipped += (skipped.empty() ? "" : ", ") + registry[index].name + " (" + why + ")";
  }
  return "technique " + technique() + ": no other technique renders this frame; passed over " + skipped;
}

std::string ViewerSession::cycleBuffer(int step)
{
  const std::vector<std::string> names = bufferNames();
  const auto found = std::find(names.begin(), names.end(), buffer_);
  const int count = static_cast<int>(names.size());
  const int current = found == names.end() ? 0 : static_cast<int>(found - names.begin());
  buffer_ = names[static_cast<std::size_t>(((current + step) % count + count) % count)];
  rebuildCanvas();
  const NamedImage* buffer = frame_.find(buffer_);
  return "buffer " + buffer_ + (buffer && !buffer->unit.empty() ? " [" + buffer->unit + "]" : "");
}

std::string ViewerSession::selectParameter(int step)
{
  const std::vector<const ParameterSpec*> specs = adjustableParameters();
  if (specs.empty())
  {
    return "parameter: " + technique() + " has none";
  }
  const int count = static_cast<int>(specs.size());
  std::size_t& selected = selectedParameter_[technique()];
  selected = static_cast<std::size_t>(((static_cast<int>(selected) + step) % count + count) % count);
  Settings current = settings_;
  return "parameter " + parameterText(*specs[selected], parametersOf(current, current.techniqueIndex));
}

std::string ViewerSession::stepParameter(int step)
{
  const std::vector<const ParameterSpec*> specs = adjustableParameters();
  if (specs.empty())
  {
    return "parameter: " + technique() + " has none";
  }
  const ParameterSpec& spec = *specs[std::min(selectedParameter_[technique()], specs.size() - 1)];
  Settings next = settings_;
  ParameterValues& values = parametersOf(next, next.techniqueIndex);
  // From `auto`, a step goes from the size the frame chose (shadow_map_size = auto) to an explicit one.
  const bool automatic = values.automatic(spec.name);
  const double from = automatic && frame_.lightView ? frame_.lightView->resolution : values.get(spec.name);
  const double value = steppedValue(spec, from, step);
  if (value == values.get(spec.name))
  {
    return "parameter " + parameterText(spec, values) + " (at the end of its range)";
  }
  values.set(spec.name, value);
  renderSettings(next);
  return "parameter " + parameterText(spec, values);
}

std::string ViewerSession::stepLightSize(int step)
{
  const Light& light = scene_.lights[static_cast<std::size_t>(start_.lightIndex)];
  if (light.type != LightType::Area)
  {
    return format("light size: light ", start_.lightIndex, " is not an area light (it has no size)");
  }
  Settings next = settings_;
  next.lightSize = light.size * std::pow(kLightSizeFactor, step);
  renderSettings(next);
  return "light size " + readableNumber(scene_.lights[static_cast<std::size_t>(start_.lightIndex)].size);
}

std::string ViewerSession::resetParameters()
{
  Settings next = settings_;
  const TechniqueDescriptor& descriptor = techniqueRegistry()[next.techniqueIndex];
  next.parameters[descriptor.name] =
    next.techniqueIndex == startTechniqueIndex_ ? startParameters_ : descriptor.defaultParameters();
  next.lightSize.reset();
  renderSettings(next);
  return "reset " + technique() + "'s parameters and the light size";
}

std::string ViewerSession::probeAt(glm::ivec2 pixel)
{
  probedPixel_ = pixel;
  const std::string found = reprobe();
  rebuildCanvas();
  return found;
}

std::string ViewerSession::clearProbe()
{
  probedPixel_.reset();
  probe_.reset();
  probeFigure_ = ImageU8();
  probeStatus_.clear();
  rebuildCanvas();
  return "probe cleared";
}

std::string ViewerSession::reprobe()
{
  probe_.reset();
  probeFigure_ = ImageU8();
  if (!probedPixel_)
  {
    probeStatus_.clear();
    return probeStatus_;
  }
  const std::string where = format("probe (", probedPixel_->x, ", ", probedPixel_->y, ") ", technique());
  try
  {
    probe_ = probePixel(frame_, scene_, start_.lightIndex, *probedPixel_);
    probeFigure_ = probeFigure(*probe_, frame_, scene_);
  }
  catch (const InputError& error)
  {
    // A background pixel, a technique without a probe: the marker stays, the status says why.
    probe_.reset();
    probeFigure_ = ImageU8();
    probeStatus_ = where + ": " + error.what();
    return probeStatus_;
  }
  std::ostringstream text;
  text << std::setprecision(4) << where << ": GPU visibility " << probe_->gpuVisibility << ", twin "
       << probe_->outcome.visibility;
  if (!probe_->outcome.ambiguity.empty())
  {
    text << " (ambiguous: " << probe_->outcome.ambiguity << ")";
  }
  else
  {
    text << (probe_->agrees() ? " (agree" : " (DIFFER") << " within " << probe_->outcome.tolerance << ")";
  }
  probeStatus_ = text.str();
  return probeStatus_;
}

ViewerCanvas ViewerSession::drawBuffer(const std::string& name) const
{
  ViewerCanvas canvas;
  canvas.zoom = zoom_;
  canvas.imageSize = frame_.resolution;
  if (name == "image")
  {
    canvas.rgb = enlarged(frame_.image, zoom_);
    return canvas;
  }
  const NamedImage* buffer = frame_.find(name);
  const NamedImage* coverage = frame_.find("coverage");
  SL_CHECK(buffer && coverage);
  // As the heat map PNGs: grey where the buffer has no value (not covered, or not shadow-tested for a quantity defined
  // only there), a bit mask as its count of set bits.
  const ImageU8 mask = bufferValueMask(*buffer, frame_.buffers);
  // The colour scale comes from the frame's own pixels (the enlarged copy repeats each zoom^2 times).
  const HeatMapOptions options = bufferHeatMapOptions(*buffer, &mask);
  const ImageU8 enlargedMask = enlarged(mask, zoom_);
  canvas.rgb = renderHeatMap(enlarged(heatMapValues(*buffer), zoom_), &enlargedMask, options);
  return canvas;
}

void ViewerSession::rebuildCanvas()
{
  canvas_ = drawBuffer(buffer_);
  if (probedPixel_)
  {
    // A ring two pixels out from the probed pixel's block, in the probe figure's marker colour.
    const int z = canvas_.zoom;
    strokeRect(canvas_.rgb, probedPixel_->x * z - 3, probedPixel_->y * z - 3, z + 6, z + 6, kProbeMarkerColor, 2);
  }
}

std::vector<glm::ivec2> ViewerSession::canvasSizesOfAllBuffers() const
{
  std::vector<glm::ivec2> sizes;
  for (const std::string& name : bufferNames())
  {
    const ViewerCanvas canvas = drawBuffer(name);
    sizes.emplace_back(canvas.rgb.width, canvas.rgb.height);
  }
  return sizes;
}

std::optional<glm::ivec2> ViewerSession::imagePixelAt(glm::ivec2 canvasPixel) const
{
  if (canvasPixel.x < 0 || canvasPixel.y < 0)
  {
    return std::nullopt;
  }
  const glm::ivec2 pixel = canvasPixel / canvas_.zoom;
  if (pixel.x >= canvas_.imageSize.x || pixel.y >= canvas_.imageSize.y)
  {
    return std::nullopt;
  }
  return pixel;
}

std::string ViewerSession::parameterText(const ParameterSpec& spec, const ParameterValues& values) const
{
  if (!spec.choices.empty())
  {
    std::string choices;
    for (const std::string& choice : spec.choices)
    {
      choices += (choices.empty() ? "" : "|") + choice;
    }
    return spec.name + " = " + values.choice(spec.name) + " (" + choices + ")";
  }
  if (values.automatic(spec.name))
  {
    const std::string chosen = frame_.lightView ? format(", now ", frame_.lightView->resolution) : std::string();
    return spec.name + " = " + spec.automatic + chosen + (spec.unit.empty() ? "" : " " + spec.unit) + " (" +
      readableNumber(spec.minValue) + " .. " + readableNumber(spec.maxValue) + " or " + spec.automatic + ")";
  }
  // Rounded as a person reads them (1.17, not 1.171875); the render command keeps every digit (renderCommand).
  return spec.name + " = " + readableNumber(values.get(spec.name)) + (spec.unit.empty() ? "" : " " + spec.unit) + " (" +
    readableNumber(spec.minValue) + " .. " + readableNumber(spec.maxValue) + ")";
}

std::vector<std::string> ViewerSession::statusLines() const
{
  const std::vector<TechniqueDescriptor>& registry = techniqueRegistry();
  const TechniqueDescriptor& descriptor = registry[settings_.techniqueIndex];
  std::vector<std::string> lines;
  lines.push_back(format("technique  ", descriptor.name, " (", settings_.techniqueIndex + 1, "/", registry.size(),
    "): ", descriptor.title));
  const std::vector<std::string> names = bufferNames();
  const auto position = std::find(names.begin(), names.end(), buffer_) - names.begin() + 1;
  const NamedImage* buffer = frame_.find(buffer_);
  lines.push_back(format("buffer     ", buffer_ == "image" ? "image (shaded)" : buffer_,
    buffer && !buffer->unit.empty() ? " [" + buffer->unit + "]" : std::string(), " (", position, "/", names.size(),
    ")"));
  const std::vector<const ParameterSpec*> specs = adjustableParameters();
  std::string parameter = "none";
  if (!specs.empty())
  {
    const auto selected = selectedParameter_.find(descriptor.name);
    const std::size_t index = selected == selectedParameter_.end() ? 0 : std::min(selected->second, specs.size() - 1);
    Settings current = settings_;
    parameter = parameterText(*specs[index], parametersOf(current, current.techniqueIndex));
  }
  const Light& light = scene_.lights[static_cast<std::size_t>(start_.lightIndex)];
  lines.push_back("parameter  " + parameter + "   light size " +
    (light.type == LightType::Area ? readableNumber(light.size) : std::string("-")));
  lines.push_back(probeStatus_.empty() ? "click a pixel to probe it; h: keys" : probeStatus_);
  return lines;
}

std::string ViewerSession::renderCommand() const
{
  // Words the shell would split or expand are single-quoted.
  const auto quoted = [](const std::string& word) {
    static const char* const plain = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-+=.,/:@%";
    if (!word.empty() && word.find_first_not_of(plain) == std::string::npos)
    {
      return word;
    }
    std::string text = "'";
    for (const char c : word)
    {
      text += c == '\'' ? std::string("'\\''") : std::string(1, c);
    }
    return text + "'";
  };
  std::string command = "shadowlab render " + quoted(start_.sceneFile) + " -t " + technique();
  Settings current = settings_;
  for (const std::string& assignment : settingsOf(parametersOf(current, current.techniqueIndex)))
  {
    command += " --set " + quoted(assignment);
  }
  for (const std::string& assignment : sceneOverridesOf(settings_))
  {
    command += " --scene-set " + quoted(assignment);
  }
  if (start_.resolution)
  {
    command += format(" --resolution ", start_.resolution->x, "x", start_.resolution->y);
  }
  if (start_.lightIndex != 0)
  {
    command += format(" --light ", start_.lightIndex);
  }
  return printable(command);
}

} // namespace sl
