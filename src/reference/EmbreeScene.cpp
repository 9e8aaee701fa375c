#include "reference/EmbreeScene.h"

#include "core/Error.h"
#include "scene/AlphaTexture.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sl
{
namespace
{

const char* errorName(RTCError code)
{
  switch (code)
  {
    case RTC_ERROR_NONE:
      return "no error";
    case RTC_ERROR_UNKNOWN:
      return "unknown error";
    case RTC_ERROR_INVALID_ARGUMENT:
      return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION:
      return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY:
      return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU:
      return "unsupported CPU";
    case RTC_ERROR_CANCELLED:
      return "cancelled";
  }
  return "unrecognised error code";
}

void recordError(void* userPtr, RTCError code, const char* message)
{
  *static_cast<std::string*>(userPtr) = format(errorName(code), message && *message ? ": " : "",
    message ? message : "");
}

// Occlusion filter of a perforated geometry: a hit in a hole is no hit (shaders/common/AlphaMask.glsl).
void rejectHitsInHoles(const RTCFilterFunctionNArguments* args)
{
  const auto* perforation = static_cast<const EmbreeScene::Perforation*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i)
  {
    if (args->valid[i] != -1)
    {
      continue;
    }
    if (perforation->isHole(RTCHitN_primID(args->hit, args->N, i), RTCHitN_u(args->hit, args->N, i),
          RTCHitN_v(args->hit, args->N, i)))
    {
      args->valid[i] = 0;
    }
  }
}

// What crossings() hands its intersection filter: Embree passes the RTCIntersectContext it was given to every
// filter call, so the per-ray record travels in a struct that starts with it (Embree's tutorials' idiom).
struct RawCrossing
{
  unsigned geometry;
  unsigned primitive;
  float t;
};

struct CrossingContext
{
  RTCIntersectContext embree; // must stay the first member: the filter casts the context back
  std::vector<RawCrossing>* crossed;
};

// Intersection filter of every geometry (used by crossings() only: rtcOccluded1 calls the occlusion filter):
// records the hit unless it lies in a hole or its triangle was already recorded for this ray (spatial splits
// report one triangle once per BVH leaf it was split into), then rejects it so that traversal goes on.
void recordCrossingAndContinue(const RTCFilterFunctionNArguments* args)
{
  auto* context = reinterpret_cast<CrossingContext*>(args->context);
  const auto* perforation = static_cast<const EmbreeScene::Perforation*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i)
  {
    if (args->valid[i] != -1)
    {
      continue;
    }
    args->valid[i] = 0; // rejected: the ray's tfar stays, every farther hit is still reported
    const unsigned primitive = RTCHitN_primID(args->hit, args->N, i);
    if (perforation && perforation->isHole(primitive, RTCHitN_u(args->hit, args->N, i),
                         RTCHitN_v(args->hit, args->N, i)))
    {
      continue;
    }
    const unsigned geometry = RTCHitN_geomID(args->hit, args->N, i);
    std::vector<RawCrossing>& crossed = *context->crossed;
    const bool seen = std::any_of(crossed.begin(), crossed.end(), [&](const RawCrossing& crossing) {
      return crossing.geometry == geometry && crossing.primitive == primitive;
    });
    if (!seen)
    {
      // During an intersection filter call Embree holds the candidate's distance in the ray's tfar.
      crossed.push_back({ geometry, primitive, RTCRayN_tfar(args->ray, args->N, i) });
    }
  }
}

RTCRay makeRay(const glm::dvec3& origin, const glm::dvec3& direction, double tNear, double tFar)
{
  RTCRay ray;
  ray.org_x = static_cast<float>(origin.x);
  ray.org_y = static_cast<float>(origin.y);
  ray.org_z = static_cast<float>(origin.z);
  ray.tnear = static_cast<float>(tNear);
  ray.dir_x = static_cast<float>(direction.x);
  ray.dir_y = static_cast<float>(direction.y);
  ray.dir_z = static_cast<float>(direction.z);
  ray.time = 0.0f;
  ray.tfar = tFar >= double(std::numeric_limits<float>::max()) ? std::numeric_limits<float>::infinity()
                                                                : static_cast<float>(tFar);
  ray.mask = 0xFFFFFFFFu;
  ray.id = 0;
  ray.flags = 0;
  return ray;
}

} // namespace

bool EmbreeScene::Perforation::isHole(unsigned primitive, float u, float v) const
{
  if (alpha.empty())
  {
    return false;
  }
  glm::dvec2 uv(0.0);
  if (!uvs.empty())
  {
    const glm::dvec2 a(uvs[indices[3 * primitive + 0]]);
    const glm::dvec2 b(uvs[indices[3 * primitive + 1]]);
    const glm::dvec2 c(uvs[indices[3 * primitive + 2]]);
    uv = (1.0 - double(u) - double(v)) * a + double(u) * b + double(v) * c;
  }
  return alphaHoleAt(alpha, uv);
}

EmbreeScene::EmbreeScene(const Scene& scene)
{
  device_ = rtcNewDevice(nullptr);
  if (!device_)
  {
    throw GraphicsError(format("Embree: cannot create a device (", errorName(rtcGetDeviceError(nullptr)), ")"));
  }
  try
  {
    rtcSetDeviceErrorFunction(device_, recordError, &lastError_);
    if (rtcGetDeviceProperty(device_, RTC_DEVICE_PROPERTY_BACKFACE_CULLING_ENABLED) != 0)
    {
      throw GraphicsError("Embree: this Embree was built with backface culling; the reference needs two-sided "
                          "triangles (casters block light from both sides)");
    }
    filtersSupported_ = rtcGetDeviceProperty(device_, RTC_DEVICE_PROPERTY_FILTER_FUNCTION_SUPPORTED) != 0;

    scene_ = rtcNewScene(device_);
    throwIfFailed("creating the scene");
    rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);

    for (std::size_t objectIndex = 0; objectIndex < scene.objects.size(); ++objectIndex)
    {
      const SceneObject& object = scene.objects[objectIndex];
      const TriangleMesh& mesh = object.mesh;
      if (!object.castShadows || mesh.triangleCount() == 0)
      {
        continue;
      }
      RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
      throwIfFailed("creating a geometry");
      auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0,
        RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.positions.size()));
      auto* triangles = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0,
        RTC_FORMAT_UINT3, 3 * sizeof(unsigned), mesh.triangleCount()));
      if (!vertices || !triangles)
      {
        rtcReleaseGeometry(geometry);
        throwIfFailed(format("allocating buffers for ", object.name).c_str());
        throw GraphicsError(format("Embree: cannot allocate buffers for ", object.name));
      }
      for (std::size_t i = 0; i < mesh.positions.size(); ++i)
      {
        // Embree asserts (SIGABRT) on rays near ~1e30-sized geometry; loadScene bounds every coordinate by
        // kMaxSceneMagnitude, so this only catches a Scene built in code that skipped the loader.
        const glm::vec3& p = mesh.positions[i];
        if (!(std::max({ std::abs(p.x), std::abs(p.y), std::abs(p.z) }) <= kMaxSceneMagnitude))
        {
          rtcReleaseGeometry(geometry);
          throw InputError(format(object.name, ": vertex ", i, " at (", p.x, ", ", p.y, ", ", p.z,
            ") is outside the scene's magnitude limit of ", kMaxSceneMagnitude, " units"));
        }
        vertices[3 * i + 0] = mesh.positions[i].x;
        vertices[3 * i + 1] = mesh.positions[i].y;
        vertices[3 * i + 2] = mesh.positions[i].z;
      }
      for (std::size_t i = 0; i < mesh.indices.size(); ++i)
      {
        SL_CHECK_MSG(mesh.indices[i] < mesh.positions.size(), object.name, ": index ", mesh.indices[i],
          " out of range");
        triangles[i] = mesh.indices[i];
      }
      if (object.hasAlphaTexture)
      {
        if (!filtersSupported_)
        {
          rtcReleaseGeometry(geometry);
          throw GraphicsError(format("Embree: this Embree was built without filter functions, needed for the "
                                     "perforated caster ", object.name));
        }
        auto perforation = std::make_unique<Perforation>();
        perforation->uvs = mesh.uvs;
        perforation->indices = mesh.indices;
        perforation->alpha = object.alphaTexture.alpha;
        rtcSetGeometryUserData(geometry, perforation.get());
        rtcSetGeometryOccludedFilterFunction(geometry, rejectHitsInHoles);
        perforations_.push_back(std::move(perforation));
      }
      if (filtersSupported_)
      {
        rtcSetGeometryIntersectFilterFunction(geometry, recordCrossingAndContinue); // crossings() only
      }
      rtcCommitGeometry(geometry);
      const unsigned geometryId = rtcAttachGeometry(scene_, geometry);
      rtcReleaseGeometry(geometry); // the scene holds it now
      throwIfFailed(format("adding ", object.name).c_str());
      if (objectOfGeometry_.size() <= geometryId)
      {
        objectOfGeometry_.resize(geometryId + 1, 0);
      }
      objectOfGeometry_[geometryId] = objectIndex;
      ++geometryCount_;
      triangleCount_ += mesh.triangleCount();
    }
    rtcCommitScene(scene_);
    throwIfFailed("building the BVH");
  }
  catch (...)
  {
    if (scene_)
    {
      rtcReleaseScene(scene_);
    }
    rtcReleaseDevice(device_);
    throw;
  }
}

EmbreeScene::~EmbreeScene()
{
  rtcReleaseScene(scene_);
  rtcReleaseDevice(device_);
}

void EmbreeScene::throwIfFailed(const char* what) const
{
  const RTCError code = rtcGetDeviceError(device_);
  if (code != RTC_ERROR_NONE)
  {
    throw GraphicsError(format("Embree: ", what, ": ", lastError_.empty() ? errorName(code) : lastError_));
  }
}

bool EmbreeScene::occluded(const glm::dvec3& origin, const glm::dvec3& direction, double tNear, double tFar) const
{
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray = makeRay(origin, direction, tNear, tFar);
  rtcOccluded1(scene_, &context, &ray);
  return ray.tfar < 0.0f; // Embree sets tfar to -inf on a hit
}

int EmbreeScene::crossings(const glm::dvec3& origin, const glm::dvec3& direction, double tNear, double tFar,
  std::vector<Crossing>* crossed) const
{
  if (!filtersSupported_)
  {
    throw GraphicsError("Embree: this Embree was built without filter functions, needed to count the casters a "
                        "segment crosses");
  }
  // One record per calling thread, reused: no allocation per ray once it has grown.
  thread_local std::vector<RawCrossing> raw;
  raw.clear();
  CrossingContext context;
  rtcInitIntersectContext(&context.embree);
  context.crossed = &raw;
  RTCRayHit rayHit;
  rayHit.ray = makeRay(origin, direction, tNear, tFar);
  rayHit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rayHit.hit.primID = RTC_INVALID_GEOMETRY_ID;
  rayHit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_, &context.embree, &rayHit);
  SL_CHECK_MSG(rayHit.hit.geomID == RTC_INVALID_GEOMETRY_ID, "Embree accepted a hit the crossing filter rejected");
  if (crossed)
  {
    crossed->clear();
    for (const RawCrossing& crossing : raw)
    {
      SL_CHECK(crossing.geometry < objectOfGeometry_.size());
      crossed->push_back({ objectOfGeometry_[crossing.geometry], crossing.primitive, crossing.t });
    }
  }
  return static_cast<int>(raw.size());
}

} // namespace sl
