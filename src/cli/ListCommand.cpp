// shadowlab list: every technique in the registry with its parameters (default, range, unit), its
// light-space structures and the buffers it publishes; --json for tools.
#include "cli/Commands.h"

#include "lightspace/LightSpaceStructure.h"
#include "techniques/Registry.h"

#include <nlohmann/json.hpp>

#include <iomanip>
#include <sstream>

namespace sl
{
namespace
{

std::string describeRange(const ParameterSpec& spec)
{
  if (spec.file)
  {
    return "file path";
  }
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
  if (spec.file)
  {
    return "(none)";
  }
  if (!spec.choices.empty())
  {
    return spec.choices.at(static_cast<std::size_t>(spec.defaultValue));
  }
  std::ostringstream value;
  value << spec.defaultValue;
  return value.str();
}

void listAsJson(std::ostream& out)
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
        { "integer", spec.integer }, { "file", spec.file }, { "doc", spec.doc } });
    }
    nlohmann::json buffers = nlohmann::json::array();
    for (const BufferSpec& buffer : technique.buffers)
    {
      buffers.push_back({ { "name", buffer.name }, { "unit", buffer.unit }, { "doc", buffer.doc } });
    }
    nlohmann::json structures = nlohmann::json::array();
    for (const LightSpaceStructure* structure : technique.lightStructures)
    {
      structures.push_back(structure->name);
    }
    techniques.push_back({ { "name", technique.name }, { "title", technique.title }, { "paper", technique.paper },
      { "parameters", parameters }, { "buffers", buffers }, { "light_structures", structures } });
  }
  out << techniques.dump(2) << "\n";
}

void listAsText(std::ostream& out)
{
  for (const TechniqueDescriptor& technique : techniqueRegistry())
  {
    out << technique.name << " - " << technique.title << " (" << technique.paper << ")\n";
    std::string structures;
    for (const LightSpaceStructure* structure : technique.lightStructures)
    {
      structures += (structures.empty() ? "" : ", ") + structure->name;
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
}

} // namespace

int runList(bool asJson, std::ostream& out)
{
  if (asJson)
  {
    listAsJson(out);
  }
  else
  {
    listAsText(out);
  }
  return 0;
}

} // namespace sl
