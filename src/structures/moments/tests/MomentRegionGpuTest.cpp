// prefilter_region = receivers (structures/moments/ReceiverTiles.h) on llvmpipe: the frames of vsm and esm (moment
// map), msm (power-moment map) and convsm (Fourier basis) equal those of prefilter_region = whole_map bit for bit
// (every buffer), the map's built texels equal the whole map's bit for bit, the unbuilt ones are 0 and marked 0 in its
// `*_built` array, and every shadow-tested pixel's lookup texel is built; on three datasets and random rectangle
// stacks, with the blur drawn over tiles (small maps) and sparse, at the listed texels alone (maps of 512^2 and more
// at 96^2 pixels). The tile and texel counts are printed.
#include "support/TestSupport.h"
#include "scene/Scene.h"
#include "structures/moments/ReceiverTiles.h"

#include <gtest/gtest.h>

#include <iostream>
#include <random>

namespace sl
{
namespace
{

double momentRegionStatistic(const FrameResult& frame, const std::string& name)
{
  const auto found = frame.techniqueStatistics.find(name);
  return found == frame.techniqueStatistics.end() ? -1.0 : found->second;
}

// The prefiltered map a technique reads, as light_space.vti exports it: its built mask, its arrays, the prefix of its
// statistics.
struct PrefilteredMapExport
{
  std::string built;
  std::vector<std::string> arrays;
  std::string statistics;
};

PrefilteredMapExport prefilteredMapOf(const std::string& technique)
{
  if (technique == "msm")
  {
    return { "power_moment_built", { "power_moment_1", "power_moment_2", "power_moment_3", "power_moment_4" },
      "power_moment_map" };
  }
  if (technique == "convsm")
  {
    PrefilteredMapExport basis{ "fourier_built", {}, "fourier_basis" };
    for (int k = 1; k <= 16; ++k)
    {
      basis.arrays.push_back(format("fourier_sin_", k));
      basis.arrays.push_back(format("fourier_cos_", k));
    }
    return basis;
  }
  return { "moment_built", { "moment_mean", "moment_second", "moment_exponential" }, "moment_map" };
}

void checkMomentRegion(const Scene& scene, const std::string& label, const std::string& technique,
  const std::vector<std::string>& settings)
{
  const PrefilteredMapExport map = prefilteredMapOf(technique);
  const auto momentRegionStatistic = [&](const FrameResult& frame, const std::string& name) {
    return sl::momentRegionStatistic(frame, map.statistics + name);
  };
  std::vector<std::string> receivers = settings;
  receivers.push_back("prefilter_region=receivers");
  std::vector<std::string> whole = settings;
  whole.push_back("prefilter_region=whole_map");
  const FrameResult tiled = test::renderDataset(scene, technique, 96, 96, receivers);
  const FrameResult full = test::renderDataset(scene, technique, 96, 96, whole);
  const std::string where = test::caseLabel(label + " " + technique, receivers);

  // Every buffer of the frame, bit for bit.
  test::expectBuffersBitIdentical(tiled, full, where + " against prefilter_region=whole_map");

  // The moment map: built texels as the whole map's, the others 0 and marked.
  const ImageF& built = test::lightSpaceArray(tiled, map.built);
  const ImageF& wholeBuilt = test::lightSpaceArray(full, map.built);
  std::size_t builtTexels = 0;
  for (const float value : wholeBuilt.data)
  {
    ASSERT_EQ(value, 1.0f) << where << ": whole_map leaves a texel unbuilt";
  }
  for (const std::string& name : map.arrays)
  {
    test::expectBuiltTexelsOfWhole(tiled, full, name, built, where);
  }
  for (const float value : built.data)
  {
    builtTexels += value != 0.0f ? 1 : 0;
  }

  // Every texel a lookup reads (the one holding the receiver's projection, prefilteredFetch) is built, by the CPU's
  // double-precision projection.
  int lookups = 0;
  const int unbuiltLookups = test::unbuiltLookupTexels(tiled, built, lookups);
  const int mapSize = built.width;
  EXPECT_GT(lookups, 0) << where;
  EXPECT_EQ(unbuiltLookups, 0) << where << ": lookups of unbuilt texels";

  const double allTiles = momentRegionStatistic(tiled, "_tiles");
  if (!receiverRegionCanPay(static_cast<long long>(tiled.resolution.x) * tiled.resolution.y, mapSize))
  {
    // Too few texels per pixel for the region to pay: the whole map, unmarked.
    EXPECT_EQ(allTiles, -1.0) << where;
    EXPECT_EQ(builtTexels, static_cast<std::size_t>(mapSize) * mapSize) << where;
    std::cout << "[ measured ] " << where << ": " << mapSize << "^2 map, whole (under "
              << receiverRegionTexelsPerPixel << " texels per pixel)\n";
    return;
  }
  const double receiverTiles = momentRegionStatistic(tiled, "_receiver_tiles");
  EXPECT_GT(receiverTiles, 0.0) << where;
  EXPECT_LE(receiverTiles, allTiles) << where;
  if (momentRegionStatistic(tiled, "_sparse_blur") > 0)
  {
    // The moments formed inline: neither the moments pass nor the horizontal pass ran.
    EXPECT_EQ(momentRegionStatistic(tiled, "_source_tiles"), 0.0) << where;
    EXPECT_EQ(momentRegionStatistic(tiled, "_horizontal_tiles"), 0.0) << where;
  }
  else
  {
    EXPECT_LE(receiverTiles, momentRegionStatistic(tiled, "_source_tiles")) << where;
  }
  std::cout << "[ measured ] " << where << ": " << mapSize << "^2 map, receiver tiles " << receiverTiles << " of "
            << allTiles << ", horizontal pass " << momentRegionStatistic(tiled, "_horizontal_tiles")
            << ", moments " << momentRegionStatistic(tiled, "_source_tiles") << "; built texels "
            << builtTexels << " of " << mapSize * mapSize << ", " << lookups << " lookups, "
            << momentRegionStatistic(tiled, "_read_texels") << " listed texels, "
            << (momentRegionStatistic(tiled, "_sparse_blur") > 0 ? "sparse blur" : "blur over tiles") << "\n";
}

TEST(MomentRegion, ReceiversEqualTheWholeMapOnDatasets)
{
  for (const std::string dataset : { "stacked-occluders", "bunny", "contact" })
  {
    const Scene scene = test::loadDataset(dataset);
    for (const std::string technique : { "vsm", "esm" })
    {
      checkMomentRegion(scene, dataset, technique, { "shadow_map_size=256", "prefilter=blur", "prefilter_texels=5" });
    }
    checkMomentRegion(scene, dataset, "vsm", { "shadow_map_size=512", "prefilter=blur", "prefilter_texels=33" });
    checkMomentRegion(scene, dataset, "vsm", { "shadow_map_size=128", "prefilter=blur", "prefilter_texels=1" });
    // Sparse: the blur at the listed texels alone.
    checkMomentRegion(scene, dataset, "esm", { "shadow_map_size=1024", "prefilter=blur", "prefilter_texels=5" });
    checkMomentRegion(scene, dataset, "vsm", { "shadow_map_size=2048", "prefilter=blur", "prefilter_texels=12" });
  }
}

TEST(MomentRegion, ReceiversEqualTheWholeMapOnRandomStacks)
{
  std::mt19937 generator(3303u);
  std::uniform_int_distribution<int> width(1, 24);
  for (int k = 0; k < 4; ++k)
  {
    const Scene scene = loadScene(test::datasetPath("stacked-occluders"), test::randomRectangleStack(generator, 3));
    const std::string texels = std::to_string(width(generator));
    checkMomentRegion(scene, "random stack " + std::to_string(k), k % 2 == 0 ? "vsm" : "esm",
      { "shadow_map_size=" + std::to_string(k < 2 ? 256 : k == 2 ? 384 : 1024), "prefilter=blur",
        "prefilter_texels=" + texels });
  }
}

// msm's power moments and convsm's Fourier basis follow the moment map's plan: over tiles, sparse (each with its own
// inline function of the depth, shaders/SparseBoxBlur.glsl), without a blur, and the whole map below 16 texels a pixel.
TEST(MomentRegion, PowerMomentsAndFourierBasisEqualTheWholeMap)
{
  std::mt19937 generator(3309u);
  std::uniform_int_distribution<int> width(1, 24);
  for (const std::string dataset : { "stacked-occluders", "bunny", "contact" })
  {
    const Scene scene = test::loadDataset(dataset);
    for (const std::string technique : { "msm", "convsm" })
    {
      checkMomentRegion(scene, dataset, technique, { "shadow_map_size=256", "prefilter=blur", "prefilter_texels=5" });
      checkMomentRegion(scene, dataset, technique, { "shadow_map_size=512", "prefilter=blur", "prefilter_texels=33" });
      checkMomentRegion(scene, dataset, technique, { "shadow_map_size=512", "prefilter=blur", "prefilter_texels=1" });
      checkMomentRegion(scene, dataset, technique, { "shadow_map_size=1024", "prefilter=blur", "prefilter_texels=5" });
      checkMomentRegion(scene, dataset, technique,
        { "shadow_map_size=1024", "prefilter=blur", "prefilter_texels=" + std::to_string(width(generator)) });
    }
  }
}

// The Fourier basis decides between the tiles and the sparse blur by its own cost (fourierSparseBlurIsCheaper): here
// the moment map's rule, fetches alone, blurs msm's power moments over tiles while the basis, whose terms cost more
// than a fetch per texel of the tiles, takes the sparse blur, and still equals the whole map bit for bit.
TEST(MomentRegion, FourierBasisTakesTheSparseBlurByItsOwnCost)
{
  const Scene scene = test::loadDataset("stacked-occluders");
  const std::vector<std::string> settings = { "shadow_map_size=512", "prefilter=blur", "prefilter_texels=12",
    "prefilter_region=receivers" };
  const FrameResult powerMoments = test::renderDataset(scene, "msm", 96, 96, settings);
  const FrameResult basis = test::renderDataset(scene, "convsm", 96, 96, settings);
  EXPECT_GT(momentRegionStatistic(powerMoments, "power_moment_map_read_texels"), 0.0);
  EXPECT_EQ(momentRegionStatistic(powerMoments, "power_moment_map_sparse_blur"), 0.0);
  EXPECT_EQ(momentRegionStatistic(basis, "fourier_basis_sparse_blur"), 1.0);
  checkMomentRegion(scene, "stacked-occluders", "convsm", { "shadow_map_size=512", "prefilter=blur", "prefilter_texels=12" });
}

TEST(MomentRegion, MipmapBuildsTheWholeMap)
{
  const FrameResult frame = test::renderDataset(test::loadDataset("bunny"), "vsm", 64, 64,
    { "shadow_map_size=128", "prefilter=mipmap", "prefilter_region=receivers" });
  for (const float value : test::lightSpaceArray(frame, "moment_built").data)
  {
    ASSERT_EQ(value, 1.0f) << "prefilter=mipmap averages every texel: the whole map is built";
  }
  EXPECT_EQ(momentRegionStatistic(frame, "moment_map_receiver_tiles"), -1.0);
}

} // namespace
} // namespace sl
