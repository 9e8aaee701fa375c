// Helpers the shadowlab commands share: the --resolution and --set checks, the dropped-triangle warning,
// the files a scene reads.
#include "cli/Commands.h"

#include "core/Error.h"
#include "core/Image.h"
#include "frame/Approximations.h"
#include "frame/FrameResult.h"
#include "pipeline/ShadowRenderer.h"
#include "scene/Scene.h"
#include "techniques/Registry.h"

#include <algorithm>
#include <iomanip>
#include <map>
#include <regex>
#include <set>

namespace sl
{
RenderRequest checkedRenderRequest(const std::string& technique, const std::vector<std::string>& settings,
  int lightIndex, const std::string& resolution)
{
  RenderRequest request;
  request.technique = technique;
  request.settings = settings;
  request.lightIndex = lightIndex;
  if (!resolution.empty())
  {
    request.resolution = parseResolution(resolution);
  }
  checkSettings(findTechnique(technique), settings);
  return request;
}

CheckedFrameCommand checkFrameCommand(const FrameCommandOptions& options, const std::string& command)
{
  RenderRequest request =
    checkedRenderRequest(options.technique, options.settings, options.lightIndex, options.resolution);
  checkSceneOverrides(options.sceneOverrides);
  Scene scene = loadScene(options.sceneFile, options.sceneOverrides);
  std::vector<std::filesystem::path> inputs = sceneInputs(scene, options.sceneFile);
  const std::vector<std::filesystem::path> parameterFiles =
    fileParameterInputs(findTechnique(options.technique), options.settings);
  inputs.insert(inputs.end(), parameterFiles.begin(), parameterFiles.end());
  OutputTarget output{ options.outDir, command, options.force, inputs };
  checkOutputTarget(output);
  return { std::move(request), std::move(scene), std::move(output) };
}

glm::ivec2 parseResolution(const std::string& text)
{
  static const std::regex pattern(R"((\d{1,6})x(\d{1,6}))");
  std::smatch match;
  if (!std::regex_match(text, match, pattern))
  {
    throw InputError("--resolution " + text + ": expected WxH, e.g. 512x512");
  }
  const glm::ivec2 size{ std::stoi(match[1]), std::stoi(match[2]) };
  if (size.x < 1 || size.y < 1 || size.x > kMaxImageSide || size.y > kMaxImageSide)
  {
    throw InputError(format("--resolution ", text, ": each side must be in 1 .. ", kMaxImageSide));
  }
  return size;
}

void checkSettings(const TechniqueDescriptor& technique, const std::vector<std::string>& settings)
{
  ParameterValues check = technique.defaultParameters();
  std::set<std::string> keys;
  for (const std::string& assignment : settings)
  {
    check.set(assignment);
    const std::string key = assignment.substr(0, assignment.find('='));
    if (!keys.insert(key).second)
    {
      throw InputError("--set " + assignment + ": " + key + " is given more than once");
    }
  }
}

void checkSceneOverrides(const std::vector<std::string>& overrides, const std::vector<std::string>& sweeps)
{
  std::map<std::string, std::string> given; // pointer -> the option that gave it
  const auto check = [&given](const std::string& option, const std::string& text) {
    const std::string pointer = text.substr(0, text.find('='));
    const auto [at, inserted] = given.emplace(pointer, option);
    if (!inserted)
    {
      throw InputError(format(option, " ", text, ": ", pointer, at->second == option
        ? " is given more than once" : " is also given by " + at->second));
    }
  };
  for (const std::string& override : overrides)
  {
    check("--scene-set", override);
  }
  for (const std::string& sweep : sweeps)
  {
    check("--scene-sweep", sweep);
  }
}

std::size_t reportDroppedTriangles(const Scene& scene, const std::string& sceneFile, std::ostream& log)
{
  std::size_t dropped = 0;
  for (const SceneObject& object : scene.objects)
  {
    if (object.droppedDegenerateTriangles > 0)
    {
      log << "shadowlab: warning: " << printable(sceneFile) << ": " << printable(object.name) << ": dropped "
          << object.droppedDegenerateTriangles << " degenerate triangle(s)\n";
      dropped += object.droppedDegenerateTriangles;
    }
  }
  return dropped;
}

std::size_t reportCutShortPixels(const FrameResult& frame, std::ostream& log)
{
  const std::optional<CutShortPixels> cutShort = cutShortPixels(frame);
  if (!cutShort || cutShort->count == 0)
  {
    return 0;
  }
  const double percent = 100.0 * static_cast<double>(cutShort->count) /
    static_cast<double>(std::max(1, frame.resolution.x * frame.resolution.y));
  log << "shadowlab: warning: " << frame.technique << ": " << cutShort->count << " pixel(s) (" << std::fixed
      << std::setprecision(2) << percent << std::defaultfloat << " % of the image) were cut short and are not exact ("
      << cutShort->buffer << " = " << cutShort->label << "; counted as cut_short_pixels in stats.json)\n";
  return cutShort->count;
}

std::size_t reportFlaggedPixels(const FrameResult& frame, std::ostream& log)
{
  std::size_t total = 0;
  for (const FlaggedPixels& flagged : flaggedPixels(frame))
  {
    if (flagged.count == 0)
    {
      continue;
    }
    const double percent = 100.0 * static_cast<double>(flagged.count) /
      static_cast<double>(std::max(1, frame.resolution.x * frame.resolution.y));
    log << "shadowlab: warning: " << frame.technique << ": " << flagged.count << " pixel(s) (" << std::fixed
        << std::setprecision(2) << percent << std::defaultfloat << " % of the image) have " << flagged.buffer
        << " >= " << flagged.threshold << ": " << flagged.warning << " (counted as " << flagged.buffer
        << "_flagged_pixels in stats.json)\n";
    total += flagged.count;
  }
  return total;
}

std::size_t reportApproximatePixels(const FrameResult& frame, std::ostream& log)
{
  const ApproximatePixels marked = approximatePixels(frame);
  if (marked.count == 0)
  {
    return 0;
  }
  log << "shadowlab: note: " << frame.technique << ": " << marked.count
      << " pixel(s) lie where the technique is approximate by design (";
  for (std::size_t index = 0; index < marked.byApproximation.size(); ++index)
  {
    log << (index ? ", " : "") << marked.byApproximation[index].first << " " << marked.byApproximation[index].second;
  }
  log << "; buffer approximation, counted as approximate_pixels in stats.json)\n";
  return marked.count;
}

std::vector<std::filesystem::path> sceneInputs(const Scene& scene, const std::string& sceneFile)
{
  std::vector<std::filesystem::path> inputs = scene.inputFiles;
  inputs.emplace_back(sceneFile);
  return inputs;
}

std::vector<std::filesystem::path> fileParameterInputs(const TechniqueDescriptor& technique,
  const std::vector<std::string>& settings)
{
  ParameterValues values = technique.defaultParameters();
  for (const std::string& assignment : settings)
  {
    values.set(assignment);
  }
  std::vector<std::filesystem::path> inputs;
  for (const ParameterSpec& spec : values.specs())
  {
    if (spec.file && !values.file(spec.name).empty())
    {
      inputs.emplace_back(values.file(spec.name));
    }
  }
  return inputs;
}

} // namespace sl
