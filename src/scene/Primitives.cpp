#include "scene/Primitives.h"

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

namespace sl
{

namespace
{

// Below this sine of the angle between two directions we call them parallel: a frame built from them would
// be numerically meaningless.
constexpr double kParallelSine = 1e-6;

void addVertex(TriangleMesh& mesh, const glm::dvec3& position, const glm::dvec3& normal, const glm::dvec2& uv)
{
  mesh.positions.emplace_back(position);
  mesh.normals.emplace_back(normal);
  mesh.uvs.emplace_back(uv);
}

void addTriangle(TriangleMesh& mesh, std::uint32_t a, std::uint32_t b, std::uint32_t c)
{
  mesh.indices.insert(mesh.indices.end(), { a, b, c });
}

std::uint32_t nextIndex(const TriangleMesh& mesh)
{
  return static_cast<std::uint32_t>(mesh.positions.size());
}

// Appends a quad to `mesh`; shared by makeQuad and the six faces of makeBox.
void appendQuad(TriangleMesh& mesh, const glm::dvec3& center, const glm::dvec2& size, const glm::dvec3& unitNormal,
  const glm::dvec3& unitUp)
{
  const glm::dvec3 right = glm::normalize(glm::cross(unitUp, unitNormal));
  const glm::dvec3 halfRight = 0.5 * size.x * right;
  const glm::dvec3 halfUp = 0.5 * size.y * unitUp;
  const std::uint32_t first = nextIndex(mesh);
  // right x up = normal, so this (u,v) order is counter-clockwise seen from the normal's side.
  addVertex(mesh, center - halfRight - halfUp, unitNormal, { 0.0, 0.0 });
  addVertex(mesh, center + halfRight - halfUp, unitNormal, { 1.0, 0.0 });
  addVertex(mesh, center + halfRight + halfUp, unitNormal, { 1.0, 1.0 });
  addVertex(mesh, center - halfRight + halfUp, unitNormal, { 0.0, 1.0 });
  addTriangle(mesh, first, first + 1, first + 2);
  addTriangle(mesh, first, first + 2, first + 3);
}

} // namespace

bool isParallel(const glm::dvec3& a, const glm::dvec3& b)
{
  const double sine = glm::length(glm::cross(glm::normalize(a), glm::normalize(b)));
  return sine < kParallelSine;
}

glm::dvec3 defaultUp(const glm::dvec3& unitNormal)
{
  const glm::dvec3 worldY{ 0.0, 1.0, 0.0 };
  if (!isParallel(worldY, unitNormal))
    return orthogonalizedUp(worldY, unitNormal);
  return orthogonalizedUp(glm::dvec3{ 1.0, 0.0, 0.0 }, unitNormal);
}

glm::dvec3 orthogonalizedUp(const glm::dvec3& up, const glm::dvec3& unitNormal)
{
  return glm::normalize(up - glm::dot(up, unitNormal) * unitNormal);
}

TriangleMesh makeQuad(const glm::dvec3& center, const glm::dvec2& size, const glm::dvec3& unitNormal,
  const glm::dvec3& unitUp)
{
  TriangleMesh mesh;
  appendQuad(mesh, center, size, unitNormal, unitUp);
  return mesh;
}

TriangleMesh makeBox(const glm::dvec3& center, const glm::dvec3& size)
{
  struct Face
  {
    glm::dvec3 normal;
    glm::dvec3 up;
  };
  // Side faces keep +y as up; the top and bottom faces use -z / +z so their right is +x.
  const Face faces[] = {
    { { 1, 0, 0 }, { 0, 1, 0 } },
    { { -1, 0, 0 }, { 0, 1, 0 } },
    { { 0, 1, 0 }, { 0, 0, -1 } },
    { { 0, -1, 0 }, { 0, 0, 1 } },
    { { 0, 0, 1 }, { 0, 1, 0 } },
    { { 0, 0, -1 }, { 0, 1, 0 } },
  };
  TriangleMesh mesh;
  for (const Face& face : faces)
  {
    const glm::dvec3 right = glm::cross(face.up, face.normal);
    // The axes are unit and axis-aligned, so |axis| . size picks the box extent along that axis.
    const glm::dvec2 faceSize{ glm::dot(glm::abs(right), size), glm::dot(glm::abs(face.up), size) };
    const glm::dvec3 faceCenter = center + 0.5 * face.normal * size;
    appendQuad(mesh, faceCenter, faceSize, face.normal, face.up);
  }
  return mesh;
}

TriangleMesh makeSphere(const glm::dvec3& center, double radius)
{
  const double twoPi = glm::two_pi<double>();
  const double pi = glm::pi<double>();
  // Unit direction for (u, v): azimuth 2pi*u from +x toward -z, polar angle pi*v from the south pole.
  const auto direction = [&](double u, double v) {
    const double azimuth = twoPi * u;
    const double polar = pi * v;
    return glm::dvec3{ std::sin(polar) * std::cos(azimuth), -std::cos(polar), -std::sin(polar) * std::sin(azimuth) };
  };

  TriangleMesh mesh;
  // Pole vertices: one per segment, each with the u of its segment's middle, so the cap triangles map
  // to the texture without a shared, arbitrary u.
  const std::uint32_t southPole = nextIndex(mesh);
  for (int segment = 0; segment < kSphereSegments; ++segment)
  {
    const glm::dvec2 uv{ (segment + 0.5) / kSphereSegments, 0.0 };
    const glm::dvec3 dir{ 0.0, -1.0, 0.0 };
    addVertex(mesh, center + radius * dir, dir, uv);
  }
  const std::uint32_t northPole = nextIndex(mesh);
  for (int segment = 0; segment < kSphereSegments; ++segment)
  {
    const glm::dvec2 uv{ (segment + 0.5) / kSphereSegments, 1.0 };
    const glm::dvec3 dir{ 0.0, 1.0, 0.0 };
    addVertex(mesh, center + radius * dir, dir, uv);
  }
  // Interior rings 1 .. rings-1, each with kSphereSegments + 1 vertices (the seam is duplicated).
  const std::uint32_t firstRing = nextIndex(mesh);
  const std::uint32_t ringStride = kSphereSegments + 1;
  for (int ring = 1; ring < kSphereRings; ++ring)
  {
    for (int segment = 0; segment <= kSphereSegments; ++segment)
    {
      const glm::dvec2 uv{ static_cast<double>(segment) / kSphereSegments, static_cast<double>(ring) / kSphereRings };
      const glm::dvec3 dir = direction(uv.x, uv.y);
      addVertex(mesh, center + radius * dir, dir, uv);
    }
  }
  const auto ringVertex = [&](int ring, int segment) {
    return firstRing + static_cast<std::uint32_t>(ring - 1) * ringStride + static_cast<std::uint32_t>(segment);
  };

  // Moving along a segment goes east, along a ring index goes north; east x north points outward, so
  // (here, east, north-east) is counter-clockwise seen from outside.
  for (int segment = 0; segment < kSphereSegments; ++segment)
  {
    const auto s = static_cast<std::uint32_t>(segment);
    addTriangle(mesh, southPole + s, ringVertex(1, segment + 1), ringVertex(1, segment));
    for (int ring = 1; ring < kSphereRings - 1; ++ring)
    {
      addTriangle(mesh, ringVertex(ring, segment), ringVertex(ring, segment + 1), ringVertex(ring + 1, segment + 1));
      addTriangle(mesh, ringVertex(ring, segment), ringVertex(ring + 1, segment + 1), ringVertex(ring + 1, segment));
    }
    const int lastRing = kSphereRings - 1;
    addTriangle(mesh, ringVertex(lastRing, segment), ringVertex(lastRing, segment + 1), northPole + s);
  }
  return mesh;
}

TriangleMesh makeDisk(const glm::dvec3& center, double radius, const glm::dvec3& unitNormal,
  const glm::dvec3& unitUp)
{
  const glm::dvec3 right = glm::normalize(glm::cross(unitUp, unitNormal));
  TriangleMesh mesh;
  const std::uint32_t hub = nextIndex(mesh);
  addVertex(mesh, center, unitNormal, { 0.5, 0.5 });
  const std::uint32_t firstRim = nextIndex(mesh);
  for (int segment = 0; segment < kDiskSegments; ++segment)
  {
    const double angle = glm::two_pi<double>() * segment / kDiskSegments;
    const glm::dvec2 local = radius * glm::dvec2{ std::cos(angle), std::sin(angle) };
    addVertex(mesh, center + local.x * right + local.y * unitUp, unitNormal, (local + radius) / (2.0 * radius));
  }
  // The angle grows from right toward up, and right x up = normal: counter-clockwise seen from the normal.
  for (std::uint32_t segment = 0; segment < kDiskSegments; ++segment)
    addTriangle(mesh, hub, firstRim + segment, firstRim + (segment + 1) % kDiskSegments);
  return mesh;
}

glm::dmat4 Transform::worldFromLocal() const
{
  const glm::dmat4 identity{ 1.0 };
  const glm::dmat4 rotation = glm::rotate(identity, glm::radians(rotateDeg.z), glm::dvec3{ 0, 0, 1 }) *
    glm::rotate(identity, glm::radians(rotateDeg.y), glm::dvec3{ 0, 1, 0 }) *
    glm::rotate(identity, glm::radians(rotateDeg.x), glm::dvec3{ 1, 0, 0 });
  return glm::translate(identity, translate) * rotation * glm::scale(identity, scale);
}

void transformMesh(TriangleMesh& mesh, const glm::dmat4& worldFromLocal)
{
  const glm::dmat3 normalFromLocal = glm::transpose(glm::inverse(glm::dmat3(worldFromLocal)));
  for (glm::vec3& position : mesh.positions)
    position = glm::vec3(worldFromLocal * glm::dvec4(glm::dvec3(position), 1.0));
  for (glm::vec3& normal : mesh.normals)
    normal = glm::vec3(glm::normalize(normalFromLocal * glm::dvec3(normal)));
}

} // namespace sl
