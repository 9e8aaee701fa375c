// libFuzzer target: the scene loader with --scene-set overrides.
//
// Input layout: every leading line that starts with '/' is one override ("/json/pointer=value", what
// --scene-set takes); the rest of the input is the scene document. A JSON document cannot start with '/',
// so a plain scene.json is an input with no overrides. Relative mesh and alpha-texture paths resolve against
// tests/fuzz/assets (a tiny OBJ with texture coordinates, a PLY, a PNG), so the corpus reaches the mesh and
// alpha-texture readers through the scene as `render` does.
//
// After a scene is accepted, the target checks what the loader promises about a validated scene (Scene.h):
// finite numbers, vertices within kMaxSceneMagnitude, indices inside the vertex arrays, unit normals, alpha
// values in [0,1]. A scene that passes validation but breaks one of these is a crash, like a sanitizer
// report.
#include "FuzzSupport.h"

#include "core/Error.h"
#include "scene/Scene.h"

#include <glm/glm.hpp>

#include <cmath>
#include <string>
#include <string_view>
#include <vector>

namespace
{

using sl::fuzz::expect;

bool isFinite(const glm::dvec3& v)
{
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

bool isFinite(const glm::vec3& v)
{
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Float normals that went through a transform and a renormalisation: 1e-3 is far above float rounding and
// far below any real error (a zero or NaN vector, an unnormalised one).
bool isUnit(const glm::dvec3& v)
{
  return isFinite(v) && std::abs(glm::length(v) - 1.0) < 1e-3;
}

void checkMesh(const sl::SceneObject& object)
{
  const sl::TriangleMesh& mesh = object.mesh;
  const std::string& name = object.name;
  expect(!mesh.indices.empty() && mesh.indices.size() % 3 == 0, name + ": accepted with no whole triangle");
  expect(mesh.normals.size() == mesh.positions.size(), name + ": one normal per vertex expected");
  expect(mesh.uvs.empty() || mesh.uvs.size() == mesh.positions.size(), name + ": uvs are not per vertex");
  for (const std::uint32_t index : mesh.indices)
    expect(index < mesh.positions.size(), name + ": triangle index past the vertex array");
  // Scene.h: final vertex positions lie within kMaxSceneMagnitude (float rounding of the bound allowed).
  const double magnitudeBound = sl::kMaxSceneMagnitude * (1.0 + 1e-6);
  for (const glm::vec3& position : mesh.positions)
  {
    expect(isFinite(position), name + ": non-finite vertex position in a validated scene");
    expect(std::abs(position.x) <= magnitudeBound && std::abs(position.y) <= magnitudeBound &&
        std::abs(position.z) <= magnitudeBound,
      name + ": vertex position beyond kMaxSceneMagnitude in a validated scene");
  }
  for (const glm::vec3& normal : mesh.normals)
    expect(isUnit(glm::dvec3(normal)), name + ": vertex normal is not a unit vector");
  for (const glm::vec2& uv : mesh.uvs)
    expect(std::isfinite(uv.x) && std::isfinite(uv.y), name + ": non-finite texture coordinate");
  if (object.hasAlphaTexture)
  {
    const sl::ImageF& alpha = object.alphaTexture.alpha;
    expect(alpha.width > 0 && alpha.height > 0 && alpha.components == 1 &&
        alpha.data.size() == alpha.pixelCount(),
      name + ": alpha texture with a wrong shape");
    for (const float value : alpha.data)
      expect(value >= 0.0f && value <= 1.0f, name + ": alpha value outside [0,1] (or NaN)");
  }
}

void checkScene(const sl::Scene& scene)
{
  const sl::Camera& camera = scene.camera;
  expect(isFinite(camera.position) && isFinite(camera.focalPoint) && isFinite(camera.viewUp),
    "camera: non-finite vector in a validated scene");
  expect(std::isfinite(camera.viewAngleDeg) && std::isfinite(camera.parallelScale) && camera.parallelScale > 0.0,
    "camera: non-finite or non-positive angle or scale");
  expect(camera.resolution.x > 0 && camera.resolution.y > 0, "camera: non-positive resolution accepted");
  expect(!scene.lights.empty() && !scene.objects.empty(), "a scene without lights or objects was accepted");
  for (const sl::Light& light : scene.lights)
  {
    expect(isFinite(light.center) && std::isfinite(light.size) && std::isfinite(light.intensity) &&
        std::isfinite(light.coneAngleDeg),
      "light: non-finite number in a validated scene");
    expect(isUnit(light.normal) && isUnit(light.up) && isUnit(light.direction),
      "light: normal, up or direction is not a unit vector");
  }
  for (const sl::SceneObject& object : scene.objects)
  {
    checkMesh(object);
    expect(isFinite(object.material.albedo), object.name + ": non-finite albedo");
  }
}

struct SceneInput
{
  std::vector<std::string> overrides;
  std::string document;
};

SceneInput splitInput(std::string_view text)
{
  SceneInput input;
  while (!text.empty() && text.front() == '/')
  {
    const std::size_t end = text.find('\n');
    input.overrides.emplace_back(text.substr(0, end));
    text = end == std::string_view::npos ? std::string_view() : text.substr(end + 1);
  }
  input.document = std::string(text);
  return input;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const SceneInput input = splitInput(std::string_view(reinterpret_cast<const char*>(data), size));
  try
  {
    const sl::Scene scene =
      sl::parseScene(input.document, input.overrides, "fuzz-input.json", SL_FUZZ_ASSET_DIR);
    checkScene(scene);
  }
  catch (const sl::InputError&)
  {
    // A refused input: the normal outcome for most of what the fuzzer writes.
  }
  return 0;
}
