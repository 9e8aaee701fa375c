// A brute-force CPU ray caster (double precision, every caster triangle, Moller-Trumbore), used as an
// independent reference for hard shadows from a point: is the segment from a surface point to the
// light's centre blocked? Perforated triangles are honoured by sampling their alpha texture at the hit's
// interpolated uv exactly as shaders/common/AlphaMask.glsl does (nearest texel, repeat).
#pragma once

#include "core/Image.h"
#include "frame/FrameResult.h"
#include "scene/Scene.h"

#include <glm/glm.hpp>

namespace sl::test
{

class RayCaster
{
public:
  explicit RayCaster(const Scene& scene);
  // True if any caster blocks the open segment (origin + tMin*dir, origin + tMax*dir).
  bool occluded(const glm::dvec3& origin, const glm::dvec3& direction, double tMin, double tMax) const;

  // Visibility of the light's centre from the surface point (0/1), with `offset` along the normal to
  // leave the surface. Applies the same reach rules as the GPU (facing, one-sided area light, spot cone).
  double pointVisibility(const Light& light, const glm::dvec3& pWs, const glm::dvec3& nWs, double offset) const;

private:
  struct Triangle
  {
    glm::dvec3 a, edge1, edge2;
    glm::dvec2 uvA, uvB, uvC;
    const AlphaTexture* alpha = nullptr;
  };
  std::vector<Triangle> triangles_;
};

// The exact single ray (pointVisibility, offset 1e-4) at every covered pixel of `frame` that receives shadows and
// that the scene's first light can reach; -1 at every other pixel.
ImageF exactPointVisibility(const FrameResult& frame, const Scene& scene, const RayCaster& rays);

} // namespace sl::test
