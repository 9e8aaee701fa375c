// scene.json -> Scene. The format is specified in README.md ("Scene format"); this file is its reference
// implementation. Decisions the specification leaves open, made here:
//  - Only a light's `type` is required. Other light keys default to the Light struct's values; keys of another
//    light type (`size` on a point light) are errors, as are `view_angle` on an orthographic camera and
//    `parallel_scale` on a perspective one.
//  - Primitive `size` defaults to 1 (quad [1,1], box [1,1,1], sphere/disk radius 1). `center`, `size`,
//    `normal`, `up` are errors on a mesh object (a mesh is placed with `transform`); `normal`/`up` are errors
//    on a box or sphere.
//  - `alpha_texture` "fence" and "leaves" name the procedural patterns; any other string is a PNG path
//    relative to the scene file. Mesh paths are relative to the scene file too (absolute paths work).
//  - Integers (`resolution`) may be written as 512 or 512.0, not 512.5. View vectors are normalised.
//
// Structure: a small helper layer (Range, JsonNode, ObjectFields) does the type, finiteness and range checks
// and builds the one-line messages "<file>: <json path>: <problem>"; the readers below it (readCamera,
// readLight, readObject) then read each key in one line and only add the checks that involve several keys.
#include "core/Error.h"
#include "scene/AlphaTexture.h"
#include "scene/MeshIO.h"
#include "scene/Primitives.h"
#include "scene/Scene.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <initializer_list>
#include <iterator>
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

constexpr int kMaxResolution = 16384;

// ---- helper layer ---------------------------------------------------------------------------------------

// An allowed interval for a number, with its description for messages ("must be > 0, got -1").
struct Range
{
  double min = -HUGE_VAL;
  double max = HUGE_VAL;
  bool minOpen = false;
  bool maxOpen = false;

  static Range any() { return {}; }
  static Range greaterThan(double bound) { return { bound, HUGE_VAL, true, false }; }
  static Range atLeast(double bound) { return { bound, HUGE_VAL, false, false }; }
  static Range open(double low, double high) { return { low, high, true, true }; }
  static Range closed(double low, double high) { return { low, high, false, false }; }

  bool contains(double value) const
  {
    const bool aboveMin = minOpen ? value > min : value >= min;
    const bool belowMax = maxOpen ? value < max : value <= max;
    return aboveMin && belowMax;
  }
  std::string describe() const
  {
    if (max == HUGE_VAL)
      return format(minOpen ? "> " : ">= ", min);
    return format("in ", minOpen ? "(" : "[", min, ", ", max, maxOpen ? ")" : "]");
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
  std::string shown = value.dump();
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
      fail(format("must be ", range.describe(), ", got ", describeValue(value_)));
    return number;
  }

  int integer(const Range& range) const
  {
    const double value = number();
    if (std::floor(value) != value)
      fail(format("expected an integer, got ", describeValue(value_)));
    if (!range.contains(value))
      fail(format("must be ", range.describe(), ", got ", describeValue(value_)));
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

  // A non-zero 3-vector, returned normalised.
  glm::dvec3 direction() const
  {
    const glm::dvec3 vector = vec3();
    const double length = glm::length(vector);
    if (!(length > 0.0) || !std::isfinite(length))
      fail(format("must be a non-zero vector, got ", value_.dump()));
    return vector / length;
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

  camera.position = fields.vec3("position", camera.position);
  camera.focalPoint = fields.vec3("focal_point", camera.focalPoint);
  camera.viewUp = fields.direction("view_up", camera.viewUp);
  camera.viewAngleDeg = fields.number("view_angle", camera.viewAngleDeg, Range::open(0.0, 180.0));
  camera.parallelScale = fields.number("parallel_scale", camera.parallelScale, Range::greaterThan(0.0));
  if (const auto resolution = fields.optional("resolution"))
  {
    if (!resolution->json().is_array() || resolution->json().size() != 2)
      resolution->fail(
        format("expected an array of 2 integers [width, height], got ", describeValue(resolution->json())));
    const Range pixels = Range::closed(1, kMaxResolution);
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
    light.center = fields.vec3("center", light.center);
    light.normal = fields.direction("normal", light.normal);
    light.size = fields.number("size", light.size, Range::greaterThan(0.0));
    light.up = fields.planeUp("up", light.normal);
    break;
  case LightType::Point:
    fields.allowOnly({ "type", "intensity", "center" }, allLightKeys, "a point light");
    light.center = fields.vec3("center", light.center);
    break;
  case LightType::Spot:
    fields.allowOnly({ "type", "intensity", "center", "normal", "cone_angle_deg" }, allLightKeys, "a spot light");
    light.center = fields.vec3("center", light.center);
    light.normal = fields.direction("normal", light.normal);
    light.coneAngleDeg = fields.number("cone_angle_deg", light.coneAngleDeg, Range::open(0.0, 90.0));
    break;
  case LightType::Directional:
    fields.allowOnly({ "type", "intensity", "direction" }, allLightKeys, "a directional light");
    light.direction = fields.direction("direction", light.direction);
    break;
  }
  light.intensity = fields.number("intensity", light.intensity, Range::atLeast(0.0));
  return light;
}

Transform readTransform(const ObjectFields& fields)
{
  fields.allowOnly({ "translate", "rotate_deg", "scale" });
  Transform transform;
  transform.translate = fields.vec3("translate", transform.translate);
  transform.rotateDeg = fields.vec3("rotate_deg", transform.rotateDeg);
  if (const auto scale = fields.optional("scale"))
  {
    // A single number scales uniformly.
    const Range positive = Range::greaterThan(0.0);
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
    "up", "transform", "material", "alpha_texture", "cast_shadows", "receive_shadows" };
  const Range positive = Range::greaterThan(0.0);
  const glm::dvec3 defaultNormal{ 0.0, 0.0, 1.0 };

  switch (kind)
  {
  case PrimitiveKind::Quad:
  case PrimitiveKind::Disk:
  {
    fields.allowOnly({ "primitive", "center", "size", "normal", "up", "transform", "material", "alpha_texture",
                       "cast_shadows", "receive_shadows" },
      allObjectKeys, kind == PrimitiveKind::Quad ? "a quad" : "a disk");
    const glm::dvec3 center = fields.vec3("center", glm::dvec3(0.0));
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
    const glm::dvec3 center = fields.vec3("center", glm::dvec3(0.0));
    if (kind == PrimitiveKind::Box)
      return makeBox(center, fields.vec3("size", glm::dvec3(1.0), positive));
    return makeSphere(center, fields.number("size", 1.0, positive));
  }
  }
  SL_CHECK_MSG(false, "unhandled primitive kind");
  return {};
}

SceneObject readObject(const ObjectFields& fields, std::size_t index, const std::filesystem::path& baseDir)
{
  const bool hasMesh = fields.has("mesh");
  const bool hasPrimitive = fields.has("primitive");
  if (hasMesh && hasPrimitive)
    fields.node().fail("has both 'mesh' and 'primitive'; give exactly one");
  if (!hasMesh && !hasPrimitive)
    fields.node().fail("needs 'mesh' (a file) or 'primitive' (quad, box, sphere, disk)");

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
    }
    catch (const InputError& error)
    {
      alpha->fail(error.what());
    }
    object.hasAlphaTexture = true;
  }
  object.castShadows = fields.boolean("cast_shadows", object.castShadows);
  object.receiveShadows = fields.boolean("receive_shadows", object.receiveShadows);
  return object;
}

// Builds the document like Json::parse, but knows the JSON path of the value being parsed when parsing
// fails. nlohmann 3.11 rejects a number too large for a double (1e999) while parsing ("number overflow",
// out_of_range.406) instead of producing inf; with the path we report it like any other non-finite number:
// "objects[0].center[1]: must be a finite number, got 1e999".
class PathTrackingDomBuilder
{
public:
  struct Failure
  {
    int id = 0;             // nlohmann's exception id: 101.. syntax, 406 number overflow
    std::string what;       // nlohmann's message
    std::string path;       // where the failing value would have gone
    std::string lastToken;  // the text nlohmann read last (the overflowing number for 406)
  };

  explicit PathTrackingDomBuilder(Json& root)
    : root_(root)
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
    Json& slot = parent[keys_.back()]; // a repeated key overwrites, as Json::parse does
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
  std::vector<Json*> open_;       // open containers, outermost first
  std::vector<std::string> keys_; // per open container: the key of its value being parsed (objects)
  std::optional<Failure> failure_;
};

constexpr int kNlohmannNumberOverflow = 406;

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

Json parseJson(const std::string& jsonText, const std::string& label)
{
  Json document;
  PathTrackingDomBuilder builder(document);
  if (Json::sax_parse(jsonText, &builder))
    return document;
  SL_CHECK(builder.failure().has_value());
  const PathTrackingDomBuilder::Failure& failure = *builder.failure();
  if (failure.id == kNlohmannNumberOverflow)
    JsonNode::failAt(label, failure.path, format("must be a finite number, got ", failure.lastToken));
  throw InputError(format(label, ": ", describeParseError(failure.what)));
}

} // namespace

Scene parseScene(const std::string& jsonText, const std::string& label, const std::filesystem::path& baseDir)
{
  const Json document = parseJson(jsonText, label);
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
    scene.objects.push_back(readObject(ObjectFields(objects.element(i)), i, baseDir));
  return scene;
}

Scene loadScene(const std::filesystem::path& file)
{
  return loadScene(file, {});
}

Scene loadScene(const std::filesystem::path& file, const std::vector<std::string>& overrides)
{
  const std::string label = file.string();
  std::error_code error;
  if (!std::filesystem::exists(file, error))
    throw InputError(format(label, ": cannot read scene file (no such file)"));
  std::ifstream stream(file, std::ios::binary);
  if (!stream || std::filesystem::is_directory(file, error))
    throw InputError(format(label, ": cannot read scene file"));
  std::string text{ std::istreambuf_iterator<char>(stream), std::istreambuf_iterator<char>() };

  if (!overrides.empty())
  {
    // Overrides replace values of the document before validation, so every check and message applies to
    // the result as if the file had said it.
    nlohmann::json document;
    try
    {
      document = nlohmann::json::parse(text);
    }
    catch (const nlohmann::json::exception&)
    {
      return parseScene(text, label, file.parent_path()); // reports the syntax error with its position
    }
    for (const std::string& override : overrides)
    {
      const std::size_t equals = override.find('=');
      if (equals == std::string::npos || override.empty() || override[0] != '/')
      {
        throw InputError(format("--scene-set '", override, "': expected /json/pointer=value, e.g. /lights/0/size=2"));
      }
      const std::string pointer = override.substr(0, equals);
      const std::string valueText = override.substr(equals + 1);
      nlohmann::json value;
      try
      {
        value = nlohmann::json::parse(valueText);
      }
      catch (const nlohmann::json::exception&)
      {
        value = valueText; // a bare word is a string: /lights/0/shape=disk
      }
      try
      {
        const nlohmann::json::json_pointer location(pointer);
        if (!document.contains(location.parent_pointer()))
        {
          throw InputError(format("--scene-set ", override, ": ", label, " has nothing at ", location.parent_pointer().to_string()));
        }
        document[location] = value;
      }
      catch (const nlohmann::json::exception& failure)
      {
        throw InputError(format("--scene-set ", override, ": ", failure.what()));
      }
    }
    text = document.dump();
  }
  Scene scene = parseScene(text, label, file.parent_path());
  scene.file = file;
  return scene;
}

} // namespace sl
