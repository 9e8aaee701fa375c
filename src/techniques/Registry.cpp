// The technique registry: one entry per technique. Adding a technique means adding its folder under
// src/techniques/, its shaders, one line here, and its tests.
#include "techniques/Registry.h"

#include "core/Error.h"
#include "techniques/hard/HardTechnique.h"
#include "techniques/pcf/PcfTechnique.h"
#include "techniques/esm/EsmTechnique.h"
#include "techniques/gbp06/Gbp06Technique.h"
#include "techniques/gbp07/Gbp07Technique.h"
#include "techniques/yfgl09/Yfgl09Technique.h"
#include "techniques/ss08/Ss08Technique.h"
#include "techniques/pcss/PcssTechnique.h"
#include "techniques/referencesm/ReferenceSmTechnique.h"
#include "techniques/savsm/SavsmTechnique.h"
#include "techniques/vsm/VsmTechnique.h"
#include "techniques/vssm/VssmTechnique.h"
#include "techniques/vtk/VtkTechnique.h"
#include "techniques/dcs/DcsTechnique.h"
#include "techniques/penumbrawedge/PenumbraWedgeTechnique.h"
#include "techniques/shadowvolume/ShadowVolumeTechnique.h"

namespace sl
{

const std::vector<TechniqueDescriptor>& techniqueRegistry()
{
  static const std::vector<TechniqueDescriptor> registry = {
    hardTechnique(),
    pcfTechnique(),
    pcssTechnique(),
    vsmTechnique(),
    esmTechnique(),
    savsmTechnique(),
    vssmTechnique(),
    gbp06Technique(),
    gbp07Technique(),
    yfgl09Technique(),
    ss08Technique(),
    vtkTechnique(),
    referenceSmTechnique(),
    shadowVolumeTechnique(),
    dcsTechnique(),
    penumbraWedgeTechnique(),
  };
  return registry;
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
