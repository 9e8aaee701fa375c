#include "lightspace/PartitionViews.h"

#include "core/Error.h"
#include "lightspace/FittedVirtualShadowMap.h"

#include <algorithm>
#include <cmath>

namespace sl
{

const char* partitionKindName(PartitionKind kind)
{
  switch (kind)
  {
    case PartitionKind::Cascades:
      return "cascades";
    case PartitionKind::CubeFaces:
      return "cube_faces";
    case PartitionKind::FvsmTiles:
      return "fvsm_tiles";
  }
  return "cascades";
}

bool ownerRegionHolds(const std::vector<glm::dvec4>& planes, const glm::dvec3& pWs)
{
  return std::all_of(planes.begin(), planes.end(),
    [&](const glm::dvec4& plane) { return glm::dot(plane, glm::dvec4(pWs, 1.0)) >= 0.0; });
}

bool mapHolds(const LightView& view, double marginTexels, const glm::dvec3& pWs, double& edgeFraction)
{
  const glm::dvec4 clip = view.clipFromWorld * glm::dvec4(pWs, 1.0);
  const double depthLin = -(view.viewFromWorld * glm::dvec4(pWs, 1.0)).z;
  edgeFraction = 0.0;
  if (!(clip.w > 0.0) || depthLin < view.nearDepth || depthLin > view.farDepth)
  {
    return false;
  }
  const double inner = 1.0 - 2.0 * marginTexels / view.resolution; // NDC half-width inside the margin
  const double distance = inner - std::max(std::abs(clip.x / clip.w), std::abs(clip.y / clip.w));
  if (distance < 0.0)
  {
    return false;
  }
  edgeFraction = distance / inner;
  return true;
}


ViewSelection selectView(const PartitionSet& partitions, const CameraView& camera, const glm::dvec3& pWs)
{
  switch (partitions.kind)
  {
    case PartitionKind::Cascades:
      return selectCascade(partitions, camera, pWs);
    case PartitionKind::FvsmTiles:
    {
      // The tile whose rectangle holds the point's light x/y; 0 where none (no receiver of the pre-pass there).
      SL_CHECK(partitions.fvsm != nullptr);
      const int tile = std::max(0, partitions.fvsm->quadtree.tileAt(lightXYOf(partitions.fvsm->rootView, pWs)));
      return { tile, tile, 1.0 };
    }
    case PartitionKind::CubeFaces:
      return selectCubeFace(partitions, pWs);
  }
  SL_CHECK_MSG(false, "no selection for partition kind ", partitionKindName(partitions.kind));
  return {};
}

std::string partitionViewSuffix(const PartitionSet& partitions, int view)
{
  SL_CHECK(view >= 0 && view < partitions.viewCount());
  if (partitions.kind == PartitionKind::CubeFaces)
  {
    return std::string("_") + cubeFaceTag(partitions.viewFaces.at(static_cast<std::size_t>(view)));
  }
  return (partitions.kind == PartitionKind::FvsmTiles ? "_t" : "_c") + std::to_string(view);
}

std::string partitionViewLabel(const PartitionSet& partitions, int view)
{
  SL_CHECK(view >= 0 && view < partitions.viewCount());
  if (partitions.kind == PartitionKind::FvsmTiles)
  {
    const bool tiled = partitions.fvsm && view < static_cast<int>(partitions.fvsm->quadtree.tiles.size());
    return tiled ? format("tile ", view, " (level ", partitions.fvsm->quadtree.tiles[static_cast<std::size_t>(view)].level, ")")
                 : std::string("root (no receiver)");
  }
  if (partitions.kind == PartitionKind::CubeFaces)
  {
    return std::string("cube face ") + cubeFaceName(partitions.viewFaces.at(static_cast<std::size_t>(view)));
  }
  return "cascade " + std::to_string(view);
}

} // namespace sl
