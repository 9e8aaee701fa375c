// libFuzzer target: loadMesh, OpenMesh's readers behind the project's checks.
//
// Input layout: the first byte picks the file extension, which is what selects OpenMesh's reader:
// byte % 4 = 0 PLY, 1 OBJ, 2 OFF, 3 STL (the seed files start with '0'..'3'); the rest is the file. PLY and
// OBJ are what the datasets use and what most seeds are; OFF and STL come along because loadMesh takes them
// too. The file is written to a path of this process's own (ScratchDirectory).
//
// After a mesh is accepted, the target checks what MeshIO.h promises: whole triangles, indices inside the
// vertex array, finite positions, unit normals per vertex, texture coordinates per vertex or none.
#include "FuzzSupport.h"

#include "core/Error.h"
#include "scene/MeshIO.h"

#include <glm/glm.hpp>

#include <array>
#include <cmath>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  static const sl::fuzz::ScratchDirectory scratch;
  static const std::array<const char*, 4> kNames = { "input.ply", "input.obj", "input.off", "input.stl" };
  if (size == 0)
    return 0;
  const std::filesystem::path file = scratch.write(kNames[data[0] % kNames.size()], data + 1, size - 1);
  try
  {
    const sl::TriangleMesh mesh = sl::loadMesh(file).mesh;
    using sl::fuzz::expect;
    expect(!mesh.indices.empty() && mesh.indices.size() % 3 == 0, "loadMesh accepted a mesh with no whole triangle");
    expect(mesh.normals.size() == mesh.positions.size(), "loadMesh: not one normal per vertex");
    expect(mesh.uvs.empty() || mesh.uvs.size() == mesh.positions.size(), "loadMesh: texture coordinates not per vertex");
    for (const std::uint32_t index : mesh.indices)
      expect(index < mesh.positions.size(), "loadMesh: triangle index past the vertex array");
    for (const glm::vec3& p : mesh.positions)
      expect(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z), "loadMesh: non-finite vertex position");
    // Unit within 1e-3: far above float rounding, far below a zero, NaN or unnormalised vector.
    for (const glm::vec3& n : mesh.normals)
      expect(std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z) &&
          std::abs(glm::length(glm::dvec3(n)) - 1.0) < 1e-3,
        "loadMesh: vertex normal is not a unit vector");
    for (const glm::vec2& uv : mesh.uvs)
      expect(std::isfinite(uv.x) && std::isfinite(uv.y), "loadMesh: non-finite texture coordinate");
  }
  catch (const sl::InputError&)
  {
    // A refused file: the normal outcome for most of what the fuzzer writes.
  }
  return 0;
}
