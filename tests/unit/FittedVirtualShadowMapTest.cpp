// Fitted virtual shadow maps (survey §4.3.3, lightspace/FittedVirtualShadowMap.h) on the CPU: the required resolution
// against closed forms, the quadtree on hand-computed cases (refinement, the level and tile limits), random
// configurations (every sample in exactly one leaf, each leaf meets its samples unless a limit was hit, no leaf finer
// than needed, the budget), the owner planes against the light xy, and a leaf's view giving texel_ratio = R / its
// effective resolution.
#include "core/Error.h"
#include "lightspace/CameraView.h"
#include "lightspace/FittedVirtualShadowMap.h"
#include "lightspace/PartitionViews.h"
#include "lightspace/ShadowMapMath.h"
#include "scene/Scene.h"
#include "structures/shadowmap/ShadowMapStructure.h"
#include "techniques/Registry.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>

namespace sl
{
namespace
{

FvsmPrepass prepassOf(const std::vector<glm::dvec2>& points, const std::vector<double>& required)
{
  FvsmPrepass prepass;
  prepass.width = static_cast<int>(points.size());
  prepass.height = 1;
  prepass.lightXY = points;
  prepass.requiredResolution = required;
  prepass.samples = static_cast<int>(points.size());
  return prepass;
}

FvsmSettings fvsmSettings(int tileSize, int maxLevel, int maxTiles)
{
  FvsmSettings settings;
  settings.enabled = true;
  settings.tileSize = tileSize;
  settings.maxLevel = maxLevel;
  settings.maxTiles = maxTiles;
  return settings;
}

TEST(FittedVirtualShadowMap, QuadtreeOnAHandComputedCase)
{
  // Root [0, 8]^2, 18-texel tiles with a 1-texel margin: 16 texels across a tile, 16 2^L across the root at level L.
  // A sample at (0.5, 0.5) needs 64 (level 2 exactly), one at (7.5, 7.5) needs 10 (level 0 would do). The root splits
  // (64 > 16) into its two non-empty quadrants; the lower-left one (64 > 32) into its one non-empty child at level 2,
  // [0, 2]^2, which meets 64; the upper-right quadrant [4, 8]^2 meets 10.
  const FvsmPrepass prepass = prepassOf({ { 0.5, 0.5 }, { 7.5, 7.5 } }, { 64.0, 10.0 });
  const FvsmQuadtree tree = buildFvsmQuadtree(prepass, { 0.0, 8.0, 0.0, 8.0 }, fvsmSettings(18, 3, 16), 1.0);
  ASSERT_EQ(tree.tiles.size(), 2u);
  EXPECT_EQ(tree.tiles[0].level, 1);
  EXPECT_EQ(tree.tiles[0].rect, glm::dvec4(4.0, 8.0, 4.0, 8.0));
  EXPECT_EQ(tree.tiles[0].effectiveResolution, 32.0);
  EXPECT_EQ(tree.tiles[1].level, 2);
  EXPECT_EQ(tree.tiles[1].rect, glm::dvec4(0.0, 2.0, 0.0, 2.0));
  EXPECT_EQ(tree.tiles[1].effectiveResolution, 64.0);
  EXPECT_TRUE(tree.tiles[0].met() && tree.tiles[1].met());
  EXPECT_FALSE(tree.budgetReached || tree.levelReached);
  EXPECT_EQ(tree.tileAt({ 0.5, 0.5 }), 1);
  EXPECT_EQ(tree.tileAt({ 7.5, 7.5 }), 0);
  EXPECT_EQ(tree.tileAt({ 3.0, 3.0 }), -1) << "no sample there: no map";
  EXPECT_EQ(tree.tileAt({ 8.0, 8.0 }), 0) << "the root's far edge belongs to the last cell";
  // The grid: 8 x 8 cells of 1 x 1 holding each cell's maximum requirement.
  EXPECT_EQ(tree.gridSize, 8);
  EXPECT_EQ(tree.requiredGrid[0], 64.0);
  EXPECT_EQ(tree.requiredGrid[63], 10.0);
  EXPECT_EQ(tree.sampleGrid[0] + tree.sampleGrid[63], 2);

  // The same with one tile allowed: the root alone, its 16 texels short of 64 (budget).
  const FvsmQuadtree budget = buildFvsmQuadtree(prepass, { 0.0, 8.0, 0.0, 8.0 }, fvsmSettings(18, 3, 1), 1.0);
  ASSERT_EQ(budget.tiles.size(), 1u);
  EXPECT_EQ(budget.tiles[0].level, 0);
  EXPECT_FALSE(budget.tiles[0].met());
  EXPECT_TRUE(budget.budgetReached);
  EXPECT_FALSE(budget.levelReached);
  // Two tiles allowed: the root's split fits (2 quadrants), the level-1 quadrant's split too (1 child): as unlimited.
  const FvsmQuadtree two = buildFvsmQuadtree(prepass, { 0.0, 8.0, 0.0, 8.0 }, fvsmSettings(18, 3, 2), 1.0);
  EXPECT_EQ(two.tiles.size(), 2u);
  EXPECT_FALSE(two.budgetReached);
  // At most level 1: the lower-left quadrant stops at 32 texels (level limit).
  const FvsmQuadtree shallow = buildFvsmQuadtree(prepass, { 0.0, 8.0, 0.0, 8.0 }, fvsmSettings(18, 1, 16), 1.0);
  ASSERT_EQ(shallow.tiles.size(), 2u);
  EXPECT_EQ(shallow.tiles[0].rect, glm::dvec4(0.0, 4.0, 0.0, 4.0));
  EXPECT_FALSE(shallow.tiles[0].met());
  EXPECT_TRUE(shallow.levelReached);
  // Nothing needs more than the root: one tile.
  const FvsmQuadtree coarse = buildFvsmQuadtree(
    prepassOf({ { 0.5, 0.5 }, { 7.5, 7.5 } }, { 16.0, 3.0 }), { 0.0, 8.0, 0.0, 8.0 }, fvsmSettings(18, 3, 16), 1.0);
  ASSERT_EQ(coarse.tiles.size(), 1u);
  EXPECT_EQ(coarse.tiles[0].rect, glm::dvec4(0.0, 8.0, 0.0, 8.0));
}

TEST(FittedVirtualShadowMap, RandomConfigurationsPartitionTheSamplesAndMeetThemUnlessALimitIsHit)
{
  std::mt19937 generator(29);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int budgetCases = 0, levelCases = 0, refinedCases = 0;
  for (int trial = 0; trial < 300; ++trial)
  {
    const glm::dvec4 root(-10.0 * unit(generator), 10.0 * unit(generator) + 0.1, -3.0 * unit(generator),
      20.0 * unit(generator) + 0.1);
    const int margin = static_cast<int>(3 * unit(generator)) + 1;
    const FvsmSettings settings = fvsmSettings(8 + static_cast<int>(56 * unit(generator)), static_cast<int>(6 * unit(generator)),
      1 + static_cast<int>(80 * unit(generator)));
    // Clustered samples (a few hot spots needing much more than the rest), some on the root's edges.
    std::vector<glm::dvec2> points;
    std::vector<double> required;
    const int count = 20 + static_cast<int>(400 * unit(generator));
    const glm::dvec2 hot(unit(generator), unit(generator));
    for (int i = 0; i < count; ++i)
    {
      glm::dvec2 f(unit(generator), unit(generator));
      const bool nearHot = unit(generator) < 0.3;
      if (nearHot)
      {
        f = glm::clamp(hot + 0.05 * (f - 0.5), 0.0, 1.0);
      }
      if (unit(generator) < 0.05)
      {
        f[i % 2] = static_cast<double>(i % 4 < 2); // on an edge of the root
      }
      // f = 1 on the far edge exactly (lo + 1 (hi - lo) may round past hi).
      points.push_back({ f.x == 1.0 ? root.y : root.x + f.x * (root.y - root.x),
        f.y == 1.0 ? root.w : root.z + f.y * (root.w - root.z) });
      required.push_back(unit(generator) < 0.05 ? 0.0 : std::exp2((nearHot ? 11.0 : 7.0) * unit(generator)));
    }
    const FvsmQuadtree tree = buildFvsmQuadtree(prepassOf(points, required), root, settings, margin);
    const std::string label = format("trial ", trial, " tile ", settings.tileSize, " max level ", settings.maxLevel,
      " max tiles ", settings.maxTiles, " margin ", margin);
    ASSERT_FALSE(tree.tiles.empty()) << label;
    EXPECT_LE(static_cast<int>(tree.tiles.size()), settings.maxTiles) << label;
    budgetCases += tree.budgetReached ? 1 : 0;
    levelCases += tree.levelReached ? 1 : 0;
    refinedCases += tree.tiles.size() > 1 ? 1 : 0;
    std::vector<int> samplesPerTile(tree.tiles.size(), 0);
    for (std::size_t i = 0; i < points.size(); ++i)
    {
      const int tile = tree.tileAt(points[i]);
      ASSERT_GE(tile, 0) << label << " sample " << i;
      ++samplesPerTile[static_cast<std::size_t>(tile)];
      // Exactly one leaf's rectangle holds it (closed rectangles: a point on a shared edge is on both, so strictly
      // inside one and at most on the edge of others).
      int strictlyInside = 0, touching = 0;
      for (std::size_t t = 0; t < tree.tiles.size(); ++t)
      {
        const glm::dvec4& r = tree.tiles[t].rect;
        const glm::dvec2& p = points[i];
        const bool closed = p.x >= r.x && p.x <= r.y && p.y >= r.z && p.y <= r.w;
        const bool open = p.x > r.x && p.x < r.y && p.y > r.z && p.y < r.w;
        strictlyInside += open ? 1 : 0;
        touching += closed ? 1 : 0;
        if (static_cast<int>(t) == tile)
        {
          EXPECT_TRUE(closed) << label << " sample " << i << " outside its own leaf";
        }
      }
      EXPECT_LE(strictlyInside, 1) << label;
      EXPECT_GE(touching, 1) << label;
      const FvsmTile& leaf = tree.tiles[static_cast<std::size_t>(tile)];
      if (!resolutionMet(leaf.effectiveResolution, required[i]))
      {
        // Unmet only where a limit stopped the refinement.
        EXPECT_TRUE(leaf.level == settings.maxLevel || tree.budgetReached) << label << " sample " << i;
        EXPECT_FALSE(leaf.met()) << label;
      }
    }
    for (std::size_t t = 0; t < tree.tiles.size(); ++t)
    {
      const FvsmTile& leaf = tree.tiles[t];
      EXPECT_EQ(samplesPerTile[t], leaf.samples) << label << " tile " << t;
      EXPECT_GT(leaf.samples, 0) << label << " an empty leaf has no map";
      EXPECT_NEAR(leaf.rect.y - leaf.rect.x, (root.y - root.x) / (1 << leaf.level), 1e-12 * (root.y - root.x)) << label;
      EXPECT_EQ(leaf.effectiveResolution, (settings.tileSize - 2.0 * margin) * (1 << leaf.level)) << label;
      // No leaf finer than needed: its parent's samples needed more than the parent's resolution.
      if (leaf.level > 0)
      {
        const double parentResolution = (settings.tileSize - 2.0 * margin) * (1 << (leaf.level - 1));
        double parentRequired = 0.0;
        const int span = 1 << (settings.maxLevel - leaf.level + 1);
        for (std::size_t i = 0; i < points.size(); ++i)
        {
          const glm::ivec2 cell = tree.cellOf(points[i]);
          if (cell.x / span == leaf.cell.x / 2 && cell.y / span == leaf.cell.y / 2)
          {
            parentRequired = std::max(parentRequired, required[i]);
          }
        }
        EXPECT_FALSE(resolutionMet(parentResolution, parentRequired)) << label << " tile " << t;
      }
      // Leaves do not overlap.
      for (std::size_t u = t + 1; u < tree.tiles.size(); ++u)
      {
        const glm::dvec4& a = leaf.rect;
        const glm::dvec4& b = tree.tiles[u].rect;
        const bool overlap = a.x < b.y && b.x < a.y && a.z < b.w && b.z < a.w;
        EXPECT_FALSE(overlap) << label << " tiles " << t << ", " << u;
      }
    }
  }
  std::cout << "[ measured ] 300 random quadtrees: " << refinedCases << " refined, " << budgetCases
            << " stopped by the tile budget, " << levelCases << " by the level limit\n";
  EXPECT_GT(budgetCases, 20);
  EXPECT_GT(levelCases, 20);
  EXPECT_GT(refinedCases, 150);
}

TEST(FittedVirtualShadowMap, OwnerPlanesHoldExactlyTheTilesLightXY)
{
  std::mt19937 generator(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (const LightProjection projection : { LightProjection::Orthographic, LightProjection::Perspective })
  {
    LightView view;
    view.projection = projection;
    view.viewFromWorld = glm::lookAt(glm::dvec3(1.0, 9.0, 2.0), glm::dvec3(0.5, 0.0, -1.0), glm::dvec3(0.0, 0.0, -1.0));
    const glm::dvec4 rect = projection == LightProjection::Perspective ? glm::dvec4(-0.3, 0.1, 0.05, 0.4)
                                                                       : glm::dvec4(-2.0, 1.0, 0.5, 3.0);
    const std::vector<glm::dvec4> planes = tileOwnerPlanes(view, rect);
    ASSERT_EQ(planes.size(), 4u);
    int inside = 0;
    for (int i = 0; i < 20000; ++i)
    {
      const glm::dvec3 pWs(4.0 * unit(generator), 4.0 * unit(generator), 4.0 * unit(generator));
      const glm::dvec2 xy = lightXYOf(view, pWs);
      const bool inRect = xy.x >= rect.x && xy.x <= rect.y && xy.y >= rect.z && xy.y <= rect.w;
      double smallest = 1e300;
      for (const glm::dvec4& plane : planes)
      {
        smallest = std::min(smallest, glm::dot(plane, glm::dvec4(pWs, 1.0)));
      }
      if (std::abs(smallest) < 1e-9)
      {
        continue;
      }
      EXPECT_EQ(smallest > 0.0, inRect) << i;
      inside += inRect ? 1 : 0;
    }
    EXPECT_GT(inside, 500);
  }
}

Bounds fvsmGroundBounds()
{
  Bounds bounds;
  bounds.extend({ -50.0, -0.5, -100.0 });
  bounds.extend({ 50.0, 5.0, 100.0 });
  return bounds;
}

TEST(FittedVirtualShadowMap, RequiredResolutionIsOneTexelPerPixelAndALeafsViewMeetsItExactly)
{
  // Orthographic camera straight down over the ground (0.04 world units per pixel) and an orthographic light tilted
  // by theta toward +z, root rectangle [-1, 1]^2: a t-texel of size T lies T / cos(theta) long on the ground, so one
  // texel per pixel needs T <= 0.04 cos(theta): R = 2 / (0.04 cos(theta)) = 50 / cos(theta) texels across the root,
  // whatever the root map's own resolution. A leaf's view then has texel_ratio = R / ((tile - 2 margin) 2^level).
  Camera camera;
  camera.projection = Projection::Orthographic;
  camera.position = { 0.0, 5.0, 0.0 };
  camera.focalPoint = { 0.0, 0.0, 0.0 };
  camera.viewUp = { 0.0, 0.0, -1.0 };
  camera.parallelScale = 1.0;
  const CameraView cameraView = makeCameraView(camera, fvsmGroundBounds(), { 50, 50 });
  for (const double thetaDeg : { 0.0, 30.0, 70.0 })
  {
    const double theta = glm::radians(thetaDeg);
    const glm::dvec3 towardLight(0.0, std::cos(theta), std::sin(theta));
    Light light;
    light.type = LightType::Directional;
    light.direction = -towardLight;
    const int tileSize = 34; // 32 texels inside a 1-texel margin
    LightView root;
    root.projection = LightProjection::Orthographic;
    root.viewFromWorld = glm::lookAt(50.0 * towardLight, glm::dvec3(0.0), glm::dvec3(0.0, 0.0, -1.0));
    root.window = { -1.0 * 34.0 / 32.0, 1.0 * 34.0 / 32.0, -1.0 * 34.0 / 32.0, 1.0 * 34.0 / 32.0 };
    root.nearDepth = 1.0;
    root.farDepth = 100.0;
    root.resolution = tileSize;
    root.clipFromView = glm::ortho(root.window.x, root.window.y, root.window.z, root.window.w, 1.0, 100.0);
    root.clipFromWorld = root.clipFromView * root.viewFromWorld;
    const glm::dvec4 rootRect = receiverRectOf(root.window, tileSize, 1.0);
    EXPECT_NEAR(rootRect.x, -1.0, 1e-12);
    EXPECT_NEAR(rootRect.w, 1.0, 1e-12);
    ImageF position(50, 50, 4), normal(50, 50, 4);
    for (int y = 0; y < 50; ++y)
    {
      for (int x = 0; x < 50; ++x)
      {
        const glm::dvec3 pWs = unprojectPixel(cameraView, x + 0.5, y + 0.5, -1.0) * glm::dvec3(1.0, 0.0, 1.0);
        position.at(x, y, 0) = static_cast<float>(pWs.x);
        position.at(x, y, 2) = static_cast<float>(pWs.z);
        position.at(x, y, 3) = (x + y) % 7 == 0 ? 0.0f : 1.0f; // some pixels uncovered
        normal.at(x, y, 1) = 1.0f;
        normal.at(x, y, 3) = 1.0f;
      }
    }
    const FvsmPrepass prepass = requiredResolutions(cameraView, light, root, rootRect, position, normal);
    int samples = 0;
    double smallest = 1e300, largest = 0.0;
    for (int y = 0; y < 50; ++y)
    {
      for (int x = 0; x < 50; ++x)
      {
        const double required = prepass.requiredResolution[static_cast<std::size_t>(y) * 50 + x];
        if ((x + y) % 7 == 0)
        {
          EXPECT_EQ(required, -1.0);
          continue;
        }
        ++samples;
        smallest = std::min(smallest, required);
        largest = std::max(largest, required);
      }
    }
    EXPECT_EQ(prepass.samples, samples);
    std::cout << "[ measured ] theta " << thetaDeg << ": R in [" << smallest << ", " << largest << "], closed form "
              << 50.0 / std::cos(theta) << "\n";
    EXPECT_NEAR(smallest, 50.0 / std::cos(theta), 1e-5 * 50.0 / std::cos(theta)) << thetaDeg;
    EXPECT_NEAR(largest, 50.0 / std::cos(theta), 1e-5 * 50.0 / std::cos(theta)) << thetaDeg;

    // 34-texel tiles (32 inside): the root's 32 < R splits to level 1 (64 >= 57.7) at 0 and 30 deg, level 2 at 70 deg
    // (50 / cos 70 = 146 > 128: the level limit 2 flags it).
    const FvsmQuadtree tree = buildFvsmQuadtree(prepass, rootRect, fvsmSettings(tileSize, 2, 64), 1.0);
    const int expectedLevel = thetaDeg < 60.0 ? 1 : 2;
    for (const FvsmTile& tile : tree.tiles)
    {
      EXPECT_EQ(tile.level, expectedLevel) << thetaDeg;
      EXPECT_EQ(tile.met(), thetaDeg < 60.0) << thetaDeg;
      const LightView leaf = tileView(root, tile.rect, tileSize, 1.0);
      const glm::dvec3 centre = glm::dvec3(glm::inverse(root.viewFromWorld) *
        glm::dvec4(0.5 * (tile.rect.x + tile.rect.y), 0.5 * (tile.rect.z + tile.rect.w), -50.0, 1.0));
      // The ground point under the tile's centre, along the light.
      const glm::dvec3 ground = centre - towardLight * (centre.y / towardLight.y);
      const glm::dvec2 pixel = glm::dvec2(cameraView.resolution) * 0.5 + glm::dvec2(ground.x, -ground.z) / 0.04;
      const SamplingError error = samplingError(cameraView, leaf, pixel.x, pixel.y, ground, { 0.0, 1.0, 0.0 });
      EXPECT_NEAR(std::max(error.texelRatioS, error.texelRatioT), 50.0 / std::cos(theta) / tile.effectiveResolution,
        1e-6) << thetaDeg;
    }
    EXPECT_EQ(tree.levelReached, thetaDeg > 60.0);
  }
}

TEST(FittedVirtualShadowMap, OnlyHardAndPcfListTheParametersAndTheSettingsReadThem)
{
  // As cascades: the tile loop picks one map per pixel; techniques reading a structure built from one map must not
  // list fvsm.
  int listing = 0;
  for (const TechniqueDescriptor& technique : techniqueRegistry())
  {
    const bool lists = technique.findParameter("fvsm") != nullptr;
    for (const char* name : { "fvsm_tile_size", "fvsm_max_level", "fvsm_max_tiles" })
    {
      EXPECT_EQ(lists, technique.findParameter(name) != nullptr) << technique.name << " " << name;
    }
    EXPECT_EQ(lists, technique.name == "hard" || technique.name == "pcf") << technique.name;
    listing += lists ? 1 : 0;
    if (technique.needs(shadowMapStructure()))
    {
      EXPECT_FALSE(shadowMapSettings(technique, technique.defaultParameters()).fvsm.active()) << technique.name;
    }
  }
  EXPECT_EQ(listing, 2);
  ParameterValues values = findTechnique("pcf").defaultParameters();
  values.set("fvsm=on");
  values.set("fvsm_tile_size=128");
  values.set("fvsm_max_level=4");
  values.set("fvsm_max_tiles=20");
  const FvsmSettings settings = shadowMapSettings(findTechnique("pcf"), values).fvsm;
  EXPECT_TRUE(settings.active());
  EXPECT_EQ(settings.tileSize, 128);
  EXPECT_EQ(settings.maxLevel, 4);
  EXPECT_EQ(settings.maxTiles, 20);
  // pcf's widest kernel leaves no texel of a 16-texel tile: one line naming the key.
  values.set("fvsm_tile_size=16");
  values.set("kernel_texels=31");
  try
  {
    shadowMapSettings(findTechnique("pcf"), values);
    FAIL() << "a tile narrower than the filter's margins was accepted";
  }
  catch (const InputError& error)
  {
    EXPECT_NE(std::string(error.what()).find("--set fvsm_tile_size=16"), std::string::npos) << error.what();
  }
}

TEST(FittedVirtualShadowMap, ATileSetIsAPartitionKindSelectedByTheTileHoldingThePoint)
{
  // The hand-computed tree (QuadtreeOnAHandComputedCase) under an orthographic light straight down (light x/y = world
  // x, -z): selectView picks the tile holding the point, 0 where no tile does; views are named _t<k> and by level.
  auto fvsm = std::make_shared<FittedVirtualShadowMap>();
  fvsm->rootView.projection = LightProjection::Orthographic;
  fvsm->rootView.viewFromWorld =
    glm::lookAt(glm::dvec3(0.0, 10.0, 0.0), glm::dvec3(0.0, 0.0, 0.0), glm::dvec3(0.0, 0.0, -1.0));
  fvsm->quadtree = buildFvsmQuadtree(
    prepassOf({ { 0.5, 0.5 }, { 7.5, 7.5 } }, { 64.0, 10.0 }), { 0.0, 8.0, 0.0, 8.0 }, fvsmSettings(18, 3, 16), 1.0);
  PartitionSet tiles;
  tiles.kind = PartitionKind::FvsmTiles;
  tiles.fvsm = fvsm;
  for (const FvsmTile& tile : fvsm->quadtree.tiles)
  {
    tiles.views.push_back(tileView(fvsm->rootView, tile.rect, 18, 1.0));
    tiles.ownerPlanes.push_back(tileOwnerPlanes(fvsm->rootView, tile.rect));
  }
  const CameraView camera;
  EXPECT_EQ(lightXYOf(fvsm->rootView, { 0.5, 0.0, -0.5 }), glm::dvec2(0.5, 0.5));
  EXPECT_EQ(selectView(tiles, camera, { 0.5, 0.0, -0.5 }).primary, 1);
  EXPECT_EQ(selectView(tiles, camera, { 7.5, 3.0, -7.5 }).primary, 0);
  EXPECT_EQ(selectView(tiles, camera, { 3.0, 0.0, -3.0 }).primary, 0) << "no tile: view 0";
  EXPECT_TRUE(ownerRegionHolds(tiles.ownerPlanes[1], { 0.5, 0.0, -0.5 }));
  EXPECT_FALSE(ownerRegionHolds(tiles.ownerPlanes[0], { 0.5, 0.0, -0.5 }));
  EXPECT_EQ(std::string(partitionKindName(tiles.kind)), "fvsm_tiles");
  EXPECT_EQ(partitionViewSuffix(tiles, 1), "_t1");
  EXPECT_EQ(partitionViewLabel(tiles, 1), "tile 1 (level 2)");
  // A tile's view covers its rectangle plus one texel of margin each side: 16 of its 18 texels.
  EXPECT_NEAR(tiles.views[1].window.y - tiles.views[1].window.x, 2.0 * 18.0 / 16.0, 1e-12);
}

TEST(FittedVirtualShadowMap, RefusesCascadesAndWarps)
{
  FvsmSettings on = fvsmSettings(256, 5, 64);
  EXPECT_NO_THROW(requireFvsmCombination(on, 1, false));
  EXPECT_THROW(requireFvsmCombination(on, 4, false), InputError);
  EXPECT_THROW(requireFvsmCombination(on, 1, true), InputError);
  on.enabled = false;
  EXPECT_NO_THROW(requireFvsmCombination(on, 4, true));
}

} // namespace
} // namespace sl
