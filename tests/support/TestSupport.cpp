#include "support/TestSupport.h"
#include "support/TempDir.h"

#include "techniques/ProbeSupport.h"

#include "core/Error.h"
#include "lightspace/ShadowMapMath.h"
#include "io/ImageIO.h"
#include "techniques/Registry.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <optional>
#include <stdexcept>

namespace sl::test
{

const ImageF& bufferOf(const FrameResult& frame, const std::string& name)
{
  const NamedImage* image = frame.find(name);
  if (image == nullptr)
  {
    throw std::runtime_error("frame has no buffer '" + name + "'");
  }
  return image->image;
}

const NamedImage& arrayNamed(const std::vector<NamedImage>& arrays, const std::string& name)
{
  const NamedImage* named = findNamed(arrays, name);
  if (named == nullptr)
  {
    throw std::runtime_error("no array " + name);
  }
  return *named;
}

nlohmann::json readJson(const std::filesystem::path& path)
{
  return nlohmann::json::parse(readFile(path));
}

Scene sceneFromJson(const std::string& camera, const std::string& light, const std::string& objects)
{
  const std::string text =
    R"({ "camera": )" + camera + R"(, "lights": [ )" + light + R"( ], "objects": [ )" + objects + " ] }";
  return parseScene(text, "test scene", sourceDir());
}
// One EGL context + VTK window per test process (creating them is the slow part on llvmpipe).
ShadowRenderer& sharedRenderer()
{
  static ShadowRenderer renderer;
  return renderer;
}

vtkSLEglRenderWindow* sharedRenderWindow()
{
  return sharedRenderer().window();
}

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

std::filesystem::path freshOutputDir(const std::string& name)
{
  const std::filesystem::path dir = testOutputDir() / name;
  std::filesystem::remove_all(dir);
  return dir;
}

RunResult runShadowlabInTempDir(const std::vector<std::string>& arguments)
{
  const TempDir workDir;
  return runShadowlabIn(arguments, workDir.path());
}

std::vector<std::string> wideKernelOverrides()
{
  return { "/lights/0/center/1=4", "/lights/0/size=2", "/objects/2/center=[0.2, 3.0, -0.4]", "/objects/2/size=[0.8, 0.6]" };
}

std::vector<std::string> sceneSetArguments(const std::vector<std::string>& overrides)
{
  std::vector<std::string> arguments;
  for (const std::string& assignment : overrides)
  {
    arguments.insert(arguments.end(), { "--scene-set", assignment });
  }
  return arguments;
}

std::vector<std::string> stackedRectangles(const std::vector<std::array<double, 5>>& rectangles, double lightHeight,
  double lightSize)
{
  std::vector<std::string> overrides = { "/lights/0/center/1=" + std::to_string(lightHeight), "/lights/0/size=" + std::to_string(lightSize) };
  for (std::size_t k = 0; k < rectangles.size(); ++k)
  {
    const auto& [x, y, z, width, depth] = rectangles[k];
    overrides.push_back("/objects/" + std::to_string(k + 1) + "={\"primitive\": \"quad\", \"center\": [" + std::to_string(x) + ", " +
      std::to_string(y) + ", " + std::to_string(z) + "], \"size\": [" + std::to_string(width) + ", " + std::to_string(depth) +
      "], \"normal\": [0, 1, 0], \"up\": [0, 0, -1]}");
  }
  return overrides;
}

std::vector<std::string> randomRectangleStack(std::mt19937& generator, int count)
{
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double lightHeight = 3.0 + 2.0 * unit(generator);
  std::vector<std::array<double, 5>> rectangles;
  for (int k = 0; k < count; ++k)
  {
    const double height = k + 1 == count ? lightHeight - 0.6 - 0.6 * unit(generator) : 0.3 + (lightHeight - 1.5) * unit(generator);
    // Braced lists evaluate left to right: the draws keep their order.
    rectangles.push_back({ 1.6 * unit(generator) - 0.8, height, 1.6 * unit(generator) - 0.8, 0.3 + 1.2 * unit(generator), 0.3 + 1.2 * unit(generator) });
  }
  const double lightSize = 1.0 + 2.0 * unit(generator);
  return stackedRectangles(rectangles, lightHeight, lightSize);
}

std::vector<std::string> borderClampedKernelOverrides()
{
  return { R"(/objects/2={"primitive": "quad", "center": [0.3, 2.85, 0], "size": [0.05, 0.05], "normal": [0, 1, 0], "up": [0, 0, -1]})" };
}

std::filesystem::path datasetPath(const std::string& name)
{
  return sourceDir() / "datasets" / name / "scene.json";
}

void appendTetrahedron(std::vector<glm::dvec3>& corners, const std::array<glm::dvec3, 4>& vertices)
{
  const glm::dvec3 centre = 0.25 * (vertices[0] + vertices[1] + vertices[2] + vertices[3]);
  const int faces[4][3] = { { 0, 1, 2 }, { 0, 3, 1 }, { 0, 2, 3 }, { 1, 3, 2 } };
  for (const auto& face : faces)
  {
    glm::dvec3 a = vertices[face[0]], b = vertices[face[1]], c = vertices[face[2]];
    if (glm::dot(glm::cross(b - a, c - a), a - centre) < 0.0)
    {
      std::swap(b, c);
    }
    corners.insert(corners.end(), { a, b, c });
  }
}

SceneObject flatObject(const std::string& name, const std::vector<glm::dvec3>& corners)
{
  SceneObject object;
  object.name = name;
  for (std::size_t first = 0; first + 2 < corners.size(); first += 3)
  {
    const glm::dvec3 normal =
      glm::normalize(glm::cross(corners[first + 1] - corners[first], corners[first + 2] - corners[first]));
    for (std::size_t corner = first; corner < first + 3; ++corner)
    {
      object.mesh.indices.push_back(static_cast<std::uint32_t>(object.mesh.positions.size()));
      object.mesh.positions.emplace_back(corners[corner]);
      object.mesh.normals.emplace_back(normal);
    }
  }
  return object;
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
    if (std::filesystem::is_regular_file(entry.path() / "scene.json") && entry.path().filename() != "facing-tiles")
    {
      names.push_back(entry.path().filename().string());
    }
  }
  std::sort(names.begin(), names.end());
  return names;
}

void PrintTo(const DatasetTechnique& pair, std::ostream* os)
{
  *os << pair.dataset << "/" << pair.technique;
}

const std::vector<std::string>& wallRingTechniques()
{
  static const std::vector<std::string> names = { "shadow-volume", "dcs", "vtk", "hard", "pcf", "izb" };
  return names;
}

bool rendersDataset(const std::string& technique, const std::string& dataset)
{
  const std::vector<std::string>& renderers = wallRingTechniques();
  return dataset != "wall-ring" || std::find(renderers.begin(), renderers.end(), technique) != renderers.end();
}

std::vector<DatasetTechnique> datasetTechniquePairs()
{
  // Evaluated when the parameterised suites register, in every gpu_tests process (one per ctest case): only the
  // datasets' lights matter, so each scene is parsed with its first object alone (a scene needs one; the datasets'
  // first is their ground quad), not with the bunny's or fence-meshed's tens of thousands of triangles, and only once
  // per process.
  static const std::vector<DatasetTechnique> pairs = [] {
    std::vector<DatasetTechnique> list;
    for (const std::string& dataset : datasetNames())
    {
      std::optional<Light> light;
      try
      {
        const std::filesystem::path file = sourceDir() / "datasets" / dataset / "scene.json";
        std::ifstream stream(file);
        nlohmann::json json = nlohmann::json::parse(stream);
        if (json.contains("objects") && json["objects"].is_array() && json["objects"].size() > 1)
        {
          json["objects"] = nlohmann::json::array({ json["objects"].front() });
        }
        const Scene scene = parseScene(json.dump(), file.string(), file.parent_path());
        if (!scene.lights.empty())
        {
          light = scene.lights.front();
        }
      }
      catch (const std::exception&)
      {
      }
      for (const TechniqueDescriptor& technique : techniqueRegistry())
      {
        if ((!light || technique.supports(*light)) && rendersDataset(technique.name, dataset))
        {
          list.push_back({ dataset, technique.name });
        }
      }
    }
    return list;
  }();
  return pairs;
}

std::vector<std::string> datasetsRenderedBy(const std::string& technique)
{
  std::vector<std::string> datasets;
  for (const DatasetTechnique& pair : datasetTechniquePairs())
  {
    if (pair.technique == technique)
    {
      datasets.push_back(pair.dataset);
    }
  }
  return datasets;
}

std::string datasetTechniqueName(const testing::TestParamInfo<DatasetTechnique>& info)
{
  std::string name = info.param.dataset + "_" + info.param.technique;
  std::replace_if(name.begin(), name.end(), [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); }, '_');
  return name;
}

Scene stackedOccludersUnder(const std::string& lightJson)
{
  const std::string text = R"({
    "camera": { "position": [0, 4.5, 3.5], "focal_point": [0, 0, 0], "view_angle": 35 },
    "lights": [ )" + lightJson + R"( ],
    "objects": [
      { "primitive": "quad", "size": [6, 6], "normal": [0, 1, 0], "up": [0, 0, -1] },
      { "primitive": "quad", "center": [-0.35, 0.6, 0], "size": [0.8, 0.8], "normal": [0, 1, 0], "up": [0, 0, -1] },
      { "primitive": "quad", "center": [0.35, 1.5, 0.1], "size": [0.8, 0.8], "normal": [0, 1, 0], "up": [0, 0, -1] },
      { "primitive": "sphere", "center": [1.2, 0.4, -0.6], "size": 0.4 }
    ] })";
  return parseScene(text, "stacked-occluders (test variant)", sourceDir());
}

double parallelSquaresVisibility(
  double lightSize, double lightHeight, double occluderSize, double occluderHeight, double x, double z)
{
  const auto overlap = [](double aMin, double aMax, double bMin, double bMax) {
    return std::max(0.0, std::min(aMax, bMax) - std::max(aMin, bMin));
  };
  const double scale = lightHeight / occluderHeight;
  const double centerX = x - x * scale;
  const double centerZ = z - z * scale;
  const double half = 0.5 * occluderSize * scale;
  const double lightHalf = 0.5 * lightSize;
  const double covered = overlap(centerX - half, centerX + half, -lightHalf, lightHalf) *
    overlap(centerZ - half, centerZ + half, -lightHalf, lightHalf);
  return 1.0 - covered / (lightSize * lightSize);
}

GroundError groundErrorAgainst(const FrameResult& frame, const std::function<double(double x, double z)>& exact)
{
  const ImageF& position = frame.find("position")->image;
  const ImageF& coverage = frame.find("coverage")->image;
  const ImageF& visibility = frame.find("visibility")->image;
  GroundError error;
  double squared = 0.0;
  double squaredPenumbra = 0.0;
  for (int y = 0; y < position.height; ++y)
  {
    for (int x = 0; x < position.width; ++x)
    {
      if (coverage.at(x, y) < 0.5f || std::abs(position.at(x, y, 1)) > 1e-4)
      {
        continue;
      }
      const double expected = exact(position.at(x, y, 0), position.at(x, y, 2));
      const double difference = visibility.at(x, y) - expected;
      squared += difference * difference;
      error.maxError = std::max(error.maxError, std::abs(difference));
      ++error.ground;
      if (expected > 0.0 && expected < 1.0)
      {
        squaredPenumbra += difference * difference;
        ++error.penumbra;
      }
    }
  }
  error.rmse = std::sqrt(squared / std::max(1, error.ground));
  error.penumbraRmse = std::sqrt(squaredPenumbra / std::max(1, error.penumbra));
  return error;
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

FrameResult renderSs08(const Scene& scene, int width, int height, const std::vector<std::string>& settings)
{
  std::vector<std::string> withDefaults = settings;
  const auto sets = [&](const std::string& key) {
    return std::any_of(settings.begin(), settings.end(), [&](const std::string& s) { return s.rfind(key + "=", 0) == 0; });
  };
  if (!sets("micro_occluder"))
  {
    withDefaults.insert(withDefaults.begin(), "micro_occluder=micropatch");
  }
  if (!sets("accumulation"))
  {
    withDefaults.insert(withDefaults.begin(), "accumulation=area");
  }
  return renderDataset(scene, "ss08", width, height, withDefaults);
}

std::vector<FrameResult> renderSampleGBuffers(const Scene& scene, int width, int height, int samples)
{
  RenderRequest request;
  request.resolution = glm::ivec2(width, height);
  return sharedRenderer().renderSampleGBuffers(scene, request, samples);
}

ReferenceInputs referenceInputs(const FrameResult& frame, const Scene& scene, int lightIndex)
{
  return referenceInputsOf(frame, scene, lightIndex);
}

std::string sixteenHoleMaskPng(const std::string& fileName)
{
  const std::filesystem::path path = testOutputDir() / fileName;
  ImageU8 mask(20, 20, 3);
  for (int y = 0; y < 20; ++y)
  {
    for (int x = 0; x < 20; ++x)
    {
      const bool hole = x % 5 >= 2 && x % 5 < 4 && y % 5 >= 2 && y % 5 < 4;
      for (int c = 0; c < 3; ++c)
      {
        mask.at(x, y, c) = hole ? 0 : 255;
      }
    }
  }
  writePng(path, mask);
  return path.string();
}

std::string caseLabel(const std::string& dataset, const std::vector<std::string>& settings)
{
  std::string label = dataset;
  for (const std::string& setting : settings)
  {
    label += " " + setting;
  }
  return label;
}

void expectFiniteBuffersAndVisibilityInRange(const FrameResult& frame, const std::string& label)
{
  for (const auto* list : { &frame.buffers, &frame.lightSpace })
  {
    for (const NamedImage& named : *list)
    {
      std::size_t bad = 0;
      for (const float value : named.image.data)
      {
        bad += std::isfinite(value) ? 0 : 1;
      }
      EXPECT_EQ(bad, 0u) << label << ": " << named.name;
    }
  }
  const NamedImage* visibility = frame.find("visibility");
  ASSERT_NE(visibility, nullptr) << label << ": no visibility buffer";
  std::size_t outside = 0;
  for (const float value : visibility->image.data)
  {
    outside += value >= 0.0f && value <= 1.0f ? 0 : 1;
  }
  EXPECT_EQ(outside, 0u) << label << ": visibility values outside [0, 1]";
}

void expectBuffersBitIdentical(const FrameResult& actual, const FrameResult& expected, const std::string& where)
{
  EXPECT_EQ(actual.buffers.size(), expected.buffers.size()) << where;
  for (std::size_t b = 0; b < std::min(actual.buffers.size(), expected.buffers.size()); ++b)
  {
    const NamedImage& mine = actual.buffers[b];
    const NamedImage& theirs = expected.buffers[b];
    EXPECT_EQ(mine.name, theirs.name) << where;
    EXPECT_EQ(mine.image.data.size(), theirs.image.data.size()) << where << " " << mine.name;
    std::size_t differing = 0;
    for (std::size_t i = 0; i < std::min(mine.image.data.size(), theirs.image.data.size()); ++i)
    {
      differing += mine.image.data[i] == theirs.image.data[i] ? 0 : 1;
    }
    EXPECT_EQ(differing, 0u) << where << ": buffer " << mine.name << " differs";
  }
}

void expectBuiltTexelsOfWhole(
  const FrameResult& actual, const FrameResult& whole, const std::string& name, const ImageF& builtMask, const std::string& where)
{
  const ImageF& mine = lightSpaceArray(actual, name);
  const ImageF& theirs = lightSpaceArray(whole, name);
  ASSERT_EQ(mine.data.size(), builtMask.data.size()) << where << ": " << name;
  ASSERT_EQ(theirs.data.size(), builtMask.data.size()) << where << ": " << name;
  std::size_t differing = 0;
  std::size_t nonZeroUnbuilt = 0;
  for (std::size_t i = 0; i < mine.data.size(); ++i)
  {
    if (builtMask.data[i] != 0.0f)
    {
      differing += mine.data[i] == theirs.data[i] ? 0 : 1;
    }
    else
    {
      nonZeroUnbuilt += mine.data[i] == 0.0f ? 0 : 1;
    }
  }
  EXPECT_EQ(differing, 0u) << where << ": " << name << " differs from whole_map on built texels";
  EXPECT_EQ(nonZeroUnbuilt, 0u) << where << ": " << name << " holds data on unbuilt texels";
}

int unbuiltLookupTexels(const FrameResult& frame, const ImageF& builtMask, int& lookups)
{
  const ImageF& tested = bufferOf(frame, "shadow_tested");
  const ImageF& position = bufferOf(frame, "position");
  const int mapSize = builtMask.width;
  lookups = 0;
  int unbuilt = 0;
  for (int y = 0; y < tested.height; ++y)
  {
    for (int x = 0; x < tested.width; ++x)
    {
      if (tested.at(x, y) < 0.5f)
      {
        continue;
      }
      const ShadowMapSample sample = projectToShadowMap(*frame.lightView, vec3At(position, x, y));
      const int texelX = std::clamp(static_cast<int>(std::floor(sample.uvTexels.x)), 0, mapSize - 1);
      const int texelY = std::clamp(static_cast<int>(std::floor(sample.uvTexels.y)), 0, mapSize - 1);
      ++lookups;
      unbuilt += builtMask.at(texelX, texelY) != 0.0f ? 0 : 1;
    }
  }
  return unbuilt;
}

const ImageF& lightSpaceArray(const FrameResult& frame, const std::string& name)
{
  const NamedImage* named = findNamed(frame.lightSpace, name);
  if (!named)
  {
    throw std::runtime_error("no light-space array " + name);
  }
  return named->image;
}

ImageF floatSummedAreaTable(const FrameResult& frame)
{
  const ImageF& sumZ = lightSpaceArray(frame, "sat_z");
  const ImageF& sumZ2 = lightSpaceArray(frame, "sat_z2");
  ImageF table(sumZ.width, sumZ.height, 2);
  for (std::size_t i = 0; i < sumZ.data.size(); ++i)
  {
    table.data[i * 2] = sumZ.data[i];
    table.data[i * 2 + 1] = sumZ2.data[i];
  }
  return table;
}

ShadowMapInputs shadowMapInputs(const FrameResult& frame, const Scene& scene, int lightIndex)
{
  return shadowMapInputsOf(frame, scene, lightIndex);
}

} // namespace sl::test
