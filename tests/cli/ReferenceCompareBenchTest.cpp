// shadowlab reference / compare / bench, end to end through the executable.
#include "io/ImageIO.h"
#include "metrics/ErrorMetrics.h"
#include "support/CliRun.h"
#include "support/TempDir.h"
#include "support/TestSupport.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace sl
{
namespace
{

using test::RunResult;

using test::arrayNamed;

using test::readJson;

TEST(ReferenceCommand, WritesTheBufferSchemaWithStandardErrorAndStats)
{
  const std::filesystem::path out = test::freshOutputDir("reference-out");
  const RunResult run = test::runShadowlabInTempDir({ "reference", test::datasetPath("stacked-occluders").string(), "--reference-samples", "64",
    "--resolution", "64x48", "--out", out.string(), "--quiet" });
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_TRUE(run.err.empty()) << run.err;
  const std::vector<NamedImage> buffers = readVti(out / "buffers.vti");
  for (const char* name : { "visibility", "visibility_stderr", "position", "normal", "depth", "coverage" })
  {
    const NamedImage& named = arrayNamed(buffers, name);
    EXPECT_EQ(named.image.width, 64) << name;
    EXPECT_EQ(named.image.height, 48) << name;
  }
  const ImageF& visibility = arrayNamed(buffers, "visibility").image;
  const ImageF& standardError = arrayNamed(buffers, "visibility_stderr").image;
  int penumbra = 0;
  for (std::size_t i = 0; i < visibility.data.size(); ++i)
  {
    ASSERT_GE(visibility.data[i], 0.0f);
    ASSERT_LE(visibility.data[i], 1.0f);
    if (visibility.data[i] > 0.0f && visibility.data[i] < 1.0f)
    {
      ++penumbra;
      EXPECT_GT(standardError.data[i], 0.0f) << "penumbra pixels have a nonzero standard error";
    }
  }
  EXPECT_GT(penumbra, 20);
  const nlohmann::json stats = readJson(out / "stats.json");
  EXPECT_GT(stats.at("rays_per_second").get<double>(), 0.0);
  EXPECT_EQ(stats.at("samples").get<int>(), 64);
  EXPECT_TRUE(std::filesystem::exists(out / "visibility.exr"));
  EXPECT_TRUE(std::filesystem::exists(out / "heatmap_visibility_stderr.png"));
}

TEST(ReferenceCommand, BadSettingsAreOneLineErrorsWithNoOutput)
{
  const std::filesystem::path out = test::freshOutputDir("reference-bad");
  // {option, value, what the message names}: the multisample mode takes 1 or 4 samples, and no light-sample set
  // (its per-sample facts are of one surface point).
  const std::vector<std::array<std::string, 3>> cases = { { "--reference-samples", "0", "--reference-samples" },
    { "--sampling", "sobol", "--sampling" }, { "--msaa", "3", "--msaa" }, { "--msaa", "0", "--msaa" },
    { "--msaa", "4 --light-samples stratified", "--light-samples" } };
  for (const auto& [option, value, named] : cases)
  {
    std::vector<std::string> arguments = { "reference", test::datasetPath("planar-occluder").string(), option };
    std::istringstream words(value);
    for (std::string word; words >> word;)
    {
      arguments.push_back(word);
    }
    arguments.insert(arguments.end(), { "--resolution", "32x32", "--out", out.string() });
    const RunResult run = test::runShadowlabInTempDir(arguments);
    EXPECT_NE(run.exitCode, 0) << option << " " << value;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    EXPECT_NE(run.err.find(named), std::string::npos) << run.err;
    EXPECT_FALSE(std::filesystem::exists(out));
  }
}

TEST(CompareCommand, MetricsMatchTheFilesAndErrorsNameTheInput)
{
  const std::filesystem::path hard = test::freshOutputDir("compare-hard");
  const std::filesystem::path reference = test::freshOutputDir("compare-reference");
  const std::filesystem::path out = test::freshOutputDir("compare-out");
  const std::string scene = test::datasetPath("planar-occluder").string();
  ASSERT_EQ(test::runShadowlabInTempDir({ "render", scene, "-t", "hard", "-r", "64x64", "-q", "--out", hard.string() }).exitCode, 0);
  ASSERT_EQ(
    test::runShadowlabInTempDir({ "reference", scene, "--reference-samples", "64", "-r", "64x64", "-q", "--out", reference.string() }).exitCode, 0);
  const RunResult run = test::runShadowlabInTempDir({ "compare", (hard / "buffers.vti").string(), (reference / "buffers.vti").string(),
    "-q", "--out", out.string() });
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const nlohmann::json metrics = readJson(out / "metrics.json");
  const std::vector<NamedImage> a = readVti(hard / "buffers.vti");
  const std::vector<NamedImage> b = readVti(reference / "buffers.vti");
  const ErrorMetrics expected = computeErrorMetrics(arrayNamed(a, "visibility").image, arrayNamed(b, "visibility").image,
    arrayNamed(a, "coverage").image, arrayNamed(b, "coverage").image);
  EXPECT_DOUBLE_EQ(metrics.at("covered").at("rmse").get<double>(), expected.covered.rmse);
  EXPECT_DOUBLE_EQ(metrics.at("penumbra").at("rmse").get<double>(), expected.penumbra.rmse);
  EXPECT_GT(expected.penumbra.pixels, 50u) << "a hard shadow against a soft reference has penumbra errors";
  EXPECT_GT(expected.penumbra.rmse, expected.covered.rmse);
  EXPECT_TRUE(std::filesystem::exists(out / "error.vti"));
  EXPECT_TRUE(std::filesystem::exists(out / "error.png"));

  // Mismatched sizes, a missing array: one line naming the file, no output.
  const std::filesystem::path small = test::freshOutputDir("compare-small");
  ASSERT_EQ(test::runShadowlabInTempDir({ "render", scene, "-t", "hard", "-r", "32x32", "-q", "--out", small.string() }).exitCode, 0);
  const std::filesystem::path badOut = test::freshOutputDir("compare-bad-out");
  const RunResult mismatched = test::runShadowlabInTempDir({ "compare", (small / "buffers.vti").string(),
    (reference / "buffers.vti").string(), "--out", badOut.string() });
  EXPECT_NE(mismatched.exitCode, 0);
  EXPECT_EQ(std::count(mismatched.err.begin(), mismatched.err.end(), '\n'), 1) << mismatched.err;
  EXPECT_NE(mismatched.err.find("32x32"), std::string::npos) << mismatched.err;
  const RunResult missing = test::runShadowlabInTempDir({ "compare", (hard / "buffers.vti").string(),
    (reference / "buffers.vti").string(), "--array", "kernel_size", "--out", badOut.string() });
  EXPECT_NE(missing.exitCode, 0);
  EXPECT_NE(missing.err.find("kernel_size"), std::string::npos) << missing.err;
  EXPECT_FALSE(std::filesystem::exists(badOut));
}

TEST(BenchCommand, ReportsAFailingConfigurationAndFinishesTheRest)
{
  // A scene that loads but fails at render time: a point light just above a wide ground sees visible
  // receivers all around it, which one shadow map cannot cover (cube_map=off keeps hard and pcf to one map).
  const std::filesystem::path sceneDir = test::freshOutputDir("bench-scenes");
  std::filesystem::create_directories(sceneDir);
  {
    std::ofstream bad(sceneDir / "surrounded.json");
    bad << R"({ "camera": { "position": [0, 6, 6], "focal_point": [0, 0, 0] },
      "lights": [ { "type": "point", "center": [0, 0.05, 0] } ],
      "objects": [ { "primitive": "quad", "size": [40, 40], "normal": [0, 1, 0], "up": [0, 0, -1] } ] })";
  }
  const std::filesystem::path out = test::freshOutputDir("bench-out");
  const std::filesystem::path cache = test::freshOutputDir("bench-cache");
  const std::vector<std::string> arguments = { "bench", test::datasetPath("planar-occluder").string(),
    (sceneDir / "surrounded.json").string(), "-t", "hard,pcf", "--set", "cube_map=off", "--sweep", "kernel_texels=1,5", "--repeat", "2", "-r",
    "48x48", "--reference-samples", "16", "--cache", cache.string(), "--out", out.string() };
  const RunResult run = test::runShadowlabInTempDir(arguments);
  EXPECT_EQ(run.exitCode, 4) << run.err; // some configurations failed
  const nlohmann::json bench = readJson(out / "bench.json");
  int ok = 0;
  int failed = 0;
  for (const nlohmann::json& row : bench.at("configurations"))
  {
    if (row.at("status") == "ok")
    {
      ++ok;
      const nlohmann::json& result = row.at("result");
      EXPECT_GT(result.at("frame_gpu_ms").get<double>(), 0.0);
      EXPECT_TRUE(result.contains("error")) << "every good configuration is measured against the reference";
      EXPECT_GE(result.at("error").at("covered").at("rmse").get<double>(), 0.0);
    }
    else
    {
      ++failed;
      EXPECT_NE(row.at("error").get<std::string>().find("point light"), std::string::npos) << row.dump();
    }
  }
  // hard, pcf x {1, 5} on each scene: 3 configurations per scene.
  EXPECT_EQ(ok, 3);
  EXPECT_EQ(failed, 3);
  std::ifstream csv(out / "bench.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_NE(header.find("frame_gpu_ms"), std::string::npos);
  EXPECT_NE(header.find("rmse"), std::string::npos);
  EXPECT_TRUE(std::filesystem::exists(out / "summary.md"));
  EXPECT_TRUE(std::filesystem::exists(out / "speed_vs_error_planar-occluder.png"));
  const ImageU8 chart = readPng(out / "speed_vs_error_planar-occluder.png");
  EXPECT_GT(chart.width, 200);

  // The references are cached: a second run computes none.
  std::vector<std::string> quietArguments = arguments;
  quietArguments.push_back("--quiet");
  const RunResult again = test::runShadowlabInTempDir(quietArguments);
  EXPECT_EQ(again.exitCode, 4);
  EXPECT_EQ(again.err.find("ray-traced reference of"), std::string::npos) << again.err;
}

TEST(BenchCommand, SceneSweepsReachEveryChildAndGetTheirOwnReferences)
{
  // A light-size sweep (the papers' benchmarks): each size is its own scene variant with its own cached
  // reference; hard shadows sample the light's centre, so their error must grow with the light.
  const std::filesystem::path out = test::freshOutputDir("bench-sweep-out");
  const std::filesystem::path cache = test::freshOutputDir("bench-sweep-cache");
  const RunResult run = test::runShadowlabInTempDir({ "bench", test::datasetPath("planar-occluder").string(), "-t", "hard",
    "--scene-sweep", "/lights/0/size=0.25,1,2", "--repeat", "1", "-r", "48x48", "--reference-samples", "64", "--quiet", "--cache",
    cache.string(), "--out", out.string() });
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const nlohmann::json bench = readJson(out / "bench.json");
  std::vector<double> rmse;
  for (const nlohmann::json& row : bench.at("configurations"))
  {
    ASSERT_EQ(row.at("status"), "ok") << row.dump();
    EXPECT_NE(row.at("scene_overrides").get<std::string>().find("/lights/0/size="), std::string::npos);
    rmse.push_back(row.at("result").at("error").at("covered").at("rmse").get<double>());
  }
  ASSERT_EQ(rmse.size(), 3u);
  EXPECT_LT(rmse[0], rmse[1]);
  EXPECT_LT(rmse[1], rmse[2]);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(cache), std::filesystem::directory_iterator()), 3)
    << "one cached reference per light size";
}

TEST(BenchCommand, WorkCounterColumnsAreTheImageTotalsOfTheCounterBuffers)
{
  // gbp07's visited_cells and contour_edges are work counters (summed over sub-lights): the bench reports
  // each one's total over the covered pixels as <buffer>_sum, the number Yang et al. 2009's Eq. 9 is about.
  // The totals must be those of the buffers `shadowlab render` writes for the same configuration.
  const std::filesystem::path out = test::freshOutputDir("bench-counters-out");
  const std::filesystem::path cache = test::freshOutputDir("bench-counters-cache");
  const std::vector<std::string> common = { "-s", "shadow_map_size=128", "-r", "32x32" };
  std::vector<std::string> bench = { "bench", test::datasetPath("planar-occluder").string(), "-t", "gbp07", "--sweep",
    "sublights=1,2", "--repeat", "1", "--reference-samples", "16", "--quiet", "--cache", cache.string(), "--out", out.string() };
  bench.insert(bench.end(), common.begin(), common.end());
  const RunResult run = test::runShadowlabInTempDir(bench);
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const nlohmann::json rows = readJson(out / "bench.json").at("configurations");
  ASSERT_EQ(rows.size(), 2u);
  for (const nlohmann::json& row : rows)
  {
    ASSERT_EQ(row.at("status"), "ok") << row.dump();
    const nlohmann::json& sums = row.at("result").at("work_counter_sums");
    EXPECT_EQ(sums.size(), 2u) << sums.dump() << ": only the counters, not averaged buffers such as kernel_texels";
    EXPECT_GT(sums.at("visited_cells").get<double>(), 0.0);
  }

  const std::filesystem::path rendered = test::freshOutputDir("bench-counters-render");
  std::vector<std::string> render = { "render", test::datasetPath("planar-occluder").string(), "--technique", "gbp07",
    "-s", "sublights=2", "--out", rendered.string() };
  render.insert(render.end(), common.begin(), common.end());
  const RunResult renderRun = test::runShadowlabInTempDir(render);
  ASSERT_EQ(renderRun.exitCode, 0) << renderRun.err;
  const std::vector<NamedImage> buffers = readVti(rendered / "buffers.vti");
  const ImageF& coverage = arrayNamed(buffers, "coverage").image;
  for (const std::string& counter : { std::string("visited_cells"), std::string("contour_edges") })
  {
    const ImageF& image = arrayNamed(buffers, counter).image;
    double total = 0.0;
    for (std::size_t i = 0; i < image.pixelCount(); ++i)
    {
      total += coverage.data[i] > 0.5f ? image.data[i] : 0.0;
    }
    ASSERT_NE(rows[1].at("settings").get<std::string>().find("sublights=2"), std::string::npos) << rows[1].dump();
    EXPECT_NEAR(rows[1].at("result").at("work_counter_sums").at(counter).get<double>(), total, 1e-6 * total) << counter;
  }

  std::ifstream csv(out / "bench.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_NE(header.find(",visited_cells_sum,"), std::string::npos) << header;
  EXPECT_NE(header.find(",contour_edges_sum,"), std::string::npos) << header;
}

TEST(BenchCommand, ViewStatsAreTheBuffersDistributionOverTheViewAgainstTheFirstSweptKey)
{
  // --view-stats (docs/bench/fig18): each configuration's largest, 99th-percentile and mean texel_ratio over the
  // covered pixels the map tests must be those of the buffer `shadowlab render` writes for the same configuration;
  // with a joint sweep of cascades and shadow_map_size (equal total texels) the charts are drawn against cascades.
  const std::filesystem::path out = test::freshOutputDir("bench-view-out");
  const std::filesystem::path cache = test::freshOutputDir("bench-view-cache");
  const std::string scene = test::datasetPath("deep-view").string();
  const RunResult run = test::runShadowlabInTempDir({ "bench", scene, "-t", "hard", "--sweep",
    "cascades+shadow_map_size=1+128,4+64", "--view-stats", "texel_ratio,texel_ratio_t", "-r", "48x32", "--repeat", "1",
    "--reference-samples", "1", "--quiet", "--cache", cache.string(), "--out", out.string() });
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const nlohmann::json rows = readJson(out / "bench.json").at("configurations");
  ASSERT_EQ(rows.size(), 2u);
  const std::filesystem::path rendered = test::freshOutputDir("bench-view-render");
  const RunResult renderRun = test::runShadowlabInTempDir({ "render", scene, "-t", "hard", "-s", "cascades=4", "-s",
    "shadow_map_size=64", "-r", "48x32", "-q", "--out", rendered.string() });
  ASSERT_EQ(renderRun.exitCode, 0) << renderRun.err;
  const std::vector<NamedImage> buffers = readVti(rendered / "buffers.vti");
  const ImageF& coverage = arrayNamed(buffers, "coverage").image;
  const ImageF& ratio = arrayNamed(buffers, "texel_ratio").image;
  std::vector<double> tested;
  for (std::size_t i = 0; i < ratio.pixelCount(); ++i)
  {
    if (coverage.data[i] > 0.5f && ratio.data[i] > 0.0f)
    {
      tested.push_back(ratio.data[i]);
    }
  }
  ASSERT_GT(tested.size(), 300u);
  std::sort(tested.begin(), tested.end());
  double sum = 0.0;
  for (const double value : tested)
  {
    sum += value;
  }
  const nlohmann::json& stats = rows[1].at("result").at("view_stats").at("texel_ratio");
  ASSERT_NE(rows[1].at("settings").get<std::string>().find("cascades=4"), std::string::npos) << rows[1].dump();
  EXPECT_EQ(stats.at("pixels").get<std::size_t>(), tested.size());
  EXPECT_NEAR(stats.at("max").get<double>(), tested.back(), 1e-6 * tested.back());
  EXPECT_NEAR(stats.at("mean").get<double>(), sum / tested.size(), 1e-6 * tested.back());
  const double p99 = tested[static_cast<std::size_t>(std::ceil(0.99 * tested.size())) - 1];
  EXPECT_NEAR(stats.at("p99").get<double>(), p99, 1e-6 * p99);
  EXPECT_LE(rows[1].at("result").at("view_stats").at("texel_ratio_t").at("max").get<double>(), tested.back());

  std::ifstream csv(out / "bench.csv");
  std::string header;
  std::getline(csv, header);
  for (const char* column : { ",texel_ratio_max,", ",texel_ratio_p99,", ",texel_ratio_mean," })
  {
    EXPECT_NE(header.find(column), std::string::npos) << header;
  }
  for (const char* chart : { "view_texel_ratio_deep-view.png", "view_texel_ratio_t_deep-view.png",
         "sweep_above_0.05_deep-view.png" })
  {
    EXPECT_TRUE(std::filesystem::is_regular_file(out / chart)) << chart;
  }
}

TEST(BenchCommand, CutShortPixelsAreAColumnAndAWarningEvenWhenQuiet)
{
  // yfgl09's brute force over ~400-texel kernels at a 1024² map (its default before auto) outruns llvmpipe's loop
  // cap (issue 13): the row's cut_short_pixels column holds the count and bench says so, with --quiet too. The map is
  // given: shadow_map_size=auto would size it to the 16x12 image, whose kernels the cap does not cut.
  const std::filesystem::path out = test::freshOutputDir("bench-cut-out");
  const std::filesystem::path cache = test::freshOutputDir("bench-cut-cache");
  std::vector<std::string> bench = { "bench", test::datasetPath("stacked-occluders").string(), "-t", "yfgl09", "--sweep",
    "hierarchy=off,on", "--set", "shadow_map_size=1024", "-r", "16x12", "--repeat", "1", "--reference-samples", "16",
    "--quiet", "--cache", cache.string(), "--out", out.string() };
  const std::vector<std::string> scene = test::sceneSetArguments(test::wideKernelOverrides());
  bench.insert(bench.end(), scene.begin(), scene.end());
  const RunResult run = test::runShadowlabInTempDir(bench);
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const nlohmann::json rows = readJson(out / "bench.json").at("configurations");
  ASSERT_EQ(rows.size(), 2u);
  const double cut = rows[0].at("result").at("technique_statistics").at("cut_short_pixels").get<double>();
  EXPECT_EQ(rows[1].at("result").at("technique_statistics").at("cut_short_pixels").get<double>(), 0.0) << "hierarchy on";
  if (rows[0].at("result").value("gl_renderer", "").find("llvmpipe") == std::string::npos)
  {
    GTEST_SKIP() << "no loop cap on this GL";
  }
  EXPECT_GT(cut, 0.0);
  EXPECT_NE(run.err.find("hierarchy=off on stacked-occluders"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("pixel(s) cut short"), std::string::npos) << run.err;
  EXPECT_EQ(run.err.find("hierarchy=on on"), std::string::npos) << run.err << ": only the row with cut pixels is named";
  std::ifstream csv(out / "bench.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_NE(header.find(",cut_short_pixels"), std::string::npos) << header;
}

TEST(SceneOverrides, BadPointersAndValuesAreOneLineErrors)
{
  const std::filesystem::path out = test::freshOutputDir("scene-set-bad");
  for (const std::string& override : { std::string("/lights/9/size=2"), std::string("/lights/0/size=0"),
         std::string("lights/0/size=2") })
  {
    const RunResult run = test::runShadowlabInTempDir({ "render", test::datasetPath("planar-occluder").string(), "--scene-set", override,
      "-r", "32x32", "--out", out.string() });
    EXPECT_EQ(run.exitCode, 1) << override;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << override;
  }
}

TEST(BenchCommand, DepthProfileAndJointSweepWriteOneRowPerConfigurationAndBin)
{
  // Two configurations from one joint sweep (warp and warp_n together), texel_ratio_t profiled over 20 bins on
  // facing-tiles: depth_profile.csv has 2 x 20 rows, each bin one tile's pixels, and the Fig. 12 closed form beside
  // the median within the 3 % WarpFig12 holds them to; the chart is written.
  const std::filesystem::path out = test::freshOutputDir("bench-profile-out");
  const std::filesystem::path cache = test::freshOutputDir("bench-profile-cache");
  const RunResult run = test::runShadowlabInTempDir({ "bench", test::datasetPath("facing-tiles").string(), "-t", "hard",
    "-s", "shadow_map_size=256", "--sweep", "warp+warp_n=lispsm+1e6,lispsm+0", "--depth-profile", "texel_ratio_t",
    "--depth-bins", "20", "--depth-range", "1,100", "--repeat", "1", "-r", "128x32", "--reference-samples", "1", "--quiet",
    "--cache", cache.string(), "--out", out.string() });
  ASSERT_EQ(run.exitCode, 0) << run.err;
  std::vector<std::string> lines;
  std::ifstream csv(out / "depth_profile.csv");
  for (std::string line; std::getline(csv, line);)
  {
    lines.push_back(line);
  }
  ASSERT_EQ(lines.size(), 41u);
  EXPECT_EQ(lines[0].rfind("scene,scene_overrides,technique,settings,buffer,bin,", 0), 0u) << lines[0];
  EXPECT_NE(lines[1].find("warp=lispsm warp_n=1e6"), std::string::npos) << lines[1];
  EXPECT_NE(lines[21].find("warp=lispsm warp_n=0"), std::string::npos) << lines[21];
  for (std::size_t i = 1; i < lines.size(); ++i)
  {
    std::vector<std::string> cells;
    std::stringstream row(lines[i]);
    for (std::string cell; std::getline(row, cell, ',');)
    {
      cells.push_back(cell);
    }
    ASSERT_EQ(cells.size(), 19u) << lines[i];
    EXPECT_GT(std::stoi(cells[8]), 0) << "every bin holds a tile: " << lines[i];
    EXPECT_NEAR(std::stod(cells[14]), 1.0, 0.03) << "median over the closed form: " << lines[i];
  }
  EXPECT_TRUE(std::filesystem::is_regular_file(out / "depth_profile_facing-tiles.png"));
}

TEST(BenchCommand, BadArgumentsFailBeforeRunningAnything)
{
  const std::filesystem::path out = test::freshOutputDir("bench-bad");
  for (const auto& [option, value] : { std::pair<std::string, std::string>("-t", "hard,nope"),
         { "--sweep", "kernel_texels" }, { "--sweep", "kernel_texels=0,3" }, { "--repeat", "0" },
         { "--sweep", "kernel_texels+nope=3+1" }, { "--sweep", "kernel_texels+bias_slope_texels=3+1,5" },
         { "--depth-bins", "0" }, { "--depth-range", "10,1" }, { "--view-stats", "texel_ratio,,texel_ratio_t" } })
  {
    const RunResult run = test::runShadowlabInTempDir({ "bench", test::datasetPath("planar-occluder").string(), option, value, "-r",
      "32x32", "--out", out.string() });
    EXPECT_EQ(run.exitCode, 1) << option << " " << value << ": " << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << option << " " << value;
  }
}

} // namespace
} // namespace sl
