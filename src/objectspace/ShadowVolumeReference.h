// CPU twins of the technique `shadow-volume` (double precision), used by its tests:
//  - what the volumes say: the winding number of the generated volume triangles at a point, i.e. the number
//    of volumes that contain it, from the very vertices the pass uploads;
//  - what it should be: the number of caster triangles the segment from the point to the light crosses
//    (the definition of `depth_complexity_center`), counted directly.
#pragma once

#include "core/Parameters.h"
#include "frame/ProbeRecord.h"
#include "scene/Scene.h"
#include "objectspace/ShadowVolumeGeometry.h"

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace sl
{

// The generalised winding number (Jacobson et al. 2013) of the volumes' closed homogeneous triangle list at
// `point`: (1 / 4 pi) times the sum of the triangles' signed solid angles (Van Oosterom & Strackee 1983). A
// vertex at infinity (w = 0) is seen from every point in its direction xyz, so infinite volumes need no cut.
// An integer up to rounding when `point` is not on a volume surface; callers round it.
double volumeWindingNumber(const ShadowVolumeGeometry& geometry, const glm::dvec3& point);

// Caster triangles (objects with castShadows, every triangle, alpha textures ignored as the volumes do)
// crossed by the open segment from `point` to the light (to infinity against a directional light's
// direction). Moller-Trumbore in double. `recorder` (optional, `shadowlab probe`): each crossing's point
// (crossing_point) and triangle (crossed_triangle: object and triangle index), in the current group. `opaqueOnly`:
// perforated objects (hasAlphaTexture) are left out, as the techniques that shadow them by STSVs leave them out of
// their volumes (TechniqueDescriptor::perforatedCastersByStsv).
int casterCrossings(const Scene& scene, const VolumeLight& light, const glm::dvec3& point,
  ProbeRecorder* recorder = nullptr, bool opaqueOnly = false);

// The point whose crossings the z-fail count describes (the parameter receiver_offset): the visible point `pWs`
// moved `receiverOffset` of its distance to the eye toward the camera (orthographic cameras: of the scene's
// radius), so its own caster's near cap lies behind it.
glm::dvec3 shadowVolumeReceiverPoint(const Scene& scene, double receiverOffset, const glm::dvec3& pWs);
// The parameter receiver_offset, typed: part of the settings of every technique that counts volumes at the point
// (shadow-volume, dcs, penumbra-wedge; each declares its own default), and what their shared pass reads.
double receiverOffsetOf(const ParameterValues& values);
// Its declaration, with the technique's default and its reason (`why`, appended as is to what the offset does).
ParameterSpec receiverOffsetParameter(double defaultValue, const std::string& why);

} // namespace sl
