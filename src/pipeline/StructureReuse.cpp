#include "pipeline/StructureReuse.h"

#include "core/Error.h"
#include "scene/Scene.h"
#include "structures/LightSpaceStructure.h"
#include "structures/shadowmap/ShadowMapStructure.h"

#include <vtkTextureObject.h>

#include <atomic>
#include <cstring>
#include <type_traits>

namespace sl
{

namespace
{

// A splitmix64-style mix over 64-bit words: fast enough to run over every vertex of the scene each frame (the GPU
// scene is uploaded again each frame anyway), and a change of any bit changes the hash.
class SceneHasher
{
public:
  void word(std::uint64_t value)
  {
    state_ += 0x9e3779b97f4a7c15ull + value;
    std::uint64_t z = state_;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    state_ = z ^ (z >> 31);
  }
  void bytes(const void* data, std::size_t size)
  {
    word(size);
    const auto* bytes = static_cast<const unsigned char*>(data);
    std::size_t offset = 0;
    for (; offset + 8 <= size; offset += 8)
    {
      std::uint64_t value = 0;
      std::memcpy(&value, bytes + offset, 8);
      word(value);
    }
    // An empty vector's data() may be null, and memcpy from null is undefined even for 0 bytes.
    std::uint64_t tail = 0;
    if (size > offset)
      std::memcpy(&tail, bytes + offset, size - offset);
    word(tail);
  }
  template <class T>
  void vector(const std::vector<T>& values)
  {
    static_assert(std::is_trivially_copyable<T>::value, "hashed as bytes");
    bytes(values.data(), values.size() * sizeof(T));
  }
  std::uint64_t value() const { return state_; }

private:
  std::uint64_t state_ = 0;
};

// The key as bytes: every double by its bit pattern, so that equal keys mean bit-identical inputs.
class KeyWriter
{
public:
  template <class T>
  void raw(const T& value)
  {
    static_assert(std::is_trivially_copyable<T>::value, "written as bytes");
    key_.append(reinterpret_cast<const char*>(&value), sizeof(T));
  }
  void text(const std::string& value)
  {
    raw(value.size());
    key_ += value;
  }
  void matrix(const glm::dmat4& m)
  {
    for (int column = 0; column < 4; ++column)
    {
      raw(m[column]);
    }
  }
  std::string take() { return std::move(key_); }

private:
  std::string key_;
};

void writeLightView(KeyWriter& key, const LightView& view)
{
  key.raw(view.projection);
  key.raw(view.eyeWs);
  key.matrix(view.viewFromWorld);
  key.matrix(view.clipFromView);
  key.matrix(view.clipFromWorld);
  key.raw(view.window);
  key.raw(view.nearDepth);
  key.raw(view.farDepth);
  key.raw(view.resolution);
  key.raw(view.receiverSampleCount);
  const PerspectiveWarp& warp = view.warp;
  key.raw(warp.kind);
  for (const double value :
    { warp.n, warp.nOpt, warp.gammaDeg, warp.zNear, warp.zFar, warp.nearDistance, warp.farDistance })
  {
    key.raw(value);
  }
}

void writeLight(KeyWriter& key, const Light& light)
{
  key.raw(light.type);
  key.raw(light.shape);
  key.raw(light.center);
  key.raw(light.normal);
  key.raw(light.up);
  key.raw(light.direction);
  key.raw(light.size);
  key.raw(light.coneAngleDeg);
  key.raw(light.intensity);
}

// The values of the parameters `structure` declares, and those of every structure it is built from.
void writeStructureParameters(KeyWriter& key, const FrameResources& frame, const LightSpaceStructure& structure)
{
  for (const LightSpaceStructure* each : withBuildDependencies({ &structure }))
  {
    key.text(each->name);
    for (const ParameterSpec& spec : each->parameters)
    {
      if (!frame.parameters.has(spec.name))
      {
        continue; // a setting the technique does not list (its build then uses the structure's default)
      }
      key.text(spec.name);
      key.raw(frame.parameters.get(spec.name));
      if (spec.file)
      {
        key.text(frame.parameters.file(spec.name));
      }
    }
    for (const std::string& name : each->sharedParameters)
    {
      if (frame.parameters.has(name))
      {
        key.text(name);
        key.raw(frame.parameters.get(name));
      }
    }
  }
}

} // namespace

std::uint64_t sceneGeometryHash(const Scene& scene)
{
  SceneHasher hasher;
  hasher.word(scene.objects.size());
  for (const SceneObject& object : scene.objects)
  {
    hasher.vector(object.mesh.positions);
    hasher.vector(object.mesh.normals);
    hasher.vector(object.mesh.uvs);
    hasher.vector(object.mesh.indices);
    hasher.bytes(&object.material.albedo, sizeof(object.material.albedo));
    hasher.word((object.castShadows ? 1u : 0u) | (object.receiveShadows ? 2u : 0u) | (object.hasAlphaTexture ? 4u : 0u));
    if (object.hasAlphaTexture)
    {
      const ImageF& alpha = object.alphaTexture.alpha;
      hasher.word(static_cast<std::uint64_t>(alpha.width) << 32 | static_cast<std::uint32_t>(alpha.height));
      hasher.vector(alpha.data);
    }
  }
  return hasher.value();
}

std::string structureBuildKey(const FrameResources& frame, const LightSpaceStructure& structure)
{
  SL_CHECK(frame.technique != nullptr && frame.light != nullptr);
  KeyWriter key;
  key.text(structure.name);
  key.raw(frame.viewIndex);
  key.raw(frame.partitions.has_value());
  key.raw(frame.hasLightView);
  if (frame.hasLightView)
  {
    writeLightView(key, frame.lightView);
  }
  writeLight(key, *frame.light);
  // The camera and what the G-buffer is rendered with: a build that reads the G-buffer (the polygon-id map's receiver
  // ids; a build limited to where receivers look up) reads them.
  key.matrix(frame.camera.clipFromWorld);
  key.matrix(frame.camera.viewFromWorld);
  key.raw(frame.camera.resolution);
  key.raw(frame.alphaTestOffset);
  key.raw(frame.multisample.samples);
  key.raw(frame.sceneGeometryHash);
  writeStructureParameters(key, frame, structure);
  // What the technique asks of every light-space build (TechniqueDescriptor::lightSpaceRequest): the moment map reads
  // its exponent from there, not from a parameter of its own.
  const LightSpaceRequest request = frame.technique->lightSpaceRequestFor(frame.parameters);
  key.text(request.filterParameter);
  key.raw(request.filterTexels);
  key.raw(request.momentExponent);
  key.raw(request.minMaxQueriesWithinNearPlaneKernel);
  for (const LightSpaceStructure* source : structure.builtFrom)
  {
    const auto version = frame.structureVersions.find(source->name);
    key.text(source->name);
    key.raw(version == frame.structureVersions.end() ? std::uint64_t(0) : version->second);
  }
  return key.take();
}

StructureBuildReuse::StructureBuildReuse(const LightSpaceStructure& structure)
  : structure_(structure)
  , isShadowMap_(&structure == &shadowMapStructure())
{
}

bool StructureBuildReuse::restore(FrameResources& frame)
{
  pendingKey_ = structureBuildKey(frame, structure_);
  // Views that partition the pixels keep one pair of shadow-map targets per view, and each view's fit differs: one
  // remembered build cannot serve them, so they always build.
  const bool reusable = remembered_ && !frame.partitions && remembered_->key == pendingKey_ &&
    (!isShadowMap_ || (remembered_->shadowMapLinear && remembered_->shadowMapLinear->GetHandle() != 0 &&
                        remembered_->shadowMapDepth && remembered_->shadowMapDepth->GetHandle() != 0));
  if (!reusable)
  {
    remembered_.reset(); // the build about to run may overwrite the textures it refers to
    return false;
  }
  if (isShadowMap_)
  {
    frame.shadowMapLinear = remembered_->shadowMapLinear;
    frame.shadowMapDepth = remembered_->shadowMapDepth;
  }
  if (remembered_->data)
  {
    frame.lightSpaceData[structure_.name] = remembered_->data;
  }
  else
  {
    frame.lightSpaceData.erase(structure_.name);
  }
  frame.structureVersions[structure_.name] = remembered_->version;
  return true;
}

void StructureBuildReuse::remember(FrameResources& frame, double gpuMilliseconds)
{
  // A new version at every build, unique across structures and renderers: the keys of the structures built from
  // this one change with it.
  static std::atomic<std::uint64_t> lastVersion{ 0 };
  Remembered remembered;
  remembered.key = pendingKey_;
  remembered.version = ++lastVersion;
  remembered.buildGpuMilliseconds = gpuMilliseconds;
  if (isShadowMap_)
  {
    remembered.shadowMapLinear = frame.shadowMapLinear;
    remembered.shadowMapDepth = frame.shadowMapDepth;
  }
  const auto data = frame.lightSpaceData.find(structure_.name);
  if (data != frame.lightSpaceData.end())
  {
    remembered.data = data->second;
  }
  remembered_ = std::move(remembered);
  frame.structureVersions[structure_.name] = remembered_->version;
}

void StructureBuildReuse::forget()
{
  remembered_.reset();
}

} // namespace sl
