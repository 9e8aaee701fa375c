// Named, typed parameters with defaults and ranges (bgfx-style table: default, range, unit, doc), and their values.
// A technique declares its parameters (frame/TechniqueDescriptor.h), and so does each light-space structure
// (structures/LightSpaceStructure.h); ParameterValues resolves `--set key=value` against such a table.
#pragma once

#include <initializer_list>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace sl
{

struct ParameterSpec
{
  std::string name;
  double defaultValue = 0.0;
  double minValue = 0.0;
  double maxValue = 0.0;
  std::string unit;                 // "texels", "", ...
  std::string doc;                  // one line, cites the paper where it comes from
  std::vector<std::string> choices; // non-empty: an enumeration, the value is the index of the choice
  bool integer = false;             // integer-valued numeric parameter
  // A file path (`--set key=PATH`, e.g. ss08's budget image): its number is 1 once a path is set, 0 before (the
  // range 0..1); ParameterValues::file gives the path. Checked by whoever reads the file, which names it.
  bool file = false;
  // Non-empty: a word (`auto`) that leaves the value to each frame, stored as kAutomaticValue (outside the range);
  // the default may be it. shadow_map_size=auto: the size the focus stage derives from the view (ShadowMapStructure.h).
  std::string automatic;
};

// The value an `automatic` word stands for.
constexpr double kAutomaticValue = 0.0;

// Whether `value` of `spec` is its automatic word's.
bool isAutomaticValue(const ParameterSpec& spec, double value);

// The spec called `name` in `specs`, or nullptr.
const ParameterSpec* findParameterSpec(const std::vector<ParameterSpec>& specs, const std::string& name);

// Parameter values resolved against a table of specs: every parameter has a value, all within range.
// `owner` names the table's owner (a technique) in messages; the specs must outlive the values (the registry's).
class ParameterValues;
[[noreturn]] void unpairedChoice(const ParameterValues& values, const std::string& name); // choiceOf's failure

class ParameterValues
{
public:
  ParameterValues() = default;
  ParameterValues(std::string owner, const std::vector<ParameterSpec>& specs);

  bool has(const std::string& name) const { return values_.count(name) != 0; }
  double get(const std::string& name) const;        // SL_CHECKs the name exists
  int getInt(const std::string& name) const;
  const std::string& choice(const std::string& name) const; // enumeration's chosen name
  const std::string& file(const std::string& name) const;   // a file parameter's path ("" when unset)
  // Whether `name` holds its spec's automatic word (e.g. shadow_map_size=auto): the frame chooses the value.
  bool automatic(const std::string& name) const;
  // Parses "key=value" (a number, or a choice name for enumerations, or true/false for 0..1 integers, or the spec's
  // automatic word).
  // Throws InputError naming the technique, key and value when unknown or out of range.
  void set(const std::string& assignment);
  void set(const std::string& key, double value);
  const std::map<std::string, double>& values() const { return values_; }
  const std::vector<ParameterSpec>& specs() const;
  const std::string& owner() const { return owner_; }

private:
  std::string owner_;
  const std::vector<ParameterSpec>* specs_ = nullptr;
  std::map<std::string, double> values_;
  std::map<std::string, std::string> files_;
};

// Typed settings, parsed once (as pbrt-v4's Create() does): each technique and structure turns its ParameterValues
// into a struct of its own (e.g. PcfSettings::from) in one function, which is the only place its parameters are
// read by name; its passes, twin, probe and approximation rules read the struct. Defaults and ranges stay in the
// ParameterSpec table alone (the structs' fields are value-initialised, not given defaults of their own). An
// enumeration parameter becomes an enum through choiceOf.

// The enumerator paired with `name`'s chosen choice in `choices` ({choice name, enumerator} for every choice the
// spec lists); SL_CHECKs that the chosen name is paired, so a renamed choice fails at once instead of mapping wrong.
template <class Enum>
Enum choiceOf(const ParameterValues& values, const std::string& name,
  std::initializer_list<std::pair<const char*, Enum>> choices)
{
  const std::string& chosen = values.choice(name);
  for (const auto& [choiceName, value] : choices)
  {
    if (chosen == choiceName)
    {
      return value;
    }
  }
  unpairedChoice(values, name);
}

} // namespace sl
