// Tests of the scene module: scene.json parsing and validation, primitives, transforms, mesh and alpha
// texture loading, and the datasets shipped in datasets/. Bad-input files are written at run time into a
// fresh temporary directory per test.
#include "core/Error.h"
#include "scene/AlphaTexture.h"
#include "scene/MeshIO.h"
#include "scene/Primitives.h"
#include "scene/Scene.h"
#include "support/TempDir.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <future>
#include <limits>
#include <random>
#include <set>
#include <string>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace sl
{
namespace
{

namespace fs = std::filesystem;
using Json = nlohmann::json;

const fs::path kRepoRoot = SL_SOURCE_DIR;
const fs::path kDatasets = kRepoRoot / "datasets";

// ---- helpers --------------------------------------------------------------------------------------------

// A temporary directory that also writes binary files and scene JSON.
class SceneDir : public test::TempDir
{
public:
  using TempDir::write;
  fs::path write(const std::string& name, const std::vector<unsigned char>& bytes) const
  {
    return write(name, std::string(bytes.begin(), bytes.end()));
  }
  fs::path writeScene(const Json& scene, const std::string& name = "scene.json") const
  {
    return write(name, scene.dump(2));
  }
};

// One point light and one default quad: the smallest valid scene; tests mutate it.
Json minimalScene()
{
  return Json::parse(R"({
    "lights": [ { "type": "point", "center": [0, 3, 0] } ],
    "objects": [ { "primitive": "quad" } ]
  })");
}

// The message of the InputError that loading `file` throws ("" and a test failure when it throws none).
std::string loadError(const fs::path& file)
{
  try
  {
    loadScene(file);
  }
  catch (const InputError& error)
  {
    return error.what();
  }
  ADD_FAILURE() << "loading " << file << " did not throw InputError";
  return {};
}

// Loads `file`, expects an InputError whose single-line message starts with the file name and contains
// every one of `parts`.
void expectLoadError(const fs::path& file, const std::vector<std::string>& parts)
{
  const std::string message = loadError(file);
  EXPECT_EQ(message.rfind(file.string() + ": ", 0), 0u) << "message does not start with the file: " << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << "message is not one line: " << message;
  for (const std::string& part : parts)
    EXPECT_NE(message.find(part), std::string::npos) << "expected '" << part << "' in: " << message;
}

void expectSceneError(const Json& scene, const std::vector<std::string>& parts)
{
  const SceneDir dir;
  expectLoadError(dir.writeScene(scene), parts);
}

void expectSceneTextError(const std::string& text, const std::vector<std::string>& parts)
{
  const SceneDir dir;
  expectLoadError(dir.write("scene.json", text), parts);
}

double triangleArea(const TriangleMesh& mesh, std::size_t triangle)
{
  const glm::dvec3 a(mesh.positions[mesh.indices[3 * triangle]]);
  const glm::dvec3 b(mesh.positions[mesh.indices[3 * triangle + 1]]);
  const glm::dvec3 c(mesh.positions[mesh.indices[3 * triangle + 2]]);
  return 0.5 * glm::length(glm::cross(b - a, c - a));
}

// Unnormalised geometric normal from the winding (counter-clockwise = front).
glm::dvec3 windingNormal(const TriangleMesh& mesh, std::size_t triangle)
{
  const glm::dvec3 a(mesh.positions[mesh.indices[3 * triangle]]);
  const glm::dvec3 b(mesh.positions[mesh.indices[3 * triangle + 1]]);
  const glm::dvec3 c(mesh.positions[mesh.indices[3 * triangle + 2]]);
  return glm::cross(b - a, c - a);
}

double totalArea(const TriangleMesh& mesh)
{
  double area = 0.0;
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
    area += triangleArea(mesh, t);
  return area;
}

Bounds meshBounds(const TriangleMesh& mesh)
{
  Bounds bounds;
  for (const glm::vec3& p : mesh.positions)
    bounds.extend(glm::dvec3(p));
  return bounds;
}

void expectNear(const glm::dvec3& actual, const glm::dvec3& expected, double tolerance, const std::string& what)
{
  EXPECT_LE(glm::length(actual - expected), tolerance)
    << what << ": got (" << actual.x << ", " << actual.y << ", " << actual.z << "), expected (" << expected.x
    << ", " << expected.y << ", " << expected.z << ")";
}

// Every index in range, every normal unit, counts consistent.
void expectWellFormed(const TriangleMesh& mesh)
{
  ASSERT_EQ(mesh.indices.size() % 3, 0u);
  ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
  ASSERT_TRUE(mesh.uvs.empty() || mesh.uvs.size() == mesh.positions.size());
  for (const std::uint32_t index : mesh.indices)
    ASSERT_LT(index, mesh.positions.size());
  for (std::size_t v = 0; v < mesh.normals.size(); ++v)
    ASSERT_NEAR(glm::length(glm::dvec3(mesh.normals[v])), 1.0, 1e-5) << "vertex " << v;
}

// ---- minimal file encoders, independent of the code under test ----------------------------------------

void appendBigEndian32(std::vector<unsigned char>& out, std::uint32_t value)
{
  for (int shift = 24; shift >= 0; shift -= 8)
    out.push_back(static_cast<unsigned char>(value >> shift));
}

std::uint32_t testCrc32(const unsigned char* bytes, std::size_t count)
{
  std::uint32_t crc = 0xFFFFFFFFu;
  for (std::size_t i = 0; i < count; ++i)
  {
    crc ^= bytes[i];
    for (int bit = 0; bit < 8; ++bit)
      crc = (crc & 1u) ? (crc >> 1) ^ 0xEDB88320u : crc >> 1;
  }
  return ~crc;
}

void appendChunk(std::vector<unsigned char>& png, const char* type, const std::vector<unsigned char>& data)
{
  appendBigEndian32(png, static_cast<std::uint32_t>(data.size()));
  std::vector<unsigned char> typeAndData(type, type + 4);
  typeAndData.insert(typeAndData.end(), data.begin(), data.end());
  png.insert(png.end(), typeAndData.begin(), typeAndData.end());
  appendBigEndian32(png, testCrc32(typeAndData.data(), typeAndData.size()));
}

// An 8-bit PNG (color type 0 gray, 2 RGB, 4 gray+alpha, 6 RGBA) with rows given TOP row first, as PNG
// stores them; compressed with zlib "stored" blocks so no zlib is needed here.
std::vector<unsigned char> encodePng(int width, int height, int colorType,
  const std::vector<std::vector<unsigned char>>& rowsTopFirst)
{
  std::vector<unsigned char> raw;
  for (const auto& row : rowsTopFirst)
  {
    raw.push_back(0); // filter type None
    raw.insert(raw.end(), row.begin(), row.end());
  }
  std::vector<unsigned char> zlib = { 0x78, 0x01 };
  zlib.push_back(1); // final block, stored
  const auto length = static_cast<std::uint16_t>(raw.size());
  zlib.push_back(static_cast<unsigned char>(length & 0xFF));
  zlib.push_back(static_cast<unsigned char>(length >> 8));
  zlib.push_back(static_cast<unsigned char>(~length & 0xFF));
  zlib.push_back(static_cast<unsigned char>((~length >> 8) & 0xFF));
  zlib.insert(zlib.end(), raw.begin(), raw.end());
  std::uint32_t a = 1, b = 0; // Adler-32
  for (const unsigned char byte : raw)
  {
    a = (a + byte) % 65521u;
    b = (b + a) % 65521u;
  }
  appendBigEndian32(zlib, (b << 16) | a);

  std::vector<unsigned char> png = { 0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n' };
  std::vector<unsigned char> header;
  appendBigEndian32(header, static_cast<std::uint32_t>(width));
  appendBigEndian32(header, static_cast<std::uint32_t>(height));
  header.insert(header.end(), { 8, static_cast<unsigned char>(colorType), 0, 0, 0 });
  appendChunk(png, "IHDR", header);
  appendChunk(png, "IDAT", zlib);
  appendChunk(png, "IEND", {});
  return png;
}

// A binary little-endian PLY (so NaN coordinates can be stored) with triangles only.
std::string binaryPly(const std::vector<glm::vec3>& vertices, const std::vector<std::array<int, 3>>& triangles)
{
  std::string ply = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(vertices.size()) +
    "\nproperty float x\nproperty float y\nproperty float z\nelement face " + std::to_string(triangles.size()) +
    "\nproperty list uchar int vertex_indices\nend_header\n";
  static_assert(sizeof(float) == 4 && sizeof(int) == 4, "PLY float/int are 32-bit");
  const auto appendBytes = [&ply](const void* data, std::size_t size) {
    ply.append(static_cast<const char*>(data), size); // x86/ARM little-endian hosts
  };
  for (const glm::vec3& v : vertices)
    appendBytes(&v[0], 3 * sizeof(float));
  for (const auto& triangle : triangles)
  {
    const unsigned char count = 3;
    appendBytes(&count, 1);
    appendBytes(triangle.data(), 3 * sizeof(int));
  }
  return ply;
}

// Three triangles that are each degenerate in a different way: collinear corners, coincident corners, and a
// needle (area below MeshIO's 1e-10 of the longest edge squared). They use their own vertices, so dropping them
// leaves those vertices unused. (A NaN corner is not dropped but refused by the mesh reader.)
void addDegenerateTriangles(std::vector<glm::vec3>& vertices, std::vector<std::array<int, 3>>& triangles)
{
  const int first = static_cast<int>(vertices.size());
  vertices.insert(vertices.end(), { { 2, 0, 0 }, { 3, 0, 0 }, { 4, 0, 0 } });       // collinear
  vertices.insert(vertices.end(), { { 5, 5, 5 }, { 5, 5, 5 }, { 5, 5, 5 } });       // one point
  vertices.insert(vertices.end(), { { 6, 0, 0 }, { 8, 0, 0 }, { 7, 1e-11f, 0 } });  // needle
  triangles.push_back({ first, first + 1, first + 2 });
  triangles.push_back({ first + 3, first + 4, first + 5 });
  triangles.push_back({ first + 6, first + 7, first + 8 });
}

// ---- datasets -------------------------------------------------------------------------------------------

const std::vector<std::string> kExpectedDatasets = { "bunny", "planar-occluder", "near-light", "contact",
  "stacked-occluders", "grazing", "fence", "fence-meshed", "sphere-point", "deep-view", "deep-view-behind",
  "wall-ring" };

TEST(SceneDatasets, AllExpectedDatasetsExistAndLoad)
{
  std::set<std::string> found;
  for (const fs::directory_entry& entry : fs::directory_iterator(kDatasets))
  {
    const fs::path sceneFile = entry.path() / "scene.json";
    if (!fs::exists(sceneFile))
      continue;
    found.insert(entry.path().filename().string());
    SCOPED_TRACE(sceneFile.string());
    Scene scene;
    ASSERT_NO_THROW(scene = loadScene(sceneFile));
    EXPECT_EQ(scene.file, sceneFile);
    EXPECT_FALSE(scene.lights.empty());
    EXPECT_FALSE(scene.objects.empty());
    // facing-tiles lays its tiles along the horizon (Fig. 12's closed forms are stated on the view axis): 4:1.
    EXPECT_EQ(scene.camera.resolution,
      entry.path().filename() == "facing-tiles" ? glm::ivec2(1024, 256) : glm::ivec2(512, 512));
    EXPECT_TRUE(fs::exists(entry.path() / "SOURCE.md"));
    for (const SceneObject& object : scene.objects)
    {
      SCOPED_TRACE(object.name);
      expectWellFormed(object.mesh);
      EXPECT_GT(object.mesh.triangleCount(), 0u);
    }
  }
  for (const std::string& name : kExpectedDatasets)
    EXPECT_EQ(found.count(name), 1u) << "dataset " << name << " missing or has no scene.json";
}

// Every dataset: the camera sees the ground's front face and every object; area/spot lights face the scene.
TEST(SceneDatasets, ObjectsVisibleAndLightsFaceTheScene)
{
  for (const std::string& name : kExpectedDatasets)
  {
    SCOPED_TRACE(name);
    const Scene scene = loadScene(kDatasets / name / "scene.json");
    const Camera& camera = scene.camera;
    ASSERT_EQ(camera.projection, Projection::Perspective);
    const glm::dmat4 clipFromWorld =
      glm::perspective(glm::radians(camera.viewAngleDeg),
        static_cast<double>(camera.resolution.x) / camera.resolution.y, 0.01, 100.0) *
      glm::lookAt(camera.position, camera.focalPoint, camera.viewUp);
    const auto inView = [&](const glm::dvec3& pWs) {
      const glm::dvec4 clip = clipFromWorld * glm::dvec4(pWs, 1.0);
      return clip.w > 0.0 && std::abs(clip.x) <= clip.w && std::abs(clip.y) <= clip.w;
    };

    // objects[0] is the ground in every dataset (6 x 6; deep-view's 60 x 300, wall-ring's disk): larger than the
    // view, so only its center must show, and the camera must be on its front (+y) side.
    ASSERT_GE(scene.objects.size(), 2u);
    EXPECT_GT(camera.position.y, 0.0);
    EXPECT_TRUE(inView(meshBounds(scene.objects[0].mesh).center()));
    for (std::size_t i = 1; i < scene.objects.size(); ++i)
    {
      const Bounds bounds = meshBounds(scene.objects[i].mesh);
      for (int corner = 0; corner < 8; ++corner)
      {
        const glm::dvec3 p{ (corner & 1) ? bounds.max.x : bounds.min.x, (corner & 2) ? bounds.max.y : bounds.min.y,
          (corner & 4) ? bounds.max.z : bounds.min.z };
        EXPECT_TRUE(inView(p)) << scene.objects[i].name << " bounds corner " << corner << " (" << p.x << ", " << p.y
                               << ", " << p.z << ") outside the view";
      }
    }

    const glm::dvec3 sceneCenter = scene.bounds().center();
    for (const Light& light : scene.lights)
    {
      EXPECT_GT(light.center.y, 0.0);
      if (light.type == LightType::Area || light.type == LightType::Spot)
      {
        EXPECT_GT(glm::dot(light.normal, sceneCenter - light.center), 0.0) << "light faces away from the scene";
      }
      if (light.type == LightType::Area)
      {
        EXPECT_NEAR(glm::length(light.normal), 1.0, 1e-12);
        EXPECT_NEAR(glm::length(light.up), 1.0, 1e-12);
        EXPECT_NEAR(glm::dot(light.up, light.normal), 0.0, 1e-12);
      }
    }
  }
}

// The generated sampling-error datasets (datasets/generator) are the configurations their SOURCE.md names: the deep
// view's light perpendicular to the (horizontal) view, as in the survey's Fig. 12; the variant's light behind the
// viewer, 15 degrees off the view direction (Fig. 14-15); wall-ring's point light enclosed by its walls.
// facing-tiles (the survey's Fig. 12): a horizontal view, the light straight down (view ⟂ light), every tile inside
// the 4:1 view, facing the bisector of the directions to the eye and to the light (Eq. 1's cos(alpha) = cos(beta)),
// and the nearest and farthest tile corners at eye depth 1 and 100.
TEST(SceneDatasets, FacingTilesIsFig12sConfiguration)
{
  const Scene scene = loadScene(kDatasets / "facing-tiles" / "scene.json");
  const Camera& camera = scene.camera;
  ASSERT_EQ(scene.lights.size(), 1u);
  EXPECT_EQ(scene.lights[0].type, LightType::Directional);
  EXPECT_NEAR(glm::dot(glm::normalize(scene.lights[0].direction), glm::dvec3(0, -1, 0)), 1.0, 1e-12);
  EXPECT_NEAR(camera.focalPoint.y - camera.position.y, 0.0, 1e-12);
  const glm::dmat4 viewFromWorld = glm::lookAt(camera.position, camera.focalPoint, camera.viewUp);
  const glm::dmat4 clipFromWorld = glm::perspective(glm::radians(camera.viewAngleDeg),
    static_cast<double>(camera.resolution.x) / camera.resolution.y, 0.01, 1000.0) * viewFromWorld;
  ASSERT_EQ(scene.objects.size(), 20u);
  double nearest = 1e30, farthest = 0.0;
  for (const SceneObject& object : scene.objects)
  {
    const TriangleMesh& mesh = object.mesh;
    const glm::dvec3 centre = meshBounds(mesh).center();
    const glm::dvec3 toEye = glm::normalize(camera.position - centre);
    const glm::dvec3 normal = glm::normalize(glm::dvec3(mesh.normals.front()));
    EXPECT_NEAR(glm::dot(normal, toEye), glm::dot(normal, glm::dvec3(0, 1, 0)), 2e-3) << object.name;
    for (const glm::vec3& p : mesh.positions)
    {
      const glm::dvec4 clip = clipFromWorld * glm::dvec4(glm::dvec3(p), 1.0);
      EXPECT_TRUE(clip.w > 0.0 && std::abs(clip.x) <= clip.w && std::abs(clip.y) <= clip.w) << object.name;
      const double depth = -(viewFromWorld * glm::dvec4(glm::dvec3(p), 1.0)).z;
      nearest = std::min(nearest, depth);
      farthest = std::max(farthest, depth);
    }
  }
  EXPECT_NEAR(nearest, 1.0, 2e-3);
  EXPECT_NEAR(farthest, 100.0, 0.05);
}

TEST(SceneDatasets, SamplingDatasetsHaveTheirLightConfigurations)
{
  const Scene deep = loadScene(kDatasets / "deep-view" / "scene.json");
  const Scene behind = loadScene(kDatasets / "deep-view-behind" / "scene.json");
  for (const Scene* scene : { &deep, &behind })
  {
    ASSERT_EQ(scene->lights.size(), 1u);
    ASSERT_EQ(scene->lights[0].type, LightType::Directional);
    EXPECT_EQ(scene->camera.position, glm::dvec3(0.0, 1.7, 0.0)); // eye height
    EXPECT_EQ(scene->camera.focalPoint.y, scene->camera.position.y);
  }
  const glm::dvec3 view = glm::normalize(deep.camera.focalPoint - deep.camera.position);
  const glm::dvec3 overhead = glm::normalize(deep.lights[0].direction);
  EXPECT_NEAR(glm::dot(view, overhead), 0.0, 1e-15);
  EXPECT_GT(-overhead.y, std::cos(glm::radians(35.0))) << "the light should come from within 35 degrees of overhead";
  const double behindDeg = glm::degrees(std::acos(glm::dot(view, glm::normalize(behind.lights[0].direction))));
  EXPECT_NEAR(behindDeg, 15.07, 0.01);
  // The same geometry under both lights.
  ASSERT_EQ(deep.objects.size(), behind.objects.size());
  for (std::size_t i = 0; i < deep.objects.size(); ++i)
  {
    EXPECT_EQ(meshBounds(deep.objects[i].mesh).min, meshBounds(behind.objects[i].mesh).min) << i;
    EXPECT_EQ(meshBounds(deep.objects[i].mesh).max, meshBounds(behind.objects[i].mesh).max) << i;
  }

  // wall-ring: the ten walls turn all the way around the light (every azimuth hits a wall or one of its ten gaps,
  // each gap narrower than a wall), and they stand taller than the light, so receivers lie in every direction.
  const Scene ring = loadScene(kDatasets / "wall-ring" / "scene.json");
  ASSERT_EQ(ring.lights[0].type, LightType::Point);
  const glm::dvec3 light = ring.lights[0].center;
  std::vector<double> azimuths;
  for (const SceneObject& object : ring.objects)
  {
    const Bounds bounds = meshBounds(object.mesh);
    const glm::dvec3 center = bounds.center();
    const double distance = glm::length(glm::dvec2(center.x - light.x, center.z - light.z));
    if (distance > 3.5 && distance < 4.5)
    {
      EXPECT_GT(bounds.max.y, light.y + 0.4);
      azimuths.push_back(glm::degrees(std::atan2(center.z - light.z, center.x - light.x)));
    }
  }
  ASSERT_EQ(azimuths.size(), 10u);
  std::sort(azimuths.begin(), azimuths.end());
  for (std::size_t i = 0; i < azimuths.size(); ++i)
  {
    const double next = i + 1 < azimuths.size() ? azimuths[i + 1] : azimuths[0] + 360.0;
    EXPECT_NEAR(next - azimuths[i], 36.0, 0.01); // positions rounded to 1e-4 in the file
  }
}

TEST(SceneDatasets, BunnyLoadsFromPlyWithTransform)
{
  const Scene scene = loadScene(kDatasets / "bunny" / "scene.json");
  ASSERT_EQ(scene.objects.size(), 2u);
  const SceneObject& bunny = scene.objects[1];
  EXPECT_EQ(bunny.name, "objects[1] (mesh bunny.ply)");
  EXPECT_EQ(bunny.mesh.triangleCount(), 3674u);
  EXPECT_EQ(bunny.mesh.positions.size(), 1839u);
  EXPECT_EQ(bunny.droppedDegenerateTriangles, 0u);
  EXPECT_TRUE(bunny.mesh.uvs.empty());
  EXPECT_EQ(bunny.material.albedo, glm::dvec3(0.85, 0.75, 0.6));

  // File extents x[-4.958, 4.949] y[-0.00315, 9.655] z[-3.730, 3.811], scaled by 0.1, lifted by 0.00032.
  const Bounds bounds = meshBounds(bunny.mesh);
  expectNear(bounds.min, { -0.4958475, -0.0003149 + 0.00032, -0.3729833 }, 1e-6, "bunny min");
  expectNear(bounds.max, { 0.494885, 0.9654748 + 0.00032, 0.3810639 }, 1e-6, "bunny max");
  EXPECT_GE(bounds.min.y, 0.0) << "the bunny must rest on, not sink into, the ground";

  // The scene's light: normal normalised toward the origin, default up = +y projected onto the light plane.
  const Light& light = scene.lights[0];
  expectNear(light.normal, glm::normalize(glm::dvec3(-0.8, -3.0, -0.8)), 1e-12, "light normal");
  const glm::dvec3 worldY{ 0, 1, 0 };
  expectNear(light.up, glm::normalize(worldY - glm::dot(worldY, light.normal) * light.normal), 1e-12, "light up");
  EXPECT_DOUBLE_EQ(light.area(), 0.36);
}

TEST(SceneDatasets, FenceUsesProceduralAlpha)
{
  const Scene scene = loadScene(kDatasets / "fence" / "scene.json");
  const SceneObject& canopy = scene.objects[1];
  ASSERT_TRUE(canopy.hasAlphaTexture);
  EXPECT_EQ(canopy.alphaTexture.source, "fence");
  EXPECT_EQ(canopy.alphaTexture.alpha.width, kProceduralAlphaSize);
  EXPECT_EQ(canopy.mesh.uvs.size(), canopy.mesh.positions.size());
  EXPECT_FALSE(scene.objects[0].hasAlphaTexture);
}

// ---- defaults -------------------------------------------------------------------------------------------

TEST(SceneDefaults, MinimalSceneGetsDocumentedDefaults)
{
  const SceneDir dir;
  const Scene scene = loadScene(dir.writeScene(minimalScene()));
  const Camera& camera = scene.camera;
  EXPECT_EQ(camera.projection, Projection::Perspective);
  EXPECT_EQ(camera.position, glm::dvec3(0, 0, 5));
  EXPECT_EQ(camera.focalPoint, glm::dvec3(0, 0, 0));
  EXPECT_EQ(camera.viewUp, glm::dvec3(0, 1, 0));
  EXPECT_EQ(camera.viewAngleDeg, 30.0);
  EXPECT_EQ(camera.parallelScale, 1.0);
  EXPECT_EQ(camera.resolution, glm::ivec2(512, 512));

  ASSERT_EQ(scene.lights.size(), 1u);
  EXPECT_EQ(scene.lights[0].type, LightType::Point);
  EXPECT_EQ(scene.lights[0].intensity, 1.0);
  EXPECT_EQ(scene.lights[0].area(), 0.0);

  ASSERT_EQ(scene.objects.size(), 1u);
  const SceneObject& quad = scene.objects[0];
  EXPECT_EQ(quad.name, "objects[0] (quad)");
  EXPECT_EQ(quad.material.albedo, glm::dvec3(0.8, 0.8, 0.8));
  EXPECT_TRUE(quad.castShadows);
  EXPECT_TRUE(quad.receiveShadows);
  EXPECT_FALSE(quad.hasAlphaTexture);
  // Default quad: 1 x 1 at the origin, normal +z, up = +y (world +y projected onto the xy plane).
  EXPECT_NEAR(totalArea(quad.mesh), 1.0, 1e-12);
  for (const glm::vec3& normal : quad.mesh.normals)
    EXPECT_EQ(normal, glm::vec3(0, 0, 1));
  const Bounds bounds = meshBounds(quad.mesh);
  expectNear(bounds.min, { -0.5, -0.5, 0 }, 1e-12, "quad min");
  expectNear(bounds.max, { 0.5, 0.5, 0 }, 1e-12, "quad max");
}

TEST(SceneDefaults, AreaLightUpRule)
{
  Json json = minimalScene();
  json["lights"] = Json::parse(R"([
    { "type": "area", "center": [0, 3, 0], "normal": [0, -2, 0], "size": 1 },
    { "type": "area", "center": [3, 3, 0], "normal": [-1, -1, 0], "size": 1 },
    { "type": "area", "center": [0, 3, 0], "normal": [0, -1, 0], "up": [0, 1, 1], "size": 2, "shape": "disk" }
  ])");
  const SceneDir dir;
  const Scene scene = loadScene(dir.writeScene(json));
  ASSERT_EQ(scene.lights.size(), 3u);

  // Normal parallel to +y: the rule falls back to +x.
  expectNear(scene.lights[0].normal, { 0, -1, 0 }, 0.0, "normalised normal");
  expectNear(scene.lights[0].up, { 1, 0, 0 }, 1e-12, "up when +y is parallel to the normal");
  EXPECT_EQ(scene.lights[0].shape, LightShape::Square);
  EXPECT_EQ(scene.lights[0].intensity, 1.0);
  EXPECT_DOUBLE_EQ(scene.lights[0].area(), 1.0);
  // Oblique normal: +y projected onto the plane.
  expectNear(scene.lights[1].up, glm::normalize(glm::dvec3(-1, 1, 0)), 1e-12, "+y projected");
  // A given up is orthogonalised against the normal and normalised.
  expectNear(scene.lights[2].up, { 0, 0, 1 }, 1e-12, "orthogonalised up");
  EXPECT_EQ(scene.lights[2].shape, LightShape::Disk);
  EXPECT_NEAR(scene.lights[2].area(), glm::pi<double>(), 1e-12); // diameter 2
  expectNear(scene.lights[2].right(), glm::cross(scene.lights[2].up, scene.lights[2].normal), 1e-12, "right");
}

TEST(SceneDefaults, OtherLightTypesAndOrthographicCamera)
{
  Json json = minimalScene();
  json["camera"] = Json::parse(R"({ "projection": "orthographic", "parallel_scale": 2.5, "resolution": [640, 480] })");
  json["lights"] = Json::parse(R"([
    { "type": "directional", "direction": [0, -3, 0], "intensity": 2 },
    { "type": "spot", "center": [1, 2, 3], "normal": [0, 0, -5], "cone_angle_deg": 20 }
  ])");
  const SceneDir dir;
  const Scene scene = loadScene(dir.writeScene(json));
  EXPECT_EQ(scene.camera.projection, Projection::Orthographic);
  EXPECT_EQ(scene.camera.parallelScale, 2.5);
  EXPECT_EQ(scene.camera.resolution, glm::ivec2(640, 480));
  EXPECT_EQ(scene.lights[0].type, LightType::Directional);
  expectNear(scene.lights[0].direction, { 0, -1, 0 }, 1e-15, "directional normalised");
  EXPECT_EQ(scene.lights[0].intensity, 2.0);
  EXPECT_EQ(scene.lights[1].type, LightType::Spot);
  expectNear(scene.lights[1].normal, { 0, 0, -1 }, 1e-15, "spot normalised");
  EXPECT_EQ(scene.lights[1].coneAngleDeg, 20.0);
}

TEST(SceneDefaults, BoundsAndCasterBounds)
{
  Json json = minimalScene();
  json["objects"] = Json::parse(R"([
    { "primitive": "box", "center": [0, 0, 0], "size": [2, 2, 2] },
    { "primitive": "sphere", "center": [10, 0, 0], "size": 1, "cast_shadows": false, "receive_shadows": false }
  ])");
  const SceneDir dir;
  const Scene scene = loadScene(dir.writeScene(json));
  EXPECT_FALSE(scene.objects[1].castShadows);
  EXPECT_FALSE(scene.objects[1].receiveShadows);
  expectNear(scene.bounds().min, { -1, -1, -1 }, 1e-6, "bounds min");
  expectNear(scene.bounds().max, { 11, 1, 1 }, 1e-6, "bounds max");
  expectNear(scene.casterBounds().max, { 1, 1, 1 }, 1e-6, "caster bounds exclude the non-caster");
  EXPECT_TRUE(Scene{}.bounds().empty());
}

// ---- primitives -----------------------------------------------------------------------------------------

TEST(Primitives, QuadAreaNormalWindingAndUvs)
{
  const glm::dvec3 normal = glm::normalize(glm::dvec3(1, 2, 3));
  const glm::dvec3 up = defaultUp(normal);
  const TriangleMesh quad = makeQuad({ 1, 2, 3 }, { 2.5, 0.75 }, normal, up);
  expectWellFormed(quad);
  EXPECT_EQ(quad.triangleCount(), 2u);
  EXPECT_EQ(quad.positions.size(), 4u);
  EXPECT_NEAR(totalArea(quad), 2.5 * 0.75, 1e-6);
  const glm::dvec3 right = glm::normalize(glm::cross(up, normal));
  for (std::size_t t = 0; t < quad.triangleCount(); ++t)
    EXPECT_NEAR(glm::dot(glm::normalize(windingNormal(quad, t)), normal), 1.0, 1e-6) << "triangle " << t;
  for (std::size_t v = 0; v < quad.positions.size(); ++v)
  {
    expectNear(glm::dvec3(quad.normals[v]), normal, 1e-6, "quad normal");
    // u runs along right over size.x, v along up over size.y, (0.5, 0.5) at the center.
    const glm::dvec3 offset = glm::dvec3(quad.positions[v]) - glm::dvec3(1, 2, 3);
    EXPECT_NEAR(quad.uvs[v].x, 0.5 + glm::dot(offset, right) / 2.5, 1e-6);
    EXPECT_NEAR(quad.uvs[v].y, 0.5 + glm::dot(offset, up) / 0.75, 1e-6);
  }
}

TEST(Primitives, BoxHas12OutwardTrianglesWithFlatNormals)
{
  const glm::dvec3 center{ 0.5, -1, 2 };
  const TriangleMesh box = makeBox(center, { 1, 2, 3 });
  expectWellFormed(box);
  EXPECT_EQ(box.triangleCount(), 12u);
  EXPECT_EQ(box.positions.size(), 24u);
  EXPECT_NEAR(totalArea(box), 2 * (1 * 2 + 2 * 3 + 1 * 3), 1e-5);
  for (std::size_t t = 0; t < box.triangleCount(); ++t)
  {
    const glm::dvec3 faceNormal = glm::normalize(windingNormal(box, t));
    glm::dvec3 centroid{ 0.0 };
    for (int corner = 0; corner < 3; ++corner)
    {
      const std::uint32_t v = box.indices[3 * t + corner];
      expectNear(glm::dvec3(box.normals[v]), faceNormal, 1e-6, "flat normal matches winding");
      centroid += glm::dvec3(box.positions[v]) / 3.0;
    }
    EXPECT_GT(glm::dot(faceNormal, centroid - center), 0.0) << "triangle " << t << " faces inward";
  }
  const Bounds bounds = meshBounds(box);
  expectNear(bounds.min, { 0, -2, 0.5 }, 1e-6, "box min");
  expectNear(bounds.max, { 1, 0, 3.5 }, 1e-6, "box max");
  for (const glm::vec2& uv : box.uvs)
    EXPECT_TRUE(uv.x >= 0 && uv.x <= 1 && uv.y >= 0 && uv.y <= 1);
}

TEST(Primitives, SphereNormalsUnitOutwardAndTessellation)
{
  const glm::dvec3 center{ 1, 2, -3 };
  const double radius = 0.5;
  const TriangleMesh sphere = makeSphere(center, radius);
  expectWellFormed(sphere);
  // Interior bands are two triangles per segment, the two pole bands one.
  EXPECT_EQ(sphere.triangleCount(), static_cast<std::size_t>(2 * kSphereSegments * (kSphereRings - 1)));
  for (std::size_t v = 0; v < sphere.positions.size(); ++v)
  {
    const glm::dvec3 offset = glm::dvec3(sphere.positions[v]) - center;
    ASSERT_NEAR(glm::length(offset), radius, 1e-6) << "vertex " << v;
    expectNear(glm::dvec3(sphere.normals[v]), offset / radius, 1e-6, "smooth normal = outward radial");
    ASSERT_TRUE(sphere.uvs[v].x >= 0 && sphere.uvs[v].x <= 1 && sphere.uvs[v].y >= 0 && sphere.uvs[v].y <= 1);
  }
  for (std::size_t t = 0; t < sphere.triangleCount(); ++t)
  {
    const glm::dvec3 a(sphere.positions[sphere.indices[3 * t]]);
    ASSERT_GT(triangleArea(sphere, t), 0.0) << "degenerate triangle " << t;
    ASSERT_GT(glm::dot(windingNormal(sphere, t), a - center), 0.0) << "triangle " << t << " winds inward";
  }
  // Inscribed polyhedron: area slightly below 4 pi r^2.
  const double sphereArea = 4.0 * glm::pi<double>() * radius * radius;
  EXPECT_LT(totalArea(sphere), sphereArea);
  EXPECT_GT(totalArea(sphere), 0.99 * sphereArea);
}

TEST(Primitives, DiskFanPlanarUvs)
{
  const glm::dvec3 normal{ 0, 1, 0 };
  const glm::dvec3 up{ 0, 0, -1 };
  const TriangleMesh disk = makeDisk({ 0, 1, 0 }, 2.0, normal, up);
  expectWellFormed(disk);
  EXPECT_EQ(disk.triangleCount(), static_cast<std::size_t>(kDiskSegments));
  const double polygonArea = 0.5 * kDiskSegments * 4.0 * std::sin(glm::two_pi<double>() / kDiskSegments);
  EXPECT_NEAR(totalArea(disk), polygonArea, 1e-5);
  for (std::size_t t = 0; t < disk.triangleCount(); ++t)
    EXPECT_NEAR(glm::dot(glm::normalize(windingNormal(disk, t)), normal), 1.0, 1e-6);
  const glm::dvec3 right = glm::cross(up, normal); // +x
  for (std::size_t v = 0; v < disk.positions.size(); ++v)
  {
    const glm::dvec3 local = glm::dvec3(disk.positions[v]) - glm::dvec3(0, 1, 0);
    EXPECT_NEAR(disk.uvs[v].x, (glm::dot(local, right) + 2.0) / 4.0, 1e-6);
    EXPECT_NEAR(disk.uvs[v].y, (glm::dot(local, up) + 2.0) / 4.0, 1e-6);
  }
}

TEST(Primitives, UpHelpers)
{
  expectNear(defaultUp({ 0, 1, 0 }), { 1, 0, 0 }, 0.0, "+y normal");
  expectNear(defaultUp({ 0, -1, 0 }), { 1, 0, 0 }, 0.0, "-y normal");
  expectNear(defaultUp({ 0, 0, 1 }), { 0, 1, 0 }, 0.0, "+z normal");
  EXPECT_TRUE(isParallel({ 0, 2, 0 }, { 0, -1, 0 }));
  EXPECT_FALSE(isParallel({ 0, 1, 0.01 }, { 0, 1, 0 }));
}

// ---- transforms -----------------------------------------------------------------------------------------

// Finds, for each expected point, a vertex within 1e-6.
void expectVerticesAt(const TriangleMesh& mesh, const std::vector<glm::dvec3>& expected)
{
  ASSERT_EQ(mesh.positions.size(), expected.size());
  for (const glm::dvec3& point : expected)
  {
    double nearest = 1e300;
    for (const glm::vec3& p : mesh.positions)
      nearest = std::min(nearest, glm::length(glm::dvec3(p) - point));
    EXPECT_LT(nearest, 1e-6) << "no vertex at (" << point.x << ", " << point.y << ", " << point.z << ")";
  }
}

TEST(Transforms, RotateXThenYThenZ)
{
  Json json = minimalScene();
  json["objects"][0] = Json::parse(R"({ "primitive": "quad", "size": [2, 2], "normal": [0, 0, 1], "up": [0, 1, 0],
    "transform": { "translate": [1, 2, 3], "rotate_deg": [90, 90, 0], "scale": 2 } })");
  const SceneDir dir;
  const Scene scene = loadScene(dir.writeScene(json));
  const TriangleMesh& mesh = scene.objects[0].mesh;
  // R = Ry(90) * Rx(90): Rx(90) takes (x, y, z) to (x, -z, y), then Ry(90) takes that to (y, -z, -x).
  // (Rx * Ry would give (z, x, y) instead.) p_world = t + R * (2 p).
  const auto expected = [](const glm::dvec3& p) { return glm::dvec3(1, 2, 3) + 2.0 * glm::dvec3(p.y, -p.z, -p.x); };
  expectVerticesAt(
    mesh, { expected({ -1, -1, 0 }), expected({ 1, -1, 0 }), expected({ 1, 1, 0 }), expected({ -1, 1, 0 }) });
  for (const glm::vec3& normal : mesh.normals)
    expectNear(glm::dvec3(normal), { 0, -1, 0 }, 1e-6, "normal rotated like a direction");
}

TEST(Transforms, PrimitiveIsPlacedAtItsCenterBeforeTheTransform)
{
  Json json = minimalScene();
  json["objects"][0] = Json::parse(R"({ "primitive": "quad", "center": [1, 0, 0], "size": [1, 1],
    "transform": { "scale": [2, 3, 1], "rotate_deg": [0, 0, 90] } })");
  const SceneDir dir;
  const Scene scene = loadScene(dir.writeScene(json));
  // Scale about the world origin: center (1,0,0) -> (2,0,0); Rz(90): (x, y) -> (-y, x).
  const auto expected = [](const glm::dvec3& p) {
    const glm::dvec3 scaled{ 2 * p.x, 3 * p.y, p.z };
    return glm::dvec3(-scaled.y, scaled.x, scaled.z);
  };
  expectVerticesAt(scene.objects[0].mesh,
    { expected({ 0.5, -0.5, 0 }), expected({ 1.5, -0.5, 0 }), expected({ 1.5, 0.5, 0 }), expected({ 0.5, 0.5, 0 }) });
}

TEST(Transforms, NormalsUseInverseTranspose)
{
  // The plane x + y = 0, stretched by 2 along x, becomes x/2 + y = 0: normal along (1/2, 1, 0), not (2, 1, 0).
  TriangleMesh quad = makeQuad({ 0, 0, 0 }, { 1, 1 }, glm::normalize(glm::dvec3(1, 1, 0)), { 0, 0, 1 });
  Transform stretch;
  stretch.scale = { 2, 1, 1 };
  transformMesh(quad, stretch.worldFromLocal());
  for (const glm::vec3& normal : quad.normals)
    expectNear(glm::dvec3(normal), glm::normalize(glm::dvec3(0.5, 1, 0)), 1e-6, "inverse-transpose normal");
  for (std::size_t t = 0; t < quad.triangleCount(); ++t)
    EXPECT_NEAR(glm::dot(glm::normalize(windingNormal(quad, t)), glm::dvec3(quad.normals[0])), 1.0, 1e-6);
}

// ---- meshes ---------------------------------------------------------------------------------------------

TEST(MeshFiles, BunnyPlyDirect)
{
  const LoadedMesh loaded = loadMesh(kDatasets / "bunny" / "bunny.ply");
  expectWellFormed(loaded.mesh);
  EXPECT_EQ(loaded.mesh.triangleCount(), 3674u);
  EXPECT_EQ(loaded.droppedDegenerateTriangles, 0u);
  const Bounds bounds = meshBounds(loaded.mesh);
  expectNear(bounds.min, { -4.958475, -0.003149, -3.729833 }, 1e-5, "file min");
  expectNear(bounds.max, { 4.94885, 9.654748, 3.810639 }, 1e-5, "file max");
}

TEST(MeshFiles, DegenerateTrianglesDroppedAndCounted)
{
  std::vector<glm::vec3> vertices = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 1, 1, 0 } };
  std::vector<std::array<int, 3>> triangles = { { 0, 1, 2 }, { 1, 3, 2 } };
  addDegenerateTriangles(vertices, triangles);
  const SceneDir dir;
  dir.write("mixed.ply", binaryPly(vertices, triangles));
  Json json = minimalScene();
  json["objects"][0] = Json::parse(R"({ "mesh": "mixed.ply" })");
  const Scene scene = loadScene(dir.writeScene(json));
  const SceneObject& object = scene.objects[0];
  expectWellFormed(object.mesh);
  EXPECT_EQ(object.droppedDegenerateTriangles, 3u);
  EXPECT_EQ(object.mesh.triangleCount(), 2u);
  EXPECT_EQ(object.mesh.positions.size(), 4u) << "vertices of dropped triangles are removed";
  const Bounds bounds = meshBounds(object.mesh);
  expectNear(bounds.min, { 0, 0, 0 }, 0.0, "min");
  expectNear(bounds.max, { 1, 1, 0 }, 0.0, "max");
  // No normals in the file: smooth normals from the (counter-clockwise, +z facing) triangles.
  for (const glm::vec3& normal : object.mesh.normals)
    expectNear(glm::dvec3(normal), { 0, 0, 1 }, 1e-6, "computed normal");
}

TEST(MeshFiles, ObjPolygonIsFanTriangulatedAndKeepsUvs)
{
  const SceneDir dir;
  dir.write("square.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 1.5 0\n"
                          "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0.5 1\n"
                          "f 1/1 2/2 3/3 5/5 4/4\n");
  Json json = minimalScene();
  json["objects"][0] = Json::parse(R"({ "mesh": "square.obj", "alpha_texture": "leaves",
    "transform": { "translate": [0, 0, 1] } })");
  const Scene scene = loadScene(dir.writeScene(json));
  const SceneObject& object = scene.objects[0];
  expectWellFormed(object.mesh);
  EXPECT_EQ(object.mesh.triangleCount(), 3u); // pentagon -> fan of 3
  EXPECT_NEAR(totalArea(object.mesh), 1.25, 1e-6);
  ASSERT_EQ(object.mesh.uvs.size(), object.mesh.positions.size());
  for (std::size_t v = 0; v < object.mesh.positions.size(); ++v)
  {
    const glm::vec3& p = object.mesh.positions[v];
    EXPECT_EQ(p.z, 1.0f);
    // The file's uv is (x, min(y, 1)) for every vertex.
    EXPECT_NEAR(object.mesh.uvs[v].x, p.x, 1e-6);
    EXPECT_NEAR(object.mesh.uvs[v].y, std::min(p.y, 1.0f), 1e-6);
  }
  for (std::size_t t = 0; t < object.mesh.triangleCount(); ++t)
    EXPECT_GT(windingNormal(object.mesh, t).z, 0.0) << "file winding kept";
  EXPECT_TRUE(object.hasAlphaTexture);
  EXPECT_EQ(object.alphaTexture.source, "leaves");
}

TEST(MeshFiles, FileNormalsAreUsedAndTransformed)
{
  const SceneDir dir;
  // Deliberately "wrong" but valid normals (+x) so we can tell they came from the file, not the geometry.
  dir.write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 2 0 0\nf 1//1 2//1 3//1\n");
  Json json = minimalScene();
  json["objects"][0] = Json::parse(R"({ "mesh": "tri.obj", "transform": { "rotate_deg": [0, 0, 90] } })");
  const Scene scene = loadScene(dir.writeScene(json));
  for (const glm::vec3& normal : scene.objects[0].mesh.normals)
    expectNear(glm::dvec3(normal), { 0, 1, 0 }, 1e-6, "file normal +x rotated to +y");
}

// ---- alpha textures -------------------------------------------------------------------------------------

TEST(AlphaTextures, FencePattern)
{
  const ImageF fence = makeFenceAlpha();
  ASSERT_EQ(fence.width, kProceduralAlphaSize);
  ASSERT_EQ(fence.height, kProceduralAlphaSize);
  ASSERT_EQ(fence.components, 1);
  std::size_t holes = 0;
  for (const float alpha : fence.data)
  {
    ASSERT_TRUE(alpha == 0.0f || alpha == 1.0f);
    holes += alpha == 0.0f ? 1 : 0;
  }
  // Holes: both fract(8u') and fract(8v') in (0.15, 0.85): 0.7^2 = 49% of the area. Sampling at texel
  // centres quantises 8u' and 8v' to steps of 1/32, which moves the discrete fraction to about 0.52.
  EXPECT_NEAR(static_cast<double>(holes) / fence.data.size(), 0.49, 0.035);
  // Texel (0,0): u = v = 0.5/256, u' = u + v -> fract(8u') = 0.03: on a wire.
  EXPECT_EQ(fence.at(0, 0), 1.0f);
  // Texel (16,0): 8(u+v) = 0.53, 8(u-v) = 0.5: middle of a hole.
  EXPECT_EQ(fence.at(16, 0), 0.0f);
  // Rotated 45 degrees: the pattern is symmetric under swapping u and v (u' unchanged, v' negated).
  for (int y = 0; y < fence.height; y += 7)
    for (int x = 0; x < fence.width; x += 5)
      ASSERT_EQ(fence.at(x, y), fence.at(y, x)) << x << "," << y;
}

TEST(AlphaTextures, LeavesPatternIsDeterministicAndHalfCovered)
{
  const ImageF leaves = makeLeavesAlpha();
  ASSERT_EQ(leaves.width, kProceduralAlphaSize);
  std::size_t opaque = 0;
  for (const float alpha : leaves.data)
  {
    ASSERT_TRUE(alpha == 0.0f || alpha == 1.0f);
    opaque += alpha == 1.0f ? 1 : 0;
  }
  const double coverage = static_cast<double>(opaque) / leaves.data.size();
  EXPECT_GT(coverage, 0.4);
  EXPECT_LT(coverage, 0.6);
  EXPECT_EQ(makeLeavesAlpha().data, leaves.data) << "pattern must not change between calls";
}

TEST(AlphaTextures, PngAlphaChannelAndRowOrder)
{
  const SceneDir dir;
  // 2 x 2 RGBA; top row alpha 255, 0; bottom row alpha 51, 102. Colors are noise that must be ignored.
  const fs::path rgba = dir.write("rgba.png",
    encodePng(2, 2, 6, { { 10, 20, 30, 255, 40, 50, 60, 0 }, { 70, 80, 90, 51, 100, 110, 120, 102 } }));
  const ImageF alpha = readAlphaPng(rgba);
  ASSERT_EQ(alpha.width, 2);
  ASSERT_EQ(alpha.height, 2);
  ASSERT_EQ(alpha.components, 1);
  // Row 0 is v near 0, the bottom of the picture.
  EXPECT_NEAR(alpha.at(0, 0), 0.2f, 1e-6);
  EXPECT_NEAR(alpha.at(1, 0), 0.4f, 1e-6);
  EXPECT_NEAR(alpha.at(0, 1), 1.0f, 1e-6);
  EXPECT_NEAR(alpha.at(1, 1), 0.0f, 1e-6);
}

TEST(AlphaTextures, PngWithoutAlphaUsesLuminance)
{
  const SceneDir dir;
  const ImageF gray = readAlphaPng(dir.write("gray.png", encodePng(1, 2, 0, { { 255 }, { 51 } })));
  EXPECT_NEAR(gray.at(0, 0), 0.2f, 1e-6);
  EXPECT_NEAR(gray.at(0, 1), 1.0f, 1e-6);
  // Pure green: Rec. 709 luminance weight 0.7152.
  const ImageF rgb = readAlphaPng(dir.write("rgb.png", encodePng(1, 1, 2, { { 0, 255, 0 } })));
  EXPECT_NEAR(rgb.at(0, 0), 0.7152f, 1e-5);
  // Gray + alpha: the alpha.
  const ImageF grayAlpha = readAlphaPng(dir.write("ga.png", encodePng(1, 1, 4, { { 200, 102 } })));
  EXPECT_NEAR(grayAlpha.at(0, 0), 0.4f, 1e-6);
}

TEST(AlphaTextures, PngThroughSceneRelativeToSceneFile)
{
  const SceneDir dir;
  fs::create_directories(dir.path() / "textures");
  dir.write("textures/mask.png", encodePng(1, 1, 0, { { 255 } }));
  Json json = minimalScene();
  json["objects"][0]["alpha_texture"] = "textures/mask.png";
  const Scene scene = loadScene(dir.writeScene(json));
  ASSERT_TRUE(scene.objects[0].hasAlphaTexture);
  EXPECT_EQ(scene.objects[0].alphaTexture.source, "textures/mask.png");
  EXPECT_EQ(scene.objects[0].alphaTexture.alpha.at(0, 0), 1.0f);
}

TEST(AlphaTextures, CorruptPngIsAnInputErrorNotACrash)
{
  const SceneDir dir;
  std::vector<unsigned char> png = encodePng(2, 1, 0, { { 1, 2 } });
  std::vector<unsigned char> badCrc = png;
  badCrc[40] ^= 0xFF; // inside the IDAT data
  std::vector<unsigned char> truncated(png.begin(), png.begin() + 45);
  for (const auto& [name, bytes] : { std::pair{ "bad-crc.png", badCrc }, std::pair{ "truncated.png", truncated },
         std::pair{ "text.png", std::vector<unsigned char>{ 'h', 'e', 'l', 'l', 'o' } } })
  {
    const fs::path file = dir.write(name, bytes);
    try
    {
      readAlphaPng(file);
      ADD_FAILURE() << name << " was accepted";
    }
    catch (const InputError& error)
    {
      EXPECT_NE(std::string(error.what()).find(name), std::string::npos) << error.what();
    }
  }
}

// ---- bad input ------------------------------------------------------------------------------------------

TEST(SceneErrors, MissingSceneFile)
{
  const SceneDir dir;
  const fs::path file = dir.path() / "nope.json";
  expectLoadError(file, { "nope.json", "no such file" });
}

TEST(SceneErrors, MalformedJson)
{
  expectSceneTextError("{\n  \"lights\": [\n    }\n", { "malformed JSON at line 3, column 5", "syntax error" });
  expectSceneTextError("", { "malformed JSON at line 1" });
  expectSceneTextError("[1, 2]", { "(top level): expected an object" });
}

TEST(SceneErrors, DuplicateKeysAreRefusedNotOverwritten) // probe S13
{
  expectSceneTextError(R"({"lights": [{"type": "point", "center": [0, 3, 0], "center": [0, 9, 0]}],
    "objects": [{"primitive": "quad"}]})",
    { "lights[0].center: is given twice" });
  expectSceneTextError(R"({"objects": [{"primitive": "quad"}], "lights": [{"type": "point"}], "objects": []})",
    { "objects: is given twice" });
}

TEST(SceneErrors, UnknownKeys)
{
  Json topLevel = minimalScene();
  topLevel["colour"] = 1;
  expectSceneError(topLevel, { "(top level): unknown key 'colour'" });

  Json camera = minimalScene();
  camera["camera"] = Json::parse(R"({ "fov": 30 })");
  expectSceneError(camera, { "camera: unknown key 'fov'" });

  Json object = minimalScene();
  object["objects"].push_back(Json::parse(R"({ "primitive": "box", "colour": [1, 0, 0] })"));
  expectSceneError(object, { "objects[1]: unknown key 'colour'" });

  Json transform = minimalScene();
  transform["objects"][0]["transform"] = Json::parse(R"({ "rotate": [0, 0, 0] })");
  expectSceneError(transform, { "objects[0].transform: unknown key 'rotate'" });

  Json material = minimalScene();
  material["objects"][0]["material"] = Json::parse(R"({ "albedo": [1, 1, 1], "roughness": 0.5 })");
  expectSceneError(material, { "objects[0].material: unknown key 'roughness'" });
}

TEST(SceneErrors, KeysOfAnotherKind)
{
  Json pointWithSize = minimalScene();
  pointWithSize["lights"][0]["size"] = 1;
  expectSceneError(pointWithSize, { "lights[0]: key 'size' does not apply to a point light" });

  Json sphereWithNormal = minimalScene();
  sphereWithNormal["objects"][0] = Json::parse(R"({ "primitive": "sphere", "normal": [0, 1, 0] })");
  expectSceneError(sphereWithNormal, { "objects[0]: key 'normal' does not apply to a sphere" });

  Json meshWithCenter = minimalScene();
  meshWithCenter["objects"][0] = Json::parse(R"({ "mesh": "x.ply", "center": [0, 1, 0] })");
  expectSceneError(meshWithCenter, { "objects[0]: key 'center' does not apply to a mesh" });

  Json orthographicWithAngle = minimalScene();
  orthographicWithAngle["camera"] = Json::parse(R"({ "projection": "orthographic", "view_angle": 30 })");
  expectSceneError(orthographicWithAngle, { "camera: key 'view_angle' does not apply to an orthographic camera" });
}

TEST(SceneErrors, MissingMeshFile)
{
  Json json = minimalScene();
  json["objects"][0] = Json::parse(R"({ "mesh": "missing.ply" })");
  expectSceneError(json, { "objects[0].mesh: cannot read '", "missing.ply' (no such file)" });
}

TEST(SceneErrors, CorruptMeshFile)
{
  const SceneDir dir;
  std::string garbage;
  std::mt19937 random(12345);
  for (int i = 0; i < 4096; ++i)
    garbage.push_back(static_cast<char>(random() & 0xFF));
  dir.write("garbage.ply", garbage);
  Json json = minimalScene();
  json["objects"][0] = Json::parse(R"({ "mesh": "garbage.ply" })");
  expectLoadError(dir.writeScene(json), { "objects[0].mesh: cannot read '", "garbage.ply", "corrupt" });
}

TEST(SceneErrors, EmptyMesh)
{
  const SceneDir dir;
  dir.write("empty.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                         "property float z\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n"
                         "0 0 0\n1 0 0\n0 1 0\n");
  Json json = minimalScene();
  json["objects"][0] = Json::parse(R"({ "mesh": "empty.ply" })");
  expectLoadError(dir.writeScene(json), { "objects[0].mesh: '", "empty.ply': empty mesh" });
}

TEST(SceneErrors, MeshWithOnlyDegenerateTriangles)
{
  std::vector<glm::vec3> vertices;
  std::vector<std::array<int, 3>> triangles;
  addDegenerateTriangles(vertices, triangles);
  const SceneDir dir;
  dir.write("flat.ply", binaryPly(vertices, triangles));
  Json json = minimalScene();
  json["objects"][0] = Json::parse(R"({ "mesh": "flat.ply" })");
  expectLoadError(dir.writeScene(json), { "objects[0].mesh: '", "flat.ply': all 3 triangles are degenerate" });
}

TEST(SceneErrors, NonFiniteNumbers)
{
  const std::string scene = R"({
    "lights": [ { "type": "point", "center": [0, 3, 0] } ],
    "objects": [ { "primitive": "quad", "center": [0, 1e999, 0] } ] })";
  expectSceneTextError(scene, { "objects[0].center[1]: must be a finite number, got 1e999" });
  const std::string negative = R"({
    "lights": [ { "type": "area", "center": [0, 3, 0], "normal": [0, -1, 0], "size": -1e999 } ],
    "objects": [ { "primitive": "quad" } ] })";
  expectSceneTextError(negative, { "lights[0].size: must be a finite number, got -1e999" });
}

TEST(SceneErrors, SizesMustBePositive)
{
  Json zeroLight = minimalScene();
  zeroLight["lights"][0] = Json::parse(R"({ "type": "area", "center": [0, 3, 0], "normal": [0, -1, 0], "size": 0 })");
  expectSceneError(zeroLight, { "lights[0].size: must be > 0, got 0" });

  Json negativeQuad = minimalScene();
  negativeQuad["objects"][0]["size"] = { 1, -2 };
  expectSceneError(negativeQuad, { "objects[0].size[1]: must be > 0, got -2" });

  Json zeroSphere = minimalScene();
  zeroSphere["objects"][0] = Json::parse(R"({ "primitive": "sphere", "size": 0 })");
  expectSceneError(zeroSphere, { "objects[0].size: must be > 0, got 0" });

  Json negativeScale = minimalScene();
  negativeScale["objects"][0]["transform"] = Json::parse(R"({ "scale": [1, -1, 1] })");
  expectSceneError(negativeScale, { "objects[0].transform.scale[1]: must be > 0, got -1" });

  Json albedo = minimalScene();
  albedo["objects"][0]["material"] = Json::parse(R"({ "albedo": [0.5, 1.5, 0.5] })");
  expectSceneError(albedo, { "objects[0].material.albedo[1]: must be in [0, 1], got 1.5" });

  Json zeroNormal = minimalScene();
  zeroNormal["objects"][0]["normal"] = { 0, 0, 0 };
  expectSceneError(zeroNormal, { "objects[0].normal: must be a non-zero vector" });
}

TEST(SceneErrors, WrongTypes)
{
  Json angle = minimalScene();
  angle["camera"] = Json::parse(R"({ "view_angle": "wide" })");
  expectSceneError(angle, { "camera.view_angle: expected a number, got string \"wide\"" });

  Json vector = minimalScene();
  vector["lights"][0]["center"] = { 0, 3 };
  expectSceneError(vector, { "lights[0].center: expected an array of 3 numbers, got an array of 2" });

  Json flag = minimalScene();
  flag["objects"][0]["cast_shadows"] = "yes";
  expectSceneError(flag, { "objects[0].cast_shadows: expected true or false, got string \"yes\"" });

  Json lights = minimalScene();
  lights["lights"] = Json::parse(R"({ "type": "point" })");
  expectSceneError(lights, { "lights: expected an array of lights, got an object" });
}

TEST(SceneErrors, UnknownNames)
{
  Json light = minimalScene();
  light["lights"][0]["type"] = "laser";
  expectSceneError(light, { "lights[0].type: unknown light type 'laser'", "area, point, directional, spot" });

  Json missingType = minimalScene();
  missingType["lights"][0].erase("type");
  expectSceneError(missingType, { "lights[0].type: missing" });

  Json primitive = minimalScene();
  primitive["objects"][0]["primitive"] = "cone";
  expectSceneError(primitive, { "objects[0].primitive: unknown primitive 'cone'" });
}

TEST(SceneErrors, MeshAndPrimitive)
{
  Json both = minimalScene();
  both["objects"][0]["mesh"] = "bunny.ply";
  expectSceneError(both, { "objects[0]: has both 'mesh' and 'primitive'" });

  Json neither = minimalScene();
  neither["objects"][0] = Json::parse(R"({ "material": { "albedo": [1, 1, 1] } })");
  expectSceneError(neither, { "objects[0]: needs 'mesh'" });
}

TEST(SceneErrors, AlphaTextureProblems)
{
  const SceneDir dir;
  dir.write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  Json noUvs = minimalScene();
  noUvs["objects"][0] = Json::parse(R"({ "mesh": "tri.obj", "alpha_texture": "fence" })");
  expectLoadError(dir.writeScene(noUvs), { "objects[0].alpha_texture: mesh 'tri.obj' has no texture coordinates" });

  Json missingPng = minimalScene();
  missingPng["objects"][0]["alpha_texture"] = "nope.png";
  expectSceneError(missingPng, { "objects[0].alpha_texture: cannot read '", "nope.png' (no such file)" });
}

TEST(SceneErrors, CameraProblems)
{
  Json resolution = minimalScene();
  resolution["camera"] = Json::parse(R"({ "resolution": [512, 0] })");
  expectSceneError(resolution, { "camera.resolution[1]: must be in [1, 16384], got 0" });

  Json huge = minimalScene();
  huge["camera"] = Json::parse(R"({ "resolution": [16385, 512] })");
  expectSceneError(huge, { "camera.resolution[0]: must be in [1, 16384], got 16385" });

  Json fractional = minimalScene();
  fractional["camera"] = Json::parse(R"({ "resolution": [512.5, 512] })");
  expectSceneError(fractional, { "camera.resolution[0]: expected an integer, got 512.5" });

  Json parallel = minimalScene();
  parallel["camera"] = Json::parse(R"({ "position": [0, 5, 0], "focal_point": [0, 0, 0], "view_up": [0, 1, 0] })");
  expectSceneError(parallel, { "camera.view_up: is parallel to the view direction" });

  Json samePoint = minimalScene();
  samePoint["camera"] = Json::parse(R"({ "position": [1, 2, 3], "focal_point": [1, 2, 3] })");
  expectSceneError(samePoint, { "camera.focal_point: must differ from camera.position" });

  Json angle = minimalScene();
  angle["camera"] = Json::parse(R"({ "view_angle": 180 })");
  expectSceneError(angle, { "camera.view_angle: must be in (0, 180), got 180" });
}

TEST(SceneErrors, UpParallelToNormal)
{
  Json json = minimalScene();
  json["lights"][0] = Json::parse(R"({ "type": "area", "normal": [0, -1, 0], "up": [0, 2, 0] })");
  expectSceneError(json, { "lights[0].up: is parallel to the normal" });
}

TEST(SceneErrors, NoLightsOrObjects)
{
  Json noLights = minimalScene();
  noLights.erase("lights");
  expectSceneError(noLights, { "lights: missing" });

  Json emptyLights = minimalScene();
  emptyLights["lights"] = Json::array();
  expectSceneError(emptyLights, { "lights: is empty" });

  Json noObjects = minimalScene();
  noObjects.erase("objects");
  expectSceneError(noObjects, { "objects: missing" });

  Json emptyObjects = minimalScene();
  emptyObjects["objects"] = Json::array();
  expectSceneError(emptyObjects, { "objects: is empty" });
}

TEST(SceneErrors, ParseSceneUsesLabelAndBaseDir)
{
  const SceneDir dir;
  dir.write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const std::string text =
    R"({ "lights": [ { "type": "point" } ], "objects": [ { "mesh": "tri.obj" } ] })";
  const Scene scene = parseScene(text, "inline", dir.path());
  EXPECT_EQ(scene.objects[0].mesh.triangleCount(), 1u);
  EXPECT_TRUE(scene.file.empty());
  try
  {
    parseScene(R"({ "lights": [] })", "inline", dir.path());
    ADD_FAILURE() << "no error";
  }
  catch (const InputError& error)
  {
    EXPECT_EQ(std::string(error.what()).rfind("inline: lights: ", 0), 0u) << error.what();
  }
}

// ---- issue 11: files that are not scene files, nesting, overrides, scale -------------------------------

// The message of the InputError that loading `file` with `overrides` throws; a test failure when it throws
// none, or a message that is not one line.
std::string overrideError(const fs::path& file, const std::vector<std::string>& overrides)
{
  try
  {
    loadScene(file, overrides);
  }
  catch (const InputError& error)
  {
    const std::string message = error.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << "message is not one line: " << message;
    return message;
  }
  ADD_FAILURE() << "loading " << file << " with the overrides did not throw InputError";
  return {};
}

void expectContains(const std::string& message, const std::vector<std::string>& parts)
{
  for (const std::string& part : parts)
    EXPECT_NE(message.find(part), std::string::npos) << "expected '" << part << "' in: " << message;
}

std::string nestedArrays(std::size_t depth)
{
  return std::string(depth, '[') + std::string(depth, ']');
}

TEST(SceneFiles, FifoIsRefusedPromptly)
{
  const SceneDir dir;
  const fs::path fifo = dir.path() / "scene.json";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0) << std::strerror(errno);
  // Before the fix this blocked forever in open(); run it aside so a regression fails instead of hanging.
  auto loading = std::async(std::launch::async, [&fifo]() { return loadError(fifo); });
  if (loading.wait_for(std::chrono::seconds(10)) != std::future_status::ready)
  {
    // Unblock the reader (a writer appearing and leaving gives it end of file), then report the hang.
    const int writer = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
    if (writer >= 0)
      ::close(writer);
    loading.wait();
    FAIL() << "loadScene on a FIFO did not return within 10 s";
  }
  const std::string message = loading.get();
  EXPECT_EQ(message.rfind(fifo.string() + ": ", 0), 0u) << message;
  expectContains(message, { "a FIFO, not a regular file" });
}

TEST(SceneFiles, DevicesDirectoriesAndSymlinksToThemAreRefused)
{
  // /dev/zero would be read until memory runs out (probe S15).
  expectLoadError("/dev/zero", { "cannot read scene file (it is a character device, not a regular file)" });
  const SceneDir dir;
  expectLoadError(dir.path(), { "cannot read scene file (it is a directory, not a regular file)" });
  // The type is that of the file a symlink resolves to: a link to a scene loads, a link to /dev/zero does not.
  const fs::path real = dir.writeScene(minimalScene(), "real.json");
  const fs::path goodLink = dir.path() / "good.json";
  const fs::path zeroLink = dir.path() / "zero.json";
  fs::create_symlink(real, goodLink);
  fs::create_symlink("/dev/zero", zeroLink);
  EXPECT_NO_THROW(loadScene(goodLink));
  expectLoadError(zeroLink, { "character device" });
}

TEST(SceneFiles, OversizedFileIsRefusedBeforeParsing)
{
  const SceneDir dir;
  // A valid scene followed by whitespace up to one byte over the limit: only the size can make it fail.
  const fs::path file = dir.writeScene(minimalScene());
  std::error_code error;
  fs::resize_file(file, kMaxSceneFileBytes + 1, error);
  ASSERT_FALSE(error) << error.message();
  expectLoadError(file, { "scene file is larger than 64 MiB" });
}

TEST(SceneNesting, DeepDocumentsAreRefusedWhileParsing)
{
  // The top-level object is level 1, so an unknown key holding 255 nested arrays is exactly at the limit: it
  // parses, and the error is the unknown key. One more level is the nesting error, with where it happened.
  static_assert(kMaxJsonDepth == 256, "docs/scene-format.md documents 256 levels");
  const std::string prefix = R"({ "lights": [ { "type": "point", "center": [0, 3, 0] } ], "objects": [ { "primitive": "quad" } ], "deep": )";
  expectSceneTextError(prefix + nestedArrays(255) + "}", { "(top level): unknown key 'deep'" });
  expectSceneTextError(prefix + nestedArrays(256) + "}", { "deep[0][0][0]", "nest deeper than 256 levels" });
  // Probe S11/S12b: 100 000 levels, in a file and through --scene-set (which used to re-serialise the
  // document recursively and overflow the stack).
  const SceneDir dir;
  const fs::path deep = dir.write("deep.json", nestedArrays(100000));
  expectLoadError(deep, { ": [0][0][0]", "...: objects and arrays nest deeper than 256 levels" });
  const std::string withOverride = overrideError(deep, { "/lights/0/size=2" });
  EXPECT_EQ(withOverride.rfind(deep.string() + ": ", 0), 0u) << withOverride;
  expectContains(withOverride, { "nest deeper than 256 levels" });
  EXPECT_LT(withOverride.size(), 400u) << "the message must not echo the whole path";
}

TEST(SceneNesting, DeepOverrideValuesAreRefused)
{
  const SceneDir dir;
  const fs::path file = dir.writeScene(minimalScene());
  const std::string message = overrideError(file, { "/objects/0/material=" + nestedArrays(100000) });
  expectContains(message, { "--scene-set /objects/0/material=[[[", "the value nests deeper than", "256 levels" });
  EXPECT_LT(message.size(), 400u) << "the message must not echo the whole value";
  // The value's limit counts from the document's top: at /objects/0/material (3 levels down) 253 nested arrays
  // fit, which the scene then rejects for its type, and 254 do not.
  expectContains(overrideError(file, { "/objects/0/material=" + nestedArrays(253) }),
    { "objects[0].material: expected an object" });
  expectContains(overrideError(file, { "/objects/0/material=" + nestedArrays(254) }), { "nests deeper" });
}

TEST(SceneOverrides, ReplaceAppendAndRefusePastTheEnd)
{
  const SceneDir dir;
  const fs::path file = dir.writeScene(minimalScene());
  const Scene replaced = loadScene(file, { "/lights/0/center/1=4", "/camera={\"view_angle\": 40}" });
  EXPECT_EQ(replaced.lights[0].center, glm::dvec3(0, 4, 0));
  EXPECT_EQ(replaced.camera.viewAngleDeg, 40.0);

  // index == size appends one element (as "-" does); nothing larger.
  const Scene appended = loadScene(file, { "/objects/1={\"primitive\": \"box\", \"center\": [0, 0, 1]}",
                                           "/objects/-={\"primitive\": \"sphere\", \"size\": 0.1}" });
  ASSERT_EQ(appended.objects.size(), 3u);
  EXPECT_EQ(appended.objects[1].name, "objects[1] (box)");
  EXPECT_EQ(appended.objects[2].name, "objects[2] (sphere)");

  // Probe P30: used to resize the array to 2e12 elements and die of std::bad_alloc.
  expectContains(overrideError(file, { "/objects/2000000000000=1" }),
    { "--scene-set /objects/2000000000000=1: index 2000000000000 is past the end of /objects, which has 1 "
      "element(s)" });
  expectContains(overrideError(file, { "/objects/99999999999999999999999=1" }), { "is past the end of /objects" });
  expectContains(overrideError(file, { "/objects/01=1" }), { "'01' is not an index of the array at /objects" });
  // Parents must exist, whatever their type.
  expectContains(overrideError(file, { "/lights/9/size=2" }), { "has nothing at /lights/9" });
  expectContains(overrideError(file, { "/objects/0/primitive/x=2" }),
    { "has string at /objects/0/primitive, which has no members" });
  expectContains(overrideError(file, { "/nothing/here/x=2" }), { "has nothing at /nothing" });
  // RFC 6901 escapes: ~1 is '/', so this sets the key "a/b", which the scene then refuses by name.
  expectContains(overrideError(file, { "/objects/0/a~1b=1" }), { "objects[0]: unknown key 'a/b'" });
  expectContains(overrideError(file, { "/objects/0/a~2b=1" }), { "'~' in a JSON pointer must be followed by 0 or 1" });
  // Control characters in the echo are escaped, so the message stays one line.
  expectContains(overrideError(file, { "/lights/9\n/size=2" }), { "/lights/9\\x0a" });
}

TEST(SceneOverrides, NonFiniteValuesAreNamedAsSuch)
{
  const SceneDir dir;
  Json scene = minimalScene();
  scene["lights"][0] = Json::parse(R"({ "type": "area", "center": [0, 3, 0], "normal": [0, -1, 0] })");
  const fs::path file = dir.writeScene(scene);
  // Probe P33: used to say "expected a number, got string".
  expectContains(overrideError(file, { "/lights/0/size=1e999" }),
    { "--scene-set /lights/0/size=1e999: the value 1e999 is not a finite number" });
  expectContains(overrideError(file, { "/lights/0/center=[0,-1e999,0]" }),
    { "the value -1e999 (at [1]) is not a finite number" });
  // A bare word is still a string, and gets the scene's own message.
  expectContains(overrideError(file, { "/lights/0/size=big" }), { "lights[0].size: expected a number, got string" });
}

// The scale rule (docs/scene-format.md): magnitudes <= kMaxSceneMagnitude, lights and camera within
// kMaxLightDistanceInSceneRadii / kMaxCameraDistanceInSceneRadii bounding radii. Each probe case gets a one-line error naming its JSON path.
TEST(SceneScale, AbsoluteMagnitudesAreBounded)
{
  static_assert(kMaxSceneMagnitude == 1e6, "docs/scene-format.md documents 1e6");
  const auto withLight = [](const std::string& light) {
    Json scene = minimalScene();
    scene["lights"][0] = Json::parse(light);
    return scene;
  };
  // F18, L40: point light at y = 1e20; L25: point light at 1e300, area light at 1e308.
  expectSceneError(withLight(R"({ "type": "point", "center": [0, 1e20, 0] })"),
    { "lights[0].center[1]: must be in [-1e6, 1e6] (scene units", "got 1e+20" });
  expectSceneError(withLight(R"({ "type": "point", "center": [0, 1e300, 0] })"), { "lights[0].center[1]: must be in" });
  expectSceneError(withLight(R"({ "type": "area", "center": [0, 1e308, 0], "normal": [0, -1, 0] })"),
    { "lights[0].center[1]: must be in [-1e6, 1e6]" });
  expectSceneError(withLight(R"({ "type": "spot", "center": [-1e7, 3, 0], "normal": [0, -1, 0] })"),
    { "lights[0].center[0]: must be in [-1e6, 1e6]" });
  expectSceneError(withLight(R"({ "type": "area", "center": [0, 3, 0], "normal": [0, -1, 0], "size": 1e7 })"),
    { "lights[0].size: must be <= 1e6 (scene units" });
  expectSceneError(withLight(R"({ "type": "point", "center": [0, 3, 0], "intensity": 1e300 })"),
    { "lights[0].intensity: must be <= 1e6" });

  // F15, O09: a 1e30 sphere (Embree asserted; the camera's depth range collapsed).
  Json sphere = minimalScene();
  sphere["objects"].push_back(Json::parse(R"({ "primitive": "sphere", "center": [0, 0, -10], "size": 1e30 })"));
  expectSceneError(sphere, { "objects[1].size: must be <= 1e6" });
  Json farQuad = minimalScene();
  farQuad["objects"][0]["center"] = { 0, 0, -2e6 };
  expectSceneError(farQuad, { "objects[0].center[2]: must be in [-1e6, 1e6]" });
  Json translate = minimalScene();
  translate["objects"][0]["transform"] = Json::parse(R"({ "translate": [1e9, 0, 0] })");
  expectSceneError(translate, { "objects[0].transform.translate[0]: must be in [-1e6, 1e6]" });
  // Products are checked on the final vertices: each value is in range, the scaled quad is not.
  Json scaled = minimalScene();
  scaled["objects"][0]["size"] = { 1e6, 1e6 };
  scaled["objects"][0]["transform"] = Json::parse(R"({ "scale": 10 })");
  expectSceneError(scaled, { "objects[0]: vertex 0 lies at (-5e+06, -5e+06, 0) after the transform" });

  // A mesh file with a huge coordinate (finite, so the mesh reader keeps it).
  const SceneDir dir;
  dir.write("huge.obj", "v 0 0 0\nv 2e6 0 0\nv 0 2e6 0\nf 1 2 3\n");
  Json mesh = minimalScene();
  mesh["objects"][0] = Json::parse(R"({ "mesh": "huge.obj" })");
  expectLoadError(dir.writeScene(mesh), { "objects[0]: vertex 1 lies at (2e+06, 0, 0); coordinates must be in [-1e6, 1e6]" });

  // C04: the camera at 1e308 is a magnitude problem, not "view_up is parallel".
  Json camera = minimalScene();
  camera["camera"] = Json::parse(R"({ "position": [1e308, 1e308, 1e308] })");
  const std::string message = loadError(SceneDir().writeScene(camera));
  EXPECT_NE(message.find("camera.position[0]: must be in [-1e6, 1e6]"), std::string::npos) << message;
  EXPECT_EQ(message.find("parallel"), std::string::npos) << message;
  Json focal = minimalScene();
  focal["camera"] = Json::parse(R"({ "focal_point": [0, 0, -1e300] })");
  expectSceneError(focal, { "camera.focal_point[2]: must be in [-1e6, 1e6]" });
}

TEST(SceneScale, LightsAndCameraWithinTheRelativeDistance)
{
  // minimalScene's only object is the unit quad at the origin: bounding radius sqrt(2)/2.
  const double radius = std::sqrt(2.0) / 2.0;
  const double limit = kMaxLightDistanceInSceneRadii * radius;
  Json scene = minimalScene();
  scene["lights"][0]["center"] = { 0, 0, 0.99 * limit };
  EXPECT_NO_THROW(loadScene(SceneDir().writeScene(scene))) << "just inside the limit";
  scene["lights"][0]["center"] = { 0, 0, 1.01 * limit };
  expectSceneError(scene, { "lights[0].center: lies ", "from the centre of the objects' bounding box, more than 3000 ",
                            "times their bounding radius 0.707" });

  // L39: a point light at y = 1e5 over a dataset (radius 4.3) loses the shadow; the probe's y = 1e4 rendered
  // within the ray tracer's error and must still load.
  const fs::path dataset = kDatasets / "sphere-point" / "scene.json";
  EXPECT_NO_THROW(loadScene(dataset, { "/lights/0/center=[0.5, 1e4, 0.3]" }));
  expectContains(overrideError(dataset, { "/lights/0/center=[0.5, 1e5, 0.3]" }), { "lights[0].center: lies " });

  Json spot = minimalScene();
  spot["lights"].push_back(Json::parse(R"({ "type": "spot", "center": [0, 0, 0], "normal": [0, -1, 0] })"));
  spot["lights"][1]["center"] = { 2.0 * limit, 0, 0 };
  expectSceneError(spot, { "lights[1].center: lies " });
  // The directional light has no position: nothing to check.
  Json directional = minimalScene();
  directional["lights"][0] = Json::parse(R"({ "type": "directional", "direction": [0, -1, 0] })");
  EXPECT_NO_THROW(loadScene(SceneDir().writeScene(directional)));

  // The camera's limit is looser. A 1e-3 quad keeps 2x the limit inside the absolute bound.
  Json camera = minimalScene();
  camera["objects"][0]["size"] = { 1e-3, 1e-3 };
  camera["lights"][0]["center"] = { 0, 1e-3, 0 };
  const double cameraLimit = kMaxCameraDistanceInSceneRadii * 1e-3 * radius;
  camera["camera"] = Json::parse(R"({ "focal_point": [0, 0, 0] })");
  camera["camera"]["position"] = { 0, 0, 0.99 * cameraLimit };
  EXPECT_NO_THROW(loadScene(SceneDir().writeScene(camera))) << "just inside the camera's limit";
  camera["camera"]["position"] = { 0, 0, 1.01 * cameraLimit };
  expectSceneError(camera, { "camera.position: lies ", "more than 1e6 times their bounding radius" });

  // Objects too small for float32 to tell their vertices apart leave nothing to measure distances against.
  Json tiny = minimalScene();
  tiny["objects"][0]["size"] = { 1e-300, 1e-300 };
  expectSceneError(tiny, { "objects: all objects together collapse to a single point in float32" });
}

TEST(SceneScale, DirectionsOfAnyFiniteMagnitudeAreDirections)
{
  // L38: [1e308, -1e308, 0] used to overflow |v| and be called "a non-zero vector" problem.
  Json scene = minimalScene();
  scene["lights"][0] = Json::parse(R"({ "type": "area", "center": [0, 3, 0], "normal": [1e308, -1e308, 0] })");
  scene["objects"][0]["normal"] = { 0, 1e-320, 0 };
  const Scene loaded = loadScene(SceneDir().writeScene(scene));
  expectNear(loaded.lights[0].normal, glm::normalize(glm::dvec3(1, -1, 0)), 1e-15, "light normal");
  expectNear(glm::dvec3(loaded.objects[0].mesh.normals[0]), { 0, 1, 0 }, 1e-7, "quad normal");
  Json zero = minimalScene();
  zero["objects"][0]["normal"] = { 0, 0, 0 };
  expectSceneError(zero, { "objects[0].normal: must be a non-zero vector" });
}

// The probe's "What held up": hard but legal scenes that rendered correctly and must still load.
TEST(SceneScale, AcceptedHardCasesStillLoad)
{
  const fs::path dataset = kDatasets / "contact" / "scene.json"; // ground 6 x 6, box [0.5, 1, 0.5] at y 0.5
  const std::vector<std::vector<std::string>> cases = {
    { "/camera/position=[0, 0.5, 0]", "/camera/focal_point=[1, 0.5, 0]" },      // camera inside the box
    { "/camera/position=[0, -2, 0]", "/camera/focal_point=[0, 0, 0]", "/camera/view_up=[0, 0, 1]" }, // below the ground
    { "/camera/focal_point=[10, 2.2, 30]" },                                       // looking at nothing
    { "/lights/0/normal=[0, 1, 0]" },                                              // area light facing away
    { "/lights/0/center=[1, 0, 1]", "/lights/0/normal=[0, -1, 0]" },               // on the receiver plane
    { "/lights/0/center=[0, 0.5, 0]" },                                            // inside the occluder
    { "/lights/0/center=[0, -1, 0]", "/lights/0/normal=[0, -1, 0]" },             // objects behind the light
    { "/camera/view_angle=179.9" },                                                // extreme view angles
    { "/camera/view_angle=0.001" },
    { "/lights/0={\"type\": \"spot\", \"center\": [0, 3, 0], \"normal\": [0, -1, 0], \"cone_angle_deg\": 89.99}" },
    { "/lights/0={\"type\": \"spot\", \"center\": [0, 3, 0], \"normal\": [0, -1, 0], \"cone_angle_deg\": 0.001}" },
    { "/lights/0/size=1e-12" },                                                    // a 1e-12 light
    { "/objects/0/cast_shadows=false", "/objects/1/cast_shadows=false" },         // nothing casts
  };
  for (const std::vector<std::string>& overrides : cases)
  {
    std::string label;
    for (const std::string& override : overrides)
      label += override + " ";
    EXPECT_NO_THROW(loadScene(dataset, overrides)) << label;
  }
}

TEST(SceneInputFiles, SceneMeshAndAlphaFilesAreListed)
{
  // bunny: the scene and its PLY; fence's alpha texture is the procedural "fence", which is no file.
  const Scene bunny = loadScene(kDatasets / "bunny" / "scene.json");
  const std::vector<fs::path> bunnyFiles = { fs::absolute(kDatasets / "bunny" / "scene.json").lexically_normal(),
    fs::absolute(kDatasets / "bunny" / "bunny.ply").lexically_normal() };
  EXPECT_EQ(bunny.inputFiles, bunnyFiles);
  const Scene fence = loadScene(kDatasets / "fence" / "scene.json");
  EXPECT_EQ(fence.inputFiles,
    std::vector<fs::path>{ fs::absolute(kDatasets / "fence" / "scene.json").lexically_normal() });

  // A PNG alpha texture and a mesh in a subdirectory, named through "..": listed absolute and normal.
  const SceneDir dir;
  fs::create_directories(dir.path() / "meshes");
  dir.write("meshes/tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n");
  dir.write("holes.png", encodePng(1, 1, 0, { { 255 } }));
  Json json = minimalScene();
  json["objects"][0]["alpha_texture"] = "meshes/../holes.png";
  json["objects"].push_back(Json::parse(R"({ "mesh": "meshes/../meshes/tri.obj" })"));
  const Scene scene = loadScene(dir.writeScene(json));
  const fs::path root = fs::absolute(dir.path()).lexically_normal();
  const std::vector<fs::path> expected = { root / "scene.json", root / "holes.png", root / "meshes" / "tri.obj" };
  EXPECT_EQ(scene.inputFiles, expected);
  for (const fs::path& file : scene.inputFiles)
    EXPECT_TRUE(file.is_absolute()) << file;

  // parseScene has no scene file: only what it read.
  const Scene parsed = parseScene(json.dump(), {}, "inline", dir.path());
  EXPECT_EQ(parsed.inputFiles, std::vector<fs::path>(expected.begin() + 1, expected.end()));
}

TEST(SceneDatasets, EveryDatasetLoadsUnderTheLimits)
{
  // Every scene.json under datasets/, including any added later, within the scale rule with room to spare.
  for (const fs::directory_entry& entry : fs::directory_iterator(kDatasets))
  {
    const fs::path file = entry.path() / "scene.json";
    if (!fs::exists(file))
      continue;
    SCOPED_TRACE(file.string());
    Scene scene;
    ASSERT_NO_THROW(scene = loadScene(file));
    const Bounds bounds = scene.bounds();
    for (const Light& light : scene.lights)
      if (light.type != LightType::Directional)
        EXPECT_LT(glm::length(light.center - bounds.center()), 0.01 * kMaxLightDistanceInSceneRadii * bounds.radius());
    EXPECT_EQ(scene.inputFiles.front(), fs::absolute(file).lexically_normal());
  }
}

} // namespace
} // namespace sl
