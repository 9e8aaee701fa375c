// The differential test's scene generator (scene/RandomScenes.h): deterministic per seed, every scene valid, and the
// configuration space issue 27 lists reached over a few hundred seeds.
#include "scene/RandomScenes.h"
#include "scene/Scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

namespace sl
{
namespace
{

TEST(RandomScenes, ASeedGivesOneSceneAndSeedsDiffer)
{
  EXPECT_EQ(randomScene(7).json, randomScene(7).json);
  EXPECT_NE(randomScene(7).json, randomScene(8).json);
  EXPECT_EQ(randomScene(7).mapSizeHalvings, randomScene(7).mapSizeHalvings);
}

TEST(RandomScenes, SeedsCoverTheConfigurationSpace)
{
  double smallestLight = 1e9;
  double largestLight = 0.0;
  double smallestGap = 1e9;
  std::set<std::size_t> occluderCounts;
  std::set<int> halvings;
  int disks = 0;
  int contact = 0;
  int perforated = 0;
  int tilted = 0;
  int nonSquare = 0;
  for (std::uint64_t seed = 1; seed <= 300; ++seed)
  {
    const RandomScene random = randomScene(seed, 128);
    const Scene scene = parseScene(random.json, "seed " + std::to_string(seed), ".");
    ASSERT_EQ(scene.lights.size(), 1u);
    const Light& light = scene.lights.front();
    smallestLight = std::min(smallestLight, light.size);
    largestLight = std::max(largestLight, light.size);
    disks += light.shape == LightShape::Disk ? 1 : 0;
    occluderCounts.insert(scene.objects.size() - 1);
    halvings.insert(random.mapSizeHalvings);
    double highest = 0.0;
    for (std::size_t index = 1; index < scene.objects.size(); ++index)
    {
      for (const glm::vec3& p : scene.objects[index].mesh.positions)
      {
        highest = std::max(highest, static_cast<double>(p.y));
        // Nothing pokes through the ground or the light's plane (nearly horizontal when it is close).
        ASSERT_GE(p.y, -1e-6) << "seed " << seed;
        ASSERT_LT(p.y, light.center.y) << "seed " << seed;
      }
      perforated += scene.objects[index].hasAlphaTexture ? 1 : 0;
    }
    smallestGap = std::min(smallestGap, light.center.y - highest);
    contact += random.summary.find("box on the ground") != std::string::npos ? 1 : 0;
    tilted += random.summary.find("tilted quad") != std::string::npos ? 1 : 0;
    nonSquare += scene.camera.resolution.x != scene.camera.resolution.y ? 1 : 0;
    EXPECT_LE(std::max(scene.camera.resolution.x, scene.camera.resolution.y), 128);
  }
  std::cout << "[ measured ] light sizes " << smallestLight << " .. " << largestLight << ", smallest gap " << smallestGap
            << ", disks " << disks << ", contact " << contact << ", perforated " << perforated << ", tilted " << tilted
            << ", non-square " << nonSquare << " of 300\n";
  EXPECT_LT(smallestLight, 0.02);
  EXPECT_GT(largestLight, 2.5);
  EXPECT_LT(smallestGap, 2e-3);
  EXPECT_EQ(occluderCounts, (std::set<std::size_t>{ 1, 2, 3, 4, 5 }));
  EXPECT_EQ(halvings, (std::set<int>{ 0, 1, 2, 3 }));
  EXPECT_GT(disks, 0);
  EXPECT_GT(contact, 0);
  EXPECT_GT(perforated, 0);
  EXPECT_GT(tilted, 0);
  EXPECT_GT(nonSquare, 150);
}

TEST(RandomScenes, MaxSideScalesTheImageDown)
{
  for (std::uint64_t seed = 1; seed <= 20; ++seed)
  {
    const Scene scene = parseScene(randomScene(seed, 64).json, "seed", ".");
    EXPECT_LE(std::max(scene.camera.resolution.x, scene.camera.resolution.y), 64);
  }
}

} // namespace
} // namespace sl
