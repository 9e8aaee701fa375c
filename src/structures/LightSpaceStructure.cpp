// What every light-space structure shares: the closure of build dependencies in registry order and texture bytes.
// The registry itself, lightSpaceStructureRegistry(), is generated from the folders' structure.cmake
// (cmake/Structures.cmake).
#include "structures/LightSpaceStructure.h"

#include "core/Error.h"

#include <vtkTextureObject.h>

#include <algorithm>

namespace sl
{

std::vector<const LightSpaceStructure*> withBuildDependencies(const std::vector<const LightSpaceStructure*>& needed)
{
  std::vector<const LightSpaceStructure*> closure;
  std::vector<const LightSpaceStructure*> pending = needed;
  while (!pending.empty())
  {
    const LightSpaceStructure* structure = pending.back();
    pending.pop_back();
    if (std::find(closure.begin(), closure.end(), structure) == closure.end())
    {
      closure.push_back(structure);
      pending.insert(pending.end(), structure->builtFrom.begin(), structure->builtFrom.end());
    }
  }
  std::vector<const LightSpaceStructure*> ordered;
  for (const LightSpaceStructure* structure : lightSpaceStructureRegistry())
  {
    if (std::find(closure.begin(), closure.end(), structure) != closure.end())
    {
      ordered.push_back(structure);
    }
  }
  SL_CHECK_MSG(ordered.size() == closure.size(), "a light-space structure is missing from lightSpaceStructureRegistry()");
  return ordered;
}

std::size_t textureBytes(vtkTextureObject* texture, std::size_t bytesPerTexel, bool mipmapped)
{
  if (!texture)
  {
    return 0;
  }
  std::size_t width = texture->GetWidth();
  std::size_t height = texture->GetHeight();
  const std::size_t depth = std::max<std::size_t>(texture->GetDepth(), 1);
  std::size_t bytes = width * height * depth * bytesPerTexel;
  while (mipmapped && (width > 1 || height > 1))
  {
    width = std::max<std::size_t>(width / 2, 1);
    height = std::max<std::size_t>(height / 2, 1);
    bytes += width * height * depth * bytesPerTexel;
  }
  return bytes;
}

} // namespace sl
