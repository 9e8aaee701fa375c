#include "structures/mssm/DualMssmStructure.h"

#include "structures/hsm/HsmStructure.h"
#include "structures/hsm/vtkSLHsmPass.h"
#include "structures/shadowmap/ShadowMapStructure.h"

namespace sl
{

const LightSpaceStructure& dualMssmStructure()
{
  static const LightSpaceStructure structure = [] {
    LightSpaceStructure s;
    s.name = "dual_mssm";
    s.doc = "the MSSM on the dual grid of 2 x 2 sample blocks (Yang et al. 2009 §4.2)";
    s.builtFrom = { &shadowMapStructure() };
    s.parameters = { hsmLevelsParameter("mssm_levels", "dual-grid MSSM") };
    s.createBuildPasses = [] {
      auto pass = vtkSmartPointer<vtkSLHsmPass>::New();
      pass->SetDualGrid(true);
      return std::vector<vtkSmartPointer<vtkSLStagePass>>{ pass };
    };
    const auto data = [](const FrameResources& frame) -> const MinMaxDepthData& {
      return frame.structureData<MinMaxDepthData>(dualMssmStructure().name);
    };
    s.exportImages = [data](const FrameResources& frame, FrameResult& result) {
      return exportMinMaxDepth(data(frame), frame.lightView.resolution, result, "mssm");
    };
    s.gpuBytes = [data](const FrameResources& frame) { return minMaxDepthBytes(data(frame)); };
    s.shaderDefines = [](const FrameResources&) { return vtkSLHsmPass::LayoutDefines(HsmLayout::DualMssm); };
    s.bind = [data](vtkShaderProgram* program, const FrameResources& frame) {
      return bindMinMaxDepth(program, data(frame), frame.lightView.resolution);
    };
    // (N + 1)^2 texels per layer (vtkSLHsmPass).
    s.largestMapSize = [](const ParameterValues&, int max3dTextureSize) { return max3dTextureSize - 1; };
    return s;
  }();
  return structure;
}

} // namespace sl
