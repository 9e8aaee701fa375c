// Writes the scene.json of the sampling-error datasets (issue 29): `deep-view`, `deep-view-behind`, `facing-tiles`
// and `wall-ring`. The committed files are this program's output; the test Datasets.GeneratedScenesAreCommitted
// regenerates them into a scratch folder and compares byte for byte. After changing a number here:
//   build/tests/generate_sampling_datasets datasets
// C++17 and nlohmann-json, no library of the project, so the files do not depend on how the scene loader reads them.
//
// deep-view: a long ground seen from eye height (the survey's §3 perspective aliasing: dp/ds ~ 1/z under a uniform
// map), posts and small buildings at geometrically growing distances (d_k = 5 * 1.5^k), so every depth range has
// shadow edges. The camera looks horizontally, so an overhead light in the x-y plane is exactly perpendicular to
// the view (the setting of the survey's Fig. 12). deep-view-behind: the same geometry with the light behind the
// viewer, 15 degrees off the view direction (Fig. 14-15: warping cannot help, partitioning must). wall-ring: a
// point light inside a ring of walls, its visible receivers all around it (§2: one map cannot cover them).
// facing-tiles: the survey's Fig. 12 as a scene, tiles from eye depth 1 to 100 each turned halfway between the eye
// and the overhead light, so that Eq. 1's projection factor is 1 and a map's error along its t axis is the
// perspective part alone.
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

namespace
{

using Json = nlohmann::ordered_json;

// Rounded to 1e-4, so that a last-bit difference in a platform's sin or cos never changes the file; whole numbers
// as integers ("0", never "0.0" or "-0").
Json num(double value)
{
  const double rounded = std::round(value * 1e4) / 1e4;
  if (rounded == std::round(rounded))
  {
    return Json(static_cast<std::int64_t>(rounded));
  }
  return Json(rounded);
}

Json str(const std::string& text)
{
  return Json(text);
}

Json vec(std::vector<double> values)
{
  Json array = Json::array();
  for (const double value : values)
  {
    array.push_back(num(value));
  }
  return array;
}

// nlohmann's two-space layout with every array of numbers on one line, as the hand-written datasets are.
std::string layout(const Json& scene)
{
  const std::string dumped = scene.dump(2);
  std::string out;
  std::size_t i = 0;
  while (i < dumped.size())
  {
    const std::size_t close = dumped[i] == '[' ? dumped.find(']', i) : std::string::npos;
    const std::string inside = close == std::string::npos ? "" : dumped.substr(i + 1, close - i - 1);
    if (close != std::string::npos && inside.find_first_of("{[\"") == std::string::npos)
    {
      std::string joined;
      for (const char c : inside)
      {
        if (c != '\n' && c != ' ')
        {
          joined += c == ',' ? std::string(", ") : std::string(1, c);
        }
      }
      out += "[" + joined + "]";
      i = close + 1;
      continue;
    }
    out += dumped[i++];
  }
  return out;
}

constexpr double kPi = 3.14159265358979323846;

Json camera(std::vector<double> position, std::vector<double> focalPoint, double viewAngleDeg)
{
  return Json::object({ { "projection", str("perspective") }, { "position", vec(std::move(position)) },
    { "focal_point", vec(std::move(focalPoint)) }, { "view_up", vec({ 0, 1, 0 }) },
    { "view_angle", num(viewAngleDeg) }, { "resolution", vec({ 512, 512 }) } });
}

Json box(std::vector<double> center, std::vector<double> size)
{
  return Json::object(
    { { "primitive", str("box") }, { "center", vec(std::move(center)) }, { "size", vec(std::move(size)) } });
}

Json ground(Json shape)
{
  shape["normal"] = vec({ 0, 1, 0 });
  shape["up"] = vec({ 0, 0, -1 });
  shape["material"] = Json::object({ { "albedo", vec({ 0.8, 0.8, 0.8 }) } });
  return shape;
}

// The deep view under a directional light travelling along `direction`. Eye at height 1.7 looking along -z,
// horizontally, with a 70-degree vertical field: its lowest ray meets the ground 2.43 ahead, and the ground
// (60 x 300, from 2 to 302 ahead) ends 124 times farther; the camera's near plane (0.99 times the scene box's
// nearest depth, 2) and far plane (1.01 times its farthest, 302) are 154 apart (src/lightspace/CameraView.cpp).
Json deepView(std::vector<double> direction)
{
  Json objects = Json::array();
  objects.push_back(ground(Json::object({ { "primitive", str("quad") }, { "center", vec({ 0, 0, -152 }) },
    { "size", vec({ 60, 300 }) } })));
  // Left of the view axis, posts of one size: their shadows thin out to below a pixel with distance. Right of it,
  // buildings that grow with distance (side 0.1 d, height 0.15 d), so that every depth keeps a shadow edge a few
  // pixels long on the screen.
  for (int k = 0; k < 10; ++k)
  {
    const double distance = 5.0 * std::pow(1.5, k);
    objects.push_back(box({ -2, 1.25, -distance }, { 0.2, 2.5, 0.2 }));
    const double side = 0.1 * distance;
    const double height = 0.15 * distance;
    objects.push_back(box({ 2.5 + 0.5 * side, 0.5 * height, -distance }, { side, height, side }));
  }
  return Json::object({ { "camera", camera({ 0, 1.7, 0 }, { 0, 1.7, -10 }, 70) },
    { "lights",
      Json::array({ Json::object(
        { { "type", str("directional") }, { "direction", vec(std::move(direction)) }, { "intensity", num(1) } }) }) },
    { "objects", std::move(objects) } });
}

// A point light at height 1 inside ten walls (radius 4, 1.5 high, covering 75 % of the circle), with three casters
// around it on a ground disk: receivers in every direction from the light, inside the ring (ground, the walls'
// inner faces) and outside it (the ground lit through the gaps).
Json wallRing()
{
  Json objects = Json::array();
  objects.push_back(ground(Json::object({ { "primitive", str("disk") }, { "center", vec({ 0, 0, 0 }) }, { "size", num(7) } })));
  const int wallCount = 10;
  const double radius = 4.0;
  const double wallLength = 2.0 * radius * std::sin(0.75 * kPi / wallCount);
  for (int i = 0; i < wallCount; ++i)
  {
    // The box's x (its thickness) turns to the radial direction (cos a, 0, -sin a) under rotate_deg [0, a, 0].
    const double angleDeg = 360.0 * (i + 0.5) / wallCount;
    const double angle = angleDeg * kPi / 180.0;
    Json wall = box({ 0, 0.75, 0 }, { 0.25, 1.5, wallLength });
    wall["transform"] = Json::object({ { "translate", vec({ radius * std::cos(angle), 0, -radius * std::sin(angle) }) },
      { "rotate_deg", vec({ 0, angleDeg, 0 }) } });
    objects.push_back(wall);
  }
  objects.push_back(Json::object(
    { { "primitive", str("sphere") }, { "center", vec({ 1.3, 0.45, 0.7 }) }, { "size", num(0.45) } }));
  objects.push_back(box({ -1.2, 0.35, -0.9 }, { 0.7, 0.7, 0.7 }));
  objects.push_back(box({ 0.3, 0.9, -1.7 }, { 0.2, 1.8, 0.2 }));
  return Json::object({ { "camera", camera({ 0, 10, 9 }, { 0, 0, 0 }, 50) },
    { "lights",
      Json::array({ Json::object(
        { { "type", str("point") }, { "center", vec({ 0, 1, 0 }) }, { "intensity", num(1) } }) }) },
    { "objects", std::move(objects) } });
}

// Fig. 12's configuration (survey §4.2): eye at the origin looking horizontally along -z, a directional light
// straight down (view ⟂ light), and kTiles square tiles from eye depth 1 to 100: one in each of kTiles bins of equal
// depth ratio over [1, 100] (`bench --depth-bins 20 --depth-range 1,100`), at the bin's geometric centre, except the
// nearest tile, whose nearest corner is at depth 1, and the farthest, whose farthest corner is at 100, so that the
// focus's z_n and z_f are the figure's (each tile's depth extent, under 1 %, stays in its bin). Each sits on the horizon
// line at its own azimuth (no tile hides or shadows another), spans the same angle seen from the eye, and faces the
// bisector of the directions to the eye and to the light: cos(alpha) = cos(beta) (Eq. 1), on the view axis's
// plane. The vertical field, 2 atan(1/16), makes one pixel span 1/(8 H) at unit distance: with a map of 8 H + 2
// texels (a margin of one on each side) a texel_ratio_t equals the survey's dp/ds, which assumes equal screen and
// map resolutions and a unit near plane.
Json facingTiles()
{
  constexpr int kTiles = 20;
  constexpr double kMaxAzimuthDeg = 12.0; // the 4:1 image spans +-14 degrees horizontally
  constexpr double kTileAngle = 0.9 * kPi / 180.0;
  Json objects = Json::array();
  const auto azimuthOf = [&](int i) { return (-kMaxAzimuthDeg + 2.0 * kMaxAzimuthDeg * i / (kTiles - 1)) * kPi / 180.0; };
  // A tile of side kTileAngle * distance reaches kappa * z_c nearer and farther than its centre's depth z_c.
  const auto kappaOf = [&](double azimuth) {
    return 0.5 * kTileAngle / std::cos(azimuth) * (std::cos(azimuth) / std::sqrt(2.0) + std::abs(std::sin(azimuth)));
  };
  const double firstDepth = 1.0 / (1.0 - kappaOf(azimuthOf(0)));
  const double lastDepth = 100.0 / (1.0 + kappaOf(azimuthOf(kTiles - 1)));
  for (int i = 0; i < kTiles; ++i)
  {
    const double azimuth = azimuthOf(i);
    const double depth = i == 0 ? firstDepth
      : i == kTiles - 1         ? lastDepth
                                : std::pow(100.0, (i + 0.5) / kTiles);
    const double distance = depth / std::cos(azimuth);
    const double s = std::sin(azimuth), c = std::cos(azimuth);
    const double r = 1.0 / std::sqrt(2.0);
    objects.push_back(Json::object({ { "primitive", str("quad") }, { "center", vec({ distance * s, 0, -distance * c }) },
      { "size", vec({ kTileAngle * distance, kTileAngle * distance }) }, { "normal", vec({ -s * r, r, c * r }) },
      { "up", vec({ s * r, r, -c * r }) },
      { "material", Json::object({ { "albedo", vec({ 0.8, 0.8, 0.8 }) } }) } }));
  }
  Json view = camera({ 0, 0, 0 }, { 0, 0, -10 }, 2.0 * std::atan(1.0 / 16.0) * 180.0 / kPi);
  view["resolution"] = vec({ 1024, 256 });
  return Json::object({ { "camera", std::move(view) },
    { "lights",
      Json::array({ Json::object(
        { { "type", str("directional") }, { "direction", vec({ 0, -1, 0 }) }, { "intensity", num(1) } }) }) },
    { "objects", std::move(objects) } });
}

} // namespace

int main(int argc, char** argv)
{
  if (argc != 2)
  {
    std::cerr << "usage: generate_sampling_datasets DATASETS_DIR (writes <dir>/<dataset>/scene.json)\n";
    return 2;
  }
  const std::filesystem::path root = argv[1];
  // Overhead, 31 degrees toward -x: perpendicular to the horizontal view, shadows across the ground.
  // Behind the viewer: 15.1 degrees from the view direction, 13.6 degrees above the horizon.
  const std::vector<std::pair<std::string, Json>> datasets = { { "deep-view", deepView({ -0.6, -1, 0 }) },
    { "deep-view-behind", deepView({ 0.1, -0.25, -1 }) }, { "facing-tiles", facingTiles() }, { "wall-ring", wallRing() } };
  for (const auto& [name, scene] : datasets)
  {
    const std::filesystem::path file = root / name / "scene.json";
    std::error_code error;
    std::filesystem::create_directories(file.parent_path(), error);
    const std::string text = layout(scene);
    std::ofstream stream(file, std::ios::binary);
    stream << text << "\n";
    stream.close();
    if (error || !stream)
    {
      std::cerr << "generate_sampling_datasets: cannot write " << file.string() << "\n";
      return 1;
    }
    std::cout << file.string() << "\n";
  }
  return 0;
}
