#include "techniques/lvsm/vtkSLLvsmPass.h"

#include "passes/FrameResources.h"
#include "passes/PassUtilities.h"
#include "techniques/ShadowMapParameters.h"
#include "techniques/ShadowMapReference.h"
#include "structures/layeredmoments/LayeredMomentsStructure.h"
#include "techniques/MomentTechniquePass.h"
#include "techniques/lvsm/LvsmTechnique.h"

#include <sstream>

#include <vtkObjectFactory.h>
#include <vtkShaderProgram.h>

vtkStandardNewMacro(vtkSLLvsmPass);

sl::ShaderDefines vtkSLLvsmPass::GetExtraDefines() const
{
  std::ostringstream threshold;
  threshold.precision(17);
  threshold << sl::lvsmVsmLeakThreshold;
  return { { "LVSM_VSM_LEAK_THRESHOLD", threshold.str() } };
}

std::vector<vtkTextureObject*> vtkSLLvsmPass::SetTechniqueUniforms(vtkShaderProgram* program)
{
  const sl::FrameResources& frame = *this->Frame;
  const sl::LvsmSettings settings = sl::LvsmSettings::from(frame.parameters);
  program->SetUniformi("kernelWidth", settings.prefilterTexels);
  program->SetUniformi("tightestBound", settings.layerBound == sl::LvsmLayerBound::Tightest ? 1 : 0);
  this->LayerEnds = frame.structureData<sl::LayeredMomentsData>(sl::layeredMomentsStructure().name).ends;
  sl::setLeakBiasUniform(program);
  return {};
}

std::map<std::string, double> vtkSLLvsmPass::CollectStatistics()
{
  std::map<std::string, double> statistics = this->Superclass::CollectStatistics();
  sl::layeredEndStatistics(this->LayerEnds, statistics);
  return statistics;
}

void vtkSLLvsmPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "LayerEnds: " << this->LayerEnds.size() << "\n";
}
