#include "frame/TechniqueDescriptor.h"

#include <utility>

#include <algorithm>

namespace sl
{

TechniqueDescriptor describeTechnique(std::string name, std::string title, std::string paper)
{
  TechniqueDescriptor descriptor;
  descriptor.name = std::move(name);
  descriptor.title = std::move(title);
  descriptor.paper = std::move(paper);
  return descriptor;
}

const ParameterSpec* TechniqueDescriptor::findParameter(const std::string& parameterName) const
{
  return findParameterSpec(parameters, parameterName);
}

bool TechniqueDescriptor::supports(const Light& light) const
{
  const bool type = std::find(supportedLights.begin(), supportedLights.end(), light.type) != supportedLights.end();
  const bool shape = light.type != LightType::Area ||
    std::find(supportedAreaShapes.begin(), supportedAreaShapes.end(), light.shape) != supportedAreaShapes.end();
  return type && shape;
}

std::vector<std::string> TechniqueDescriptor::outputNames() const
{
  std::vector<std::string> names{ "visibility" };
  for (const BufferSpec& buffer : buffers)
  {
    if (!buffer.fromPass)
    {
      names.push_back(buffer.name);
    }
  }
  return names;
}

bool TechniqueDescriptor::needs(const LightSpaceStructure& structure) const
{
  return std::find(lightStructures.begin(), lightStructures.end(), &structure) != lightStructures.end();
}

std::vector<const LightSpaceStructure*> TechniqueDescriptor::structuresFor(const ParameterValues& values) const
{
  std::vector<const LightSpaceStructure*> needed;
  for (const LightSpaceStructure* structure : lightStructures)
  {
    if (!structureNeeded || structureNeeded(*structure, values))
    {
      needed.push_back(structure);
    }
  }
  return needed;
}

} // namespace sl
