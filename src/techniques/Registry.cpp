// The technique registry's lookup. The table itself, techniqueRegistry(), is generated from the technique folders
// (cmake/Techniques.cmake reads every src/techniques/<folder>/technique.cmake): adding a technique adds a folder.
#include "techniques/Registry.h"

#include "core/Error.h"

namespace sl
{

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
