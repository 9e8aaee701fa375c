// shadowlab bench as a results section (issue 31 item 1): the spread of the timed frames, the renderer and the
// machine, penumbra and percentile errors, the light-space structures' memory, every counter in bench.json, and the
// charts and thumbnail strips, from one small bench run end to end.
#include "io/ImageIO.h"
#include "support/CliRun.h"
#include "support/TempDir.h"
#include "support/TestSupport.h"
#include "vis/ColorMap.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace sl
{
namespace
{

// The cells of one bench.csv line, a quoted cell ("llvmpipe (LLVM 15.0.6, 256 bits)") unquoted.
std::vector<std::string> benchReportCells(const std::string& line)
{
  std::vector<std::string> cells(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i)
  {
    const char c = line[i];
    if (c == '"')
    {
      if (quoted && i + 1 < line.size() && line[i + 1] == '"')
      {
        cells.back() += '"';
        ++i;
      }
      else
      {
        quoted = !quoted;
      }
    }
    else if (c == ',' && !quoted)
    {
      cells.emplace_back();
    }
    else
    {
      cells.back() += c;
    }
  }
  return cells;
}

// The nearest-rank 99th percentile, as the bench documents it.
double benchReportP99(std::vector<double> values)
{
  std::sort(values.begin(), values.end());
  const std::size_t rank = static_cast<std::size_t>(std::ceil(0.99 * static_cast<double>(values.size())));
  return values[std::max<std::size_t>(rank, 1) - 1];
}

// Pixels of `image` within 3 of `color` in every channel.
std::size_t benchReportPixelsOf(const ImageU8& image, const RgbColor& color)
{
  std::size_t count = 0;
  for (std::size_t i = 0; i + 2 < image.data.size(); i += 3)
  {
    bool same = true;
    for (int c = 0; c < 3; ++c)
    {
      same = same && std::abs(static_cast<int>(image.data[i + c]) - static_cast<int>(std::lround(255 * color[c]))) <= 3;
    }
    count += same ? 1 : 0;
  }
  return count;
}

std::size_t benchReportDistinctColors(const ImageU8& image)
{
  std::set<int> colors;
  for (std::size_t i = 0; i + 2 < image.data.size(); i += 3)
  {
    colors.insert((image.data[i] << 16) | (image.data[i + 1] << 8) | image.data[i + 2]);
  }
  return colors.size();
}

TEST(BenchReport, SpreadRendererErrorsMemoryCountersChartsAndThumbnails)
{
  const std::filesystem::path out = test::freshOutputDir("bench-report-out");
  const std::filesystem::path cache = test::freshOutputDir("bench-report-cache");
  const std::string scene = test::datasetPath("planar-occluder").string();
  const RunResult run = test::runShadowlabInTempDir({ "bench", scene, "-t", "hard,vsm", "--sweep",
    "shadow_map_size=128,256", "--repeat", "3", "-r", "96x96", "--samples", "64", "--quiet", "--cache", cache.string(),
    "--out", out.string() });
  ASSERT_EQ(run.exitCode, 0) << run.err;

  // bench.json: the renderer and machine; per row every timed frame, whose min / median / max the row states, and
  // every counter.
  const nlohmann::json bench = test::readJson(out / "bench.json");
  const std::string renderer = bench.at("renderer").get<std::string>();
  ASSERT_FALSE(renderer.empty());
  EXPECT_GT(bench.at("machine").at("logical_cores").get<int>(), 0);
  const nlohmann::json& rows = bench.at("configurations");
  ASSERT_EQ(rows.size(), 4u);
  std::map<std::string, double> structureBytes; // "technique size" -> bytes
  for (const nlohmann::json& row : rows)
  {
    ASSERT_EQ(row.at("status"), "ok") << row.dump();
    const nlohmann::json& result = row.at("result");
    std::vector<double> frames = result.at("frame_gpu_ms_samples").get<std::vector<double>>();
    ASSERT_EQ(frames.size(), 3u);
    std::sort(frames.begin(), frames.end());
    EXPECT_DOUBLE_EQ(result.at("frame_gpu_ms_min").get<double>(), frames[0]);
    EXPECT_DOUBLE_EQ(result.at("frame_gpu_ms").get<double>(), frames[1]);
    EXPECT_DOUBLE_EQ(result.at("frame_gpu_ms_max").get<double>(), frames[2]);
    for (const auto& [stage, timing] : result.at("stages").items())
    {
      EXPECT_LE(timing.at("gpu_ms_min").get<double>(), timing.at("gpu_ms").get<double>()) << stage;
      EXPECT_LE(timing.at("gpu_ms").get<double>(), timing.at("gpu_ms_max").get<double>()) << stage;
    }
    EXPECT_EQ(result.at("gl_renderer").get<std::string>(), renderer);
    double bytes = 0.0;
    for (const auto& [name, value] : result.at("light_structure_gpu_bytes").items())
    {
      bytes += value.get<double>();
    }
    EXPECT_GT(bytes, 0.0) << row.dump();
    EXPECT_EQ(result.at("light_structure_gpu_bytes_total").get<double>(), bytes);
    structureBytes[row.at("technique").get<std::string>() + " " + row.at("settings").get<std::string>()] = bytes;
    for (const auto& [name, value] : result.at("technique_statistics").items())
    {
      EXPECT_EQ(row.at("statistics").at(name), value) << name << ": bench.json rows hold every counter";
    }
    const nlohmann::json& covered = result.at("error").at("covered");
    EXPECT_LE(covered.at("p99_abs_error").get<double>(), covered.at("max_abs_error").get<double>());
    EXPECT_GT(result.at("error").at("penumbra").at("pixels").get<double>(), 0.0);
  }
  // A map twice as wide holds four times the texels (the moments' mip chain keeps that ratio).
  for (const std::string technique : { "hard", "vsm" })
  {
    const double ratio =
      structureBytes.at(technique + " shadow_map_size=256") / structureBytes.at(technique + " shadow_map_size=128");
    EXPECT_NEAR(ratio, 4.0, 0.05) << technique;
  }

  // The 99th-percentile errors are those of the frame `render` makes, against the cached reference.
  const std::filesystem::path rendered = test::freshOutputDir("bench-report-render");
  const RunResult renderRun = test::runShadowlabInTempDir(
    { "render", scene, "-t", "hard", "-s", "shadow_map_size=256", "-r", "96x96", "-q", "--out", rendered.string() });
  ASSERT_EQ(renderRun.exitCode, 0) << renderRun.err;
  std::filesystem::path referenceFile;
  for (const auto& entry : std::filesystem::directory_iterator(cache))
  {
    referenceFile = entry.path() / "buffers.vti";
  }
  const std::vector<NamedImage> renderedBuffers = readVti(rendered / "buffers.vti");
  const std::vector<NamedImage> reference = readVti(referenceFile);
  const ImageF& visibility = test::arrayNamed(renderedBuffers, "visibility").image;
  const ImageF& coverage = test::arrayNamed(renderedBuffers, "coverage").image;
  const ImageF& referenceVisibility = test::arrayNamed(reference, "visibility").image;
  const ImageF& referenceCoverage = test::arrayNamed(reference, "coverage").image;
  std::vector<double> coveredErrors;
  std::vector<double> penumbraErrors;
  for (std::size_t i = 0; i < visibility.pixelCount(); ++i)
  {
    if (coverage.data[i] > 0.5f && referenceCoverage.data[i] > 0.5f)
    {
      const double error = std::abs(static_cast<double>(visibility.data[i]) - referenceVisibility.data[i]);
      coveredErrors.push_back(error);
      if (referenceVisibility.data[i] > 0.0f && referenceVisibility.data[i] < 1.0f)
      {
        penumbraErrors.push_back(error);
      }
    }
  }
  const nlohmann::json& hardError = rows[1].at("result").at("error");
  ASSERT_EQ(rows[1].at("settings"), "shadow_map_size=256");
  EXPECT_NEAR(hardError.at("covered").at("p99_abs_error").get<double>(), benchReportP99(coveredErrors), 1e-6);
  EXPECT_NEAR(hardError.at("penumbra").at("p99_abs_error").get<double>(), benchReportP99(penumbraErrors), 1e-6);
  EXPECT_LT(benchReportP99(coveredErrors), 1.0) << "hard shadows' largest error is 1 at a silhouette, not its p99";

  // bench.csv: the spread and error columns, min <= median <= max in every row.
  std::ifstream csv(out / "bench.csv");
  std::string line;
  std::getline(csv, line);
  const std::vector<std::string> header = benchReportCells(line);
  std::map<std::string, std::size_t> column;
  for (std::size_t i = 0; i < header.size(); ++i)
  {
    column[header[i]] = i;
  }
  for (const char* name : { "frame_gpu_ms", "frame_gpu_ms_min", "frame_gpu_ms_max", "frame_wall_ms_min",
         "shadow_map_gpu_ms_min", "shadow_map_gpu_ms_max", "rmse", "penumbra_rmse", "p99_abs_error",
         "penumbra_p99_abs_error", "fraction_above_0.05", "max_abs_error", "light_structure_gpu_bytes", "renderer" })
  {
    EXPECT_TRUE(column.count(name)) << name << " in " << line;
  }
  int dataRows = 0;
  while (std::getline(csv, line))
  {
    const std::vector<std::string> cells = benchReportCells(line);
    ASSERT_EQ(cells.size(), header.size()) << line;
    ++dataRows;
    for (const std::string stem : { "frame_gpu_ms", "frame_wall_ms", "shadow_map_gpu_ms" })
    {
      const double low = std::stod(cells[column.at(stem + "_min")]);
      const double middle = std::stod(cells[column.at(stem)]);
      const double high = std::stod(cells[column.at(stem + "_max")]);
      EXPECT_LE(low, middle) << stem << ": " << line;
      EXPECT_LE(middle, high) << stem << ": " << line;
    }
    EXPECT_GT(std::stod(cells[column.at("light_structure_gpu_bytes")]), 0.0) << line;
    EXPECT_EQ(cells[column.at("renderer")], renderer) << line;
  }
  EXPECT_EQ(dataRows, 4);

  // summary.md names the renderer and the machine, and every row's statistics cell holds at most three counters.
  std::ifstream summaryFile(out / "summary.md");
  const std::string summary((std::istreambuf_iterator<char>(summaryFile)), std::istreambuf_iterator<char>());
  EXPECT_NE(summary.find("Renderer: " + renderer), std::string::npos) << summary;
  EXPECT_NE(summary.find("logical cores"), std::string::npos) << summary;
  EXPECT_NE(summary.find("penumbra p99"), std::string::npos) << summary;

  // The charts exist and are drawn; the stage chart's bars carry each stage's colour over many pixels; no thumbnail
  // input is left behind.
  for (const char* chart : { "stages_planar-occluder.png", "speed_vs_error_planar-occluder.png",
         "speed_vs_penumbra_error_planar-occluder.png", "thumbnails_planar-occluder.png",
         "cost_growth_planar-occluder.png" })
  {
    ASSERT_TRUE(std::filesystem::is_regular_file(out / chart)) << chart;
    const ImageU8 image = readPng(out / chart);
    EXPECT_GT(image.width, 200) << chart;
    EXPECT_GT(benchReportDistinctColors(image), 20u) << chart << " is blank";
    EXPECT_NE(summary.find(chart), std::string::npos) << chart << " is listed in summary.md";
  }
  const ImageU8 stages = readPng(out / "stages_planar-occluder.png");
  // The chart stacks the stages that ran in pipeline order: gbuffer, focus, shadow_map, moment_map (a large share of
  // vsm's frame at 256: measured 33-60 % on the loaded 2-core machine), technique, shading; the legend's swatches are
  // far smaller.
  ASSERT_GT(rows[3].at("result").at("stages").at("moment_map").at("gpu_ms").get<double>(),
    0.15 * rows[3].at("result").at("frame_gpu_ms").get<double>());
  EXPECT_GT(benchReportPixelsOf(stages, ColorMap::categoryColor(3)), 1000u) << "moment_map bars";
  EXPECT_GT(benchReportPixelsOf(stages, ColorMap::categoryColor(0)), 1000u) << "gbuffer bars";
  for (const auto& entry : std::filesystem::directory_iterator(out / "runs"))
  {
    EXPECT_EQ(entry.path().extension(), ".json") << entry.path();
  }
}

// bench.csv as a table: the header's column indices and every data row's cells.
struct BenchReportTable
{
  std::map<std::string, std::size_t> column;
  std::vector<std::vector<std::string>> rows;

  const std::string& cell(std::size_t row, const std::string& name) const
  {
    EXPECT_TRUE(column.count(name)) << name;
    return rows.at(row).at(column.at(name));
  }
};

BenchReportTable benchReportTable(const std::filesystem::path& file)
{
  BenchReportTable table;
  std::ifstream csv(file);
  std::string line;
  std::getline(csv, line);
  const std::vector<std::string> header = benchReportCells(line);
  for (std::size_t i = 0; i < header.size(); ++i)
  {
    table.column[header[i]] = i;
  }
  while (std::getline(csv, line))
  {
    table.rows.push_back(benchReportCells(line));
    EXPECT_EQ(table.rows.back().size(), header.size()) << line;
  }
  return table;
}

std::string benchReportText(const std::filesystem::path& file)
{
  std::ifstream stream(file);
  return std::string((std::istreambuf_iterator<char>(stream)), std::istreambuf_iterator<char>());
}

// The chart exists, is drawn (not one colour) and summary.md lists it.
void expectBenchReportChart(const std::filesystem::path& dir, const std::string& chart, const std::string& summary)
{
  ASSERT_TRUE(std::filesystem::is_regular_file(dir / chart)) << chart;
  const ImageU8 image = readPng(dir / chart);
  EXPECT_GT(image.width, 200) << chart;
  EXPECT_GT(benchReportDistinctColors(image), 20u) << chart << " is blank";
  EXPECT_NE(summary.find(chart), std::string::npos) << chart << " is listed in summary.md";
}

// Issue 33 items 2-3: -r with several sizes runs every configuration at each (a reference per size), the size is a
// column, the charts are per size, and the cost grows on cost_growth_pixels_<scene>.png and in cost_growth.csv with
// each structure's build time (the stages of its build passes) and bytes.
TEST(BenchReport, SeveralSizesGiveRowsPerSizeCostGrowthAndStructureColumns)
{
  const std::filesystem::path out = test::freshOutputDir("bench-sizes-out");
  const std::filesystem::path cache = test::freshOutputDir("bench-sizes-cache");
  const std::string scene = test::datasetPath("planar-occluder").string();
  const RunResult run = test::runShadowlabInTempDir({ "bench", scene, "-t", "hard,pcf", "-r", "64x64,96x96",
    "--set", "shadow_map_size=256", "--repeat", "1", "--reference-samples", "16", "--quiet", "--cache",
    cache.string(), "--out", out.string() });
  ASSERT_EQ(run.exitCode, 0) << run.err;

  // A reference per size, of that size.
  std::set<int> referenceWidths;
  for (const auto& entry : std::filesystem::directory_iterator(cache))
  {
    const std::vector<NamedImage> reference = readVti(entry.path() / "buffers.vti");
    referenceWidths.insert(test::arrayNamed(reference, "visibility").image.width);
  }
  EXPECT_EQ(referenceWidths, (std::set<int>{ 64, 96 }));

  // Every configuration at every size; the size a field and a column, the frame of that size.
  const nlohmann::json bench = test::readJson(out / "bench.json");
  EXPECT_EQ(bench.at("resolutions"), (nlohmann::json{ "64x64", "96x96" }));
  const nlohmann::json& rows = bench.at("configurations");
  ASSERT_EQ(rows.size(), 4u);
  std::map<std::string, int> perSize;
  for (const nlohmann::json& row : rows)
  {
    ASSERT_EQ(row.at("status"), "ok") << row.dump();
    const std::string size = row.at("resolution").get<std::string>();
    ++perSize[size + " " + row.at("technique").get<std::string>()];
    const int side = size == "64x64" ? 64 : 96;
    EXPECT_EQ(row.at("result").at("resolution"), (nlohmann::json{ side, side })) << size;
  }
  EXPECT_EQ(perSize, (std::map<std::string, int>{ { "64x64 hard", 1 }, { "64x64 pcf", 1 }, { "96x96 hard", 1 },
                       { "96x96 pcf", 1 } }));

  // The shadow map's build is its focus and shadow_map stages; its bytes those the frame reports.
  const BenchReportTable csv = benchReportTable(out / "bench.csv");
  ASSERT_EQ(csv.rows.size(), 4u);
  for (std::size_t r = 0; r < csv.rows.size(); ++r)
  {
    EXPECT_EQ(csv.cell(r, "resolution"), rows[r].at("resolution").get<std::string>());
    const nlohmann::json& stages = rows[r].at("result").at("stages");
    const double expectedMs = stages.at("focus").at("gpu_ms").get<double>() +
      stages.at("shadow_map").at("gpu_ms").get<double>();
    EXPECT_NEAR(std::stod(csv.cell(r, "shadow_map_build_gpu_ms")), expectedMs, 1e-4 * expectedMs + 1e-6) << r;
    EXPECT_NEAR(std::stod(csv.cell(r, "structures_build_gpu_ms")), expectedMs, 1e-4 * expectedMs + 1e-6) << r;
    const double bytes = rows[r].at("result").at("light_structure_gpu_bytes").at("shadow_map").get<double>();
    EXPECT_GT(bytes, 0.0);
    EXPECT_EQ(std::stod(csv.cell(r, "shadow_map_gpu_bytes")), bytes) << r;
    EXPECT_NEAR(rows[r].at("structures").at("shadow_map").at("build_gpu_ms").get<double>(), expectedMs,
      1e-9 + 1e-9 * expectedMs);
  }

  // cost_growth.csv: a row per configuration, the pixel count of its size, its frame and technique-pass times.
  const BenchReportTable growth = benchReportTable(out / "cost_growth.csv");
  ASSERT_EQ(growth.rows.size(), 4u);
  for (std::size_t r = 0; r < growth.rows.size(); ++r)
  {
    const nlohmann::json& result = rows[r].at("result");
    EXPECT_EQ(growth.cell(r, "pixels"), rows[r].at("resolution") == "64x64" ? "4096" : "9216") << r;
    EXPECT_EQ(growth.cell(r, "shadow_map_size"), "256") << r;
    // The map the frame rendered, where bench-run reports it (given here: the size set).
    EXPECT_EQ(growth.cell(r, "shadow_map_size_chosen"), result.contains("shadow_map_size_chosen") ? "256" : "") << r;
    EXPECT_NEAR(std::stod(growth.cell(r, "frame_gpu_ms")), result.at("frame_gpu_ms").get<double>(),
      1e-5 * result.at("frame_gpu_ms").get<double>());
    EXPECT_NEAR(std::stod(growth.cell(r, "technique_gpu_ms")),
      result.at("stages").at("technique").at("gpu_ms").get<double>(),
      1e-5 * result.at("stages").at("technique").at("gpu_ms").get<double>());
    EXPECT_EQ(growth.cell(r, "shadow_map_gpu_bytes"), csv.cell(r, "shadow_map_gpu_bytes"));
  }

  const std::string summary = benchReportText(out / "summary.md");
  EXPECT_NE(summary.find("Resolutions 64x64, 96x96"), std::string::npos) << summary;
  EXPECT_NE(summary.find("structures ms (share of frame)"), std::string::npos) << summary;
  EXPECT_NE(summary.find(": shadow_map "), std::string::npos) << "the largest structure is named\n" << summary;
  // "warm frame ms" where bench-run writes warm frames (a build with light-space reuse), with the first row's spread.
  const nlohmann::json& first = rows[0].at("result");
  EXPECT_EQ(summary.find("| warm frame ms |") != std::string::npos, first.contains("warm_frame_gpu_ms")) << summary;
  if (first.contains("warm_frame_gpu_ms"))
  {
    std::ostringstream warmCell;
    warmCell << std::fixed << std::setprecision(2) << "| " << first.at("warm_frame_gpu_ms").get<double>() << " ("
             << first.at("warm_frame_gpu_ms_min").get<double>() << "-" << first.at("warm_frame_gpu_ms_max").get<double>()
             << ") |";
    EXPECT_NE(summary.find(warmCell.str()), std::string::npos) << warmCell.str() << "\n" << summary;
    EXPECT_NEAR(std::stod(csv.cell(0, "warm_frame_gpu_ms")), first.at("warm_frame_gpu_ms").get<double>(),
      1e-5 * first.at("warm_frame_gpu_ms").get<double>());
  }
  // The cost-growth table: per configuration its exponent k of frame ms ~ pixels^k, through its two sizes' times.
  const std::string growthRow = "| planar-occluder | pcf shadow_map_size=256 | ";
  const std::size_t growthAt = summary.find(growthRow);
  ASSERT_NE(growthAt, std::string::npos) << summary;
  const std::string growthLine = summary.substr(growthAt, summary.find('\n', growthAt) - growthAt);
  const double pcfFrame64 = rows[1].at("result").at("frame_gpu_ms").get<double>();
  const double pcfFrame96 = rows[3].at("result").at("frame_gpu_ms").get<double>();
  ASSERT_EQ(rows[3].at("technique"), "pcf");
  const double exponent = std::log(pcfFrame96 / pcfFrame64) / std::log(9216.0 / 4096.0);
  std::ostringstream expected;
  expected << std::fixed << std::setprecision(2) << exponent;
  EXPECT_NE(growthLine.find(" | " + expected.str() + " | "), std::string::npos) << growthLine << " vs k " << exponent;
  for (const std::string chart : { "cost_growth_pixels_planar-occluder.png", "cost_growth_pass_pixels_planar-occluder.png",
         "stages_planar-occluder_64x64.png", "stages_planar-occluder_96x96.png",
         "speed_vs_error_planar-occluder_64x64.png", "speed_vs_error_planar-occluder_96x96.png",
         "thumbnails_planar-occluder_96x96.png" })
  {
    expectBenchReportChart(out, chart, summary);
  }
  EXPECT_FALSE(std::filesystem::exists(out / "stages_planar-occluder.png")) << "charts are per size";
}

// Issue 33's "error no worse at the new defaults": --baseline flags a configuration whose RMSE grew (hard shadows
// with a 32-texel map against a 512-texel one), flags nothing in an identical re-run, and says "no baseline row"
// for a size the baseline did not run.
TEST(BenchReport, BaselineFlagsAWorseConfigurationAndNotAnIdenticalRerun)
{
  const std::filesystem::path cache = test::freshOutputDir("bench-baseline-cache");
  const std::string scene = test::datasetPath("planar-occluder").string();
  const auto bench = [&](const std::string& name, const std::string& mapSize, const std::string& sizes,
                       const std::vector<std::string>& more) {
    const std::filesystem::path out = test::freshOutputDir(name);
    std::vector<std::string> arguments{ "bench", scene, "-t", "hard,pcf", "-r", sizes, "--set",
      "shadow_map_size=" + mapSize, "--repeat", "1", "--reference-samples", "16", "--quiet", "--cache",
      cache.string(), "--out", out.string() };
    arguments.insert(arguments.end(), more.begin(), more.end());
    const RunResult run = test::runShadowlabInTempDir(arguments);
    EXPECT_EQ(run.exitCode, 0) << run.err;
    return out;
  };
  const std::filesystem::path base = bench("bench-baseline-base", "512", "64x64", {});
  const std::filesystem::path coarse = bench("bench-baseline-coarse", "32", "64x64", { "--baseline", base.string() });
  const std::filesystem::path again =
    bench("bench-baseline-again", "512", "64x64,96x96", { "--baseline", base.string() });

  const nlohmann::json baseRows = test::readJson(base / "bench.json").at("configurations");
  const nlohmann::json coarseRows = test::readJson(coarse / "bench.json").at("configurations");
  ASSERT_EQ(baseRows.size(), 2u);
  ASSERT_EQ(coarseRows.size(), 2u);
  ASSERT_EQ(coarseRows[0].at("technique"), "hard");
  const double baseRmse = baseRows[0].at("result").at("error").at("covered").at("rmse").get<double>();
  const double coarseRmse = coarseRows[0].at("result").at("error").at("covered").at("rmse").get<double>();
  ASSERT_GT(coarseRmse - baseRmse, std::max(1e-4, 0.01 * baseRmse))
    << "a 32-texel map must be measurably worse for the test to mean anything";
  const nlohmann::json& flagged = coarseRows[0].at("baseline");
  EXPECT_EQ(flagged.at("worse"), true) << flagged.dump();
  EXPECT_DOUBLE_EQ(flagged.at("rmse").get<double>(), std::stod(benchReportTable(base / "bench.csv").cell(0, "rmse")));
  const BenchReportTable coarseCsv = benchReportTable(coarse / "bench.csv");
  EXPECT_NEAR(std::stod(coarseCsv.cell(0, "baseline_rmse")), baseRmse, 1e-5 * baseRmse);
  EXPECT_NEAR(std::stod(coarseCsv.cell(0, "rmse_delta")), coarseRmse - baseRmse, 1e-5 * coarseRmse);
  const std::string coarseSummary = benchReportText(coarse / "summary.md");
  EXPECT_NE(coarseSummary.find("Error against the baseline"), std::string::npos) << coarseSummary;
  EXPECT_NE(coarseSummary.find("more than 0.0001 absolute and by more than 1 %"), std::string::npos) << coarseSummary;
  EXPECT_NE(coarseSummary.find("**worse**"), std::string::npos) << coarseSummary;

  // The identical re-run: the same errors, nothing worse; the size the baseline lacks has no row to compare with.
  const nlohmann::json againRows = test::readJson(again / "bench.json").at("configurations");
  ASSERT_EQ(againRows.size(), 4u);
  int compared = 0;
  for (const nlohmann::json& row : againRows)
  {
    const nlohmann::json& match = row.at("baseline");
    if (row.at("resolution") == "96x96")
    {
      EXPECT_EQ(match.at("problem"), "no baseline row") << row.dump();
      continue;
    }
    ++compared;
    EXPECT_EQ(match.at("worse"), false) << match.dump();
    EXPECT_EQ(match.at("rmse_delta").get<double>(), 0.0) << match.dump();
  }
  EXPECT_EQ(compared, 2);
  const std::string againSummary = benchReportText(again / "summary.md");
  EXPECT_EQ(againSummary.find("**worse**"), std::string::npos) << againSummary;
  EXPECT_NE(againSummary.find("no baseline row"), std::string::npos) << againSummary;
  EXPECT_NE(againSummary.find("0 of 2 compared configuration(s) worse"), std::string::npos) << againSummary;

  // A run sweeping the map size matches its baseline row by all settings where the swept value is the one the
  // baseline set for every row; the other value has no row to compare with.
  const std::filesystem::path swept = test::freshOutputDir("bench-baseline-swept");
  const RunResult sweptRun = test::runShadowlabInTempDir({ "bench", scene, "-t", "hard", "-r", "64x64", "--sweep",
    "shadow_map_size=512,32", "--repeat", "1", "--reference-samples", "16", "--quiet", "--cache", cache.string(),
    "--out", swept.string(), "--baseline", base.string() });
  ASSERT_EQ(sweptRun.exitCode, 0) << sweptRun.err;
  const nlohmann::json sweptRows = test::readJson(swept / "bench.json").at("configurations");
  ASSERT_EQ(sweptRows.size(), 2u);
  EXPECT_EQ(sweptRows[0].at("baseline").at("rmse_delta").get<double>(), 0.0) << sweptRows[0].at("baseline").dump();
  EXPECT_EQ(sweptRows[1].at("baseline").at("problem"), "no baseline row") << sweptRows[1].at("baseline").dump();
}

// A --baseline that is not a bench's output: one line naming it, and no output written (not even the cache).
TEST(BenchReport, BadBaselineIsOneLineAndWritesNothing)
{
  const test::TempDir temp;
  const std::string scene = test::datasetPath("planar-occluder").string();
  const std::filesystem::path empty = temp.path() / "not-a-bench";
  std::filesystem::create_directories(empty);
  const std::filesystem::path missing = temp.path() / "missing";
  for (const std::filesystem::path& dir : { missing, empty })
  {
    const RunResult run = test::runShadowlabInTempDir({ "bench", scene, "-t", "hard", "-r", "64x64", "--baseline",
      dir.string(), "--cache", (temp.path() / "cache").string(), "--out", (temp.path() / "out").string() });
    EXPECT_NE(run.exitCode, 0) << run.describe();
    EXPECT_EQ(run.errLines(), 1u) << run.describe();
    EXPECT_NE(run.err.find("--baseline " + dir.string()), std::string::npos) << run.describe();
    EXPECT_FALSE(std::filesystem::exists(temp.path() / "out")) << run.describe();
    EXPECT_FALSE(std::filesystem::exists(temp.path() / "cache")) << run.describe();
  }
}

} // namespace
} // namespace sl
