// prefilter_region = receivers for the layered moment map (lvsm; structures/moments/ReceiverTiles.h) on llvmpipe:
// lvsm's frames equal those of prefilter_region = whole_map bit for bit (every buffer), every layer's built texels
// equal the whole map's bit for bit, the unbuilt ones are 0 and marked 0 in layered_moment_built, and every
// shadow-tested pixel's lookup texel is built; on three datasets and random rectangle stacks, with the blur over tiles
// and sparse (at the listed texels alone), uniform and gap layers. The tile and texel counts are printed.
#include "support/TestSupport.h"
#include "scene/Scene.h"
#include "structures/layeredmoments/LayeredMomentsStructure.h"
#include "structures/moments/ReceiverTiles.h"

#include <gtest/gtest.h>

#include <iostream>
#include <random>

namespace sl
{
namespace
{

double regionStatistic(const FrameResult& frame, const std::string& name)
{
  const auto found = frame.techniqueStatistics.find(name);
  return found == frame.techniqueStatistics.end() ? -1.0 : found->second;
}

enum class LayeredBlur
{
  WholeMap,
  Tiles,
  Sparse
};

LayeredBlur checkLayeredRegion(const Scene& scene, const std::string& label, const std::vector<std::string>& settings)
{
  std::vector<std::string> receivers = settings;
  receivers.push_back("prefilter_region=receivers");
  std::vector<std::string> whole = settings;
  whole.push_back("prefilter_region=whole_map");
  const FrameResult tiled = test::renderDataset(scene, "lvsm", 96, 96, receivers);
  const FrameResult full = test::renderDataset(scene, "lvsm", 96, 96, whole);
  const std::string where = test::caseLabel(label + " lvsm", receivers);

  // Every buffer of the frame, bit for bit.
  test::expectBuffersBitIdentical(tiled, full, where + " against prefilter_region=whole_map");

  // Every layer: built texels as the whole map's, the others 0 and marked.
  const ImageF& built = test::lightSpaceArray(tiled, "layered_moment_built");
  for (const float value : test::lightSpaceArray(full, "layered_moment_built").data)
  {
    EXPECT_EQ(value, 1.0f) << where << ": whole_map leaves a texel unbuilt";
    if (value != 1.0f)
    {
      break;
    }
  }
  std::size_t builtTexels = 0;
  for (const float value : built.data)
  {
    builtTexels += value != 0.0f ? 1 : 0;
  }
  const int layers = static_cast<int>(full.parameters.getInt("layers"));
  for (int layer = 0; layer < layers; ++layer)
  {
    for (const std::string moment : { "_mean", "_second_moment" })
    {
      test::expectBuiltTexelsOfWhole(tiled, full, format("layer", layer, moment), built, where);
    }
  }

  // Every texel a lookup reads (the one holding the receiver's projection, LvsmVisibility.glsl's layerBound) is built,
  // by the CPU's double-precision projection.
  int lookups = 0;
  const int unbuiltLookups = test::unbuiltLookupTexels(tiled, built, lookups);
  const int mapSize = built.width;
  EXPECT_GT(lookups, 0) << where;
  EXPECT_EQ(unbuiltLookups, 0) << where << ": lookups of unbuilt texels";

  const double allTiles = regionStatistic(tiled, "layered_moments_tiles");
  if (!receiverRegionCanPay(static_cast<long long>(tiled.resolution.x) * tiled.resolution.y, mapSize))
  {
    EXPECT_EQ(allTiles, -1.0) << where;
    EXPECT_EQ(builtTexels, static_cast<std::size_t>(mapSize) * mapSize) << where;
    std::cout << "[ measured ] " << where << ": " << mapSize << "^2 map, whole (under " << receiverRegionTexelsPerPixel
              << " texels per pixel)\n";
    return LayeredBlur::WholeMap;
  }
  const double receiverTiles = regionStatistic(tiled, "layered_moments_receiver_tiles");
  const bool sparse = regionStatistic(tiled, "layered_moments_sparse_blur") > 0;
  EXPECT_GT(receiverTiles, 0.0) << where;
  EXPECT_LE(receiverTiles, allTiles) << where;
  EXPECT_EQ(regionStatistic(tiled, "layered_moments_source_tiles"), 0.0) << where << ": no pass of its own";
  if (sparse)
  {
    EXPECT_TRUE(layeredSparseBlurFits(tiled.parameters.getInt("prefilter_texels"), layers)) << where;
    EXPECT_EQ(regionStatistic(tiled, "layered_moments_horizontal_tiles"), 0.0) << where;
    EXPECT_LE(builtTexels, static_cast<std::size_t>(regionStatistic(tiled, "layered_moments_read_texels"))) << where;
  }
  else if (tiled.parameters.getInt("prefilter_texels") > 1)
  {
    EXPECT_GE(regionStatistic(tiled, "layered_moments_horizontal_tiles"), receiverTiles) << where;
  }
  else
  {
    EXPECT_EQ(regionStatistic(tiled, "layered_moments_horizontal_tiles"), 0.0) << where << ": no blur, no x pass of its own";
  }
  std::cout << "[ measured ] " << where << ": " << mapSize << "^2 map, receiver tiles " << receiverTiles << " of "
            << allTiles << ", x pass " << regionStatistic(tiled, "layered_moments_horizontal_tiles") << "; built texels "
            << builtTexels << " of " << mapSize * mapSize << ", " << lookups << " lookups, "
            << regionStatistic(tiled, "layered_moments_read_texels") << " listed texels, "
            << (sparse ? "sparse blur" : "blur over tiles") << "\n";
  return sparse ? LayeredBlur::Sparse : LayeredBlur::Tiles;
}

TEST(LayeredMomentRegion, ReceiversEqualTheWholeMapOnDatasets)
{
  int byKind[3] = {};
  for (const std::string dataset : { "stacked-occluders", "bunny", "contact" })
  {
    const Scene scene = test::loadDataset(dataset);
    ++byKind[static_cast<int>(checkLayeredRegion(scene, dataset, { "shadow_map_size=256", "prefilter_texels=5" }))];
    ++byKind[static_cast<int>(checkLayeredRegion(scene, dataset, { "shadow_map_size=512", "prefilter_texels=33" }))];
    ++byKind[static_cast<int>(
      checkLayeredRegion(scene, dataset, { "shadow_map_size=1024", "prefilter_texels=5", "layer_placement=uniform" }))];
    ++byKind[static_cast<int>(
      checkLayeredRegion(scene, dataset, { "shadow_map_size=1024", "prefilter_texels=7", "layers=16" }))];
    // No blur: the plan's source tiles are the built ones.
    ++byKind[static_cast<int>(checkLayeredRegion(scene, dataset, { "shadow_map_size=512", "prefilter_texels=1" }))];
  }
  EXPECT_GT(byKind[static_cast<int>(LayeredBlur::WholeMap)], 0) << "no case built the whole map";
  EXPECT_GT(byKind[static_cast<int>(LayeredBlur::Tiles)], 0) << "no case blurred over tiles";
  EXPECT_GT(byKind[static_cast<int>(LayeredBlur::Sparse)], 0) << "no case blurred sparse";
}

TEST(LayeredMomentRegion, ReceiversEqualTheWholeMapOnRandomStacks)
{
  std::mt19937 generator(3306u);
  std::uniform_int_distribution<int> width(1, 24);
  std::uniform_int_distribution<int> layers(1, 8);
  for (int k = 0; k < 4; ++k)
  {
    const Scene scene = loadScene(test::datasetPath("stacked-occluders"), test::randomRectangleStack(generator, 3));
    checkLayeredRegion(scene, "random stack " + std::to_string(k),
      { "shadow_map_size=" + std::to_string(k < 2 ? 512 : 1024), "prefilter_texels=" + std::to_string(width(generator)),
        "layers=" + std::to_string(layers(generator)), k % 2 == 0 ? "layer_placement=gaps" : "layer_placement=uniform" });
  }
}

} // namespace
} // namespace sl
