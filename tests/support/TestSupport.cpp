#include "support/TestSupport.h"

#include "core/Error.h"

#include <algorithm>

namespace sl::test
{

std::filesystem::path sourceDir()
{
  return SL_SOURCE_DIR;
}

std::filesystem::path testOutputDir()
{
  const std::filesystem::path dir = SL_TEST_OUTPUT_DIR;
  std::filesystem::create_directories(dir);
  return dir;
}

std::filesystem::path datasetPath(const std::string& name)
{
  return sourceDir() / "datasets" / name / "scene.json";
}

Scene loadDataset(const std::string& name)
{
  return loadScene(datasetPath(name));
}

std::vector<std::string> datasetNames()
{
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(sourceDir() / "datasets"))
  {
    if (std::filesystem::is_regular_file(entry.path() / "scene.json"))
    {
      names.push_back(entry.path().filename().string());
    }
  }
  std::sort(names.begin(), names.end());
  return names;
}

ShadowRenderer& sharedRenderer()
{
  static ShadowRenderer renderer;
  return renderer;
}

FrameResult renderDataset(const Scene& scene, const std::string& technique, int width, int height,
  const std::vector<std::string>& settings)
{
  RenderRequest request;
  request.technique = technique;
  request.settings = settings;
  request.resolution = glm::ivec2(width, height);
  return sharedRenderer().render(scene, request);
}

ShadowMapInputs shadowMapInputs(const FrameResult& frame, const Scene& scene, int lightIndex)
{
  SL_CHECK(frame.lightView.has_value());
  ShadowMapInputs inputs;
  inputs.light = &scene.lights.at(static_cast<std::size_t>(lightIndex));
  inputs.camera = frame.camera;
  inputs.lightView = *frame.lightView;
  inputs.position = frame.find("position")->image;
  inputs.normal = frame.find("normal")->image;
  inputs.coverage = frame.find("coverage")->image;
  inputs.receives = frame.find("receives_shadows")->image;
  for (const NamedImage& named : frame.lightSpace)
  {
    if (named.name == "shadow_map_depth")
    {
      inputs.shadowMapLinear = named.image;
    }
    else if (named.name == "shadow_map_window_depth")
    {
      inputs.shadowMapWindow = named.image;
    }
  }
  return inputs;
}

} // namespace sl::test
