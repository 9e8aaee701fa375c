#include "core/Parameters.h"

#include "core/Error.h"
#include "core/Parse.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <utility>

namespace sl
{

const ParameterSpec* findParameterSpec(const std::vector<ParameterSpec>& specs, const std::string& name)
{
  const auto found =
    std::find_if(specs.begin(), specs.end(), [&](const ParameterSpec& spec) { return spec.name == name; });
  return found == specs.end() ? nullptr : &*found;
}

bool isAutomaticValue(const ParameterSpec& spec, double value)
{
  return !spec.automatic.empty() && value == kAutomaticValue;
}

bool ParameterValues::automatic(const std::string& name) const
{
  const ParameterSpec* spec = findParameterSpec(specs(), name);
  return spec && isAutomaticValue(*spec, get(name));
}

const std::vector<ParameterSpec>& ParameterValues::specs() const
{
  static const std::vector<ParameterSpec> none;
  return specs_ ? *specs_ : none;
}

ParameterValues::ParameterValues(std::string owner, const std::vector<ParameterSpec>& specs)
  : owner_(std::move(owner))
  , specs_(&specs)
{
  for (const ParameterSpec& spec : specs)
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
  const ParameterSpec* spec = findParameterSpec(specs(), name);
  SL_CHECK_MSG(spec && !spec->choices.empty(), "'", name, "' is not an enumeration");
  return spec->choices.at(static_cast<std::size_t>(getInt(name)));
}

const std::string& ParameterValues::file(const std::string& name) const
{
  static const std::string unset;
  const ParameterSpec* spec = findParameterSpec(specs(), name);
  SL_CHECK_MSG(spec && spec->file, "'", name, "' is not a file parameter");
  const auto found = files_.find(name);
  return found == files_.end() ? unset : found->second;
}

void ParameterValues::set(const std::string& key, double value)
{
  const ParameterSpec* spec = findParameterSpec(specs(), key);
  if (spec && spec->file)
  {
    throw InputError(format("--set ", key, "=", value, ": technique '", owner_, "' expects a file path for ", key));
  }
  if (!spec)
  {
    std::string known;
    for (const ParameterSpec& candidate : specs())
    {
      known += (known.empty() ? "" : ", ") + candidate.name;
    }
    throw InputError(format("--set ", key, ": technique '", owner_, "' has no parameter '", key,
      "' (its parameters: ", known.empty() ? "none" : known, ")"));
  }
  if (!std::isfinite(value) || value < spec->minValue || value > spec->maxValue)
  {
    throw InputError(format("--set ", key, "=", value, ": out of range for technique '", owner_, "' (allowed ",
      spec->minValue, " to ", spec->maxValue, spec->unit.empty() ? "" : " ", spec->unit,
      spec->automatic.empty() ? "" : ", or " + spec->automatic, ")"));
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
  const ParameterSpec* spec = findParameterSpec(specs(), key);
  if (spec && spec->file)
  {
    if (text.empty())
    {
      throw InputError(format("--set ", assignment, ": expected a file path after '='"));
    }
    files_[key] = text;
    values_[key] = 1.0;
    return;
  }
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
  if (spec && !spec->automatic.empty() && text == spec->automatic)
  {
    values_[key] = kAutomaticValue;
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
    throw InputError(format("--set ", assignment, ": '", text, "' is not a number",
      spec && !spec->automatic.empty() ? " nor " + spec->automatic : std::string()));
  }
  set(key, *value);
}

void unpairedChoice(const ParameterValues& values, const std::string& name)
{
  ::sl::checkFailed("choiceOf", __FILE__, __LINE__,
    format(values.owner(), ": choice '", values.choice(name), "' of '", name, "' has no enumerator in its settings"));
}

} // namespace sl
