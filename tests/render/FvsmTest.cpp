// Fitted virtual shadow maps (survey §4.3.3, lightspace/FittedVirtualShadowMap.h) end to end on llvmpipe:
//   - the GPU's per-pixel tile (buffer `fvsm_tile`) against the CPU twin (the quadtree's tile at the pixel's light xy);
//   - after the refinement every pixel's texel_ratio_s/_t is at most one pixel per texel, except the pixels flagged
//     in `fvsm_unmet` (level or tile budget reached), and a uniform map of one tile's size is far above that;
//   - on deep-view, fewer pixels misclassified against the exact single ray than one uniform map of the same total
//     texels;
//   - hard and pcf visibility against their CPU twins run on each pixel's tile's map;
//   - the export (tile buffers, light-space grids, per-tile maps) and the one-line refusal of fvsm with cascades.
#include "support/RayCaster.h"
#include "support/TestSupport.h"
#include "core/Error.h"
#include "lightspace/Cascades.h"
#include "lightspace/FittedVirtualShadowMap.h"
#include "scene/Scene.h"
#include "techniques/ProbeSupport.h"
#include "techniques/hard/HardTechnique.h"
#include "techniques/pcf/PcfTechnique.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

namespace sl
{
namespace
{

// Whether a float evaluation of the pixel's grid cell may differ from the double twin's: its light xy within 1e-5 of
// the root rectangle's extent from an interior cell edge.
bool cellAmbiguous(const FittedVirtualShadowMap& fvsm, const glm::dvec3& pWs)
{
  const FvsmQuadtree& tree = fvsm.quadtree;
  const glm::dvec2 xy = lightXYOf(fvsm.rootView, pWs);
  const glm::dvec2 origin(tree.rootRect.x, tree.rootRect.z);
  const glm::dvec2 extent(tree.rootRect.y - tree.rootRect.x, tree.rootRect.w - tree.rootRect.z);
  for (int axis = 0; axis < 2; ++axis)
  {
    // The root's own edges are not a decision (the cell index is clamped there): a receiver face seen edge-on by the
    // light often sets them, all of its pixels on one line of light xy.
    const double scaled = (xy[axis] - origin[axis]) / extent[axis] * tree.gridSize;
    const double nearest = std::round(scaled);
    if (nearest > 0.0 && nearest < tree.gridSize && std::abs(scaled - nearest) < 1e-5 * tree.gridSize)
    {
      return true;
    }
  }
  return false;
}

TEST(FvsmGpu, TileSelectionMatchesTheCpuTwinPixelByPixel)
{
  // The two deep views (directional lights: tiles in world units) and a spot light over stacked occluders (a
  // perspective light: tiles in tangents, light x/y = x / depth).
  for (const std::string dataset : { "deep-view", "deep-view-behind", "spot" })
  {
    const Scene scene = dataset == "spot"
      ? test::stackedOccludersUnder(R"({ "type": "spot", "center": [0, 4, 0], "normal": [0, -1, 0], "cone_angle_deg": 50 })")
      : test::loadDataset(dataset);
    const std::vector<std::string> settings = { "fvsm=on", "fvsm_tile_size=64", "fvsm_max_level=5", "fvsm_max_tiles=48" };
    const FrameResult frame = test::renderDataset(scene, "hard", 96, 64, settings);
    EXPECT_EQ(frame.partitions->views.front().projection,
      dataset == "spot" ? LightProjection::Perspective : LightProjection::Orthographic);
    ASSERT_TRUE(frame.partitions.has_value() && frame.partitions->fvsm);
    const FittedVirtualShadowMap& fvsm = *frame.partitions->fvsm;
    const ImageF& tile = frame.find("fvsm_tile")->image;
    const ImageF& position = frame.find("position")->image;
    const ImageF& coverage = frame.find("coverage")->image;
    int covered = 0, ambiguous = 0, mismatched = 0;
    std::vector<int> perTile(fvsm.quadtree.tiles.size(), 0);
    std::string firstMismatch;
    for (int y = 0; y < tile.height; ++y)
    {
      for (int x = 0; x < tile.width; ++x)
      {
        if (coverage.at(x, y) <= 0.5f)
        {
          EXPECT_EQ(tile.at(x, y), 0.0f);
          continue;
        }
        ++covered;
        const glm::dvec3 pWs = test::vec3At(position, x, y);
        const int gpu = static_cast<int>(tile.at(x, y));
        const int cpu = selectView(*frame.partitions, frame.camera, pWs).primary;
        if (fvsm.tileOfPixel(x, y) >= 0)
        {
          ++perTile.at(static_cast<std::size_t>(gpu));
        }
        if (cellAmbiguous(fvsm, pWs))
        {
          ++ambiguous;
          continue;
        }
        if (gpu != cpu && mismatched++ == 0)
        {
          firstMismatch = format("pixel ", x, ",", y, " gpu ", gpu, " cpu ", cpu);
        }
      }
    }
    std::cout << "[ measured ] " << test::caseLabel(dataset, settings) << ": " << fvsm.quadtree.tiles.size()
              << " tiles, " << covered << " covered pixels, " << ambiguous << " ambiguous, " << mismatched
              << " GPU != CPU\n";
    EXPECT_GT(covered, 3000) << dataset;
    EXPECT_EQ(mismatched, 0) << dataset << ": " << firstMismatch;
    EXPECT_LT(ambiguous, covered / 100 + 1) << dataset;
    EXPECT_GT(fvsm.quadtree.tiles.size(), 1u) << dataset << ": the view refines";
    // The pre-pass's samples fall in the tiles the GPU selects for them (up to the ambiguous pixels).
    for (std::size_t k = 0; k < perTile.size(); ++k)
    {
      EXPECT_LE(std::abs(perTile[k] - fvsm.quadtree.tiles[k].samples), ambiguous) << dataset << " tile " << k;
    }
  }
}

TEST(FvsmGpu, EveryPixelGetsOneTexelPerPixelUnlessFlagged)
{
  // One texel per pixel along each map axis (texel_ratio_s, _t <= 1 pixel per texel) wherever fvsm_unmet is 0; the
  // flagged pixels are the ones the limits left short (fvsm_unmet, counted in stats as unmet_pixels). A uniform map
  // of one tile's size is far from it on the same view.
  for (const std::string dataset : { "deep-view", "deep-view-behind" })
  {
    const Scene scene = test::loadDataset(dataset);
    for (const std::vector<std::string>& settings : std::vector<std::vector<std::string>>{
           { "fvsm=on", "fvsm_tile_size=64", "fvsm_max_level=6", "fvsm_max_tiles=256" },
           { "fvsm=on", "fvsm_tile_size=64", "fvsm_max_level=3", "fvsm_max_tiles=12" } })
    {
      const FrameResult frame = test::renderDataset(scene, "hard", 96, 64, settings);
      ASSERT_TRUE(frame.partitions && frame.partitions->fvsm);
      const FittedVirtualShadowMap& fvsm = *frame.partitions->fvsm;
      const ImageF& ratioS = frame.find("texel_ratio_s")->image;
      const ImageF& ratioT = frame.find("texel_ratio_t")->image;
      const ImageF& unmet = frame.find("fvsm_unmet")->image;
      const ImageF& required = frame.find("fvsm_required_resolution")->image;
      const ImageF& tile = frame.find("fvsm_tile")->image;
      int queried = 0, flagged = 0, over = 0;
      double worstMet = 0.0, worstFlagged = 0.0;
      for (int y = 0; y < ratioS.height; ++y)
      {
        for (int x = 0; x < ratioS.width; ++x)
        {
          if (fvsm.tileOfPixel(x, y) < 0)
          {
            EXPECT_EQ(unmet.at(x, y), 0.0f);
            continue;
          }
          ++queried;
          const double ratio = std::max(ratioS.at(x, y), ratioT.at(x, y));
          const FvsmTile& own = fvsm.quadtree.tiles.at(static_cast<std::size_t>(tile.at(x, y)));
          if (unmet.at(x, y) > 0.5f)
          {
            ++flagged;
            worstFlagged = std::max(worstFlagged, ratio);
            EXPECT_GT(required.at(x, y), own.effectiveResolution * (1.0 - 1e-6));
            continue;
          }
          worstMet = std::max(worstMet, ratio);
          over += ratio > 1.0 + 1e-4 ? 1 : 0;
          // Linear in the texel size: the tile's ratio is the requirement over its resolution.
          EXPECT_NEAR(ratio, required.at(x, y) / own.effectiveResolution, 1e-4 * std::max(1.0, ratio))
            << dataset << " pixel " << x << "," << y;
        }
      }
      std::cout << "[ measured ] " << test::caseLabel(dataset, settings) << ": " << fvsm.quadtree.tiles.size()
                << " tiles (budget reached " << fvsm.quadtree.budgetReached << ", level reached "
                << fvsm.quadtree.levelReached << "), " << queried << " queried pixels, " << flagged
                << " flagged; largest texel ratio " << worstMet << " unflagged, " << worstFlagged << " flagged\n";
      EXPECT_GT(queried, 2500) << dataset;
      EXPECT_EQ(over, 0) << dataset;
      EXPECT_LE(worstMet, 1.0 + 1e-4) << dataset;
      EXPECT_EQ(flagged, fvsm.unmetPixels()) << dataset << ": the GPU's tiles flag what the CPU twin's do";
      if (settings[3] == "fvsm_max_tiles=12")
      {
        EXPECT_TRUE(fvsm.quadtree.budgetReached || fvsm.quadtree.levelReached) << dataset;
        EXPECT_GT(flagged, 0) << dataset << ": the limits leave some pixels short";
      }
    }
    const FrameResult uniform = test::renderDataset(scene, "hard", 96, 64, { "shadow_map_size=64" });
    const ImageF& s = uniform.find("texel_ratio_s")->image;
    const ImageF& t = uniform.find("texel_ratio_t")->image;
    int overOne = 0;
    for (std::size_t i = 0; i < s.data.size(); ++i)
    {
      overOne += std::max(s.data[i], t.data[i]) > 1.0f ? 1 : 0;
    }
    std::cout << "[ measured ] " << dataset << " one 64^2 map: " << overOne << " pixels above one pixel per texel\n";
    EXPECT_GT(overOne, 1000) << dataset;
  }
}

TEST(FvsmGpu, VisibilityMatchesTheCpuTwinsOnEachPixelsTile)
{
  // hard and pcf read one map per pixel, the tile's: their CPU twins (hardReference, pcfReference) run on the map of
  // the tile the CPU twin selects give the GPU's visibility on every pixel whose decision is not within rounding.
  const Scene scene = test::loadDataset("deep-view-behind");
  for (const std::string technique : { "hard", "pcf" })
  {
    const FrameResult frame = test::renderDataset(scene, technique, 80, 64,
      { "fvsm=on", "fvsm_tile_size=48", "fvsm_max_level=4", "fvsm_max_tiles=24" });
    ASSERT_TRUE(frame.partitions && frame.partitions->fvsm);
    const std::vector<ShadowMapInputs> inputs = viewInputsOf(frame, scene);
    const ImageF& visibility = frame.find("visibility")->image;
    int evaluated = 0, ambiguous = 0, mismatched = 0;
    double maxDifference = 0.0;
    std::string firstMismatch;
    for (int y = 0; y < visibility.height; ++y)
    {
      for (int x = 0; x < visibility.width; ++x)
      {
        const ReferenceSample cpu = partitionedReference(frame, inputs, x, y,
          [&](const ShadowMapInputs& in, int px, int py, ProbeRecorder*) {
            return technique == "hard" ? hardReference(in, HardSettings::from(frame.parameters).bias, px, py)
                                       : pcfReference(in, frame.parameters, px, py);
          });
        if (!cpu.evaluated)
        {
          continue;
        }
        ++evaluated;
        if (!ambiguityOf(cpu).empty() || cellAmbiguous(*frame.partitions->fvsm, test::vec3At(inputs.front().position, x, y)))
        {
          ++ambiguous;
          continue;
        }
        const double difference = std::abs(visibility.at(x, y) - cpu.visibility);
        maxDifference = std::max(maxDifference, difference);
        if (difference > (technique == "hard" ? 0.0 : 1e-5) && mismatched++ == 0)
        {
          firstMismatch = format("pixel ", x, ",", y, " gpu ", visibility.at(x, y), " cpu ", cpu.visibility);
        }
      }
    }
    std::cout << "[ measured ] deep-view-behind " << technique << " fvsm, " << frame.partitions->views.size()
              << " tiles: " << evaluated << " evaluated, " << ambiguous << " ambiguous, " << mismatched
              << " mismatched (max |GPU - CPU| " << maxDifference << ")\n";
    EXPECT_GT(evaluated, 2000) << technique;
    EXPECT_EQ(mismatched, 0) << technique << ": " << firstMismatch;
    EXPECT_LE(ambiguous, evaluated / 50) << technique;
  }
}

int fvsmMisclassified(const FrameResult& frame, const Scene& scene, const test::RayCaster& rays, ImageF& exact,
  int& evaluated)
{
  const ImageF& visibility = frame.find("visibility")->image;
  if (exact.data.empty())
  {
    exact = test::exactPointVisibility(frame, scene, rays);
  }
  int count = 0;
  evaluated = 0;
  for (std::size_t i = 0; i < exact.data.size(); ++i)
  {
    if (exact.data[i] >= 0.0f)
    {
      ++evaluated;
      count += visibility.data[i] != exact.data[i] ? 1 : 0;
    }
  }
  return count;
}

TEST(FvsmGpu, FewerMisclassifiedPixelsThanOneUniformMapOfTheSameTexels)
{
  // The same total texels: the uniform map's side is the root of the tiles' total (rounded down), 4 log cascades' the
  // root of a quarter of it (printed beside, not asserted). Counts of pixels whose hard shadow differs from the exact
  // single ray, summed over two image sizes. deep-view-behind is the survey's Fig. 14-15 case (light behind the
  // viewer), where warping cannot help.
  for (const std::string dataset : { "deep-view", "deep-view-behind" })
  {
    const Scene scene = test::loadDataset(dataset);
    const test::RayCaster rays(scene);
    int fvsmSum = 0, uniformSum = 0, cascadeSum = 0, evaluatedSum = 0;
    for (const glm::ivec2 size : { glm::ivec2(128, 96), glm::ivec2(160, 120) })
    {
      const std::vector<std::string> settings = { "fvsm=on", "fvsm_tile_size=64", "fvsm_max_level=5",
        "fvsm_max_tiles=32" };
      const FrameResult fvsm = test::renderDataset(scene, "hard", size.x, size.y, settings);
      ASSERT_TRUE(fvsm.partitions && fvsm.partitions->fvsm);
      const double totalTexels = static_cast<double>(fvsm.partitions->views.size()) * 64.0 * 64.0;
      const int side = static_cast<int>(std::floor(std::sqrt(totalTexels)));
      const int cascadeSide = static_cast<int>(std::floor(std::sqrt(totalTexels / 4.0)));
      const FrameResult uniform =
        test::renderDataset(scene, "hard", size.x, size.y, { "shadow_map_size=" + std::to_string(side) });
      const FrameResult cascaded = test::renderDataset(scene, "hard", size.x, size.y,
        { "shadow_map_size=" + std::to_string(cascadeSide), "cascades=4", "cascade_selection=containment" });
      ImageF exact;
      int evaluated = 0;
      const int fvsmCount = fvsmMisclassified(fvsm, scene, rays, exact, evaluated);
      const int uniformCount = fvsmMisclassified(uniform, scene, rays, exact, evaluated);
      const int cascadeCount = fvsmMisclassified(cascaded, scene, rays, exact, evaluated);
      std::cout << "[ measured ] " << dataset << " hard " << size.x << "x" << size.y << ": fvsm "
                << fvsm.partitions->views.size() << " tiles of 64^2 (" << totalTexels << " texels) " << fvsmCount
                << " / " << evaluated << " misclassified; one " << side << "^2 map " << uniformCount << "; 4 "
                << cascadeSide << "^2 cascades (log, containment) " << cascadeCount << "\n";
      fvsmSum += fvsmCount;
      uniformSum += uniformCount;
      cascadeSum += cascadeCount;
      evaluatedSum += evaluated;
    }
    std::cout << "[ measured ] " << dataset << " sum over both frames: fvsm " << fvsmSum << ", uniform " << uniformSum
              << ", 4 cascades " << cascadeSum << " / " << evaluatedSum << "\n";
    EXPECT_GT(evaluatedSum, 2 * 5000) << dataset;
    EXPECT_LT(fvsmSum, uniformSum) << dataset;
  }
}

TEST(FvsmGpu, ExportsTheTileMapAndRefusesCascadesInOneLine)
{
  const Scene scene = test::loadDataset("deep-view");
  const FrameResult frame = test::renderDataset(scene, "pcf", 96, 64,
    { "fvsm=on", "fvsm_tile_size=48", "fvsm_max_level=4", "fvsm_max_tiles=16" });
  ASSERT_TRUE(frame.partitions && frame.partitions->fvsm);
  const std::size_t tiles = frame.partitions->views.size();
  EXPECT_EQ(frame.find("fvsm_tile")->kind, BufferKind::Categorical);
  EXPECT_EQ(frame.find("fvsm_tile")->categoryLabels.size(), tiles);
  EXPECT_EQ(frame.find("cascade"), nullptr);
  for (const std::string name : { "fvsm_level", "fvsm_required_resolution", "fvsm_unmet", "texel_ratio_s" })
  {
    EXPECT_NE(frame.find(name), nullptr) << name;
  }
  EXPECT_EQ(test::lightSpaceArray(frame, "fvsm_required_resolution_grid").width, 48);
  EXPECT_EQ(test::lightSpaceArray(frame, "fvsm_level_grid").width, 48);
  for (std::size_t k = 0; k < tiles; ++k)
  {
    EXPECT_EQ(test::lightSpaceArray(frame, "shadow_map_depth_t" + std::to_string(k)).width, 48) << k;
  }
  // The level grid agrees with the tiles: a tile at level L covers (48 / 2^L)^2 texels of it, modulo the nearest
  // resampling of the 16 x 16 grid to 48 texels (3 per cell).
  const ImageF& levelGrid = test::lightSpaceArray(frame, "fvsm_level_grid");
  std::vector<int> texelsPerLevel(5, 0);
  for (const float level : levelGrid.data)
  {
    if (level >= 0.0f)
    {
      ++texelsPerLevel.at(static_cast<std::size_t>(level));
    }
  }
  std::vector<int> expected(5, 0);
  for (const FvsmTile& tile : frame.partitions->fvsm->quadtree.tiles)
  {
    expected.at(static_cast<std::size_t>(tile.level)) += (48 >> tile.level) * (48 >> tile.level);
  }
  EXPECT_EQ(texelsPerLevel, expected);
  test::expectFiniteBuffersAndVisibilityInRange(frame, "deep-view pcf fvsm=on");

  for (const std::vector<std::string>& settings :
    std::vector<std::vector<std::string>>{ { "fvsm=on", "cascades=3" }, { "fvsm=on", "warp=lispsm" } })
  {
    try
    {
      test::renderDataset(scene, "hard", 32, 32, settings);
      FAIL() << "accepted " << test::caseLabel("", settings);
    }
    catch (const InputError& error)
    {
      const std::string message = error.what();
      EXPECT_NE(message.find(settings[1].substr(0, settings[1].find('='))), std::string::npos) << message;
      EXPECT_NE(message.find("fvsm"), std::string::npos) << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
  }
}

} // namespace
} // namespace sl
