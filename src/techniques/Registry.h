// The technique registry: every technique's descriptor, in the order `shadowlab list` shows them.
#pragma once

#include "frame/TechniqueDescriptor.h"

#include <string>
#include <vector>

namespace sl
{

const std::vector<TechniqueDescriptor>& techniqueRegistry();
// Throws InputError listing the available techniques when `name` is unknown.
const TechniqueDescriptor& findTechnique(const std::string& name);

} // namespace sl
