// shadowlab list [TECHNIQUE...]: every technique in the registry (or only those named) with its parameters (default,
// range, unit), its light-space structures and the buffers it publishes; --json for tools; --structures lists the
// light-space structures instead, each with the techniques that use it.
#include "cli/Commands.h"

#include "core/Error.h"
#include "structures/LightSpaceStructure.h"
#include "structures/hsm/HsmStructure.h"
#include "structures/mssm/DualMssmStructure.h"
#include "techniques/Registry.h"

#include <nlohmann/json.hpp>

#include <algorithm>
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
  if (!spec.automatic.empty())
  {
    range << " or " << spec.automatic;
  }
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
  if (isAutomaticValue(spec, spec.defaultValue))
  {
    return spec.automatic;
  }
  std::ostringstream value;
  value << spec.defaultValue;
  return value.str();
}

// A bound `list` cannot print as a number: it depends on the GL a frame runs on, and knowing it would mean
// making a GL context (seconds on llvmpipe) for a command that only reads the registry. Said where it applies:
// the shadow map's size for techniques whose min-max structure may be a 3D texture (N-buffers, the dual-grid
// MSSM), which vtkSLHsmPass checks against GL_MAX_3D_TEXTURE_SIZE when the frame renders.
std::string glLimitNote(const TechniqueDescriptor& technique, const ParameterSpec& spec)
{
  const bool threeDimensional = std::any_of(technique.lightStructures.begin(), technique.lightStructures.end(),
    [](const LightSpaceStructure* structure) {
      return structure == &hierarchicalShadowMapStructure() || structure == &dualMssmStructure();
    });
  if (spec.name != "shadow_map_size" || !threeDimensional)
  {
    return {};
  }
  return "with an N-buffer or dual-grid MSSM (a 3D texture) at most the GL's GL_MAX_3D_TEXTURE_SIZE (2048 on "
         "llvmpipe), less 1 for the dual grid; a larger map is refused when the frame renders";
}

using TechniqueSelection = std::vector<const TechniqueDescriptor*>;

// The techniques `list` prints: those named (each argument a name or a comma list; registry order, each once), or
// all. An unknown name is one error line listing the valid names.
TechniqueSelection selectedTechniques(const std::vector<std::string>& arguments)
{
  std::vector<std::string> names;
  for (const std::string& argument : arguments)
  {
    std::stringstream items(argument);
    for (std::string name; std::getline(items, name, ',');)
    {
      if (name.empty())
      {
        throw InputError("list " + printable(argument) + ": an empty name in the comma-separated list");
      }
      names.push_back(name);
    }
  }
  TechniqueSelection selection;
  for (const TechniqueDescriptor& technique : techniqueRegistry())
  {
    if (names.empty() || std::find(names.begin(), names.end(), technique.name) != names.end())
    {
      selection.push_back(&technique);
    }
  }
  for (const std::string& name : names)
  {
    if (std::none_of(selection.begin(), selection.end(),
          [&name](const TechniqueDescriptor* technique) { return technique->name == name; }))
    {
      std::string valid;
      for (const TechniqueDescriptor& technique : techniqueRegistry())
      {
        valid += (valid.empty() ? "" : ", ") + technique.name;
      }
      throw InputError("list " + printable(name) + ": unknown technique (valid: " + valid + ")");
    }
  }
  return selection;
}

// The techniques of `selection` whose light-space structures include `structure`, by name.
std::vector<std::string> techniquesUsing(const LightSpaceStructure& structure, const TechniqueSelection& selection)
{
  std::vector<std::string> names;
  for (const TechniqueDescriptor* technique : selection)
  {
    const auto& used = technique->lightStructures;
    if (std::find(used.begin(), used.end(), &structure) != used.end())
    {
      names.push_back(technique->name);
    }
  }
  return names;
}

// --structures: every light-space structure (registry order) used by a technique of `selection`, or every one when
// no technique was named.
void listStructures(const TechniqueSelection& selection, bool named, bool asJson, std::ostream& out)
{
  nlohmann::json structures = nlohmann::json::array();
  for (const LightSpaceStructure* structure : lightSpaceStructureRegistry())
  {
    const std::vector<std::string> users = techniquesUsing(*structure, selection);
    if (named && users.empty())
    {
      continue;
    }
    std::vector<std::string> builtFrom;
    for (const LightSpaceStructure* source : structure->builtFrom)
    {
      builtFrom.push_back(source->name);
    }
    if (asJson)
    {
      structures.push_back({ { "name", structure->name }, { "doc", structure->doc }, { "built_from", builtFrom },
        { "techniques", users } });
      continue;
    }
    std::string usersText;
    for (const std::string& user : users)
    {
      usersText += (usersText.empty() ? "" : ", ") + user;
    }
    out << structure->name << " - " << structure->doc << "\n"
        << "  used by: " << (usersText.empty() ? "none" : usersText) << "\n";
  }
  if (asJson)
  {
    out << structures.dump(2) << "\n";
  }
}

void listAsJson(const TechniqueSelection& selection, std::ostream& out)
{
  nlohmann::json techniques = nlohmann::json::array();
  for (const TechniqueDescriptor* selected : selection)
  {
    const TechniqueDescriptor& technique = *selected;
    nlohmann::json parameters = nlohmann::json::array();
    for (const ParameterSpec& spec : technique.parameters)
    {
      const nlohmann::json defaultValue =
        spec.choices.empty() && !isAutomaticValue(spec, spec.defaultValue) ? nlohmann::json(spec.defaultValue)
                                                                            : nlohmann::json(describeDefault(spec));
      parameters.push_back({ { "name", spec.name }, { "default", defaultValue },
        { "min", spec.minValue }, { "max", spec.maxValue }, { "unit", spec.unit }, { "choices", spec.choices },
        { "integer", spec.integer }, { "file", spec.file }, { "doc", spec.doc } });
      if (const std::string note = glLimitNote(technique, spec); !note.empty())
      {
        parameters.back()["gl_limit"] = note;
      }
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

void listAsText(const TechniqueSelection& selection, std::ostream& out)
{
  for (const TechniqueDescriptor* selected : selection)
  {
    const TechniqueDescriptor& technique = *selected;
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
      if (const std::string note = glLimitNote(technique, spec); !note.empty())
      {
        out << "      GL limit: " << note << "\n";
      }
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

int runList(const ListOptions& options, std::ostream& out)
{
  const TechniqueSelection selection = selectedTechniques(options.techniques);
  if (options.structures)
  {
    listStructures(selection, !options.techniques.empty(), options.json, out);
  }
  else if (options.json)
  {
    listAsJson(selection, out);
  }
  else
  {
    listAsText(selection, out);
  }
  return 0;
}

} // namespace sl
