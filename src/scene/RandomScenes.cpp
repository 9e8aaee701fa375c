#include "scene/RandomScenes.h"

#include "core/Error.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

namespace sl
{
namespace
{

// splitmix64 (Steele, Lea & Flood 2014): one 64-bit state, the same sequence everywhere.
class Draws
{
public:
  explicit Draws(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next()
  {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double unit() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * unit(); }
  double logUniform(double lo, double hi) { return std::exp(uniform(std::log(lo), std::log(hi))); }
  int integer(int lo, int hi) { return lo + static_cast<int>(unit() * (hi - lo + 1)); } // inclusive
  bool chance(double p) { return unit() < p; }

private:
  std::uint64_t state_;
};

// Rounded to 6 significant digits so that the JSON text, and hence what a reader retypes, is the scene.
double r6(double value)
{
  std::ostringstream text;
  text.precision(6);
  text << value;
  return std::stod(text.str());
}

nlohmann::json vec(double x, double y, double z) { return nlohmann::json::array({ r6(x), r6(y), r6(z) }); }

} // namespace

RandomScene randomScene(std::uint64_t seed, int maxSide)
{
  SL_CHECK(maxSide >= 16);
  Draws draw(seed * 0x2545F4914F6CDD1Dull + 0x1234567ull);
  RandomScene result;
  std::ostringstream summary;

  // The light.
  const bool disk = draw.chance(0.2);
  const double lightSize = draw.logUniform(0.01, 3.0);
  const double lightHeight = draw.uniform(1.5, 4.0);
  const double lightX = draw.uniform(-0.4, 0.4);
  const double lightZ = draw.uniform(-0.4, 0.4);
  const bool nearLight = draw.chance(0.3);
  double topGap = nearLight ? draw.logUniform(1e-3, 0.1) : draw.uniform(0.2, 0.6 * lightHeight);
  // Aimed at the origin (tilted by up to ~20 degrees) only when small, and then the gap keeps the tilted square's
  // lower edge above the highest occluder.
  const bool aimed = !nearLight && draw.chance(0.5) && lightSize < 1.0;
  if (aimed)
  {
    const double sinTilt = std::hypot(lightX, lightZ) / std::hypot(lightX, lightHeight, lightZ);
    topGap = std::max(topGap, 0.75 * lightSize * sinTilt + 0.05);
  }
  nlohmann::json light = { { "type", "area" }, { "shape", disk ? "disk" : "square" },
    { "center", vec(lightX, lightHeight, lightZ) },
    { "normal", aimed ? vec(-lightX, -lightHeight, -lightZ) : vec(0, -1, 0) }, { "size", r6(lightSize) },
    { "intensity", 1 } };
  summary << (disk ? "disk" : "square") << " light " << r6(lightSize) << " at " << r6(lightHeight) << ", top gap "
          << r6(topGap) << ";";

  nlohmann::json objects = nlohmann::json::array();
  objects.push_back({ { "primitive", "quad" }, { "center", vec(0, 0, 0) }, { "size", { 8, 8 } },
    { "normal", vec(0, 1, 0) }, { "up", vec(0, 0, -1) }, { "material", { { "albedo", vec(0.8, 0.8, 0.8) } } },
    { "cast_shadows", false } });

  // The occluders, highest first: the first at topGap below the light, the others anywhere below it.
  const int count = draw.integer(1, 5);
  const double highest = lightHeight - topGap;
  for (int index = 0; index < count; ++index)
  {
    const double kind = draw.unit();
    const double cx = draw.uniform(-0.7, 0.7);
    const double cz = draw.uniform(-0.7, 0.7);
    const double sx = draw.uniform(0.2, 1.5);
    const double sz = draw.uniform(0.2, 1.5);
    const double heightDraw = draw.unit();
    const double tiltX = draw.uniform(-40.0, 40.0);
    const double tiltZ = draw.uniform(-40.0, 40.0);
    const double yaw = draw.uniform(0.0, 90.0);
    const double boxHeight = draw.uniform(0.1, 0.8);
    const bool contact = draw.chance(0.5);
    const bool leaves = draw.chance(0.5);
    const bool top = index == 0;
    // The first occluder of a near-light scene is a horizontal quad, so that nothing of it crosses the light's plane.
    const double k = top && nearLight ? 0.0 : kind;
    nlohmann::json object;
    if (k < 0.4)
    {
      const double y = top ? highest : 0.05 + heightDraw * (highest - 0.05);
      object = { { "primitive", "quad" }, { "center", vec(cx, y, cz) }, { "size", { r6(sx), r6(sz) } },
        { "normal", vec(0, 1, 0) }, { "up", vec(0, 0, -1) } };
      summary << " quad " << r6(sx) << "x" << r6(sz) << " at " << r6(y) << ";";
    }
    else if (k < 0.6)
    {
      // Tilted: the rotated quad's half extent in y keeps it between the ground and the top occluder's height.
      const double reach = 0.5 * std::max(sx, sz) * std::sin(40.0 * M_PI / 180.0) + 0.02;
      const double lo = 0.05 + reach;
      const double hi = std::max(lo, highest - reach);
      const double y = lo + heightDraw * (hi - lo);
      object = { { "primitive", "quad" }, { "center", vec(0, 0, 0) }, { "size", { r6(sx), r6(sz) } },
        { "normal", vec(0, 1, 0) }, { "up", vec(0, 0, -1) },
        { "transform", { { "rotate_deg", vec(tiltX, yaw, tiltZ) }, { "translate", vec(cx, y, cz) } } } };
      summary << " tilted quad " << r6(sx) << "x" << r6(sz) << " at " << r6(y) << ";";
    }
    else if (k < 0.85)
    {
      const double sy = std::min(boxHeight, std::max(0.05, highest - 0.05));
      const double bottom = contact ? 0.0 : 0.05 + heightDraw * std::max(0.0, highest - sy - 0.05);
      object = { { "primitive", "box" }, { "center", vec(0, 0, 0) }, { "size", vec(sx, sy, sz) },
        { "transform", { { "rotate_deg", vec(0, yaw, 0) }, { "translate", vec(cx, bottom + 0.5 * sy, cz) } } } };
      summary << (contact ? " box on the ground " : " box ") << r6(sx) << "x" << r6(sy) << "x" << r6(sz) << " at "
              << r6(bottom) << ";";
    }
    else
    {
      const double y = 0.05 + heightDraw * (highest - 0.05);
      object = { { "primitive", "quad" }, { "center", vec(cx, y, cz) }, { "size", { r6(sx), r6(sz) } },
        { "normal", vec(0, 1, 0) }, { "up", vec(0, 0, -1) }, { "alpha_texture", leaves ? "leaves" : "fence" } };
      summary << " perforated (" << (leaves ? "leaves" : "fence") << ") quad " << r6(sx) << "x" << r6(sz) << " at "
              << r6(y) << ";";
    }
    object["material"] = { { "albedo", vec(0.6, 0.55, 0.5) } };
    objects.push_back(object);
  }

  // The camera, and an image of 64..128 pixels a side, square one time in five.
  const double azimuth = draw.uniform(0.0, 2.0 * M_PI);
  const double distance = draw.uniform(4.5, 6.5);
  const double elevation = draw.uniform(35.0, 70.0) * M_PI / 180.0;
  const int sides[] = { 64, 80, 96, 112, 128 };
  int width = sides[draw.integer(0, 4)];
  int height = draw.chance(0.2) ? width : sides[draw.integer(0, 4)];
  const double shrink = std::min(1.0, static_cast<double>(maxSide) / std::max(width, height));
  width = std::max(8, static_cast<int>(std::lround(width * shrink)));
  height = std::max(8, static_cast<int>(std::lround(height * shrink)));
  const nlohmann::json camera = { { "projection", "perspective" },
    { "position", vec(distance * std::cos(elevation) * std::cos(azimuth), distance * std::sin(elevation),
                    distance * std::cos(elevation) * std::sin(azimuth)) },
    { "focal_point", vec(0, 0.2, 0) }, { "view_up", vec(0, 1, 0) }, { "view_angle", 40 },
    { "resolution", { width, height } } };
  summary << " " << width << "x" << height;
  result.mapSizeHalvings = draw.integer(0, 3);

  const nlohmann::json scene = { { "camera", camera }, { "lights", nlohmann::json::array({ light }) },
    { "objects", objects } };
  result.json = scene.dump(2) + "\n";
  result.summary = summary.str();
  return result;
}

} // namespace sl
