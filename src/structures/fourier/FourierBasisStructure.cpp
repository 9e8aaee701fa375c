#include "structures/fourier/FourierBasisStructure.h"

#include "core/Error.h"
#include "frame/FrameResult.h"
#include "gl/GlResources.h"
#include "passes/PassUtilities.h"
#include "structures/fourier/vtkSLFourierBasisPass.h"
#include "structures/moments/MomentMapStructure.h"
#include "structures/shadowmap/ShadowMapStructure.h"

#include <vtkTextureObject.h>

#include <string>

namespace sl
{

FourierBasisSettings FourierBasisSettings::from(const ParameterValues& values)
{
  FourierBasisSettings settings;
  settings.terms = values.getInt("terms");
  settings.depthRange = values.get("depth_range");
  if (!(settings.depthRange > 0.0))
  {
    // The declared range is (0, 1]: at 0 every basis image is sin 0 = 0, cos 0 = 1 and the series reads 1/2.
    throw InputError(format("--set depth_range=", settings.depthRange, ": must be above 0 (range (0, 1]); 0 maps every depth to 0"));
  }
  if (settings.terms % fourierTermsPerTexture != 0)
  {
    throw InputError(format("--set terms=", settings.terms, ": the Fourier terms are stored four per RGBA texture; use 4, 8, 12 or 16"));
  }
  // The prefilter is the moment map's, read from its parameters (declared once, by momentMapStructure(); a
  // technique listing this structure declares them too).
  SL_CHECK_MSG(values.has("prefilter") && values.has("prefilter_texels"),
    "a technique listing fourier_basis must declare the moment map's prefilter parameters");
  settings.mipmap = values.choice("prefilter") == "mipmap";
  settings.blurTexels = settings.mipmap ? 1 : values.getInt("prefilter_texels");
  settings.receiversOnly =
    !settings.mipmap && values.has("prefilter_region") && values.choice("prefilter_region") == "receivers";
  return settings;
}

bool fourierSparseBlurIsCheaper(const ReceiverPrefilterPlan& plan, int blurTexels, int textures)
{
  if (plan.readTexels.empty() || blurTexels <= 1)
  {
    return false; // nothing listed, or no blur: the tiles
  }
  const int reach = boxBlurReach(blurTexels);
  const ReceiverTiles horizontal = plan.read.grown(0, reach);
  const double source = static_cast<double>(horizontal.grown(reach, 0).texelCount());
  const double blurred = static_cast<double>(horizontal.texelCount() + plan.read.texelCount());
  const double width = blurTexels;
  const double tiles = source * (1.0 + textures) + blurred * width * textures;
  const double sparse =
    static_cast<double>(plan.readTexels.size()) * width * width * (1.0 + textures * fourierSparseTermCost);
  return sparse < tiles;
}

namespace
{

const FourierBasisData& fourierBasisData(const FrameResources& frame)
{
  return frame.structureData<FourierBasisData>(fourierBasisStructure().name);
}

std::vector<NamedImage> exportFourierBasis(const FrameResources& frame, FrameResult& result)
{
  const FourierBasisData& data = fourierBasisData(frame);
  const ImageF built = prefilterBuiltMask(data.region, frame.lightView.resolution);
  std::vector<NamedImage> images;
  const auto exportSet = [&](const std::vector<vtkSmartPointer<vtkTextureObject>>& textures, const char* function) {
    for (std::size_t texture = 0; texture < textures.size(); ++texture)
    {
      const ImageF basis = readFloatTexture(textures[texture], 4);
      for (int channel = 0; channel < fourierTermsPerTexture; ++channel)
      {
        const int k = static_cast<int>(texture) * fourierTermsPerTexture + channel + 1;
        images.push_back({ format("fourier_", function, "_", k), builtChannel(basis, channel, built), "",
          format("prefiltered ", function, "(c_k s z_n), c_k = pi (2k - 1), k = ", k, ", s = depth_range (Annen et al. 2007)") });
      }
    }
  };
  exportSet(data.sine, "sin");
  exportSet(data.cosine, "cos");
  images.push_back(prefilterBuiltArray("fourier_built", built, "the Fourier basis"));
  addPrefilterRegionStatistics(data.region, "fourier_basis", result);
  return images;
}

} // namespace

const LightSpaceStructure& fourierBasisStructure()
{
  static const LightSpaceStructure structure = [] {
    LightSpaceStructure s;
    s.name = "fourier_basis";
    s.doc = "sin(c_k s z_n), cos(c_k s z_n) of the shadow map, k = 1..terms, s = depth_range, box-blurred or mip-mapped (Annen et al. 2007; survey §6)";
    s.builtFrom = { &shadowMapStructure() };
    s.parameters = {
      { "terms", 16, 4, 16, "", "M, the Fourier terms of the shadow test kept (Annen et al. 2007: 16); a multiple of 4", {}, true },
      { "depth_range", 0.5, 0, 1, "",
        "s in (0, 1] (0 is refused): normalised depths z_n in [0, 1] enter the series as s z_n, so every gap s (z_n - d_n) stays in [-s, s], away from the period-2 series' jump back at +-1 (ShadowLab; 1: the whole period, the series reads 1/2 where z_n - d_n = -1)", {}, false },
    };
    s.sharedParameters = { "prefilter", "prefilter_texels", "prefilter_region" };
    s.createBuildPasses = [] {
      return std::vector<vtkSmartPointer<vtkSLStagePass>>{ vtkSmartPointer<vtkSLFourierBasisPass>::New() };
    };
    s.exportImages = exportFourierBasis;
    s.gpuBytes = [](const FrameResources& frame) {
      const FourierBasisData& data = fourierBasisData(frame);
      std::size_t bytes = 0;
      for (const auto* textures : { &data.sine, &data.cosine })
      {
        for (const vtkSmartPointer<vtkTextureObject>& texture : *textures)
        {
          bytes += textureBytes(texture, 16, data.mipmapped);
        }
      }
      return bytes;
    };
    s.shaderDefines = [](const FrameResources& frame) {
      return ShaderDefines{ { "FOURIER_TERMS", std::to_string(FourierBasisSettings::from(frame.parameters).terms) } };
    };
    s.bind = [](vtkShaderProgram* program, const FrameResources& frame) {
      const FourierBasisData& data = fourierBasisData(frame);
      std::vector<vtkTextureObject*> bound;
      for (std::size_t texture = 0; texture < data.sine.size(); ++texture)
      {
        bound.push_back(bindTexture(program, format("fourierSin", texture).c_str(), data.sine[texture]));
        bound.push_back(bindTexture(program, format("fourierCos", texture).c_str(), data.cosine[texture]));
      }
      return bound;
    };
    return s;
  }();
  return structure;
}

} // namespace sl
