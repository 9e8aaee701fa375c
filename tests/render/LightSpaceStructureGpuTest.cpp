// The light-space structures a frame builds (structures/LightSpaceStructure.h), on the GPU: exactly the
// structures a technique needs (and what they are built from) are built, once each, timed as one stage each,
// exported to light_space.vti under their own names, and their GPU memory in FrameResult and stats.json is the
// closed form of the textures each one allocates. Small frames (64 x 48, maps of 64 or 128 texels) on llvmpipe.
#include "support/CliRun.h"
#include "support/TempDir.h"
#include "support/TestSupport.h"

#include "gl/BandedPrefixSums.h"
#include "lightspace/HierarchicalShadowMap.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include <cctype>
#include <cmath>
#include <cstddef>
#include <iostream>
#include <map>
#include <ostream>
#include <set>
#include <string>
#include <vector>

namespace sl
{
namespace
{

using Bytes = std::map<std::string, std::size_t>;
using Names = std::vector<std::string>;

const char* const kDataset = "planar-occluder"; // a square area light: every shadow-map technique supports it
constexpr int kStructureFrameWidth = 64;
constexpr int kStructureFrameHeight = 48;

// GPU bytes of each structure's textures, from the formats its pass allocates (N = shadow_map_size):
std::size_t shadowMapBytes(std::size_t n)
{
  return (4 + 4) * n * n; // linear depth R32F + window depth D32F
}
std::size_t summedAreaTableBytes(std::size_t n)
{
  return 8 * n * n; // RG32F (float_centred) or RG32UI (int32): two 32-bit sums per texel
}
// The SAT's build keeps its buffers beside the table (gl/BandedPrefixSums.h): a band of as many rows as the renderer's
// band bytes hold, and one row of carries. The band is asked of the GL, so at run time (with the frame's context), not
// when the cases are listed.
Bytes withSatBuildBuffers(Bytes bytes, std::size_t n)
{
  const auto table = bytes.find("summed_area_table");
  if (table != bytes.end())
  {
    test::sharedRenderWindow(); // a current context on this machine's GL (the one a `render` subprocess gets too)
    const auto bandRows = static_cast<std::size_t>(
      BandedPrefixSums::bandRowsFor(static_cast<int>(n), 2, BandedPrefixSums::bandBytesOfThisGl()));
    table->second += 8 * n * bandRows + 8 * n;
  }
  return bytes;
}
std::size_t blurredMomentBytes(std::size_t n)
{
  return 16 * n * n; // RGBA32F
}
std::size_t mipmappedMomentBytes(std::size_t n)
{
  // RGBA32F with its full mip chain; for N = 2^m, sum_{k=0..m} (N / 2^k)^2 = (4 N^2 - 1) / 3.
  return 16 * (4 * n * n - 1) / 3;
}
std::size_t mipMapHsmBytes(std::size_t n)
{
  return 8 * n * n; // RG32F atlas of levels 1..L in N x N
}
std::size_t nBuffersHsmBytes(std::size_t n)
{
  return 8 * n * n * static_cast<std::size_t>(hsmLevelCount(static_cast<int>(n))); // RG32F, N x N per level 1..L
}
std::size_t ysmBytes(std::size_t n)
{
  // The mip-map atlas plus the MSSM part, RG32F M x M x ceil(log2 M) (SS08 §6; HierarchicalShadowMap.h).
  const std::size_t m = static_cast<std::size_t>(ysmMssmPartSize(static_cast<int>(n)));
  return mipMapHsmBytes(n) + 8 * m * m * static_cast<std::size_t>(ysmMssmPartLevelCount(static_cast<int>(n)));
}
std::size_t dualMssmBytes(std::size_t n)
{
  // RG32F, (N + 1)^2 per level 0..L (cells -1 .. N - 1 per side).
  return 8 * (n + 1) * (n + 1) * static_cast<std::size_t>(dualMssmLevelCount(static_cast<int>(n)) + 1);
}

// `prefix` + "min_k" and "max_k" for k in [first, last].
Names perLevel(const std::string& prefix, int first, int last)
{
  Names names;
  for (int level = first; level <= last; ++level)
  {
    names.push_back(prefix + "min_" + std::to_string(level));
    names.push_back(prefix + "max_" + std::to_string(level));
  }
  return names;
}

Names concatenated(std::initializer_list<Names> parts)
{
  Names all;
  for (const Names& part : parts)
  {
    all.insert(all.end(), part.begin(), part.end());
  }
  return all;
}

// What one frame must have built, timed and exported.
struct StructureCase
{
  std::string technique;
  std::vector<std::string> settings;
  int mapSize = 0;               // shadow_map_size (0: no shadow map)
  Names listed;                  // FrameResult::lightStructureNames: the technique's own list
  Bytes gpuBytes;                // every built structure and its memory
  Names stages;                  // stats.json stages, in order
  Names lightSpace;              // light_space.vti arrays (any order)
};

std::vector<StructureCase> structureCases()
{
  const Names shadowMapArrays = { "shadow_map_depth", "shadow_map_window_depth" };
  const Names tableArrays = { "sat_z", "sat_z2" };
  const Names momentArrays = { "moment_mean", "moment_second", "moment_exponential", "moment_built" };
  const std::size_t large = 128;
  const std::size_t small = 64;
  const int smallLevels = hsmLevelCount(static_cast<int>(small));
  const int smallDualLevels = dualMssmLevelCount(static_cast<int>(small));
  return {
    { "hard", { "shadow_map_size=128" }, 128, { "shadow_map" }, { { "shadow_map", shadowMapBytes(large) } },
      { "gbuffer", "focus", "shadow_map", "technique", "shading" }, shadowMapArrays },
    { "savsm", { "shadow_map_size=128", "sat_precision=int32" }, 128, { "shadow_map", "summed_area_table" },
      { { "shadow_map", shadowMapBytes(large) }, { "summed_area_table", summedAreaTableBytes(large) } },
      { "gbuffer", "focus", "shadow_map", "summed_area_table", "technique", "shading" },
      concatenated({ shadowMapArrays, tableArrays }) },
    { "savsm", { "shadow_map_size=128", "sat_precision=float_centred" }, 128, { "shadow_map", "summed_area_table" },
      { { "shadow_map", shadowMapBytes(large) }, { "summed_area_table", summedAreaTableBytes(large) } },
      { "gbuffer", "focus", "shadow_map", "summed_area_table", "technique", "shading" },
      concatenated({ shadowMapArrays, tableArrays }) },
    { "vsm", { "shadow_map_size=128", "prefilter=blur", "prefilter_texels=5" }, 128, { "shadow_map", "moment_map" },
      { { "shadow_map", shadowMapBytes(large) }, { "moment_map", blurredMomentBytes(large) } },
      { "gbuffer", "focus", "shadow_map", "moment_map", "technique", "shading" },
      concatenated({ shadowMapArrays, momentArrays }) },
    { "vsm", { "shadow_map_size=128", "prefilter=mipmap" }, 128, { "shadow_map", "moment_map" },
      { { "shadow_map", shadowMapBytes(large) }, { "moment_map", mipmappedMomentBytes(large) } },
      { "gbuffer", "focus", "shadow_map", "moment_map", "technique", "shading" },
      concatenated({ shadowMapArrays, momentArrays }) },
    { "vssm", { "shadow_map_size=128", "hsm=mipmap" }, 128,
      { "shadow_map", "summed_area_table", "hierarchical_shadow_map" },
      { { "shadow_map", shadowMapBytes(large) }, { "summed_area_table", summedAreaTableBytes(large) },
        { "hierarchical_shadow_map", mipMapHsmBytes(large) } },
      { "gbuffer", "focus", "shadow_map", "summed_area_table", "hierarchical_shadow_map", "technique", "shading" },
      concatenated({ shadowMapArrays, tableArrays, { "hsm_min", "hsm_max" } }) },
    { "vssm", { "shadow_map_size=64", "hsm=nbuffers" }, 64,
      { "shadow_map", "summed_area_table", "hierarchical_shadow_map" },
      { { "shadow_map", shadowMapBytes(small) }, { "summed_area_table", summedAreaTableBytes(small) },
        { "hierarchical_shadow_map", nBuffersHsmBytes(small) } },
      { "gbuffer", "focus", "shadow_map", "summed_area_table", "hierarchical_shadow_map", "technique", "shading" },
      concatenated({ shadowMapArrays, tableArrays, perLevel("hsm_", 1, smallLevels) }) },
    // Y shadow map at 128^2: b = 0, so the MSSM part is the N-buffers of the whole map (7 levels).
    { "vssm", { "shadow_map_size=128", "hsm=ysm" }, 128,
      { "shadow_map", "summed_area_table", "hierarchical_shadow_map" },
      { { "shadow_map", shadowMapBytes(large) }, { "summed_area_table", summedAreaTableBytes(large) },
        { "hierarchical_shadow_map", ysmBytes(large) } },
      { "gbuffer", "focus", "shadow_map", "summed_area_table", "hierarchical_shadow_map", "technique", "shading" },
      concatenated({ shadowMapArrays, tableArrays, { "hsm_min", "hsm_max" }, perLevel("ysm_mssm_", 1, 7) }) },
    // Multi-view: everything between the G-buffer and the shading runs per sub-light (4 times here), but each
    // stage is reported once (its timer sums the runs, which this test does not observe) and the structures'
    // memory is that of one sub-light's. Every level (mssm_levels=all): HsmTopLevelFrame checks a build to the
    // levels the frame reads.
    { "yfgl09", { "shadow_map_size=64", "sublights=2", "mssm_levels=all" }, 64, { "shadow_map", "dual_mssm" },
      { { "shadow_map", shadowMapBytes(small) }, { "dual_mssm", dualMssmBytes(small) } },
      { "gbuffer", "focus", "shadow_map", "hierarchical_shadow_map", "technique", "sublight_accumulate", "shading" },
      concatenated({ shadowMapArrays, perLevel("mssm_dual_", 0, smallDualLevels) }) },
    // VTK builds its own shadow map: no light-space structure of ours.
    { "vtk", {}, 0, {}, {}, { "gbuffer", "technique", "shading" }, {} },
  };
}

std::string describe(const StructureCase& expected)
{
  return expected.technique + " " + test::caseLabel(kDataset, expected.settings);
}

void PrintTo(const StructureCase& expected, std::ostream* os)
{
  *os << describe(expected);
}

// "vssm_shadow_map_size_64_hsm_nbuffers"
std::string structureCaseName(const testing::TestParamInfo<StructureCase>& info)
{
  std::string name = info.param.technique;
  for (const std::string& setting : info.param.settings)
  {
    name += "_" + setting;
  }
  for (char& character : name)
  {
    character = std::isalnum(static_cast<unsigned char>(character)) ? character : '_';
  }
  return name;
}

TEST(LightSpaceStructureGpu, LevelCountsAreTheDocumentedLogarithms)
{
  // The closed forms above use HierarchicalShadowMap.h's level counts: ceil(log2 N) and ceil(log2 (N + 1)).
  for (const int n : { 16, 64, 65, 100, 128, 255, 256 })
  {
    EXPECT_EQ(hsmLevelCount(n), static_cast<int>(std::ceil(std::log2(n)))) << n;
    EXPECT_EQ(dualMssmLevelCount(n), static_cast<int>(std::ceil(std::log2(n + 1)))) << n;
  }
}

// One frame per case (one ctest case each, so `ctest -j` spreads them).
class LightSpaceStructureFrame : public testing::TestWithParam<StructureCase>
{
};

TEST_P(LightSpaceStructureFrame, BuildsTimesExportsAndCountsExactlyItsStructures)
{
  const StructureCase& expected = GetParam();
  const Scene scene = test::loadDataset(kDataset);
  const FrameResult frame = test::renderDataset(scene, expected.technique, kStructureFrameWidth, kStructureFrameHeight, expected.settings);

  // Memory: every built structure (the listed ones and what they are built from), none other, in closed form.
  EXPECT_EQ(frame.lightStructureGpuBytes, withSatBuildBuffers(expected.gpuBytes, static_cast<std::size_t>(expected.mapSize)));
  EXPECT_EQ(frame.lightStructureNames, expected.listed);
  if (expected.mapSize > 0)
  {
    ASSERT_TRUE(frame.lightView.has_value());
    ASSERT_EQ(frame.lightView->resolution, expected.mapSize) << "the closed forms assume this map size";
  }

  // Stages: each structure's build once, in build order, between the G-buffer and the technique.
  Names stages;
  for (const StageTiming& timing : frame.stages)
  {
    stages.push_back(timing.stage);
  }
  EXPECT_EQ(stages, expected.stages);

  // light_space.vti: each built structure's arrays, per shadow-map texel (the HSM atlas, each N-buffer level and
  // each dual-grid level cropped to the map's cells).
  Names exported;
  for (const NamedImage& array : frame.lightSpace)
  {
    exported.push_back(array.name);
    EXPECT_EQ(array.image.width, expected.mapSize) << array.name;
    EXPECT_EQ(array.image.height, expected.mapSize) << array.name;
    EXPECT_EQ(array.image.components, 1) << array.name;
  }
  EXPECT_EQ(std::multiset<std::string>(exported.begin(), exported.end()),
    std::multiset<std::string>(expected.lightSpace.begin(), expected.lightSpace.end()));
}

INSTANTIATE_TEST_SUITE_P(Cases, LightSpaceStructureFrame, testing::ValuesIn(structureCases()), structureCaseName);

// SS08 Table 1: the YSM costs the HSM plus 4 MiB at 1024^2 (a 256^2 MSSM part of 8 levels, RG32F). The
// project's HSM is the N x N atlas (level 0 stays in the shadow map), so its bytes are 8 N^2 and the YSM's
// 8 N^2 + 8 * 256^2 * 8; the difference is the paper's.
TEST(LightSpaceStructureGpu, YShadowMapCostsTheHsmPlusFourMebibytesAt1024)
{
  const Scene scene = test::loadDataset(kDataset);
  std::map<std::string, std::size_t> bytes;
  for (const std::string layout : { "mipmap", "ysm" })
  {
    const FrameResult frame = test::renderDataset(scene, "gbp07", 16, 12, { "shadow_map_size=1024", "hsm=" + layout });
    bytes[layout] = frame.lightStructureGpuBytes.at("hierarchical_shadow_map");
  }
  std::cout << "[ measured ] hierarchical_shadow_map GPU bytes at 1024^2: mipmap " << bytes["mipmap"] << ", ysm "
            << bytes["ysm"] << ", difference " << (bytes["ysm"] - bytes["mipmap"]) / 1048576.0 << " MiB\n";
  EXPECT_EQ(bytes["mipmap"], mipMapHsmBytes(1024));
  EXPECT_EQ(bytes["ysm"], ysmBytes(1024));
  EXPECT_EQ(bytes["ysm"], std::size_t(8) * 1024 * 1024 + std::size_t(8) * 256 * 256 * 8);
  EXPECT_EQ(bytes["ysm"] - bytes["mipmap"], std::size_t(4) << 20);
}

// The Y shadow map the GPU built (atlas and MSSM part, read back through light_space.vti) equals the CPU build
// from the same shadow map bit for bit (min and max are exact in float), at 1024^2 (b = 2, a 256^2 part) and at
// 200^2 (b = 0, not a power of two: odd levels keep their last row and column).
TEST(LightSpaceStructureGpu, YShadowMapEqualsTheCpuBuildBitForBit)
{
  const Scene scene = test::loadDataset("stacked-occluders");
  for (const int size : { 1024, 200 })
  {
    const FrameResult frame = test::renderDataset(scene, "vssm", 32, 32, { "shadow_map_size=" + std::to_string(size), "hsm=ysm" });
    const HierarchicalShadowMap cpu = HierarchicalShadowMap::build(test::lightSpaceArray(frame, "shadow_map_depth"), HsmLayout::Ysm);
    const int b = cpu.ysmBaseLevel;
    ASSERT_EQ(static_cast<int>(cpu.mssmPart.size()), ysmMssmPartLevelCount(size));
    // The atlas as stored; the part's level k exported per shadow-map texel (x, y) as its texel (x >> b, y >> b).
    const ImageF atlas = cpu.atlas();
    const ImageF& atlasMin = test::lightSpaceArray(frame, "hsm_min");
    const ImageF& atlasMax = test::lightSpaceArray(frame, "hsm_max");
    int compared = 0;
    int differing = 0;
    for (int y = 0; y < size; ++y)
    {
      for (int x = 0; x < size; ++x)
      {
        differing += atlasMin.at(x, y) != atlas.at(x, y, 0) || atlasMax.at(x, y) != atlas.at(x, y, 1) ? 1 : 0;
        ++compared;
      }
    }
    int partDiffering = 0;
    for (int level = 1; level <= static_cast<int>(cpu.mssmPart.size()); ++level)
    {
      const ImageF& part = cpu.mssmPart[static_cast<std::size_t>(level - 1)];
      const ImageF& gpuMin = test::lightSpaceArray(frame, "ysm_mssm_min_" + std::to_string(level));
      const ImageF& gpuMax = test::lightSpaceArray(frame, "ysm_mssm_max_" + std::to_string(level));
      for (int y = 0; y < size; ++y)
      {
        for (int x = 0; x < size; ++x)
        {
          partDiffering += gpuMin.at(x, y) != part.at(x >> b, y >> b, 0) || gpuMax.at(x, y) != part.at(x >> b, y >> b, 1) ? 1 : 0;
          ++compared;
        }
      }
    }
    std::cout << "[ measured ] YSM at " << size << "^2 (b = " << b << ", part " << ysmMssmPartSize(size) << "^2 x "
              << cpu.mssmPart.size() << "): " << compared << " texel pairs compared, atlas differing " << differing
              << ", MSSM part differing " << partDiffering << "\n";
    EXPECT_EQ(b, size == 1024 ? 2 : 0);
    EXPECT_EQ(differing, 0) << size;
    EXPECT_EQ(partDiffering, 0) << size;
  }
}

// The structure passes keep their textures from one frame to the next when the size and format fit (a fresh
// 2048^2 SAT or HSM cost llvmpipe more wall time than building it). Nothing of the previous frame may leak:
// a frame of one scene, then a frame of another scene into the same textures, then the first scene again must
// give the first frame's buffers and light-space arrays bit for bit.
TEST(LightSpaceStructureGpu, ReusedTexturesKeepNothingOfThePreviousFrame)
{
  const Scene planar = test::loadDataset(kDataset);
  const Scene stacked = test::loadDataset("stacked-occluders");
  for (const Names& settings : { Names{ "shadow_map_size=128", "hsm=mipmap" },
         Names{ "shadow_map_size=64", "hsm=nbuffers", "sat_precision=float_centred" },
         Names{ "shadow_map_size=128", "hsm=ysm" } })
  {
    const std::string label = test::caseLabel(kDataset, settings);
    const FrameResult first = test::renderDataset(planar, "vssm", kStructureFrameWidth, kStructureFrameHeight, settings);
    const FrameResult other = test::renderDataset(stacked, "vssm", kStructureFrameWidth, kStructureFrameHeight, settings);
    const FrameResult again = test::renderDataset(planar, "vssm", kStructureFrameWidth, kStructureFrameHeight, settings);
    ASSERT_NE(test::lightSpaceArray(first, "shadow_map_depth").data, test::lightSpaceArray(other, "shadow_map_depth").data)
      << "the frame in between must fill the reused textures with something else";
    ASSERT_EQ(first.lightSpace.size(), again.lightSpace.size()) << label;
    for (std::size_t i = 0; i < first.lightSpace.size(); ++i)
    {
      EXPECT_EQ(first.lightSpace[i].image.data, again.lightSpace[i].image.data) << label << ": " << first.lightSpace[i].name;
    }
    ASSERT_EQ(first.buffers.size(), again.buffers.size()) << label;
    for (std::size_t i = 0; i < first.buffers.size(); ++i)
    {
      EXPECT_EQ(first.buffers[i].image.data, again.buffers[i].image.data) << label << ": " << first.buffers[i].name;
    }
  }
}

// `shadowlab render` reports the same memory in stats.json, with the structures the technique reads.
TEST(LightSpaceStructureGpu, StatsJsonReportsEachBuiltStructuresGpuBytes)
{
  test::TempDir temp;
  const std::filesystem::path outDir = temp.path() / "savsm";
  const test::RunResult run = test::runShadowlabIn({ "render", test::datasetPath(kDataset).string(), "--technique",
                                                     "savsm", "--resolution", "64x48", "--set", "shadow_map_size=128",
                                                     "--quiet", "--out", outDir.string() },
    temp.path());
  ASSERT_EQ(run.exitCode, 0) << run.describe();
  const nlohmann::json stats = nlohmann::json::parse(test::readFile(outDir / "stats.json"));
  ASSERT_TRUE(stats.contains("light_structure_gpu_bytes")) << stats.dump(2);
  const Bytes bytes = withSatBuildBuffers({ { "shadow_map", shadowMapBytes(128) },
    { "summed_area_table", summedAreaTableBytes(128) } }, 128);
  const nlohmann::json expected(bytes);
  EXPECT_EQ(stats.at("light_structure_gpu_bytes"), expected) << stats.at("light_structure_gpu_bytes").dump();
  EXPECT_EQ(stats.at("light_structures"), nlohmann::json({ "shadow_map", "summed_area_table" }));
  std::set<std::string> lightSpace;
  for (const auto& [name, summary] : stats.at("light_space").items())
  {
    lightSpace.insert(name);
  }
  EXPECT_EQ(lightSpace, (std::set<std::string>{ "shadow_map_depth", "shadow_map_window_depth", "sat_z", "sat_z2" }));
  EXPECT_TRUE(std::filesystem::exists(outDir / "light_space.vti"));
}

} // namespace
} // namespace sl
