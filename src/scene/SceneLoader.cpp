// scene.json -> Scene. The format is specified in docs/scene-format.md; this file is its reference
// implementation. Decisions the specification leaves open, made here:
//  - Only a light's `type` is required. Other light keys default to the Light struct's values; keys of another
//    light type (`size` on a point light) are errors, as are `view_angle` on an orthographic camera and
//    `parallel_scale` on a perspective one.
//  - Primitive `size` defaults to 1 (quad [1,1], box [1,1,1], sphere/disk radius 1). `center`, `size`,
//    `normal`, `up` are errors on a mesh object (a mesh is placed with `transform`); `normal`/`up` are errors
//    on a box or sphere.
//  - `alpha_texture` "fence" and "leaves" name the procedural patterns; any other string is a PNG path
//    relative to the scene file. Mesh paths are relative to the scene file too (absolute paths work).
//  - `mesh_alpha` (true or false, default false) is valid only on a quad with an `alpha_texture`, whatever its
//    value; true replaces the quad, after its transform, by the mesh of its opaque texels (scene/AlphaMesh.h,
//    the equivalent mesh of Forest et al. 2009 Fig. 11), which has no alpha texture. A mask without opaque texels is an
//    error (an object needs triangles).
//  - Integers (`resolution`) may be written as 512 or 512.0, not 512.5. View vectors are normalised; a direction
//    is any non-zero vector, however large or small its components ([1e308, -1e308, 0] is a valid normal).
//  - The limits of Scene.h (file size, nesting depth, magnitudes, light and camera distance) are checked here,
//    each failure naming the JSON path, so no scene reaches the renderers with a value float32 cannot carry.
//
// Structure: a small helper layer (Range, JsonNode, ObjectFields) does the type, finiteness and range checks
// and builds the one-line messages "<file>: <json path>: <problem>"; the readers below it (readCamera,
// readLight, readObject) then read each key in one line and only add the checks that involve several keys.
#include "core/Error.h"
#include "scene/AlphaMesh.h"
#include "scene/AlphaTexture.h"
#include "scene/MeshIO.h"
#include "scene/Primitives.h"
#include "scene/Scene.h"

#include <nlohmann/json.hpp>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <initializer_list>
#include <optional>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

namespace sl
{

namespace
{

using Json = nlohmann::json;


// ---- helper layer ---------------------------------------------------------------------------------------

// A limit as people write it: 1e6 rather than the stream's 1e+06.
std::string shortNumber(double value)
{
  std::string text = format(value);
  for (const std::string_view longForm : { "e+0", "e+" })
  {
    const std::size_t at = text.find(longForm);
    if (at != std::string::npos)
      text.replace(at, longForm.size(), "e");
  }
  return text;
}

// Why the magnitude bounds exist, appended to their messages so the user learns it is a limit, not a typo check.
const std::string kMagnitudeReason = "scene units, the limit float32 positions in the renderers can carry; see "
                                     "docs/scene-format.md";

// An allowed interval for a number, with its description for messages ("must be > 0, got -1").
struct Range
{
  double min = -HUGE_VAL;
  double max = HUGE_VAL;
  bool minOpen = false;
  bool maxOpen = false;
  std::string reason; // appended to describe() in parentheses when not empty

  static Range any() { return {}; }
  static Range greaterThan(double bound) { return { bound, HUGE_VAL, true, false, {} }; }
  static Range atLeast(double bound) { return { bound, HUGE_VAL, false, false, {} }; }
  static Range open(double low, double high) { return { low, high, true, true, {} }; }
  static Range closed(double low, double high) { return { low, high, false, false, {} }; }
  // A position or offset: |value| <= kMaxSceneMagnitude.
  static Range coordinate() { return { -kMaxSceneMagnitude, kMaxSceneMagnitude, false, false, kMagnitudeReason }; }
  // A length, scale or intensity: > 0 (or >= 0) and <= kMaxSceneMagnitude.
  static Range positiveMagnitude() { return { 0.0, kMaxSceneMagnitude, true, false, kMagnitudeReason }; }
  static Range nonNegativeMagnitude() { return { 0.0, kMaxSceneMagnitude, false, false, kMagnitudeReason }; }

  bool contains(double value) const
  {
    const bool aboveMin = minOpen ? value > min : value >= min;
    const bool belowMax = maxOpen ? value < max : value <= max;
    return aboveMin && belowMax;
  }
  // What `value` (outside the range) should have been. A magnitude range starting at 0 names only the side
  // that failed: a negative size is a sign problem ("must be > 0"), a huge one a limit ("must be <= 1e6 (...)").
  std::string describe(double value) const
  {
    if (min == 0.0 && max != HUGE_VAL && !reason.empty())
    {
      const bool belowMin = minOpen ? !(value > min) : !(value >= min);
      if (belowMin)
        return format(minOpen ? "> " : ">= ", min);
      return format(maxOpen ? "< " : "<= ", shortNumber(max), " (", reason, ")");
    }
    const std::string interval = max == HUGE_VAL
      ? format(minOpen ? "> " : ">= ", min)
      : format("in ", minOpen ? "(" : "[", shortNumber(min), ", ", shortNumber(max), maxOpen ? ")" : "]");
    return reason.empty() ? interval : format(interval, " (", reason, ")");
  }
};

// What a JSON value is, for "expected ..., got <this>" messages.
std::string describeValue(const Json& value)
{
  if (value.is_number_float() && !std::isfinite(value.get<double>()))
  {
    const double number = value.get<double>();
    return std::isnan(number) ? "nan" : (number > 0 ? "inf" : "-inf");
  }
  if (value.is_number())
    return value.dump();
  if (value.is_array())
    return format("an array of ", value.size());
  if (value.is_object())
    return "an object";
  constexpr std::size_t kMaxShown = 40;
  // Replace, not throw, on invalid UTF-8 (a --scene-set value is any bytes the shell passed).
  std::string shown = value.dump(-1, ' ', false, Json::error_handler_t::replace);
  if (shown.size() > kMaxShown)
    shown = shown.substr(0, kMaxShown) + "...";
  return format(value.type_name(), " ", shown);
}

// A JSON value together with its path in the document ("objects[2].transform.scale") and the scene's label,
// so any check can fail with a complete message.
class JsonNode
{
public:
  JsonNode(const Json& value, std::string path, const std::string& label)
    : value_(value)
    , path_(std::move(path))
    , label_(label)
  {
  }

  const Json& json() const { return value_; }
  const std::string& path() const { return path_; }
  const std::string& label() const { return label_; }

  std::string childPath(std::string_view key) const
  {
    return path_.empty() ? std::string(key) : format(path_, ".", key);
  }
  JsonNode child(std::string_view key) const { return { value_.at(std::string(key)), childPath(key), label_ }; }
  JsonNode element(std::size_t index) const { return { value_.at(index), format(path_, "[", index, "]"), label_ }; }

  [[noreturn]] void fail(const std::string& problem) const { failAt(label_, path_, problem); }
  [[noreturn]] static void failAt(const std::string& label, const std::string& path, const std::string& problem)
  {
    throw InputError(format(label, ": ", path.empty() ? "(top level)" : path, ": ", problem));
  }

  void expectObject() const
  {
    if (!value_.is_object())
      fail(format("expected an object, got ", describeValue(value_)));
  }

  // A non-empty array; `what` describes its elements for the message ("an array of lights").
  std::size_t nonEmptyArray(std::string_view what) const
  {
    if (!value_.is_array())
      fail(format("expected ", what, ", got ", describeValue(value_)));
    if (value_.empty())
      fail(format("is empty; expected ", what, " with at least one element"));
    return value_.size();
  }

  double number(const Range& range = Range::any()) const
  {
    if (!value_.is_number())
      fail(format("expected a number, got ", describeValue(value_)));
    const double number = value_.get<double>();
    if (!std::isfinite(number))
      fail(format("must be a finite number, got ", describeValue(value_)));
    if (!range.contains(number))
      fail(format("must be ", range.describe(number), ", got ", describeValue(value_)));
    return number;
  }

  int integer(const Range& range) const
  {
    const double value = number();
    if (std::floor(value) != value)
      fail(format("expected an integer, got ", describeValue(value_)));
    if (!range.contains(value))
      fail(format("must be ", range.describe(value), ", got ", describeValue(value_)));
    return static_cast<int>(value);
  }

  bool boolean() const
  {
    if (!value_.is_boolean())
      fail(format("expected true or false, got ", describeValue(value_)));
    return value_.get<bool>();
  }

  std::string string() const
  {
    if (!value_.is_string())
      fail(format("expected a string, got ", describeValue(value_)));
    return value_.get<std::string>();
  }

  // An array of exactly `count` numbers, each checked against `range` with its own path ("size[1]").
  template <int Count>
  glm::vec<Count, double> vector(const Range& range = Range::any()) const
  {
    if (!value_.is_array() || value_.size() != static_cast<std::size_t>(Count))
      fail(format("expected an array of ", Count, " numbers, got ", describeValue(value_)));
    glm::vec<Count, double> result{};
    for (int i = 0; i < Count; ++i)
      result[i] = element(static_cast<std::size_t>(i)).number(range);
    return result;
  }
  glm::dvec3 vec3(const Range& range = Range::any()) const { return vector<3>(range); }

  // A non-zero 3-vector, returned normalised. Only its direction matters, so any finite components are fine:
  // dividing by the largest first keeps |v|^2 from overflowing ([1e308, -1e308, 0]) or underflowing (1e-320).
  glm::dvec3 direction() const
  {
    const glm::dvec3 vector = vec3();
    const double largest = std::max({ std::abs(vector.x), std::abs(vector.y), std::abs(vector.z) });
    if (!(largest > 0.0))
      fail(format("must be a non-zero vector, got ", value_.dump()));
    const glm::dvec3 scaled = vector / largest;
    return scaled / glm::length(scaled);
  }

  // One of `names` (mapped to a value); `noun` names the kind in the message ("unknown light type 'laser'").
  template <typename T>
  T choice(std::initializer_list<std::pair<std::string_view, T>> names, std::string_view noun) const
  {
    const std::string name = string();
    std::string expected;
    for (const auto& [candidate, result] : names)
    {
      if (candidate == name)
        return result;
      expected += format(expected.empty() ? "" : ", ", candidate);
    }
    fail(format("unknown ", noun, " '", name, "'; expected one of: ", expected));
  }

private:
  const Json& value_;
  std::string path_;
  const std::string& label_;
};

// The keys of one JSON object: key checks, required and optional reads with defaults. Each accessor takes
// the key, so a reader's line names exactly one key of the format.
class ObjectFields
{
public:
  explicit ObjectFields(JsonNode node)
    : node_(std::move(node))
  {
    node_.expectObject();
  }

  const JsonNode& node() const { return node_; }

  // Rejects every key outside `allowed`. Keys in `otherKinds` are valid in the format but not for this kind
  // of thing (`kind`, e.g. "a point light"), and get a message saying so.
  void allowOnly(std::initializer_list<std::string_view> allowed,
    std::initializer_list<std::string_view> otherKinds = {}, std::string_view kind = {}) const
  {
    const auto contains = [](std::initializer_list<std::string_view> keys, std::string_view key) {
      return std::find(keys.begin(), keys.end(), key) != keys.end();
    };
    for (const auto& item : node_.json().items())
    {
      if (contains(allowed, item.key()))
        continue;
      if (contains(otherKinds, item.key()))
        node_.fail(format("key '", item.key(), "' does not apply to ", kind));
      node_.fail(format("unknown key '", item.key(), "'"));
    }
  }

  bool has(std::string_view key) const { return node_.json().contains(std::string(key)); }

  JsonNode required(std::string_view key) const
  {
    if (!has(key))
      fail(key, "missing (required)");
    return node_.child(key);
  }
  std::optional<JsonNode> optional(std::string_view key) const
  {
    if (!has(key))
      return std::nullopt;
    return node_.child(key);
  }

  [[noreturn]] void fail(std::string_view key, const std::string& problem) const
  {
    JsonNode::failAt(node_.label(), node_.childPath(key), problem);
  }

  double number(std::string_view key, double fallback, const Range& range = Range::any()) const
  {
    return has(key) ? node_.child(key).number(range) : fallback;
  }
  bool boolean(std::string_view key, bool fallback) const { return has(key) ? node_.child(key).boolean() : fallback; }
  glm::dvec3 vec3(std::string_view key, const glm::dvec3& fallback, const Range& range = Range::any()) const
  {
    return has(key) ? node_.child(key).vec3(range) : fallback;
  }
  glm::dvec2 vec2(std::string_view key, const glm::dvec2& fallback, const Range& range = Range::any()) const
  {
    return has(key) ? node_.child(key).vector<2>(range) : fallback;
  }
  glm::dvec3 direction(std::string_view key, const glm::dvec3& fallback) const
  {
    return has(key) ? node_.child(key).direction() : fallback;
  }
  template <typename T>
  T choice(std::string_view key, T fallback, std::initializer_list<std::pair<std::string_view, T>> names,
    std::string_view noun) const
  {
    return has(key) ? node_.child(key).choice(names, noun) : fallback;
  }

  // The `up` of a planar thing with unit normal `unitNormal`: the given vector orthogonalised against the
  // normal and normalised, or the default rule of Primitives.h (defaultUp) when the key is absent.
  glm::dvec3 planeUp(std::string_view key, const glm::dvec3& unitNormal) const
  {
    if (!has(key))
      return defaultUp(unitNormal);
    const glm::dvec3 up = node_.child(key).direction();
    if (isParallel(up, unitNormal))
      fail(key, "is parallel to the normal; it must have a component in the plane");
    return orthogonalizedUp(up, unitNormal);
  }

private:
  JsonNode node_;
};

// ---- readers --------------------------------------------------------------------------------------------

Camera readCamera(const ObjectFields& fields)
{
  Camera camera;
  camera.projection = fields.choice("projection", camera.projection,
    { { "perspective", Projection::Perspective }, { "orthographic", Projection::Orthographic } }, "projection");
  // view_angle means nothing to an orthographic camera and parallel_scale nothing to a perspective one;
  // accepting them silently would hide a forgotten "projection".
  if (camera.projection == Projection::Perspective)
    fields.allowOnly({ "projection", "position", "focal_point", "view_up", "resolution", "view_angle" },
      { "parallel_scale" }, "a perspective camera");
  else
    fields.allowOnly({ "projection", "position", "focal_point", "view_up", "resolution", "parallel_scale" },
      { "view_angle" }, "an orthographic camera");

  camera.position = fields.vec3("position", camera.position, Range::coordinate());
  camera.focalPoint = fields.vec3("focal_point", camera.focalPoint, Range::coordinate());
  camera.viewUp = fields.direction("view_up", camera.viewUp);
  camera.viewAngleDeg = fields.number("view_angle", camera.viewAngleDeg, Range::open(0.0, 180.0));
  camera.parallelScale = fields.number("parallel_scale", camera.parallelScale, Range::positiveMagnitude());
  if (const auto resolution = fields.optional("resolution"))
  {
    if (!resolution->json().is_array() || resolution->json().size() != 2)
      resolution->fail(
        format("expected an array of 2 integers [width, height], got ", describeValue(resolution->json())));
    const Range pixels = Range::closed(1, kMaxImageSide);
    camera.resolution = { resolution->element(0).integer(pixels), resolution->element(1).integer(pixels) };
  }

  const glm::dvec3 viewDirection = camera.focalPoint - camera.position;
  if (glm::length(viewDirection) == 0.0)
    fields.fail("focal_point", "must differ from camera.position");
  if (isParallel(camera.viewUp, viewDirection))
    fields.fail("view_up", "is parallel to the view direction (focal_point - position)");
  return camera;
}

Light readLight(const ObjectFields& fields)
{
  Light light;
  light.type = fields.required("type").choice<LightType>(
    { { "area", LightType::Area }, { "point", LightType::Point }, { "directional", LightType::Directional },
      { "spot", LightType::Spot } },
    "light type");
  // Every light key of the format, so a key of another light type gets "does not apply" rather than "unknown".
  const std::initializer_list<std::string_view> allLightKeys = { "type", "intensity", "shape", "center", "normal",
    "size", "up", "cone_angle_deg", "direction" };
  switch (light.type)
  {
  case LightType::Area:
    fields.allowOnly({ "type", "intensity", "shape", "center", "normal", "size", "up" }, allLightKeys, "an area light");
    light.shape = fields.choice("shape", LightShape::Square,
      { { "square", LightShape::Square }, { "disk", LightShape::Disk } }, "area light shape");
    light.center = fields.vec3("center", light.center, Range::coordinate());
    light.normal = fields.direction("normal", light.normal);
    light.size = fields.number("size", light.size, Range::positiveMagnitude());
    light.up = fields.planeUp("up", light.normal);
    break;
  case LightType::Point:
    fields.allowOnly({ "type", "intensity", "center" }, allLightKeys, "a point light");
    light.center = fields.vec3("center", light.center, Range::coordinate());
    break;
  case LightType::Spot:
    fields.allowOnly({ "type", "intensity", "center", "normal", "cone_angle_deg" }, allLightKeys, "a spot light");
    light.center = fields.vec3("center", light.center, Range::coordinate());
    light.normal = fields.direction("normal", light.normal);
    light.coneAngleDeg = fields.number("cone_angle_deg", light.coneAngleDeg, Range::open(0.0, 90.0));
    break;
  case LightType::Directional:
    fields.allowOnly({ "type", "intensity", "direction" }, allLightKeys, "a directional light");
    light.direction = fields.direction("direction", light.direction);
    break;
  }
  light.intensity = fields.number("intensity", light.intensity, Range::nonNegativeMagnitude());
  return light;
}

Transform readTransform(const ObjectFields& fields)
{
  fields.allowOnly({ "translate", "rotate_deg", "scale" });
  Transform transform;
  transform.translate = fields.vec3("translate", transform.translate, Range::coordinate());
  transform.rotateDeg = fields.vec3("rotate_deg", transform.rotateDeg);
  if (const auto scale = fields.optional("scale"))
  {
    // A single number scales uniformly. Products of scale and mesh coordinates are bounded by the vertex check
    // after the transform (checkVertices).
    const Range positive = Range::positiveMagnitude();
    if (scale->json().is_number())
      transform.scale = glm::dvec3(scale->number(positive));
    else if (scale->json().is_array())
      transform.scale = scale->vec3(positive);
    else
      scale->fail(format("expected a number or an array of 3 numbers, got ", describeValue(scale->json())));
  }
  return transform;
}

Material readMaterial(const ObjectFields& fields)
{
  fields.allowOnly({ "albedo" });
  Material material;
  material.albedo = fields.vec3("albedo", material.albedo, Range::closed(0.0, 1.0));
  return material;
}

enum class PrimitiveKind
{
  Quad,
  Box,
  Sphere,
  Disk
};

// Reads a primitive's keys and tessellates it at its center (the object transform comes later).
TriangleMesh readPrimitive(const ObjectFields& fields, std::string& kindName)
{
  const JsonNode primitive = fields.required("primitive");
  kindName = primitive.string();
  const PrimitiveKind kind = primitive.choice<PrimitiveKind>(
    { { "quad", PrimitiveKind::Quad }, { "box", PrimitiveKind::Box }, { "sphere", PrimitiveKind::Sphere },
      { "disk", PrimitiveKind::Disk } },
    "primitive");
  const std::initializer_list<std::string_view> allObjectKeys = { "mesh", "primitive", "center", "size", "normal",
    "up", "transform", "material", "alpha_texture", "mesh_alpha", "cast_shadows", "receive_shadows" };
  const Range positive = Range::positiveMagnitude();
  const glm::dvec3 defaultNormal{ 0.0, 0.0, 1.0 };

  switch (kind)
  {
  case PrimitiveKind::Quad:
  case PrimitiveKind::Disk:
  {
    // mesh_alpha on a disk never gets here: readObject refuses it on anything but a quad first.
    fields.allowOnly({ "primitive", "center", "size", "normal", "up", "transform", "material", "alpha_texture",
                       "mesh_alpha", "cast_shadows", "receive_shadows" },
      allObjectKeys, kind == PrimitiveKind::Quad ? "a quad" : "a disk");
    const glm::dvec3 center = fields.vec3("center", glm::dvec3(0.0), Range::coordinate());
    const glm::dvec3 normal = fields.direction("normal", defaultNormal);
    const glm::dvec3 up = fields.planeUp("up", normal);
    if (kind == PrimitiveKind::Quad)
      return makeQuad(center, fields.vec2("size", glm::dvec2(1.0), positive), normal, up);
    return makeDisk(center, fields.number("size", 1.0, positive), normal, up);
  }
  case PrimitiveKind::Box:
  case PrimitiveKind::Sphere:
  {
    fields.allowOnly({ "primitive", "center", "size", "transform", "material", "alpha_texture", "cast_shadows",
                       "receive_shadows" },
      allObjectKeys, kind == PrimitiveKind::Box ? "a box" : "a sphere");
    const glm::dvec3 center = fields.vec3("center", glm::dvec3(0.0), Range::coordinate());
    if (kind == PrimitiveKind::Box)
      return makeBox(center, fields.vec3("size", glm::dvec3(1.0), positive));
    return makeSphere(center, fields.number("size", 1.0, positive));
  }
  }
  SL_CHECK_MSG(false, "unhandled primitive kind");
  return {};
}

// `path` made absolute and lexically normal, for Scene::inputFiles (the path itself when the working directory
// cannot be read).
std::filesystem::path absoluteInputPath(const std::filesystem::path& path)
{
  std::error_code error;
  const std::filesystem::path absolute = std::filesystem::absolute(path, error);
  return (error ? path : absolute).lexically_normal();
}

// Every vertex finite and within kMaxSceneMagnitude after the object's transform: a mesh file or a scale can
// put vertices anywhere, and Embree asserts on ~1e30 coordinates (probe F15).
void checkVertices(const ObjectFields& fields, const SceneObject& object)
{
  for (std::size_t v = 0; v < object.mesh.positions.size(); ++v)
  {
    const glm::vec3& p = object.mesh.positions[v];
    const float largest = std::max({ std::abs(p.x), std::abs(p.y), std::abs(p.z) });
    if (!(largest <= kMaxSceneMagnitude)) // also catches NaN and inf
    {
      fields.node().fail(format("vertex ", v, " lies at (", p.x, ", ", p.y, ", ", p.z, ")",
        fields.has("transform") ? " after the transform" : "", "; coordinates must be in [", shortNumber(-kMaxSceneMagnitude),
        ", ", shortNumber(kMaxSceneMagnitude), "] (", kMagnitudeReason, ")"));
    }
  }
}

SceneObject readObject(const ObjectFields& fields, std::size_t index, const std::filesystem::path& baseDir,
  std::vector<std::filesystem::path>& inputFiles)
{
  const bool hasMesh = fields.has("mesh");
  const bool hasPrimitive = fields.has("primitive");
  if (hasMesh && hasPrimitive)
    fields.node().fail("has both 'mesh' and 'primitive'; give exactly one");
  if (!hasMesh && !hasPrimitive)
    fields.node().fail("needs 'mesh' (a file) or 'primitive' (quad, box, sphere, disk)");

  // mesh_alpha needs makeQuad's uv layout, one copy of the mask over [0,1]^2 (AlphaMesh.h), which only a quad has.
  bool meshAlpha = false;
  if (const auto key = fields.optional("mesh_alpha"))
  {
    meshAlpha = key->boolean();
    const Json& primitive = fields.node().json().value("primitive", Json());
    if (!(primitive.is_string() && primitive.get<std::string>() == "quad"))
      key->fail("applies only to a 'quad' primitive (with an 'alpha_texture')");
    if (!fields.has("alpha_texture"))
      key->fail("needs an 'alpha_texture' on the quad (the mask whose opaque texels it meshes)");
  }

  SceneObject object;
  std::string meshFile;
  if (hasMesh)
  {
    fields.allowOnly({ "mesh", "transform", "material", "alpha_texture", "cast_shadows", "receive_shadows" },
      { "center", "size", "normal", "up" }, "a mesh (place it with 'transform')");
    meshFile = fields.required("mesh").string();
    try
    {
      LoadedMesh loaded = loadMesh(baseDir / meshFile);
      object.mesh = std::move(loaded.mesh);
      object.droppedDegenerateTriangles = loaded.droppedDegenerateTriangles;
      inputFiles.push_back(absoluteInputPath(baseDir / meshFile));
    }
    catch (const InputError& error)
    {
      fields.fail("mesh", error.what());
    }
    object.name = format("objects[", index, "] (mesh ", meshFile, ")");
  }
  else
  {
    std::string kindName;
    object.mesh = readPrimitive(fields, kindName);
    object.name = format("objects[", index, "] (", kindName, ")");
  }

  if (const auto transform = fields.optional("transform"))
    transformMesh(object.mesh, readTransform(ObjectFields(*transform)).worldFromLocal());
  checkVertices(fields, object);
  if (const auto material = fields.optional("material"))
    object.material = readMaterial(ObjectFields(*material));
  if (const auto alpha = fields.optional("alpha_texture"))
  {
    const std::string source = alpha->string();
    if (object.mesh.uvs.empty())
      alpha->fail(format("mesh '", meshFile, "' has no texture coordinates (OBJ vt / PLY u,v), which an alpha ",
        "texture needs"));
    try
    {
      object.alphaTexture = makeAlphaTexture(source, baseDir);
      if (!isProceduralAlphaName(source))
        inputFiles.push_back(absoluteInputPath(baseDir / source));
    }
    catch (const InputError& error)
    {
      alpha->fail(error.what());
    }
    object.hasAlphaTexture = true;
  }
  if (meshAlpha)
  {
    try
    {
      object.mesh = meshOpaqueTexels(quadUvFrame(object.mesh), object.alphaTexture.alpha);
    }
    catch (const InputError& error)
    {
      fields.fail("mesh_alpha", error.what());
    }
    if (object.mesh.indices.empty())
      fields.fail("mesh_alpha", format("alpha texture '", object.alphaTexture.source,
        "' has no opaque texel (alpha >= 0.5), so the mesh would be empty"));
    object.name = format("objects[", index, "] (quad, alpha texture ", object.alphaTexture.source, " meshed)");
    object.hasAlphaTexture = false;
    object.alphaTexture = AlphaTexture{};
  }
  object.castShadows = fields.boolean("cast_shadows", object.castShadows);
  object.receiveShadows = fields.boolean("receive_shadows", object.receiveShadows);
  return object;
}

constexpr int kNlohmannNumberOverflow = 406;
constexpr int kNestingTooDeep = -1; // our own Failure id: a container opened beyond the depth limit
constexpr int kDuplicateKey = -2;   // our own Failure id: a key given twice in one object (probe S13)

// Builds the document like Json::parse, but knows the JSON path of the value being parsed when parsing
// fails. nlohmann 3.11 rejects a number too large for a double (1e999) while parsing ("number overflow",
// out_of_range.406) instead of producing inf; with the path we report it like any other non-finite number:
// "objects[0].center[1]: must be a finite number, got 1e999".
// It also enforces the nesting limit: nlohmann's SAX parser is iterative, and refusing the container that
// would exceed `maxDepth` means no document this returns is deeper, so the recursive parts of nlohmann
// (dump, copy, comparison) are never reached with an unbounded depth (probe S12b: a stack overflow at 100 000).
class PathTrackingDomBuilder
{
public:
  struct Failure
  {
    int id = 0;             // nlohmann's exception id: 101.. syntax, 406 number overflow; or kNestingTooDeep
    std::string what;       // nlohmann's message
    std::string path;       // where the failing value would have gone
    std::string lastToken;  // the text nlohmann read last (the overflowing number for 406)
  };

  PathTrackingDomBuilder(Json& root, int maxDepth)
    : root_(root)
    , maxDepth_(maxDepth)
  {
  }

  // nlohmann's SAX interface (see nlohmann::json_sax).
  bool null() { return add(nullptr); }
  bool boolean(bool value) { return add(value); }
  bool number_integer(Json::number_integer_t value) { return add(value); }
  bool number_unsigned(Json::number_unsigned_t value) { return add(value); }
  bool number_float(Json::number_float_t value, const Json::string_t& /*text*/) { return add(value); }
  bool string(Json::string_t& value) { return add(std::move(value)); }
  bool binary(Json::binary_t& value) { return add(Json::binary(std::move(value))); }
  bool start_object(std::size_t /*count*/) { return open(Json::object()); }
  bool key(Json::string_t& key)
  {
    keys_.back() = key;
    // A repeated key would silently overwrite the first (Json::parse keeps the last): refused instead.
    if (open_.back()->contains(key))
    {
      failure_ = Failure{ kDuplicateKey, {}, pathOfNextValue(), key };
      return false;
    }
    return true;
  }
  bool end_object() { return close(); }
  bool start_array(std::size_t /*count*/) { return open(Json::array()); }
  bool end_array() { return close(); }
  bool parse_error(std::size_t /*position*/, const std::string& lastToken, const Json::exception& error)
  {
    failure_ = Failure{ error.id, error.what(), pathOfNextValue(), lastToken };
    return false;
  }

  const std::optional<Failure>& failure() const { return failure_; }

private:
  // Puts `value` where the document's next value goes and returns where it now lives. Pointers to open
  // containers stay valid: values are only ever added to the innermost open container.
  Json* place(Json&& value)
  {
    if (open_.empty())
    {
      root_ = std::move(value);
      return &root_;
    }
    Json& parent = *open_.back();
    if (parent.is_array())
    {
      parent.push_back(std::move(value));
      return &parent.back();
    }
    Json& slot = parent[keys_.back()]; // a new key: key() refuses repeated ones
    slot = std::move(value);
    return &slot;
  }
  bool add(Json value)
  {
    place(std::move(value));
    return true;
  }
  bool open(Json container)
  {
    if (static_cast<int>(open_.size()) >= maxDepth_)
    {
      failure_ = Failure{ kNestingTooDeep, {}, pathOfNextValue(), {} };
      return false; // stops sax_parse
    }
    open_.push_back(place(std::move(container)));
    keys_.emplace_back();
    return true;
  }
  bool close()
  {
    open_.pop_back();
    keys_.pop_back();
    return true;
  }
  std::string pathOfNextValue() const
  {
    std::string path;
    for (std::size_t level = 0; level < open_.size(); ++level)
    {
      const bool innermost = level + 1 == open_.size();
      if (open_[level]->is_array()) // outer arrays already hold the open child, the innermost not yet
        path += format("[", open_[level]->size() - (innermost ? 0 : 1), "]");
      else
        path += path.empty() ? keys_[level] : format(".", keys_[level]);
    }
    return path;
  }

  Json& root_;
  int maxDepth_;
  std::vector<Json*> open_;       // open containers, outermost first
  std::vector<std::string> keys_; // per open container: the key of its value being parsed (objects)
  std::optional<Failure> failure_;
};

// "malformed JSON at line 3, column 5: <nlohmann's reason>", from nlohmann's
// "[json.exception.parse_error.101] parse error at line 3, column 5: <reason>".
std::string describeParseError(const std::string& what)
{
  const std::string marker = "parse error at ";
  const std::size_t at = what.find(marker);
  std::string description = at != std::string::npos ? format("malformed JSON at ", what.substr(at + marker.size()))
                                                      : format("malformed JSON: ", what);
  for (char& c : description) // one line, whatever the reason quotes
    if (c == '\n' || c == '\r')
      c = ' ';
  return description;
}

// A JSON path or override as shown in a message: control characters escaped (one line, no terminal escapes)
// and cut to a readable length (a 100 000-level path or value would make a megabyte-long line).
std::string shownText(std::string_view text)
{
  constexpr std::size_t kMaxShown = 80;
  std::string shown;
  for (std::size_t i = 0; i < text.size() && i < kMaxShown; ++i)
  {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c < 0x20 || c == 0x7f)
    {
      constexpr char kHex[] = "0123456789abcdef";
      shown += "\\x";
      shown += kHex[c >> 4];
      shown += kHex[c & 0xf];
    }
    else
      shown += static_cast<char>(c);
  }
  if (text.size() > kMaxShown)
    shown += "...";
  return shown;
}

// Parses `jsonText` with at most `maxDepth` nested containers; the document, or how it failed.
struct ParsedJson
{
  Json document;
  std::optional<PathTrackingDomBuilder::Failure> failure;
};
ParsedJson parseJsonLimited(const std::string& jsonText, int maxDepth)
{
  ParsedJson result;
  PathTrackingDomBuilder builder(result.document, maxDepth);
  if (!Json::sax_parse(jsonText, &builder))
  {
    SL_CHECK(builder.failure().has_value());
    result.failure = builder.failure();
    result.document = Json(); // a partial document may hold anything; nobody reads it
  }
  return result;
}

Json parseJson(const std::string& jsonText, const std::string& label)
{
  ParsedJson parsed = parseJsonLimited(jsonText, kMaxJsonDepth);
  if (!parsed.failure)
    return std::move(parsed.document);
  const PathTrackingDomBuilder::Failure& failure = *parsed.failure;
  if (failure.id == kNlohmannNumberOverflow)
    JsonNode::failAt(label, failure.path, format("must be a finite number, got ", failure.lastToken));
  if (failure.id == kNestingTooDeep)
    JsonNode::failAt(label, shownText(failure.path),
      format("objects and arrays nest deeper than ", kMaxJsonDepth, " levels (the scene format's limit)"));
  if (failure.id == kDuplicateKey)
    JsonNode::failAt(label, shownText(failure.path), "is given twice in the same object");
  throw InputError(format(label, ": ", describeParseError(failure.what)));
}

// ---- --scene-set overrides --------------------------------------------------------------------------------

// An array index token of a JSON pointer (RFC 6901: digits, no leading zero); nullopt when it is not one.
// Values too large for size_t are clamped: they are past the end of any array anyway.
std::optional<std::size_t> arrayIndex(const std::string& token)
{
  if (token.empty() || (token.size() > 1 && token[0] == '0'))
    return std::nullopt;
  std::size_t index = 0;
  for (const char c : token)
  {
    if (c < '0' || c > '9')
      return std::nullopt;
    const std::size_t digit = static_cast<std::size_t>(c - '0');
    index = index > (SIZE_MAX - digit) / 10 ? SIZE_MAX : index * 10 + digit;
  }
  return index;
}

// One "/json/pointer=value" applied to `document` in place. Written out rather than through nlohmann's
// json_pointer, whose operator[] resizes an array to any index (/objects/2000000000000 -> std::bad_alloc,
// probe P30) and creates missing parents.
void applyOverride(Json& document, const std::string& override, const std::string& label)
{
  const std::string shown = shownText(override);
  const std::size_t equals = override.find('=');
  if (equals == std::string::npos || override.empty() || override[0] != '/')
    throw InputError(format("--scene-set ", shown, ": expected /json/pointer=value, e.g. /lights/0/size=2"));
  const std::string pointer = override.substr(0, equals);
  const std::string valueText = override.substr(equals + 1);

  // Tokens of the pointer (after each '/'), unescaped (~1 is '/', ~0 is '~'), with the raw prefix up to each.
  std::vector<std::string> tokens;
  std::vector<std::size_t> tokenEnds; // pointer.substr(0, tokenEnds[i]) is the pointer to tokens[i]
  for (std::size_t start = 1; start <= pointer.size();)
  {
    const std::size_t slash = std::min(pointer.find('/', start), pointer.size());
    std::string token;
    for (std::size_t i = start; i < slash; ++i)
    {
      if (pointer[i] != '~')
      {
        token += pointer[i];
        continue;
      }
      if (i + 1 >= slash || (pointer[i + 1] != '0' && pointer[i + 1] != '1'))
        throw InputError(format("--scene-set ", shown, ": '~' in a JSON pointer must be followed by 0 or 1"));
      token += pointer[++i] == '0' ? '~' : '/';
    }
    tokens.push_back(std::move(token));
    tokenEnds.push_back(slash);
    start = slash + 1;
  }
  const auto prefix = [&](std::size_t tokenCount) {
    return tokenCount == 0 ? std::string("/") : shownText(pointer.substr(0, tokenEnds[tokenCount - 1]));
  };

  // Walk to the parent, which must exist. The document is at most kMaxJsonDepth deep, so this stops early.
  Json* parent = &document;
  for (std::size_t i = 0; i + 1 < tokens.size(); ++i)
  {
    Json* next = nullptr;
    if (parent->is_object())
    {
      const auto found = parent->find(tokens[i]);
      next = found != parent->end() ? &*found : nullptr;
    }
    else if (parent->is_array())
    {
      const std::optional<std::size_t> index = arrayIndex(tokens[i]);
      next = index && *index < parent->size() ? &(*parent)[*index] : nullptr;
    }
    if (!next)
      throw InputError(format("--scene-set ", shown, ": ", label, " has nothing at ", prefix(i + 1)));
    parent = next;
  }

  // The value: JSON, or a bare word as a string (/lights/0/shape=disk). It goes tokens.size() levels deep, so
  // its own nesting may use what is left of the limit; the document stays within kMaxJsonDepth.
  const int depthLeft = std::max(0, kMaxJsonDepth - static_cast<int>(tokens.size()));
  ParsedJson parsed = parseJsonLimited(valueText, depthLeft);
  Json value;
  if (!parsed.failure)
    value = std::move(parsed.document);
  else if (parsed.failure->id == kNlohmannNumberOverflow)
  {
    const std::string where = parsed.failure->path.empty() ? "" : format(" (at ", shownText(parsed.failure->path), ")");
    throw InputError(format("--scene-set ", shown, ": the value ", shownText(parsed.failure->lastToken),
      where, " is not a finite number"));
  }
  else if (parsed.failure->id == kNestingTooDeep)
    throw InputError(format("--scene-set ", shown, ": the value nests deeper than the scene format's limit of ",
      kMaxJsonDepth, " levels (counted from the document's top)"));
  else if (parsed.failure->id == kDuplicateKey)
    throw InputError(format("--scene-set ", shown, ": the value gives the key ", shownText(parsed.failure->lastToken),
      " twice"));
  else
    value = valueText;

  const std::string& last = tokens.back();
  if (parent->is_object())
    (*parent)[last] = std::move(value);
  else if (parent->is_array())
  {
    const std::optional<std::size_t> index = last == "-" ? std::optional<std::size_t>(parent->size()) : arrayIndex(last);
    if (!index)
      throw InputError(format("--scene-set ", shown, ": '", shownText(last), "' is not an index of the array at ",
        prefix(tokens.size() - 1)));
    if (*index > parent->size())
      throw InputError(format("--scene-set ", shown, ": index ", shownText(last), " is past the end of ",
        prefix(tokens.size() - 1), ", which has ", parent->size(), " element(s); an override replaces an element or "
        "appends one (index ", parent->size(), ")"));
    if (*index == parent->size())
      parent->push_back(std::move(value));
    else
      (*parent)[*index] = std::move(value);
  }
  else
    throw InputError(format("--scene-set ", shown, ": ", label, " has ", parent->type_name(), " at ",
      prefix(tokens.size() - 1), ", which has no members"));
}

// ---- scale sanity -----------------------------------------------------------------------------------------

// Lights within kMaxLightDistanceInSceneRadii and the camera within kMaxCameraDistanceInSceneRadii bounding
// radii of the objects' centre (Scene.h says why and how they were measured). Run after every object is read;
// the directional light has no position.
void checkDistances(const Scene& scene, const std::string& label)
{
  const Bounds bounds = scene.bounds();
  const double radius = bounds.radius();
  if (!(radius > 0.0))
    JsonNode::failAt(label, "objects", "all objects together collapse to a single point in float32 (sizes or scales "
      "too small to represent)");
  const glm::dvec3 centre = bounds.center();
  const auto check = [&](const glm::dvec3& position, double radii, const std::string& path) {
    const double distance = glm::length(position - centre);
    if (distance > radii * radius)
      JsonNode::failAt(label, path, format("lies ", distance, " from the centre of the objects' bounding box, more than ",
        shortNumber(radii), " times their bounding radius ", radius, " (", radii * radius,
        "); float32 depths cannot resolve the scene from that far (see docs/scene-format.md)"));
  };
  for (std::size_t i = 0; i < scene.lights.size(); ++i)
    if (scene.lights[i].type != LightType::Directional)
      check(scene.lights[i].center, kMaxLightDistanceInSceneRadii, format("lights[", i, "].center"));
  check(scene.camera.position, kMaxCameraDistanceInSceneRadii, "camera.position");
}

// The validated scene from a parsed (and overridden) document.
Scene readScene(const Json& document, const std::string& label, const std::filesystem::path& baseDir)
{
  const ObjectFields top(JsonNode(document, "", label));
  top.allowOnly({ "camera", "lights", "objects" });

  Scene scene;
  if (const auto camera = top.optional("camera"))
    scene.camera = readCamera(ObjectFields(*camera));

  if (!top.has("lights"))
    top.fail("lights", "missing; a scene needs at least one light");
  const JsonNode lights = top.required("lights");
  const std::size_t lightCount = lights.nonEmptyArray("an array of lights");
  for (std::size_t i = 0; i < lightCount; ++i)
    scene.lights.push_back(readLight(ObjectFields(lights.element(i))));

  if (!top.has("objects"))
    top.fail("objects", "missing; a scene needs at least one object");
  const JsonNode objects = top.required("objects");
  const std::size_t objectCount = objects.nonEmptyArray("an array of objects");
  for (std::size_t i = 0; i < objectCount; ++i)
    scene.objects.push_back(readObject(ObjectFields(objects.element(i)), i, baseDir, scene.inputFiles));

  checkDistances(scene, label);
  return scene;
}

// What a non-regular file is, for "is a FIFO, not a regular file".
std::string describeFileType(mode_t mode)
{
  if (S_ISDIR(mode))
    return "a directory";
  if (S_ISFIFO(mode))
    return "a FIFO";
  if (S_ISCHR(mode))
    return "a character device";
  if (S_ISBLK(mode))
    return "a block device";
  if (S_ISSOCK(mode))
    return "a socket";
  return "not a regular file";
}

// The scene file's text: a regular file (after following symlinks) of at most kMaxSceneFileBytes. POSIX
// rather than std::ifstream because the type must be checked on the opened descriptor without blocking:
// opening a FIFO for reading blocks until a writer appears (probe S14), and a check by path before the open
// races with a file swapped in between. O_NONBLOCK makes the open return at once; fstat then decides.
std::string readSceneText(const std::filesystem::path& file, const std::string& label)
{
  const int descriptor = ::open(file.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (descriptor < 0)
  {
    const int cause = errno;
    throw InputError(format(label, ": cannot read scene file (",
      cause == ENOENT ? std::string("no such file") : std::generic_category().message(cause), ")"));
  }
  struct Closer
  {
    int descriptor;
    ~Closer() { ::close(descriptor); }
  } closer{ descriptor };

  struct stat status
  {
  };
  if (::fstat(descriptor, &status) != 0)
    throw InputError(format(label, ": cannot read scene file (", std::generic_category().message(errno), ")"));
  if (!S_ISREG(status.st_mode))
    throw InputError(format(label, ": cannot read scene file (it is ", describeFileType(status.st_mode),
      ", not a regular file)"));
  const auto tooLarge = [&]() {
    return InputError(format(label, ": scene file is larger than ", kMaxSceneFileBytes / (1024 * 1024),
      " MiB (the scene format's limit; meshes belong in their own files)"));
  };
  if (static_cast<std::uintmax_t>(status.st_size) > kMaxSceneFileBytes)
    throw tooLarge();

  // Read at most one byte more than the limit, whatever the size said: the file may grow meanwhile.
  std::string text;
  text.resize(static_cast<std::size_t>(status.st_size));
  std::size_t filled = 0;
  for (;;)
  {
    if (filled == text.size())
    {
      if (text.size() > kMaxSceneFileBytes)
        throw tooLarge();
      text.resize(std::min<std::size_t>(std::max<std::size_t>(2 * text.size(), 4096), kMaxSceneFileBytes + 1));
    }
    const ssize_t got = ::read(descriptor, text.data() + filled, text.size() - filled);
    if (got < 0)
    {
      if (errno == EINTR)
        continue;
      throw InputError(format(label, ": cannot read scene file (", std::generic_category().message(errno), ")"));
    }
    if (got == 0)
      break;
    filled += static_cast<std::size_t>(got);
  }
  text.resize(filled);
  return text;
}

} // namespace

Scene parseScene(const std::string& jsonText, const std::vector<std::string>& overrides, const std::string& label,
  const std::filesystem::path& baseDir)
{
  Json document = parseJson(jsonText, label);
  // Overrides replace values of the document before validation, so every check and message applies to the
  // result as if the file had said it.
  for (const std::string& override : overrides)
    applyOverride(document, override, label);
  return readScene(document, label, baseDir);
}

Scene parseScene(const std::string& jsonText, const std::string& label, const std::filesystem::path& baseDir)
{
  return parseScene(jsonText, {}, label, baseDir);
}

Scene loadScene(const std::filesystem::path& file)
{
  return loadScene(file, {});
}

Scene loadScene(const std::filesystem::path& file, const std::vector<std::string>& overrides)
{
  const std::string label = file.string();
  const std::string text = readSceneText(file, label);
  Scene scene = parseScene(text, overrides, label, file.parent_path());
  scene.file = file;
  scene.inputFiles.insert(scene.inputFiles.begin(), absoluteInputPath(file));
  return scene;
}

} // namespace sl
