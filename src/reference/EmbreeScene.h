// The shadow casters of a Scene as a committed Embree 3 scene, for occlusion rays (the ray-traced ground
// truth, reference/ReferenceRenderer.h).
//
// One Embree triangle geometry per SceneObject with castShadows (objects without triangles are skipped).
// Triangles are two-sided: a caster blocks light from either side, like the light-depth pass, which
// renders without face culling. Perforated objects (hasAlphaTexture) get an occlusion filter that rejects
// a hit where the alpha texture, sampled at the hit's interpolated uv, is < 0.5 -- exactly the rule of
// shaders/common/AlphaMask.glsl: nearest texel, repeat wrap, texel (i, j) covering u in [i, i+1)/width,
// v in [j, j+1)/height; a mesh without uvs samples uv = (0, 0), as the GPU's vertex buffers do.
//
// The scene is built with RTC_SCENE_FLAG_ROBUST (no missed hits on shared edges, so no light leaks
// between the triangles of a closed caster) and high build quality. Everything it needs is copied: the
// Scene may be destroyed after construction. Queries are const and thread-safe.
//
// Crossing counts (crossings()): the depth complexity of a segment, the number of caster triangles it passes
// through, which depth complexity sampling (Forest, Barthe & Paulin 2008, used by Forest et al. 2009 §3.2) counts per
// light sample. Every geometry also gets an intersection filter that records each hit and rejects it, so that
// one rtcIntersect1 walks every triangle along the segment instead of stopping at the closest. Hits in a
// perforated caster's holes are rejected without being recorded (the occlusion filter's rule above), so a
// hole is no crossing. A high-quality build may use spatial splits: one triangle can then sit in several BVH
// leaves, and Embree calls the filter once per leaf for the same triangle, so a crossing is counted once per
// distinct (geometry, primitive) of the ray, never once per filter call. (Embree 3.13's non-robust high-quality
// build was seen to do this on overlapping triangle soups, ~0.4 % of filter calls; its robust build, ours, was
// not, but nothing in the API promises it.) A segment through a shared edge or vertex may hit each triangle
// that meets there (the robust mode's watertightness guarantees at least one): a quad crossed on its diagonal
// counts 2. Counts along such segments are ambiguous, exactly like a ray test's.
#pragma once

#include "core/Image.h"
#include "scene/Scene.h"

#include <embree3/rtcore.h>
#include <glm/glm.hpp>

#include <memory>
#include <string>
#include <vector>

namespace sl
{

class EmbreeScene
{
public:
  // Throws GraphicsError("Embree: ...") with Embree's message when the device cannot be created, the build
  // fails, or this Embree was compiled without what the reference relies on (two-sided triangles;
  // filter functions, when the scene has perforated casters).
  explicit EmbreeScene(const Scene& scene);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  // True if a caster blocks origin + t * direction for some t in (tNear, tFar). `direction` need not be
  // unit length (t is in units of it); tFar may be infinite. Computed in single precision by Embree.
  bool occluded(const glm::dvec3& origin, const glm::dvec3& direction, double tNear, double tFar) const;

  // One caster triangle a segment passes through.
  struct Crossing
  {
    std::size_t objectIndex = 0; // index into the constructor's Scene::objects
    unsigned triangle = 0;       // index into that object's mesh triangles
    float t = 0.0f;              // where, in units of `direction` (Embree's single-precision hit distance)
  };
  // The number of caster triangles (distinct object and triangle) that origin + t * direction crosses for t in
  // (tNear, tFar), holes of perforated casters excluded (see the top of this file); same ray conventions and
  // precision as occluded(). With `crossed`, it is cleared and receives them, in the order Embree found them
  // (not sorted by t). Throws GraphicsError when this Embree was built without filter functions.
  int crossings(const glm::dvec3& origin, const glm::dvec3& direction, double tNear, double tFar,
    std::vector<Crossing>* crossed = nullptr) const;

  std::size_t geometryCount() const { return geometryCount_; }
  std::size_t triangleCount() const { return triangleCount_; }

  // What the occlusion filter of a perforated geometry reads (public for the filter callback only).
  struct Perforation
  {
    std::vector<glm::vec2> uvs;           // per vertex, or empty (uv = 0 everywhere)
    std::vector<std::uint32_t> indices;   // 3 per triangle, as given to Embree
    ImageF alpha;                         // 1 component, row 0 = v near 0
    // True where the triangle's interpolated uv at barycentrics (u, v) (Embree's: p = (1-u-v) a + u b + v c)
    // samples alpha < 0.5.
    bool isHole(unsigned primitive, float u, float v) const;
  };

private:
  void throwIfFailed(const char* what) const;

  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  std::vector<std::unique_ptr<Perforation>> perforations_; // stable addresses: Embree holds pointers
  std::vector<std::size_t> objectOfGeometry_;               // Embree geometry id -> index into Scene::objects
  bool filtersSupported_ = false;
  std::size_t geometryCount_ = 0;
  std::size_t triangleCount_ = 0;
  std::string lastError_; // the last message Embree's error callback reported
};

} // namespace sl
