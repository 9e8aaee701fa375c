#include "scene/WeldedMesh.h"

#include "core/Error.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <unordered_map>

namespace sl
{

namespace
{

struct Cell
{
  std::int64_t x, y, z;
  bool operator==(const Cell& other) const { return x == other.x && y == other.y && z == other.z; }
};

struct CellHash
{
  std::size_t operator()(const Cell& cell) const
  {
    // Large odd multipliers (as in Teschner et al. 2003's spatial hash) spread neighbouring cells.
    return static_cast<std::size_t>(cell.x * 73856093LL) ^ static_cast<std::size_t>(cell.y * 19349663LL) ^
      static_cast<std::size_t>(cell.z * 83492791LL);
  }
};

Cell cellOf(const glm::vec3& position, double cellSize)
{
  return { static_cast<std::int64_t>(std::floor(position.x / cellSize)),
    static_cast<std::int64_t>(std::floor(position.y / cellSize)),
    static_cast<std::int64_t>(std::floor(position.z / cellSize)) };
}

bool withinTolerance(const glm::vec3& a, const glm::vec3& b, double tolerance)
{
  for (int axis = 0; axis < 3; ++axis)
  {
    if (std::abs(static_cast<double>(a[axis]) - static_cast<double>(b[axis])) > tolerance)
    {
      return false;
    }
  }
  return true;
}

// Welded index of every vertex of `mesh`, and the welded positions (first vertex of each cluster).
std::vector<std::uint32_t> weldVertices(const TriangleMesh& mesh, double tolerance, std::vector<glm::vec3>& positions)
{
  std::unordered_map<Cell, std::vector<std::uint32_t>, CellHash> grid;
  std::vector<std::uint32_t> weldedIndex(mesh.positions.size());
  for (std::size_t vertex = 0; vertex < mesh.positions.size(); ++vertex)
  {
    const glm::vec3& position = mesh.positions[vertex];
    const Cell cell = cellOf(position, tolerance);
    // Within the tolerance per axis means at most one cell away per axis (cell size = tolerance).
    std::uint32_t match = UINT32_MAX;
    for (std::int64_t dz = -1; dz <= 1 && match == UINT32_MAX; ++dz)
    {
      for (std::int64_t dy = -1; dy <= 1 && match == UINT32_MAX; ++dy)
      {
        for (std::int64_t dx = -1; dx <= 1 && match == UINT32_MAX; ++dx)
        {
          const auto found = grid.find(Cell{ cell.x + dx, cell.y + dy, cell.z + dz });
          if (found == grid.end())
          {
            continue;
          }
          for (const std::uint32_t candidate : found->second)
          {
            // The earliest welded vertex wins, so the order of the neighbour search does not matter.
            if (withinTolerance(positions[candidate], position, tolerance) && candidate < match)
            {
              match = candidate;
            }
          }
        }
      }
    }
    if (match == UINT32_MAX)
    {
      match = static_cast<std::uint32_t>(positions.size());
      positions.push_back(position);
      grid[cell].push_back(match);
    }
    weldedIndex[vertex] = match;
  }
  return weldedIndex;
}

void buildEdgeTable(WeldedMesh& welded)
{
  std::unordered_map<std::uint64_t, std::uint32_t> edgeIndex;
  edgeIndex.reserve(welded.triangles.size() * 2);
  welded.triangleEdges.resize(welded.triangles.size());
  for (std::size_t triangle = 0; triangle < welded.triangles.size(); ++triangle)
  {
    const auto& corners = welded.triangles[triangle];
    for (int side = 0; side < 3; ++side)
    {
      const std::uint32_t from = corners[side];
      const std::uint32_t to = corners[(side + 1) % 3];
      const std::uint32_t v0 = std::min(from, to);
      const std::uint32_t v1 = std::max(from, to);
      const std::uint64_t key = (static_cast<std::uint64_t>(v0) << 32) | v1;
      const auto [entry, inserted] = edgeIndex.emplace(key, static_cast<std::uint32_t>(welded.edges.size()));
      if (inserted)
      {
        WeldedEdge edge;
        edge.v0 = v0;
        edge.v1 = v1;
        welded.edges.push_back(edge);
      }
      welded.triangleEdges[triangle][side] = entry->second;
      ++welded.edges[entry->second].useCount;
    }
  }
  // Uses grouped by edge (counting sort), in triangle order within an edge.
  std::uint32_t next = 0;
  for (WeldedEdge& edge : welded.edges)
  {
    edge.firstUse = next;
    next += edge.useCount;
  }
  welded.edgeUses.resize(next);
  std::vector<std::uint32_t> filled(welded.edges.size(), 0);
  for (std::size_t triangle = 0; triangle < welded.triangles.size(); ++triangle)
  {
    for (int side = 0; side < 3; ++side)
    {
      const std::uint32_t edgeId = welded.triangleEdges[triangle][side];
      const WeldedEdge& edge = welded.edges[edgeId];
      EdgeUse& use = welded.edgeUses[edge.firstUse + filled[edgeId]++];
      use.triangle = static_cast<std::uint32_t>(triangle);
      use.forward = welded.triangles[triangle][side] == edge.v0;
    }
  }
}

} // namespace

std::size_t WeldedMesh::boundaryEdgeCount() const
{
  return static_cast<std::size_t>(
    std::count_if(edges.begin(), edges.end(), [](const WeldedEdge& edge) { return edge.useCount == 1; }));
}

std::size_t WeldedMesh::nonManifoldEdgeCount() const
{
  return static_cast<std::size_t>(
    std::count_if(edges.begin(), edges.end(), [](const WeldedEdge& edge) { return edge.useCount > 2; }));
}

std::size_t WeldedMesh::inconsistentEdgeCount() const
{
  return static_cast<std::size_t>(std::count_if(edges.begin(), edges.end(), [this](const WeldedEdge& edge) {
    return edge.useCount == 2 && edgeUses[edge.firstUse].forward == edgeUses[edge.firstUse + 1].forward;
  }));
}

double weldTolerance(const TriangleMesh& mesh)
{
  glm::dvec3 low(0.0), high(0.0);
  double maxAbs = 0.0;
  for (std::size_t vertex = 0; vertex < mesh.positions.size(); ++vertex)
  {
    const glm::dvec3 position(mesh.positions[vertex]);
    low = vertex == 0 ? position : glm::min(low, position);
    high = vertex == 0 ? position : glm::max(high, position);
    maxAbs = std::max({ maxAbs, std::abs(position.x), std::abs(position.y), std::abs(position.z) });
  }
  const double tolerance = std::max(1e-6 * glm::length(high - low), 4.0 * FLT_EPSILON * maxAbs);
  // Every vertex at the origin: any positive tolerance welds them all.
  return tolerance > 0.0 ? tolerance : 1.0;
}

WeldedMesh weldMesh(const TriangleMesh& mesh, std::size_t objectIndex)
{
  WeldedMesh welded;
  welded.objectIndex = objectIndex;
  welded.weldTolerance = weldTolerance(mesh);
  const std::vector<std::uint32_t> weldedIndex = weldVertices(mesh, welded.weldTolerance, welded.positions);
  for (std::size_t triangle = 0; triangle < mesh.triangleCount(); ++triangle)
  {
    const std::array<std::uint32_t, 3> corners = { weldedIndex[mesh.indices[3 * triangle]],
      weldedIndex[mesh.indices[3 * triangle + 1]], weldedIndex[mesh.indices[3 * triangle + 2]] };
    if (corners[0] == corners[1] || corners[1] == corners[2] || corners[2] == corners[0])
    {
      ++welded.collapsedTriangles;
      continue;
    }
    welded.triangles.push_back(corners);
    welded.sourceTriangles.push_back(static_cast<std::uint32_t>(triangle));
  }
  SL_CHECK(welded.positions.size() < UINT32_MAX);
  buildEdgeTable(welded);
  return welded;
}

std::vector<WeldedMesh> weldCasters(const Scene& scene, bool opaqueOnly)
{
  std::vector<WeldedMesh> casters;
  for (std::size_t object = 0; object < scene.objects.size(); ++object)
  {
    if (scene.objects[object].castShadows && !(opaqueOnly && scene.objects[object].hasAlphaTexture))
    {
      casters.push_back(weldMesh(scene.objects[object].mesh, object));
    }
  }
  return casters;
}

} // namespace sl
