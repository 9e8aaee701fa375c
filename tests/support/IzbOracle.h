// The irregular z-buffer (technique `izb`, src/techniques/izb) as an oracle for hard-shadow tests: exact visibility of
// the light's centre on the GPU at a frame's own G-buffer, with the pixels it cannot decide (within float rounding of
// a triangle edge or plane, or cut short by a budget) marked. Header only (the tests' support sources are listed in
// tests/CMakeLists.txt, which this leaves alone).
#pragma once

#include "lightspace/LightView.h"
#include "support/TestSupport.h"
#include "techniques/izb/IzbTechnique.h"

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

namespace sl::test
{

struct IzbOracleImage
{
  // Per pixel: 0 or 1 where the oracle decides (a covered pixel that receives shadows and that the light can reach;
  // 1 for a covered pixel that does not receive shadows), -1 elsewhere: uncovered, unreachable, ambiguous, cut short.
  ImageF visibility;
  ImageF undecided; // 1 where izb_ambiguous or a cut-short izb_status left the pixel undecided
  int decided = 0;
  int undecidedPixels = 0;
};

// izb's normal_offset setting that puts its tested point `offsetWorld` off the surface, as the ray caster's
// pointVisibility(..., offset) does.
inline std::string izbNormalOffsetSetting(const Scene& scene, double offsetWorld)
{
  std::ostringstream text;
  text.precision(17);
  text << "normal_offset=" << offsetWorld / scene.bounds().radius();
  return text.str();
}

// Renders `izb` for `scene` at width x height (the same camera, hence the same G-buffer, as any other technique's
// frame of that size) with the tested point `offsetWorld` off the surface. An area light is taken from its centre
// (the single ray to the centre, ReferenceModel::LightCentre, which `hard` and `pcf` are held to).
inline IzbOracleImage izbOracle(const Scene& scene, int width, int height, double offsetWorld,
  const std::vector<std::string>& settings = {})
{
  std::vector<std::string> all = settings;
  all.push_back(izbNormalOffsetSetting(scene, offsetWorld));
  const FrameResult frame = renderDataset(scene, "izb", width, height, all);
  const ImageF& position = frame.find("position")->image;
  const ImageF& normal = frame.find("normal")->image;
  const ImageF& coverage = frame.find("coverage")->image;
  const ImageF& receives = frame.find("receives_shadows")->image;
  const ImageF& visibility = frame.find("visibility")->image;
  const ImageF& ambiguous = frame.find("izb_ambiguous")->image;
  const ImageF& status = frame.find("izb_status")->image;
  IzbOracleImage oracle{ ImageF(width, height, 1, -1.0f), ImageF(width, height, 1, 0.0f) };
  for (int y = 0; y < height; ++y)
  {
    for (int x = 0; x < width; ++x)
    {
      if (coverage.at(x, y) <= 0.5f)
      {
        continue;
      }
      if (receives.at(x, y) <= 0.5f)
      {
        oracle.visibility.at(x, y) = 1.0f;
        ++oracle.decided;
        continue;
      }
      const glm::dvec3 pWs(position.at(x, y, 0), position.at(x, y, 1), position.at(x, y, 2));
      const glm::dvec3 nWs(normal.at(x, y, 0), normal.at(x, y, 1), normal.at(x, y, 2));
      if (!lightCanReach(scene.lights.front(), pWs, nWs))
      {
        continue;
      }
      if (ambiguous.at(x, y) > 0.5f || std::lround(status.at(x, y)) == static_cast<long>(IzbStatus::CutShort))
      {
        oracle.undecided.at(x, y) = 1.0f;
        ++oracle.undecidedPixels;
        continue;
      }
      oracle.visibility.at(x, y) = visibility.at(x, y);
      ++oracle.decided;
    }
  }
  return oracle;
}

} // namespace sl::test
