// The ShadowLab scene model: what a scene.json describes, after validation and tessellation.
// The JSON format is documented in README.md ("Scene format"); loadScene() is the only way in.
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
  Camera camera;
  std::vector<Light> lights;
  std::vector<SceneObject> objects;

  Bounds bounds() const;        // all objects
  Bounds casterBounds() const;  // objects with castShadows
};

// Parses and validates a scene file. Throws InputError naming the file and the JSON path on any problem.
Scene loadScene(const std::filesystem::path& file);
// The same after replacing values: each override is "/json/pointer=value" (value as JSON, or a bare word as
// a string), e.g. "/lights/0/size=2". The result is validated like a file; a pointer whose parent does not
// exist is an InputError naming it. Used by --scene-set and bench's --scene-sweep.
Scene loadScene(const std::filesystem::path& file, const std::vector<std::string>& overrides);
// Same, from JSON text; `label` names the source in messages, `baseDir` resolves relative mesh paths.
Scene parseScene(const std::string& jsonText, const std::string& label, const std::filesystem::path& baseDir);

} // namespace sl
