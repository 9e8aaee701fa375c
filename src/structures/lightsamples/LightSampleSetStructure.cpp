#include "structures/lightsamples/LightSampleSetStructure.h"

#include "gl/GlResources.h"
#include "structures/lightsamples/vtkSLLightSamplePass.h"
#include "passes/PassUtilities.h"

#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

namespace sl
{
namespace
{

// The choices of `samples`: "16", "64", "256" (lightSampleCounts()).
std::vector<std::string> sampleCountNames()
{
  std::vector<std::string> names;
  for (const int count : lightSampleCounts())
  {
    names.push_back(std::to_string(count));
  }
  return names;
}

double choiceIndex(const std::vector<std::string>& choices, const std::string& choice)
{
  const auto found = std::find(choices.begin(), choices.end(), choice);
  SL_CHECK(found != choices.end());
  return static_cast<double>(found - choices.begin());
}

// The seed's 32 bits as a GLSL int (VTK 9.1's vtkShaderProgram sets no uint uniform); the shader's uint()
// conversion keeps the bit pattern (GLSL 4.50 §5.4.1).
int seedBits(std::uint32_t seed)
{
  int bits = 0;
  std::memcpy(&bits, &seed, sizeof bits);
  return bits;
}

void setVectorIfUsed(vtkShaderProgram* program, const char* name, const glm::dvec3& value)
{
  if (program->IsUniformUsed(name))
  {
    setVector(program, name, value);
  }
}

// light_samples: the base points as the texture holds them (read back); light_sample_offsets: where they lie on
// this frame's light, in its (right, up) frame from the centre.
std::vector<NamedImage> exportSamples(const FrameResources& frame)
{
  const LightSampleSetData& data = lightSampleSetData(frame);
  const std::vector<glm::dvec2>& points = data.samples->basePoints();
  ImageF offsets(static_cast<int>(points.size()), 1, 2);
  for (std::size_t k = 0; k < points.size(); ++k)
  {
    const glm::dvec2 offset = lightPlaneOffset(*frame.light, points[k]);
    offsets.data[2 * k] = static_cast<float>(offset.x);
    offsets.data[2 * k + 1] = static_cast<float>(offset.y);
  }
  const std::string pattern = lightSamplePatternName(data.samples->settings());
  return {
    { "light_samples", readFloatTexture(data.baseTexture, 2), "unit square",
      "the " + pattern + " set's base points (pattern 0, before the per-pixel shift) in [0, 1)^2 (Forest et al. 2009 §4.1)" },
    { "light_sample_offsets", offsets, "world units",
      "the base points on the light: offsets along its right and up vectors from its centre" },
  };
}

std::vector<vtkTextureObject*> bindSamples(vtkShaderProgram* program, const FrameResources& frame)
{
  const LightSampleSetData& data = lightSampleSetData(frame);
  const LightSampleSetSettings& settings = data.samples->settings();
  setIntIfUsed(program, "lightSampleCount", settings.count);
  setIntIfUsed(program, "lightSampleSeed", seedBits(settings.seed));
  setIntIfUsed(program, "lightSampleInterleaved", settings.interleaved ? 1 : 0);
  setIntIfUsed(program, "lightSampleGridSide", static_cast<int>(std::lround(std::sqrt(settings.count))));
  // A light that is not an area light has all its samples at its centre (LightSampleSet::point).
  const Light& light = *frame.light;
  const bool area = light.type == LightType::Area;
  setIntIfUsed(program, "lightSampleDisk", area && light.shape == LightShape::Disk ? 1 : 0);
  setFloatIfUsed(program, "lightSampleSize", area ? light.size : 0.0);
  setVectorIfUsed(program, "lightSampleCenterWs", light.center);
  setVectorIfUsed(program, "lightSampleRightWs", area ? light.right() : glm::dvec3(0.0));
  setVectorIfUsed(program, "lightSampleUpWs", area ? light.up : glm::dvec3(0.0));
  if (!program->IsUniformUsed("lightSampleBase"))
  {
    return {}; // a pass of the technique that does not sample the light
  }
  return { bindTexture(program, "lightSampleBase", data.baseTexture) };
}

} // namespace

LightSampleSetSettings lightSampleSetSettings(const ParameterValues& values)
{
  return lightSampleSetSettings(values.choice("light_samples"), std::stoi(values.choice("samples")),
    static_cast<std::uint32_t>(values.getInt("sample_seed")));
}

const LightSampleSetData& lightSampleSetData(const FrameResources& frame)
{
  return frame.structureData<LightSampleSetData>(lightSampleSetStructure().name);
}

const LightSpaceStructure& lightSampleSetStructure()
{
  static const LightSpaceStructure structure = [] {
    LightSpaceStructure s;
    s.name = "light_samples";
    s.doc = "N light samples per pixel from a named pattern, toroidally shifted per pixel or per 4 x 4 tile, shared with the reference (Forest et al. 2009 §4.1)";
    // Object space: the samples live on the light, nothing is read from its view.
    s.builtFrom = {};
    const std::vector<std::string> counts = sampleCountNames();
    s.parameters = {
      { "light_samples", choiceIndex(lightSamplePatternNames(), "poisson"), 0,
        static_cast<double>(lightSamplePatternNames().size() - 1), "",
        "light-sample pattern (Forest et al. 2009 §4.1, Fig. 5): grid, stratified, poisson (Poisson disk at the paper's minimum distance, §4.1), zero_two (Sobol (0,2)-sequence, §4.1); _4x4: shifted by the pixel's place in a 4 x 4 tile (interleaved sampling, Fig. 5 f) instead of per pixel (§4.1)",
        lightSamplePatternNames(), true },
      { "samples", choiceIndex(counts, "16"), 0, static_cast<double>(counts.size() - 1), "light samples",
        "light samples per pixel, N: 16 or 64 as in Forest et al. 2009 (§4.1), or 256", counts, true },
      { "sample_seed", 1, 0, 2147483647, "",
        "seed of the stratified jitter, the Poisson set and the per-pixel shifts; the reference's --seed draws the same samples",
        {}, true },
    };
    s.createBuildPasses = [] {
      return std::vector<vtkSmartPointer<vtkSLStagePass>>{ vtkSmartPointer<vtkSLLightSamplePass>::New() };
    };
    s.exportImages = [](const FrameResources& frame, FrameResult&) { return exportSamples(frame); };
    s.gpuBytes = [](const FrameResources& frame) { return textureBytes(lightSampleSetData(frame).baseTexture, 8); };
    s.shaderDefines = [](const FrameResources& frame) {
      return ShaderDefines{ { "LIGHT_SAMPLE_COUNT", std::to_string(lightSampleSetSettings(frame.parameters).count) } };
    };
    s.bind = bindSamples;
    return s;
  }();
  return structure;
}

} // namespace sl
