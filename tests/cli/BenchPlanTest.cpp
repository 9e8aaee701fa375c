// bench --plan / --collect and the tiled reference (issue 32), end to end through the executable: the plan's job
// lines run one after another with bash (as a Slurm array task or GNU parallel would run each), the collected
// bench equals a direct bench, a missing task is named and listed for a resubmit, and a reference traced in row
// tiles and merged equals the single-process one bit for bit.
#include "support/CliRun.h"
#include "support/TempDir.h"
#include "support/TestSupport.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

namespace sl
{
namespace
{

// Runs `script` (a job list) with bash; its exit status.
int runJobList(const std::filesystem::path& list)
{
  const int status = std::system(("bash " + test::shellQuote(list.string()) + " </dev/null").c_str());
  return status != -1 && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::size_t lineCount(const std::filesystem::path& file)
{
  const std::string text = test::readFile(file);
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

// The visibility-derived numbers of a bench.json row (its error metrics); times aside.
nlohmann::json planTestMetricsOf(const nlohmann::json& row)
{
  return { { "technique", row.at("technique") }, { "settings", row.at("settings") },
    { "status", row.at("status") }, { "error", row.at("result").at("error") },
    { "statistics", row.at("result").value("technique_statistics", nlohmann::json::object()) } };
}

const std::vector<std::string> kPlanTestBench = { "-t", "hard,pcf", "--resolution", "48x32", "--reference-samples",
  "16",
  "--repeat", "1", "--quiet" };

TEST(BenchPlan, JobLinesRunAndTheCollectedBenchEqualsADirectOne)
{
  const test::TempDir temp;
  const std::string scenes[] = { test::datasetPath("planar-occluder").string(),
    test::datasetPath("stacked-occluders").string() };
  std::vector<std::string> plan = { "bench", scenes[0], scenes[1], "--plan", (temp.path() / "plan").string(), "--cache",
    (temp.path() / "plan-cache").string(), "--reference-tiles", "2", "--slurm-partition", "gpu", "--slurm-time",
    "0:30:00", "--slurm-gpus", "1", "--slurm-throttle", "8" };
  plan.insert(plan.end(), kPlanTestBench.begin(), kPlanTestBench.end());
  const test::RunResult planned = test::runShadowlabInTempDir(plan);
  ASSERT_EQ(planned.exitCode, 0) << planned.describe();
  // 2 scenes: 2 x 2 tiles, 2 merges, 2 x 2 configurations.
  EXPECT_EQ(lineCount(temp.path() / "plan" / "references.txt"), 4u);
  EXPECT_EQ(lineCount(temp.path() / "plan" / "merges.txt"), 2u);
  EXPECT_EQ(lineCount(temp.path() / "plan" / "configurations.txt"), 4u);
  EXPECT_EQ(lineCount(temp.path() / "plan" / "jobs.txt"), 10u);
  const std::string sbatch = test::readFile(temp.path() / "plan" / "task.sbatch");
  for (const char* line : { "#SBATCH --partition=gpu", "#SBATCH --time=0:30:00", "#SBATCH --gres=gpu:1" })
  {
    EXPECT_NE(sbatch.find(line), std::string::npos) << line << " not in\n" << sbatch;
  }
  EXPECT_NE(test::readFile(temp.path() / "plan" / "submit.sh").find("throttle=8"), std::string::npos);

  ASSERT_EQ(runJobList(temp.path() / "plan" / "jobs.txt"), 0);
  const test::RunResult collected = test::runShadowlabInTempDir(
    { "bench", "--collect", (temp.path() / "plan").string(), "--out", (temp.path() / "collected").string(), "-q" });
  ASSERT_EQ(collected.exitCode, 0) << collected.describe();
  EXPECT_TRUE(collected.err.empty()) << collected.err;

  std::vector<std::string> direct = { "bench", scenes[0], scenes[1], "--cache", (temp.path() / "direct-cache").string(),
    "--out", (temp.path() / "direct").string() };
  direct.insert(direct.end(), kPlanTestBench.begin(), kPlanTestBench.end());
  const test::RunResult run = test::runShadowlabInTempDir(direct);
  ASSERT_EQ(run.exitCode, 0) << run.describe();

  const nlohmann::json collectedRows = test::readJson(temp.path() / "collected" / "bench.json").at("configurations");
  const nlohmann::json directRows = test::readJson(temp.path() / "direct" / "bench.json").at("configurations");
  ASSERT_EQ(collectedRows.size(), 4u);
  ASSERT_EQ(directRows.size(), collectedRows.size());
  for (std::size_t c = 0; c < directRows.size(); ++c)
  {
    EXPECT_EQ(planTestMetricsOf(collectedRows[c]), planTestMetricsOf(directRows[c])) << "configuration " << c;
  }
  EXPECT_GT(collectedRows[1].at("result").at("error").at("penumbra").at("pixels").get<double>(), 0.0)
    << "pcf on planar-occluder has a penumbra: the comparison is not of empty metrics";
  // The same outputs as the bench's (charts, thumbnail strips, runs/), through the same code.
  EXPECT_EQ(test::entriesOf(temp.path() / "collected"), test::entriesOf(temp.path() / "direct"));
  EXPECT_EQ(test::entriesOf(temp.path() / "collected" / "runs"), test::entriesOf(temp.path() / "direct" / "runs"));
  // The tiled and merged cache entries are the direct bench's single-process references, byte for byte.
  std::size_t entries = 0;
  for (const auto& entry : std::filesystem::directory_iterator(temp.path() / "direct-cache"))
  {
    const std::filesystem::path planned = temp.path() / "plan-cache" / entry.path().filename() / "buffers.vti";
    ASSERT_TRUE(std::filesystem::is_regular_file(planned)) << planned;
    EXPECT_TRUE(test::readFile(planned) == test::readFile(entry.path() / "buffers.vti")) << planned;
    ++entries;
  }
  EXPECT_EQ(entries, 2u);

  // A lost task: named, its row failed, exit 4, and the retry list holds exactly its line, which completes the bench.
  std::filesystem::remove(temp.path() / "plan" / "runs" / "2.json");
  std::filesystem::remove(temp.path() / "plan" / "logs" / "run-2.txt");
  const test::RunResult lost = test::runShadowlabInTempDir(
    { "bench", "--collect", (temp.path() / "plan").string(), "--out", (temp.path() / "lost").string(), "-q" });
  EXPECT_EQ(lost.exitCode, 4) << lost.describe();
  EXPECT_NE(lost.err.find("configuration 2 (hard on stacked-occluders): missing (never started"), std::string::npos)
    << lost.err;
  EXPECT_NE(lost.err.find("retry"), std::string::npos) << lost.err;
  EXPECT_EQ(lineCount(temp.path() / "lost" / "retry" / "configurations.txt"), 1u);
  EXPECT_EQ(lineCount(temp.path() / "lost" / "retry" / "references.txt"), 0u);
  const nlohmann::json lostRows = test::readJson(temp.path() / "lost" / "bench.json").at("configurations");
  EXPECT_EQ(lostRows[2].at("status"), "failed");
  ASSERT_EQ(runJobList(temp.path() / "lost" / "retry" / "configurations.txt"), 0);
  const test::RunResult again = test::runShadowlabInTempDir(
    { "bench", "--collect", (temp.path() / "plan").string(), "--out", (temp.path() / "lost").string(), "-q" });
  EXPECT_EQ(again.exitCode, 0) << again.describe();
  EXPECT_EQ(planTestMetricsOf(test::readJson(temp.path() / "lost" / "bench.json").at("configurations")[2]),
    planTestMetricsOf(directRows[2]));
}

TEST(BenchPlan, ATiledReferenceMergesBitForBitIntoTheWholeOne)
{
  const test::TempDir temp;
  const std::string scene = test::datasetPath("stacked-occluders").string();
  const std::vector<std::string> common = { "--reference-samples", "16", "--resolution", "48x32", "-q" };
  std::vector<std::string> whole = { "reference", scene, "--out", (temp.path() / "whole").string() };
  whole.insert(whole.end(), common.begin(), common.end());
  ASSERT_EQ(test::runShadowlabInTempDir(whole).exitCode, 0);
  std::vector<std::string> merge = { "reference-merge", "--out", (temp.path() / "merged").string(), "-q" };
  for (const int k : { 3, 1, 0, 2 }) // any order
  {
    const std::string tileDir = (temp.path() / ("tile" + std::to_string(k))).string();
    std::vector<std::string> tile = { "reference", scene, "--tile", std::to_string(k) + "/4", "--threads", "1", "--out",
      tileDir };
    tile.insert(tile.end(), common.begin(), common.end());
    const test::RunResult run = test::runShadowlabInTempDir(tile);
    ASSERT_EQ(run.exitCode, 0) << run.describe();
    merge.push_back(tileDir);
  }
  // A tile alone is not the reference: its other rows are 0.
  const std::string wholeBytes = test::readFile(temp.path() / "whole" / "buffers.vti");
  EXPECT_FALSE(test::readFile(temp.path() / "tile1" / "buffers.vti") == wholeBytes);
  const std::vector<std::string> missingOne(merge.begin(), merge.end() - 1);
  const test::RunResult incomplete = test::runShadowlabInTempDir(missingOne);
  EXPECT_EQ(incomplete.exitCode, 1) << incomplete.describe();
  EXPECT_NE(incomplete.err.find("tile(s) 2 of 4 missing"), std::string::npos) << incomplete.err;
  EXPECT_FALSE(std::filesystem::exists(temp.path() / "merged"));
  const test::RunResult merged = test::runShadowlabInTempDir(merge);
  ASSERT_EQ(merged.exitCode, 0) << merged.describe();
  EXPECT_TRUE(test::readFile(temp.path() / "merged" / "buffers.vti") == wholeBytes)
    << "the merged buffers.vti differs from the single-process reference";
  EXPECT_EQ(test::readJson(temp.path() / "merged" / "stats.json").at("rays_traced"),
    test::readJson(temp.path() / "whole" / "stats.json").at("rays_traced"));
}

TEST(BenchPlan, StatsNameTheEglDeviceAndWhetherAnAssignmentApplied)
{
  // No GPU here: llvmpipe on the surfaceless display, no hardware device; a Slurm GPU assignment in the environment
  // is said not to apply rather than passed off as honoured.
  const test::TempDir temp;
  const std::vector<std::string> render = { "render", test::datasetPath("planar-occluder").string(), "-t", "hard", "-r",
    "32x32", "-q", "--out", (temp.path() / "frame").string() };
  ASSERT_EQ(test::runShadowlabIn(render, temp.path(), "unset CUDA_VISIBLE_DEVICES SLURM_STEP_GPUS SLURM_JOB_GPUS "
    "SHADOWLAB_EGL_DEVICE").exitCode, 0);
  const nlohmann::json stats = test::readJson(temp.path() / "frame" / "stats.json");
  const std::string platform = stats.at("egl_platform").get<std::string>();
  const nlohmann::json device = stats.at("egl_device");
  if (platform == "device")
  {
    GTEST_SKIP() << "a hardware EGL device: " << device.dump();
  }
  EXPECT_EQ(device.at("index").get<int>(), -1);
  const std::string description = device.at("description").get<std::string>();
  EXPECT_EQ(description.rfind(platform + " display (", 0), 0u) << description;
  EXPECT_EQ(description.find("does not apply"), std::string::npos) << description;
  ASSERT_EQ(test::runShadowlabIn(render, temp.path(), "export SLURM_STEP_GPUS=1 CUDA_VISIBLE_DEVICES=1").exitCode, 0);
  EXPECT_NE(test::readJson(temp.path() / "frame" / "stats.json").at("egl_device").at("description").get<std::string>()
    .find("the GPU assignment in the environment does not apply"), std::string::npos);
}

// Several -r sizes in a plan (issue 33): a reference job and configurations per size, collected into the rows a
// direct bench writes; a run result that holds warm_frame_gpu_ms (frames reusing unchanged structures) becomes the
// "warm frame ms" column, absent from a bench whose results have none.
TEST(BenchPlan, SeveralSizesPlanCollectAndAWarmFrameColumn)
{
  const test::TempDir temp;
  const std::string scene = test::datasetPath("planar-occluder").string();
  const std::vector<std::string> options = { "-t", "hard,pcf", "-r", "48x32,32x32", "--reference-samples", "16",
    "--repeat", "1", "--set", "shadow_map_size=256", "--quiet" };
  std::vector<std::string> plan = { "bench", scene, "--plan", (temp.path() / "plan").string(), "--cache",
    (temp.path() / "plan-cache").string() };
  plan.insert(plan.end(), options.begin(), options.end());
  const test::RunResult planned = test::runShadowlabInTempDir(plan);
  ASSERT_EQ(planned.exitCode, 0) << planned.describe();
  EXPECT_EQ(lineCount(temp.path() / "plan" / "references.txt"), 2u) << "a reference per size";
  EXPECT_EQ(lineCount(temp.path() / "plan" / "configurations.txt"), 4u);
  ASSERT_EQ(runJobList(temp.path() / "plan" / "jobs.txt"), 0);

  // A result as a bench-run that reuses structures writes it.
  const std::filesystem::path runFile = temp.path() / "plan" / "runs" / "1.json";
  nlohmann::json result = test::readJson(runFile);
  result["warm_frame_gpu_ms"] = 1.25;
  result["warm_frame_gpu_ms_min"] = 1.0;
  result["warm_frame_gpu_ms_max"] = 1.5;
  test::writeFile(runFile, result.dump());
  const test::RunResult collected = test::runShadowlabInTempDir(
    { "bench", "--collect", (temp.path() / "plan").string(), "--out", (temp.path() / "collected").string(), "-q" });
  ASSERT_EQ(collected.exitCode, 0) << collected.describe();

  std::vector<std::string> direct = { "bench", scene, "--cache", (temp.path() / "direct-cache").string(), "--out",
    (temp.path() / "direct").string() };
  direct.insert(direct.end(), options.begin(), options.end());
  const test::RunResult run = test::runShadowlabInTempDir(direct);
  ASSERT_EQ(run.exitCode, 0) << run.describe();
  const nlohmann::json collectedRows = test::readJson(temp.path() / "collected" / "bench.json").at("configurations");
  const nlohmann::json directRows = test::readJson(temp.path() / "direct" / "bench.json").at("configurations");
  ASSERT_EQ(collectedRows.size(), 4u);
  ASSERT_EQ(directRows.size(), 4u);
  for (std::size_t c = 0; c < directRows.size(); ++c)
  {
    EXPECT_EQ(planTestMetricsOf(collectedRows[c]), planTestMetricsOf(directRows[c])) << "configuration " << c;
    EXPECT_EQ(collectedRows[c].at("resolution"), directRows[c].at("resolution"));
    EXPECT_EQ(collectedRows[c].at("resolution"), c < 2 ? "48x32" : "32x32");
  }
  EXPECT_EQ(test::entriesOf(temp.path() / "collected"), test::entriesOf(temp.path() / "direct"));

  const std::string collectedSummary = test::readFile(temp.path() / "collected" / "summary.md");
  EXPECT_NE(collectedSummary.find("| warm frame ms |"), std::string::npos) << collectedSummary;
  EXPECT_NE(collectedSummary.find("| 1.25 (1.00-1.50) |"), std::string::npos) << collectedSummary;
  // The direct bench has the column exactly when its runs wrote warm frames (a build with light-space reuse).
  EXPECT_EQ(test::readFile(temp.path() / "direct" / "summary.md").find("| warm frame ms |") != std::string::npos,
    directRows[0].at("result").contains("warm_frame_gpu_ms"));
  const std::string csv = test::readFile(temp.path() / "collected" / "bench.csv");
  EXPECT_NE(csv.substr(0, csv.find('\n')).find("warm_frame_gpu_ms_min"), std::string::npos);
}

TEST(BenchPlan, BadInputIsOneLineWithNoOutput)
{
  const test::TempDir temp;
  const std::string scene = test::datasetPath("planar-occluder").string();
  const std::filesystem::path foreign = temp.path() / "foreign";
  std::filesystem::create_directories(foreign);
  test::writeFile(foreign / "notes.txt", "mine");
  const std::filesystem::path fresh = temp.path() / "fresh";
  // {arguments, what the one line names}
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
    { { "bench", "--collect", foreign.string(), "--out", fresh.string() }, "not a bench plan" },
    { { "bench", scene, "--plan", foreign.string() }, "--plan " + foreign.string() },
    { { "bench", scene, "--plan", fresh.string(), "--slurm-time", "1h" }, "--slurm-time 1h" },
    { { "bench", scene, "--plan", fresh.string(), "--slurm-partition", "a;b" }, "--slurm-partition a;b" },
    { { "bench", scene, "--plan", fresh.string(), "--slurm-gpus", "-1" }, "--slurm-gpus -1" },
    { { "bench", scene, "--plan", fresh.string(), "--reference-tiles", "0" }, "--reference-tiles 0" },
    { { "bench", scene, "--plan", fresh.string(), "-r", "48x32", "--reference-tiles", "33" }, "--reference-tiles 33" },
    { { "bench", scene, "--slurm-throttle", "4", "--out", fresh.string() }, "only with --plan" },
    { { "bench", scene, "--plan", fresh.string(), "--collect", foreign.string() }, "--plan and --collect" },
    { { "reference", scene, "--tile", "4/4", "--out", fresh.string() }, "--tile 4/4" },
    { { "reference", scene, "-r", "48x32", "--tile", "0/33", "--out", fresh.string() }, "--tile 0/33" },
    { { "reference-merge", foreign.string(), "--out", fresh.string() }, "not the output of reference --tile" },
  };
  for (const auto& [arguments, named] : cases)
  {
    const test::RunResult run = test::runShadowlabInTempDir(arguments);
    EXPECT_NE(run.exitCode, 0) << run.describe();
    EXPECT_EQ(run.errLines(), 1u) << run.describe();
    EXPECT_NE(run.err.find(named), std::string::npos) << named << "\n" << run.describe();
    EXPECT_FALSE(std::filesystem::exists(fresh)) << run.describe();
    EXPECT_EQ(test::entriesOf(foreign), std::vector<std::string>{ "notes.txt" }) << run.describe();
  }
}

} // namespace
} // namespace sl
