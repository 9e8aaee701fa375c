// Omnidirectional lights (survey §2): a point light's visible receivers may lie in every direction, which no single
// frustum covers; six frusta, one per face of a cube around the light, do. Each face is a view that partitions the
// pixels (PartitionViews.h): it owns the receivers in its 90-degree pyramid around the light's centre (four owner
// planes through the centre), and its map is focused on them (fitLightView with ownerPlanes and the face's axis), so
// a face's map covers only the part of the face that holds receivers, with the focus's margin of texels past them.
// That margin reaches past the 90-degree face where its receivers reach the seam: a filter kernel near a seam reads
// one map (the face's own), whose frustum holds the casters beyond the seam, so nothing changes across a seam but the
// texel size. A face that owns no visible receiver the light can reach gets no map and no pass (it costs nothing).
//
// Faces in the usual cube-map order: 0 +x, 1 -x, 2 +y, 3 -y, 4 +z, 5 -z. The pixel's face is the dominant axis of
// p - light centre (ties go to x before y before z; a point on a seam lies in both faces' pyramids, whose maps both
// hold it). GLSL twin: shaders/lightspace/PartitionSelection.glsl.
#pragma once

#include "lightspace/LightView.h"

#include <glm/glm.hpp>

#include <vector>

namespace sl
{

struct PartitionSet;
struct ViewSelection;

// cube_map: off (one map; a point light beyond it is refused), auto (cube faces when one map cannot cover the
// receivers, the refusal's condition), on (cube faces for every point light).
enum class CubeMapMode
{
  Off,
  Auto,
  On
};

constexpr int kCubeFaceCount = 6;

glm::dvec3 cubeFaceAxis(int face);
const char* cubeFaceName(int face); // "+x" .. "-z"
const char* cubeFaceTag(int face);  // "px" .. "nz": the faces' map names in light_space.vti
// The face whose pyramid holds `direction` (p - light centre) by its dominant axis.
int dominantCubeFace(const glm::dvec3& direction);
// The face's pyramid as four world-space half-spaces through the light's centre: s d_i >= |d_j| for the face's axis i
// (sign s) and the two others j, d = p - centre (each |d_j| as two planes).
std::vector<glm::dvec4> cubeFaceOwnerPlanes(const glm::dvec3& centerWs, int face);

// Throws InputError naming `--set cube_map=on` for a light that is not a point light.
void requireCubeMapLight(CubeMapMode mode, LightType lightType);

// The CPU twin (double) of the GPU's cube-face selection at a covered pixel's point: the view of its dominant face,
// unblended (view 0 where that face has no map: the light reaches none of its receivers).
ViewSelection selectCubeFace(const PartitionSet& faces, const glm::dvec3& pWs);
// The pixel's face for the `cube_face` buffer: its dominant face, or -1 where that face has no map.
int cubeFaceOf(const PartitionSet& faces, const glm::dvec3& pWs);

// Fits the faces of a point light: six fitLightView with the face's axis and owner planes; the faces without
// receivers are dropped (face +x's tiny view is kept when none has any, so every stage still runs). A PartitionSet of
// kind CubeFaces.
PartitionSet fitCubeFaces(
  const Light& light, const Scene& scene, ReceiverSource& receivers, const FocusSettings& focus);

} // namespace sl
