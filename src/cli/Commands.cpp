#include "cli/Commands.h"

#include "core/Error.h"
#include "output/OutputWriter.h"
#include "pipeline/ShadowRenderer.h"
#include "scene/Scene.h"
#include "techniques/Registry.h"

#include <nlohmann/json.hpp>

#include <iomanip>
#include <regex>
#include <set>

namespace sl
{
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
  ParameterValues check(technique);
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

std::vector<std::filesystem::path> sceneInputs(const Scene& scene, const std::string& sceneFile)
{
  std::vector<std::filesystem::path> inputs = scene.inputFiles;
  inputs.emplace_back(sceneFile);
  return inputs;
}

namespace
{

std::string describeRange(const ParameterSpec& spec)
{
  if (!spec.choices.empty())
  {
    std::string choices;
    for (const std::string& choice : spec.choices)
    {
      choices += (choices.empty() ? "" : "|") + choice;
    }
    return choices;
  }
  std::ostringstream range;
  range << spec.minValue << " .. " << spec.maxValue;
  return range.str();
}

std::string describeDefault(const ParameterSpec& spec)
{
  if (!spec.choices.empty())
  {
    return spec.choices.at(static_cast<std::size_t>(spec.defaultValue));
  }
  std::ostringstream value;
  value << spec.defaultValue;
  return value.str();
}

} // namespace

int runRender(const RenderOptions& options, std::ostream& log)
{
  // Validate everything the user typed before touching the GPU or the disk.
  RenderRequest request;
  request.technique = options.technique;
  request.settings = options.settings;
  request.lightIndex = options.lightIndex;
  if (!options.resolution.empty())
  {
    request.resolution = parseResolution(options.resolution);
  }
  checkSettings(findTechnique(request.technique), request.settings);
  const Scene scene = loadScene(options.sceneFile, options.sceneOverrides);
  const OutputTarget output{ options.outDir, "render", options.force, sceneInputs(scene, options.sceneFile) };
  checkOutputTarget(output);
  const std::size_t dropped = reportDroppedTriangles(scene, options.sceneFile, log);
  ShadowRenderer renderer;
  const FrameResult frame = renderer.render(scene, request);
  OutputContext context;
  context.sceneFile = options.sceneFile;
  context.lightIndex = options.lightIndex;
  context.droppedDegenerateTriangles = dropped;
  writeFrameOutputs(frame, context, output);
  if (!options.quiet)
  {
    double gpuMs = 0.0;
    for (const StageTiming& stage : frame.stages)
    {
      gpuMs += stage.gpuMs;
    }
    log << "shadowlab: rendered " << printable(options.sceneFile) << " with " << frame.technique << " at " << frame.resolution.x
        << "x" << frame.resolution.y << " on " << frame.glRenderer << ": GPU " << std::fixed << std::setprecision(2)
        << gpuMs << " ms, frame " << frame.frameWallMs << " ms -> " << printable(options.outDir) << "\n";
  }
  return 0;
}

int runList(bool asJson, std::ostream& out)
{
  if (asJson)
  {
    nlohmann::json techniques = nlohmann::json::array();
    for (const TechniqueDescriptor& technique : techniqueRegistry())
    {
      nlohmann::json parameters = nlohmann::json::array();
      for (const ParameterSpec& spec : technique.parameters)
      {
        const nlohmann::json defaultValue =
          spec.choices.empty() ? nlohmann::json(spec.defaultValue) : nlohmann::json(describeDefault(spec));
        parameters.push_back({ { "name", spec.name }, { "default", defaultValue },
          { "min", spec.minValue }, { "max", spec.maxValue }, { "unit", spec.unit }, { "choices", spec.choices },
          { "integer", spec.integer }, { "doc", spec.doc } });
      }
      nlohmann::json buffers = nlohmann::json::array();
      for (const BufferSpec& buffer : technique.buffers)
      {
        buffers.push_back({ { "name", buffer.name }, { "unit", buffer.unit }, { "doc", buffer.doc } });
      }
      nlohmann::json structures = nlohmann::json::array();
      for (LightStructure structure : technique.lightStructures)
      {
        structures.push_back(lightStructureName(structure));
      }
      techniques.push_back({ { "name", technique.name }, { "title", technique.title }, { "paper", technique.paper },
        { "parameters", parameters }, { "buffers", buffers }, { "light_structures", structures } });
    }
    out << techniques.dump(2) << "\n";
    return 0;
  }
  for (const TechniqueDescriptor& technique : techniqueRegistry())
  {
    out << technique.name << " - " << technique.title << " (" << technique.paper << ")\n";
    std::string structures;
    for (LightStructure structure : technique.lightStructures)
    {
      structures += (structures.empty() ? "" : ", ") + lightStructureName(structure);
    }
    out << "  light-space structures: " << (structures.empty() ? "none" : structures) << "\n";
    out << "  parameters:\n";
    for (const ParameterSpec& spec : technique.parameters)
    {
      out << "    " << std::left << std::setw(22) << spec.name << " default " << std::setw(8) << describeDefault(spec)
          << " range " << std::setw(22) << describeRange(spec) << " " << spec.unit << "\n"
          << "      " << spec.doc << "\n";
    }
    out << "  buffers: visibility, position, normal, depth, coverage, albedo";
    for (const BufferSpec& buffer : technique.buffers)
    {
      out << ", " << buffer.name;
    }
    out << "\n\n";
  }
  return 0;
}

} // namespace sl
