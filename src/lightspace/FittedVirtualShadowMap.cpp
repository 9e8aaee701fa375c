#include "lightspace/FittedVirtualShadowMap.h"

#include "core/Error.h"
#include "lightspace/CameraView.h"
#include "lightspace/ShadowMapMath.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <queue>
#include <tuple>

namespace sl
{

void requireFvsmCombination(const FvsmSettings& settings, int cascades, bool warped)
{
  if (!settings.active())
  {
    return;
  }
  if (cascades > 1)
  {
    throw InputError(format("--set cascades=", cascades,
      ": fvsm=on partitions the map itself (survey §4.3.3); combine it with cascades=1"));
  }
  if (warped)
  {
    throw InputError("--set warp: fvsm=on fits its tiles in the unwarped light frame; use warp=none");
  }
}

glm::dvec2 lightXYOf(const LightView& view, const glm::dvec3& pWs)
{
  const glm::dvec4 pLs = view.viewFromWorld * glm::dvec4(pWs, 1.0);
  if (view.projection == LightProjection::Perspective)
  {
    return glm::dvec2(pLs) / -pLs.z;
  }
  return glm::dvec2(pLs);
}

glm::dvec4 receiverRectOf(const glm::dvec4& window, int resolution, double marginTexels)
{
  const double shrink = (resolution - 2.0 * marginTexels) / resolution;
  const double xCenter = 0.5 * (window.x + window.y);
  const double yCenter = 0.5 * (window.z + window.w);
  const double xHalf = 0.5 * (window.y - window.x) * shrink;
  const double yHalf = 0.5 * (window.w - window.z) * shrink;
  return { xCenter - xHalf, xCenter + xHalf, yCenter - yHalf, yCenter + yHalf };
}

FvsmPrepass requiredResolutions(const CameraView& camera, const Light& light, const LightView& rootView,
  const glm::dvec4& rootRect, const ImageF& position, const ImageF& normal)
{
  SL_CHECK(!rootView.warp.active());
  SL_CHECK(position.width == normal.width && position.height == normal.height);
  FvsmPrepass prepass;
  prepass.width = position.width;
  prepass.height = position.height;
  prepass.requiredResolution.assign(static_cast<std::size_t>(prepass.width) * prepass.height, -1.0);
  prepass.lightXY.assign(prepass.requiredResolution.size(), glm::dvec2(0.0));
  // Pixels per unit of light xy along each axis: r / T, with T the root map's texel (window / resolution).
  const double texelS = (rootView.window.y - rootView.window.x) / rootView.resolution;
  const double texelT = (rootView.window.w - rootView.window.z) / rootView.resolution;
  const double widthS = rootRect.y - rootRect.x;
  const double widthT = rootRect.w - rootRect.z;
  for (int y = 0; y < prepass.height; ++y)
  {
    for (int x = 0; x < prepass.width; ++x)
    {
      const glm::dvec3 pWs(position.at(x, y, 0), position.at(x, y, 1), position.at(x, y, 2));
      const glm::dvec3 nWs(normal.at(x, y, 0), normal.at(x, y, 1), normal.at(x, y, 2));
      if (position.at(x, y, 3) <= 0.5f || normal.at(x, y, 3) <= 0.5f || !lightCanReach(light, pWs, nWs))
      {
        continue;
      }
      if (rootView.projection == LightProjection::Perspective && !((rootView.viewFromWorld * glm::dvec4(pWs, 1.0)).z < 0.0))
      {
        continue; // behind the light's centre: no map holds it
      }
      const SamplingError error = samplingError(camera, rootView, x + 0.5, y + 0.5, pWs, nWs);
      const std::size_t i = static_cast<std::size_t>(y) * prepass.width + x;
      prepass.requiredResolution[i] =
        std::max(widthS * error.texelRatioS / texelS, widthT * error.texelRatioT / texelT);
      prepass.lightXY[i] = lightXYOf(rootView, pWs);
      ++prepass.samples;
    }
  }
  return prepass;
}

glm::ivec2 FvsmQuadtree::cellOf(const glm::dvec2& lightXY) const
{
  const glm::dvec2 origin(rootRect.x, rootRect.z);
  const glm::dvec2 extent(rootRect.y - rootRect.x, rootRect.w - rootRect.z);
  glm::ivec2 cell;
  for (int axis = 0; axis < 2; ++axis)
  {
    const double scaled = std::floor((lightXY[axis] - origin[axis]) / extent[axis] * gridSize);
    cell[axis] = static_cast<int>(std::clamp(std::isfinite(scaled) ? scaled : 0.0, 0.0, gridSize - 1.0));
  }
  return cell;
}

int FvsmQuadtree::tileAt(const glm::dvec2& lightXY) const
{
  const glm::ivec2 cell = cellOf(lightXY);
  return tileOfCell[static_cast<std::size_t>(cell.y) * gridSize + cell.x];
}

double FvsmQuadtree::effectiveResolution(int level) const
{
  return (settings.tileSize - 2.0 * marginTexels) * std::ldexp(1.0, level);
}

namespace
{

// The grid's max-and-count pyramid: level l holds 2^l x 2^l nodes, each the maximum R and the sample count of the
// cells below it.
struct Pyramid
{
  std::vector<std::vector<double>> required;
  std::vector<std::vector<int>> samples;
};

Pyramid buildPyramid(const FvsmQuadtree& tree)
{
  const int levels = tree.settings.maxLevel + 1;
  Pyramid pyramid;
  pyramid.required.resize(static_cast<std::size_t>(levels));
  pyramid.samples.resize(static_cast<std::size_t>(levels));
  pyramid.required.back() = tree.requiredGrid;
  pyramid.samples.back() = tree.sampleGrid;
  for (int level = levels - 2; level >= 0; --level)
  {
    const int side = 1 << level;
    auto& required = pyramid.required[static_cast<std::size_t>(level)];
    auto& samples = pyramid.samples[static_cast<std::size_t>(level)];
    const auto& finerRequired = pyramid.required[static_cast<std::size_t>(level) + 1];
    const auto& finerSamples = pyramid.samples[static_cast<std::size_t>(level) + 1];
    required.assign(static_cast<std::size_t>(side) * side, 0.0);
    samples.assign(static_cast<std::size_t>(side) * side, 0);
    for (int y = 0; y < side; ++y)
    {
      for (int x = 0; x < side; ++x)
      {
        const std::size_t node = static_cast<std::size_t>(y) * side + x;
        for (int child = 0; child < 4; ++child)
        {
          const std::size_t finer = static_cast<std::size_t>(2 * y + child / 2) * (2 * side) + (2 * x + child % 2);
          required[node] = std::max(required[node], finerRequired[finer]);
          samples[node] += finerSamples[finer];
        }
      }
    }
  }
  return pyramid;
}

struct Node
{
  int level;
  glm::ivec2 cell;
};

} // namespace

FvsmQuadtree buildFvsmQuadtree(const FvsmPrepass& prepass, const glm::dvec4& rootRect, const FvsmSettings& settings,
  double marginTexels)
{
  SL_CHECK(settings.maxLevel >= 0 && settings.maxLevel <= 10 && settings.maxTiles >= 1);
  SL_CHECK(settings.tileSize > 2.0 * marginTexels);
  SL_CHECK(rootRect.y > rootRect.x && rootRect.w > rootRect.z);
  FvsmQuadtree tree;
  tree.settings = settings;
  tree.marginTexels = marginTexels;
  tree.rootRect = rootRect;
  tree.gridSize = 1 << settings.maxLevel;
  const std::size_t cells = static_cast<std::size_t>(tree.gridSize) * tree.gridSize;
  tree.requiredGrid.assign(cells, 0.0);
  tree.sampleGrid.assign(cells, 0);
  tree.tileOfCell.assign(cells, -1);
  // The scatter (survey §4.3.3: "utilizing the efficient scattering capabilities of the CPU").
  for (std::size_t i = 0; i < prepass.requiredResolution.size(); ++i)
  {
    if (prepass.requiredResolution[i] < 0.0)
    {
      continue;
    }
    const glm::ivec2 cell = tree.cellOf(prepass.lightXY[i]);
    const std::size_t index = static_cast<std::size_t>(cell.y) * tree.gridSize + cell.x;
    tree.requiredGrid[index] = std::max(tree.requiredGrid[index], prepass.requiredResolution[i]);
    ++tree.sampleGrid[index];
  }
  const Pyramid pyramid = buildPyramid(tree);
  const auto requiredAt = [&](const Node& node) {
    return pyramid.required[static_cast<std::size_t>(node.level)][static_cast<std::size_t>(node.cell.y) * (1 << node.level) + node.cell.x];
  };
  const auto samplesAt = [&](const Node& node) {
    return pyramid.samples[static_cast<std::size_t>(node.level)][static_cast<std::size_t>(node.cell.y) * (1 << node.level) + node.cell.x];
  };

  // Worst deficit (required over effective resolution) first, so a budget cut leaves the least-served leaves coarse
  // last; ties by level then position, so the tree does not depend on the queue's order.
  const auto deficit = [&](const Node& node) { return requiredAt(node) / tree.effectiveResolution(node.level); };
  const auto later = [&](const Node& a, const Node& b) {
    return std::make_tuple(-deficit(a), a.level, a.cell.y, a.cell.x) > std::make_tuple(-deficit(b), b.level, b.cell.y, b.cell.x);
  };
  std::priority_queue<Node, std::vector<Node>, decltype(later)> open(later);
  std::vector<Node> leaves;
  int tileCount = 0;
  if (samplesAt({ 0, { 0, 0 } }) > 0)
  {
    open.push({ 0, { 0, 0 } });
    tileCount = 1;
  }
  while (!open.empty())
  {
    const Node node = open.top();
    open.pop();
    if (resolutionMet(tree.effectiveResolution(node.level), requiredAt(node)))
    {
      leaves.push_back(node);
      continue;
    }
    if (node.level == settings.maxLevel)
    {
      tree.levelReached = true;
      leaves.push_back(node);
      continue;
    }
    std::vector<Node> children;
    for (int child = 0; child < 4; ++child)
    {
      const Node next{ node.level + 1, { 2 * node.cell.x + child % 2, 2 * node.cell.y + child / 2 } };
      if (samplesAt(next) > 0)
      {
        children.push_back(next);
      }
    }
    if (tileCount - 1 + static_cast<int>(children.size()) > settings.maxTiles)
    {
      tree.budgetReached = true;
      leaves.push_back(node);
      continue;
    }
    tileCount += static_cast<int>(children.size()) - 1;
    for (const Node& child : children)
    {
      open.push(child);
    }
  }
  std::sort(leaves.begin(), leaves.end(), [](const Node& a, const Node& b) {
    return std::make_tuple(a.level, a.cell.y, a.cell.x) < std::make_tuple(b.level, b.cell.y, b.cell.x);
  });
  const glm::dvec2 origin(rootRect.x, rootRect.z);
  const glm::dvec2 extent(rootRect.y - rootRect.x, rootRect.w - rootRect.z);
  for (const Node& node : leaves)
  {
    FvsmTile tile;
    tile.level = node.level;
    tile.cell = node.cell;
    // Edges from the grid's cell indices, so neighbouring tiles share them exactly.
    const int span = 1 << (settings.maxLevel - node.level);
    const auto edge = [&](int axis, int cellIndex) {
      return cellIndex == tree.gridSize ? (axis == 0 ? rootRect.y : rootRect.w)
                                        : origin[axis] + extent[axis] * cellIndex / tree.gridSize;
    };
    tile.rect = { edge(0, node.cell.x * span), edge(0, (node.cell.x + 1) * span), edge(1, node.cell.y * span),
      edge(1, (node.cell.y + 1) * span) };
    tile.requiredResolution = requiredAt(node);
    tile.effectiveResolution = tree.effectiveResolution(node.level);
    tile.samples = samplesAt(node);
    const int index = static_cast<int>(tree.tiles.size());
    for (int y = node.cell.y * span; y < (node.cell.y + 1) * span; ++y)
    {
      for (int x = node.cell.x * span; x < (node.cell.x + 1) * span; ++x)
      {
        tree.tileOfCell[static_cast<std::size_t>(y) * tree.gridSize + x] = index;
      }
    }
    tree.tiles.push_back(tile);
  }
  return tree;
}

std::vector<glm::dvec4> tileOwnerPlanes(const LightView& rootView, const glm::dvec4& rect)
{
  const glm::dmat4& m = rootView.viewFromWorld;
  const glm::dvec4 xRow(m[0][0], m[1][0], m[2][0], m[3][0]);
  const glm::dvec4 yRow(m[0][1], m[1][1], m[2][1], m[3][1]);
  if (rootView.projection == LightProjection::Perspective)
  {
    // x / depth >= xMin with depth = -z: x + xMin z >= 0; planes through the light's centre.
    const glm::dvec4 zRow(m[0][2], m[1][2], m[2][2], m[3][2]);
    return { xRow + rect.x * zRow, -xRow - rect.y * zRow, yRow + rect.z * zRow, -yRow - rect.w * zRow };
  }
  // Planes parallel to the light direction (light view z).
  const glm::dvec4 one(0.0, 0.0, 0.0, 1.0);
  return { xRow - rect.x * one, rect.y * one - xRow, yRow - rect.z * one, rect.w * one - yRow };
}

LightView tileView(const LightView& rootView, const glm::dvec4& rect, int tileSize, double marginTexels)
{
  SL_CHECK(!rootView.warp.active() && tileSize > 2.0 * marginTexels);
  LightView view = rootView;
  view.resolution = tileSize;
  const double grow = tileSize / (tileSize - 2.0 * marginTexels);
  const double xCenter = 0.5 * (rect.x + rect.y);
  const double yCenter = 0.5 * (rect.z + rect.w);
  const double xHalf = 0.5 * (rect.y - rect.x) * grow;
  const double yHalf = 0.5 * (rect.w - rect.z) * grow;
  view.window = { xCenter - xHalf, xCenter + xHalf, yCenter - yHalf, yCenter + yHalf };
  view.setProjectionFromWindow();
  return view;
}

int FittedVirtualShadowMap::tileOfPixel(int x, int y) const
{
  const std::size_t i = static_cast<std::size_t>(y) * prepass.width + x;
  return prepass.requiredResolution[i] < 0.0 ? -1 : quadtree.tileAt(prepass.lightXY[i]);
}

bool FittedVirtualShadowMap::pixelMet(int x, int y) const
{
  const int tile = tileOfPixel(x, y);
  const std::size_t i = static_cast<std::size_t>(y) * prepass.width + x;
  return tile < 0 ||
    resolutionMet(quadtree.tiles[static_cast<std::size_t>(tile)].effectiveResolution, prepass.requiredResolution[i]);
}

int FittedVirtualShadowMap::unmetPixels() const
{
  int count = 0;
  for (int y = 0; y < prepass.height; ++y)
  {
    for (int x = 0; x < prepass.width; ++x)
    {
      count += pixelMet(x, y) ? 0 : 1;
    }
  }
  return count;
}

FittedVirtualShadowMap fitFvsm(const Light& light, const Scene& scene, ReceiverSource& receivers,
  const FocusSettings& focus, const FvsmSettings& settings, const CameraView& camera, const ImageF& position,
  const ImageF& normal)
{
  SL_CHECK(focus.warp.kind == WarpKind::None && !focus.snapToTexels && focus.ownerPlanes.empty());
  FittedVirtualShadowMap fvsm;
  FocusSettings root = focus;
  root.resolution = settings.tileSize;
  fvsm.rootView = fitLightView(light, scene, receivers, root);
  const glm::dvec4 rootRect = receiverRectOf(fvsm.rootView.window, settings.tileSize, focus.marginTexels);
  fvsm.prepass = requiredResolutions(camera, light, fvsm.rootView, rootRect, position, normal);
  fvsm.quadtree = buildFvsmQuadtree(fvsm.prepass, rootRect, settings, focus.marginTexels);
  for (const FvsmTile& tile : fvsm.quadtree.tiles)
  {
    fvsm.views.push_back(tileView(fvsm.rootView, tile.rect, settings.tileSize, focus.marginTexels));
    fvsm.views.back().receiverSampleCount = tile.samples;
  }
  if (fvsm.views.empty())
  {
    // No receiver queries the map: one view, the root's, so every stage still runs.
    fvsm.views.push_back(fvsm.rootView);
  }
  return fvsm;
}

} // namespace sl
