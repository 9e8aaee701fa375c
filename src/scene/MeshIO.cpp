#include "scene/MeshIO.h"

#include "core/Error.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <limits>
#include <system_error>
#include <vector>

namespace sl
{

namespace
{

using OpenMeshTriMesh = OpenMesh::TriMesh_ArrayKernelT<>;

// Relative area threshold of MeshIO.h: twice the area below this times the longest edge squared is a
// triangle whose corners are collinear up to float rounding.
constexpr double kDegenerateAreaRatio = 1e-10;

// OpenMesh reports through its own global streams (omerr/omout/omlog) straight to the console. The loader
// must print nothing (problems become InputErrors), so the streams are muted for the duration of a read
// and restored afterwards, whatever state the rest of the program left them in.
class OpenMeshConsoleSilencer
{
public:
  OpenMeshConsoleSilencer()
    : wasEnabled_{ ::omerr().is_enabled(), ::omout().is_enabled(), ::omlog().is_enabled() }
  {
    for (OpenMesh::mostream* stream : streams())
      stream->disable();
  }
  ~OpenMeshConsoleSilencer()
  {
    const std::array<OpenMesh::mostream*, 3> all = streams();
    for (std::size_t i = 0; i < all.size(); ++i)
    {
      // Flushing while disabled discards a half-written line instead of printing it later.
      all[i]->flush();
      if (wasEnabled_[i])
        all[i]->enable();
    }
  }
  OpenMeshConsoleSilencer(const OpenMeshConsoleSilencer&) = delete;
  OpenMeshConsoleSilencer& operator=(const OpenMeshConsoleSilencer&) = delete;

private:
  static std::array<OpenMesh::mostream*, 3> streams()
  {
    return { &::omerr(), &::omout(), &::omlog() };
  }
  std::array<bool, 3> wasEnabled_;
};

glm::dvec3 toDvec3(const OpenMeshTriMesh::Point& p)
{
  return { p[0], p[1], p[2] };
}

bool isFinite(const glm::dvec3& p)
{
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

// True for a degenerate triangle (MeshIO.h); otherwise `areaNormal` receives its unnormalised normal, whose
// length is twice the area (the weight of an area-weighted vertex normal).
bool isDegenerate(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, glm::dvec3& areaNormal)
{
  if (!isFinite(a) || !isFinite(b) || !isFinite(c))
    return true;
  areaNormal = glm::cross(b - a, c - a);
  const double longestEdgeSquared =
    std::max({ glm::dot(b - a, b - a), glm::dot(c - b, c - b), glm::dot(a - c, a - c) });
  // Written as "not greater" so a NaN from overflowing products also counts as degenerate.
  return !(glm::length(areaNormal) > kDegenerateAreaRatio * longestEdgeSquared);
}

void readWithOpenMesh(const std::filesystem::path& file, OpenMeshTriMesh& mesh, OpenMesh::IO::Options& options)
{
  std::error_code error;
  if (!std::filesystem::exists(file, error))
    throw InputError(format("cannot read '", file.string(), "' (no such file)"));
  if (!std::filesystem::is_regular_file(file, error))
    throw InputError(format("cannot read '", file.string(), "' (not a regular file)"));

  mesh.request_vertex_normals();
  mesh.request_vertex_texcoords2D();
  options = OpenMesh::IO::Options::VertexNormal | OpenMesh::IO::Options::VertexTexCoord;
  bool readOk = false;
  try
  {
    const OpenMeshConsoleSilencer silencer;
    readOk = OpenMesh::IO::read_mesh(mesh, file.string(), options);
  }
  catch (const std::exception& e)
  {
    throw InputError(format("cannot read '", file.string(), "' (", e.what(), ")"));
  }
  if (!readOk)
    throw InputError(format("cannot read '", file.string(), "' (unsupported format or corrupt file)"));
  if (mesh.n_faces() == 0)
    throw InputError(format("'", file.string(), "': empty mesh (no faces)"));
}

} // namespace

LoadedMesh loadMesh(const std::filesystem::path& file)
{
  OpenMeshTriMesh source;
  OpenMesh::IO::Options readOptions;
  readWithOpenMesh(file, source, readOptions);
  const bool fileHasNormals = readOptions.vertex_has_normal();
  const bool fileHasUvs = readOptions.vertex_has_texcoord();

  constexpr std::uint32_t kUnused = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> compactIndexOf(source.n_vertices(), kUnused);
  std::vector<int> usedSourceVertices;         // compact index -> source vertex index
  std::vector<glm::dvec3> areaWeightedNormals; // per compact vertex
  std::vector<glm::dvec3> firstFaceNormal;     // per compact vertex: fallback when the sum cancels out

  LoadedMesh result;
  for (const OpenMeshTriMesh::FaceHandle face : source.faces())
  {
    std::array<int, 3> corners{};
    std::size_t cornerCount = 0;
    for (const OpenMeshTriMesh::VertexHandle vertex : source.fv_range(face))
    {
      if (cornerCount < corners.size())
        corners[cornerCount] = vertex.idx();
      ++cornerCount;
    }
    SL_CHECK_MSG(cornerCount == 3, "OpenMesh TriMesh face with ", cornerCount, " corners");

    glm::dvec3 areaNormal{ 0.0 };
    const glm::dvec3 a = toDvec3(source.point(OpenMeshTriMesh::VertexHandle(corners[0])));
    const glm::dvec3 b = toDvec3(source.point(OpenMeshTriMesh::VertexHandle(corners[1])));
    const glm::dvec3 c = toDvec3(source.point(OpenMeshTriMesh::VertexHandle(corners[2])));
    if (isDegenerate(a, b, c, areaNormal))
    {
      ++result.droppedDegenerateTriangles;
      continue;
    }
    for (const int corner : corners)
    {
      std::uint32_t& compact = compactIndexOf[static_cast<std::size_t>(corner)];
      if (compact == kUnused)
      {
        compact = static_cast<std::uint32_t>(usedSourceVertices.size());
        usedSourceVertices.push_back(corner);
        areaWeightedNormals.emplace_back(0.0);
        firstFaceNormal.push_back(glm::normalize(areaNormal));
      }
      areaWeightedNormals[compact] += areaNormal;
      result.mesh.indices.push_back(compact);
    }
  }
  if (result.mesh.indices.empty())
    throw InputError(format("'", file.string(), "': all ", result.droppedDegenerateTriangles,
      " triangles are degenerate (zero area or non-finite coordinates)"));

  TriangleMesh& mesh = result.mesh;
  mesh.positions.reserve(usedSourceVertices.size());
  mesh.normals.reserve(usedSourceVertices.size());
  for (std::size_t compact = 0; compact < usedSourceVertices.size(); ++compact)
  {
    const OpenMeshTriMesh::VertexHandle vertex(usedSourceVertices[compact]);
    mesh.positions.emplace_back(toDvec3(source.point(vertex)));

    const double smoothLength = glm::length(areaWeightedNormals[compact]);
    glm::dvec3 normal = smoothLength > 0.0 ? areaWeightedNormals[compact] / smoothLength : firstFaceNormal[compact];
    if (fileHasNormals)
    {
      const OpenMeshTriMesh::Normal& fileNormal = source.normal(vertex);
      const glm::dvec3 candidate{ fileNormal[0], fileNormal[1], fileNormal[2] };
      const double length = glm::length(candidate);
      if (std::isfinite(length) && length > 0.0)
        normal = candidate / length;
    }
    mesh.normals.emplace_back(normal);

    if (fileHasUvs)
    {
      const OpenMeshTriMesh::TexCoord2D& uv = source.texcoord2D(vertex);
      mesh.uvs.emplace_back(uv[0], uv[1]);
    }
  }
  return result;
}

} // namespace sl
