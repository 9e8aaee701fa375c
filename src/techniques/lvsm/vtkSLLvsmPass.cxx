#include "techniques/lvsm/vtkSLLvsmPass.h"

#include "passes/FrameResources.h"
#include "passes/PassUtilities.h"
#include "techniques/ShadowMapParameters.h"
#include "techniques/ShadowMapReference.h"
#include "structures/layeredmoments/LayeredMomentsStructure.h"
#include "techniques/lvsm/LvsmTechnique.h"

#include <sstream>

#include <vtkObjectFactory.h>
#include <vtkShaderProgram.h>

vtkStandardNewMacro(vtkSLLvsmPass);

sl::ShaderDefines vtkSLLvsmPass::GetExtraDefines() const
{
  // common/MomentLookup.glsl (boxPcf, leakComparisonDepth) also holds vsm's lookup of its moment map, which asks
  // for the prefilter; lvsm's layers are always box-blurred.
  std::ostringstream threshold;
  threshold.precision(17);
  threshold << sl::lvsmVsmLeakThreshold;
  return { { "PREFILTER_BLUR", "0" }, { "PREFILTER_MIPMAP", "1" }, { "PREFILTER", "0" },
    { "LVSM_VSM_LEAK_THRESHOLD", threshold.str() } };
}

std::vector<vtkTextureObject*> vtkSLLvsmPass::SetTechniqueUniforms(vtkShaderProgram* program)
{
  const sl::FrameResources& frame = *this->Frame;
  program->SetUniformi("kernelWidth", frame.parameters.getInt("prefilter_texels"));
  program->SetUniformi("tightestBound", sl::LvsmSettings::from(frame.parameters).layerBound == sl::LvsmLayerBound::Tightest ? 1 : 0);
  this->LayerEnds = frame.structureData<sl::LayeredMomentsData>(sl::layeredMomentsStructure().name).ends;
  if (program->IsUniformUsed("leakBiasTexels"))
  {
    const sl::BiasSettings leakBias = sl::defaultBiasSettings();
    sl::setVector(program, "leakBiasTexels", { leakBias.constantTexels, leakBias.slopeTexels, leakBias.maxSlope });
  }
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
