#include "techniques/Technique.h"

#include "core/Parse.h"

#include "core/Error.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace sl
{

std::string lightStructureName(LightStructure structure)
{
  switch (structure)
  {
    case LightStructure::ShadowMap: return "shadow_map";
    case LightStructure::MomentMap: return "moment_map";
    case LightStructure::SummedAreaTable: return "summed_area_table";
    case LightStructure::HierarchicalShadowMap: return "hierarchical_shadow_map";
    case LightStructure::DualMultiScaleShadowMap: return "dual_mssm";
  }
  return "unknown";
}

const ParameterSpec* TechniqueDescriptor::findParameter(const std::string& parameterName) const
{
  const auto found = std::find_if(parameters.begin(), parameters.end(),
    [&](const ParameterSpec& spec) { return spec.name == parameterName; });
  return found == parameters.end() ? nullptr : &*found;
}

bool TechniqueDescriptor::supports(const Light& light) const
{
  const bool type = std::find(supportedLights.begin(), supportedLights.end(), light.type) != supportedLights.end();
  const bool shape = light.type != LightType::Area ||
    std::find(supportedAreaShapes.begin(), supportedAreaShapes.end(), light.shape) != supportedAreaShapes.end();
  return type && shape;
}

bool TechniqueDescriptor::needs(LightStructure structure) const
{
  return std::find(lightStructures.begin(), lightStructures.end(), structure) != lightStructures.end();
}

ParameterValues::ParameterValues(const TechniqueDescriptor& descriptor)
  : descriptor_(&descriptor)
{
  for (const ParameterSpec& spec : descriptor.parameters)
  {
    values_[spec.name] = spec.defaultValue;
  }
}

double ParameterValues::get(const std::string& name) const
{
  const auto found = values_.find(name);
  SL_CHECK_MSG(found != values_.end(), "technique parameter '", name, "' is not declared");
  return found->second;
}

int ParameterValues::getInt(const std::string& name) const
{
  return static_cast<int>(std::lround(get(name)));
}

const std::string& ParameterValues::choice(const std::string& name) const
{
  const ParameterSpec* spec = descriptor_->findParameter(name);
  SL_CHECK_MSG(spec && !spec->choices.empty(), "'", name, "' is not an enumeration");
  return spec->choices.at(static_cast<std::size_t>(getInt(name)));
}

void ParameterValues::set(const std::string& key, double value)
{
  const ParameterSpec* spec = descriptor_->findParameter(key);
  if (!spec)
  {
    std::string known;
    for (const ParameterSpec& candidate : descriptor_->parameters)
    {
      known += (known.empty() ? "" : ", ") + candidate.name;
    }
    throw InputError(format("--set ", key, ": technique '", descriptor_->name, "' has no parameter '", key,
      "' (its parameters: ", known.empty() ? "none" : known, ")"));
  }
  if (!std::isfinite(value) || value < spec->minValue || value > spec->maxValue)
  {
    throw InputError(format("--set ", key, "=", value, ": out of range for technique '", descriptor_->name,
      "' (allowed ", spec->minValue, " to ", spec->maxValue, spec->unit.empty() ? "" : " ", spec->unit, ")"));
  }
  if (spec->integer && std::abs(value - std::round(value)) > 1e-9)
  {
    throw InputError(format("--set ", key, "=", value, ": must be an integer"));
  }
  values_[key] = value;
}

void ParameterValues::set(const std::string& assignment)
{
  const std::size_t equals = assignment.find('=');
  if (equals == std::string::npos || equals == 0)
  {
    throw InputError("--set '" + assignment + "': expected key=value");
  }
  const std::string key = assignment.substr(0, equals);
  const std::string text = assignment.substr(equals + 1);
  const ParameterSpec* spec = descriptor_->findParameter(key);
  if (spec && !spec->choices.empty())
  {
    const auto found = std::find(spec->choices.begin(), spec->choices.end(), text);
    if (found == spec->choices.end())
    {
      std::string allowed;
      for (const std::string& choiceName : spec->choices)
      {
        allowed += (allowed.empty() ? "" : ", ") + choiceName;
      }
      throw InputError(format("--set ", assignment, ": '", text, "' is not a choice of ", key, " (", allowed, ")"));
    }
    values_[key] = static_cast<double>(found - spec->choices.begin());
    return;
  }
  if (spec && spec->integer && spec->minValue == 0.0 && spec->maxValue == 1.0 && (text == "true" || text == "false"))
  {
    values_[key] = text == "true" ? 1.0 : 0.0;
    return;
  }
  const std::optional<double> value = parseNumber(text);
  if (!value)
  {
    throw InputError(format("--set ", assignment, ": '", text, "' is not a number"));
  }
  set(key, *value);
}

const TechniqueDescriptor& findTechnique(const std::string& name)
{
  for (const TechniqueDescriptor& descriptor : techniqueRegistry())
  {
    if (descriptor.name == name)
    {
      return descriptor;
    }
  }
  std::string available;
  for (const TechniqueDescriptor& descriptor : techniqueRegistry())
  {
    available += (available.empty() ? "" : ", ") + descriptor.name;
  }
  throw InputError("--technique " + name + ": unknown technique (available: " + available + ")");
}

} // namespace sl
