#include "scene/AlphaMesh.h"

#include "core/Error.h"
#include "scene/AlphaTexture.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace sl
{

namespace
{

constexpr std::uint32_t kNoVertex = std::numeric_limits<std::uint32_t>::max();

bool isOpaqueTexel(const ImageF& alpha, int x, int y)
{
  // The renderers' rule at the texel's centre (AlphaTexture.h): the centre lies inside the texel whatever the
  // size, so this reads texel (x, y) itself.
  return !alphaHoleAt(alpha, { (x + 0.5) / alpha.width, (y + 0.5) / alpha.height });
}

// The index of the vertex at a texel corner, per row of corners: a texel row (y) uses the corner rows y and y + 1,
// and the next texel row reuses row y + 1, so two rows of W + 1 entries hold all sharing there is (a W x H grid
// of indices would cost W H words for a mask that is mostly holes).
class CornerRow
{
public:
  explicit CornerRow(int width)
    : indices_(static_cast<std::size_t>(width) + 1, kNoVertex)
  {
  }
  std::uint32_t& at(int x) { return indices_[static_cast<std::size_t>(x)]; }
  void clear() { std::fill(indices_.begin(), indices_.end(), kNoVertex); }

private:
  std::vector<std::uint32_t> indices_;
};

} // namespace

QuadUvFrame quadUvFrame(const TriangleMesh& quad)
{
  SL_CHECK_MSG(quad.positions.size() == 4 && quad.uvs.size() == 4 && quad.normals.size() == 4 &&
      quad.triangleCount() == 2,
    "quadUvFrame expects makeQuad's layout, got ", quad.positions.size(), " vertices and ", quad.triangleCount(),
    " triangles");
  // Find the corners by their uv rather than by their order, so the frame does not rest on appendQuad's
  // vertex order.
  const auto cornerWithUv = [&](float u, float v) {
    for (std::size_t i = 0; i < 4; ++i)
      if (quad.uvs[i] == glm::vec2(u, v))
        return glm::dvec3(quad.positions[i]);
    SL_CHECK_MSG(false, "quadUvFrame: no corner with uv (", u, ", ", v, ")");
    return glm::dvec3(0.0);
  };
  QuadUvFrame frame;
  frame.corners = { cornerWithUv(0.0f, 0.0f), cornerWithUv(1.0f, 0.0f), cornerWithUv(1.0f, 1.0f),
    cornerWithUv(0.0f, 1.0f) };
  frame.normal = glm::normalize(glm::dvec3(quad.normals[0]));
  // makeQuad winds counter-clockwise around the normal (right x up = normal), and transforms keep that.
  SL_CHECK_MSG(glm::dot(glm::cross(frame.uAxis(), frame.vAxis()), frame.normal) > 0.0,
    "quadUvFrame: the uv axes do not turn counter-clockwise around the quad's normal");
  return frame;
}

std::size_t opaqueTexelCount(const ImageF& alpha)
{
  std::size_t count = 0;
  for (int y = 0; y < alpha.height; ++y)
    for (int x = 0; x < alpha.width; ++x)
      count += isOpaqueTexel(alpha, x, y) ? 1 : 0;
  return count;
}

TriangleMesh meshOpaqueTexels(const QuadUvFrame& frame, const ImageF& alpha)
{
  SL_CHECK_MSG(alpha.components == 1 && alpha.width > 0 && alpha.height > 0, "meshOpaqueTexels: a ",
    alpha.width, " x ", alpha.height, " x ", alpha.components, " mask");
  const std::size_t opaqueTexels = opaqueTexelCount(alpha);
  if (2 * opaqueTexels > kMaxAlphaMeshTriangles)
    throw InputError(format("the alpha texture (", alpha.width, " x ", alpha.height, ") has ", opaqueTexels,
      " opaque texels; meshing them would make ", 2 * opaqueTexels, " triangles, more than the limit ",
      kMaxAlphaMeshTriangles, " (a fully opaque 2048 x 2048 mask; use a mesh file instead)"));

  TriangleMesh mesh;
  mesh.indices.reserve(6 * opaqueTexels);
  const glm::vec3 normal(frame.normal);
  // Corner (i, j): one double expression per corner (the quad's own uv interpolation, AlphaMesh.h), rounded to
  // float once, and one vertex shared by every texel that uses the corner.
  const auto addCorner = [&](int i, int j) {
    const glm::dvec2 uv{ static_cast<double>(i) / alpha.width, static_cast<double>(j) / alpha.height };
    mesh.positions.emplace_back(frame.pointAt(uv));
    mesh.normals.push_back(normal);
    mesh.uvs.emplace_back(uv);
    return static_cast<std::uint32_t>(mesh.positions.size() - 1);
  };

  CornerRow lower(alpha.width); // corners (i, y)
  CornerRow upper(alpha.width); // corners (i, y + 1)
  for (int y = 0; y < alpha.height; ++y)
  {
    for (int x = 0; x < alpha.width; ++x)
    {
      if (!isOpaqueTexel(alpha, x, y))
        continue;
      const auto corner = [&](CornerRow& row, int i, int j) {
        std::uint32_t& index = row.at(i);
        if (index == kNoVertex)
          index = addCorner(i, j);
        return index;
      };
      const std::uint32_t a = corner(lower, x, y);         // (x, y)
      const std::uint32_t b = corner(lower, x + 1, y);     // (x+1, y)
      const std::uint32_t c = corner(upper, x + 1, y + 1); // (x+1, y+1)
      const std::uint32_t d = corner(upper, x, y + 1);     // (x, y+1)
      // makeQuad's diagonal and winding: (0,0) (1,0) (1,1) and (0,0) (1,1) (0,1), counter-clockwise around the
      // normal because uAxis x vAxis points along it.
      mesh.indices.insert(mesh.indices.end(), { a, b, c, a, c, d });
    }
    std::swap(lower, upper);
    upper.clear();
  }
  return mesh;
}

} // namespace sl
