// The ShadowLab scene model: what a scene.json describes, after validation and tessellation.
// The JSON format is documented in docs/scene-format.md; loadScene() is the only way in.
//
// Conventions: world space is right-handed, units are whatever the scene uses (the datasets use metres).
// All geometry is stored already transformed to world space, as triangles.
#pragma once

#include "core/Image.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace sl
{

enum class Projection
{
  Perspective,
  Orthographic
};

struct Camera
{
  Projection projection = Projection::Perspective;
  glm::dvec3 position{ 0.0, 0.0, 5.0 };
  glm::dvec3 focalPoint{ 0.0, 0.0, 0.0 };
  glm::dvec3 viewUp{ 0.0, 1.0, 0.0 };
  double viewAngleDeg = 30.0; // vertical field of view (VTK's convention), perspective only
  double parallelScale = 1.0; // half the viewport height in world units, orthographic only
  glm::ivec2 resolution{ 512, 512 };
};

enum class LightType
{
  Area,
  Point,
  Directional,
  Spot
};

enum class LightShape
{
  Square,
  Disk
};

// As the scene file spells them ("area", "point", "directional", "spot"; "square", "disk").
const char* lightTypeName(LightType type);
const char* lightShapeName(LightShape shape);

struct Light
{
  LightType type = LightType::Area;
  LightShape shape = LightShape::Square;
  glm::dvec3 center{ 0.0, 5.0, 0.0 };
  glm::dvec3 normal{ 0.0, -1.0, 0.0 };    // area/spot: unit, points toward the scene
  glm::dvec3 up{ 0.0, 0.0, 1.0 };         // area: unit, in the light plane (orients a square's edges)
  glm::dvec3 direction{ 0.0, -1.0, 0.0 }; // directional: unit, direction light travels
  double size = 1.0;                       // area: side length (square) or diameter (disk)
  double coneAngleDeg = 30.0;              // spot: half-angle of the cone
  double intensity = 1.0;

  // Unit vector in the light plane orthogonal to `up` and `normal` (right-handed: right = up x normal).
  glm::dvec3 right() const { return glm::normalize(glm::cross(up, normal)); }
  double area() const;
};

struct Material
{
  glm::dvec3 albedo{ 0.8, 0.8, 0.8 };
};

// Perforation mask: alpha < 0.5 marks holes (no surface there, casts and receives nothing).
// Sampled with the triangle's texture coordinates, repeat wrap, nearest texel.
struct AlphaTexture
{
  std::string source; // file path as written in the scene, or "fence" / "leaves"
  ImageF alpha;       // 1 component, row 0 = v near 0
};

struct TriangleMesh
{
  std::vector<glm::vec3> positions; // world space
  std::vector<glm::vec3> normals;   // world space, unit, per vertex
  std::vector<glm::vec2> uvs;       // per vertex; empty when the mesh has none
  std::vector<std::uint32_t> indices; // 3 per triangle, counter-clockwise around the outward normal

  std::size_t triangleCount() const { return indices.size() / 3; }
};

struct SceneObject
{
  std::string name; // "objects[3] (mesh bunny.ply)" style label used in messages
  TriangleMesh mesh;
  Material material;
  bool hasAlphaTexture = false;
  AlphaTexture alphaTexture;
  bool castShadows = true;
  bool receiveShadows = true;
  std::size_t droppedDegenerateTriangles = 0;
};

struct Bounds
{
  glm::dvec3 min{ 1e300 };
  glm::dvec3 max{ -1e300 };
  bool empty() const { return min.x > max.x; }
  void extend(const glm::dvec3& p)
  {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  glm::dvec3 center() const { return 0.5 * (min + max); }
  double radius() const { return 0.5 * glm::length(max - min); } // bounding-sphere radius about center()
};

struct Scene
{
  std::filesystem::path file; // the scene file this came from (empty for scenes built in code)
  // Every file the scene was read from, absolute and lexically normal: the scene file itself (loadScene only),
  // each mesh file and each alpha-texture PNG, in the order the loader read them. Output code refuses an --out
  // that would replace one of them.
  std::vector<std::filesystem::path> inputFiles;
  Camera camera;
  std::vector<Light> lights;
  std::vector<SceneObject> objects;

  Bounds bounds() const;        // all objects
  Bounds casterBounds() const;  // objects with castShadows
  std::vector<Bounds> objectBounds() const; // each object's, in order
};

// Limits of the scene format (docs/scene-format.md, "Limits"), each with the reason it exists.
// A scene file is read only when it is a regular file (after following symlinks) of at most this size: a FIFO
// would block forever and /dev/zero never ends.
constexpr std::uintmax_t kMaxSceneFileBytes = 64u * 1024u * 1024u;
// JSON objects and arrays nest at most this deep, in the file and in --scene-set values: deeper documents are
// refused while parsing, so nothing recursive ever walks an unbounded depth (the stack would overflow).
constexpr int kMaxJsonDepth = 256;
// Every coordinate (camera, light and primitive positions, translations, final vertex positions), size and
// intensity has a magnitude of at most this many scene units. Positions are float32 on the GPU and in Embree;
// with this bound every product the pipeline forms stays finite, and Embree's ray validity (|origin|,
// |direction| <= 1.8e18) holds.
constexpr double kMaxSceneMagnitude = 1e6;
// Point, spot and area lights lie at most this many bounding radii of the objects from the centre of the
// objects' bounding box, and the camera at most kMaxCameraDistanceInSceneRadii. Farther away, float32
// light-space depths (relative step 6e-8 of the distance) no longer resolve the scene. Measured against the
// ray tracer at 128x128 (docs/scene-format.md): pcss on bunny is exact to 4700 radii, loses shadow pixels
// from 7000 (RMSE 0.047 -> 0.094; 0.149 at 9300); hard on sphere-point is exact to 9300, 20x the error
// at 23000. 3000 keeps a margin of 2 and still takes a light at y = 1e4 over the datasets (2300 radii).
constexpr double kMaxLightDistanceInSceneRadii = 3e3;
// The camera is far less sensitive (the G-buffer keeps world positions): sphere-point renders the same image
// at 1.2e7 radii, 0.5% of pixels change at 1.2e8. A margin of 10 below the first.
constexpr double kMaxCameraDistanceInSceneRadii = 1e6;

// Parses and validates a scene file. Throws InputError naming the file and the JSON path on any problem.
Scene loadScene(const std::filesystem::path& file);
// The same after replacing values: each override is "/json/pointer=value" (value as JSON, or a bare word as
// a string), e.g. "/lights/0/size=2". The result is validated like a file; a pointer whose parent does not
// exist, or an array index past the end (index == size appends), is an InputError naming it. Used by
// --scene-set and bench's --scene-sweep.
Scene loadScene(const std::filesystem::path& file, const std::vector<std::string>& overrides);
// The same from JSON text (loadScene reads the file and calls this; fuzzers call it without a file). The text
// is parsed once with the depth limit, the overrides are applied to that document, and the result is
// validated. `label` names the source in messages, `baseDir` resolves relative mesh and PNG paths.
// Scene::file is left empty and Scene::inputFiles lists only the mesh and PNG files.
Scene parseScene(const std::string& jsonText, const std::vector<std::string>& overrides, const std::string& label,
  const std::filesystem::path& baseDir);
Scene parseScene(const std::string& jsonText, const std::string& label, const std::filesystem::path& baseDir);

} // namespace sl
