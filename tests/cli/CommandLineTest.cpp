// One command line (issue 31, item 5), through the executable: -t/--technique and --reference-samples wherever they
// apply, the old spellings still working with one note each, `list [TECHNIQUE...]` and `list --structures`,
// `lessons --list`, the shadowlab-<command> default outputs, and progress lines only when asked for (stderr here is
// a file, never a terminal). Runs are 16x16 with one frame; --pick is tested in ProbeCliTest.cpp.
#include "lessons/LessonRegistry.h"
#include "structures/LightSpaceStructure.h"
#include "support/CliRun.h"
#include "support/TempDir.h"
#include "support/TestSupport.h"
#include "techniques/Registry.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace sl
{
namespace
{

namespace fs = std::filesystem;
using test::RunResult;
using test::TempDir;

std::string commandLinePlanarScene()
{
  return test::datasetPath("planar-occluder").string();
}

// How many times `needle` occurs in `text`.
std::size_t commandLineOccurrences(const std::string& text, const std::string& needle)
{
  std::size_t count = 0;
  for (std::size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + needle.size()))
  {
    ++count;
  }
  return count;
}

// The note a run that uses an old spelling prints, whole.
std::string renamedNote(const std::string& oldName, const std::string& newSpelling)
{
  return "shadowlab: note: " + oldName + " is now " + newSpelling + "; the old spelling goes in the next release\n";
}

// The techniques of a bench's rows, in order.
std::vector<std::string> benchTechniques(const fs::path& out)
{
  std::ifstream file(out / "bench.json");
  const nlohmann::json bench = nlohmann::json::parse(file);
  std::vector<std::string> names;
  for (const nlohmann::json& row : bench.at("configurations"))
  {
    names.push_back(row.at("technique").get<std::string>());
  }
  return names;
}

// `bench` on planar-occluder at 16x16, one frame, 4 reference samples (unless `extra` gives the samples), quiet,
// with a cache shared by the calls of one test.
RunResult quietBench(const TempDir& temp, const std::string& out, const std::vector<std::string>& extra)
{
  std::vector<std::string> arguments = { "bench", commandLinePlanarScene(), "-r", "16x16", "--repeat", "1",
    "--cache", "cache", "--out", out, "-q" };
  arguments.insert(arguments.end(), extra.begin(), extra.end());
  return test::runShadowlabIn(arguments, temp.path());
}

TEST(CommandLine, BenchTakesTechniquesAsEveryCommandDoes)
{
  TempDir temp;
  const std::vector<std::pair<std::vector<std::string>, std::vector<std::string>>> cases = {
    { { "-t", "hard,pcf" }, { "hard", "pcf" } },
    { { "-t", "hard", "-t", "pcf" }, { "hard", "pcf" } },
    { { "--technique", "pcf" }, { "pcf" } },
    { { "--technique", "hard,pcf" }, { "hard", "pcf" } },
  };
  int index = 0;
  for (const auto& [options, expected] : cases)
  {
    std::vector<std::string> extra = options;
    extra.insert(extra.end(), { "--reference-samples", "4" });
    const std::string out = "bench-" + std::to_string(index++);
    const RunResult run = quietBench(temp, out, extra);
    ASSERT_EQ(run.exitCode, 0) << run.describe();
    EXPECT_EQ(run.err, "") << "a new spelling prints no note\n" << run.describe();
    EXPECT_EQ(benchTechniques(temp.path() / out), expected) << run.describe();
  }
  // -t takes one value: a scene after it is a scene (as with the old string option).
  const RunResult before = test::runShadowlabIn({ "bench", "-t", "pcf", "-t", "hard", commandLinePlanarScene(), "-r",
                                                  "16x16", "--repeat", "1", "--reference-samples", "4", "--cache",
                                                  "cache", "--out", "before", "-q" },
    temp.path());
  ASSERT_EQ(before.exitCode, 0) << before.describe();
  EXPECT_EQ(benchTechniques(temp.path() / "before"), (std::vector<std::string>{ "pcf", "hard" }));
}

TEST(CommandLine, OldSpellingsWorkAndPrintOneNoteEach)
{
  TempDir temp;
  // bench --techniques and --samples: the same results as the new spellings, each old one noted once.
  const RunResult old = quietBench(temp, "old", { "--techniques", "hard,pcf", "--samples", "4" });
  ASSERT_EQ(old.exitCode, 0) << old.describe();
  EXPECT_EQ(old.err, renamedNote("--techniques", "-t/--technique") + renamedNote("--samples", "--reference-samples"))
    << old.describe();
  EXPECT_EQ(benchTechniques(temp.path() / "old"), (std::vector<std::string>{ "hard", "pcf" }));
  std::ifstream file(temp.path() / "old" / "bench.json");
  EXPECT_EQ(nlohmann::json::parse(file).at("reference_samples").get<int>(), 4);

  // reference --samples N fills the same count as --reference-samples N and -n N.
  for (const std::string& spelling : { "--samples", "--reference-samples", "-n" })
  {
    const std::string out = "ref" + spelling;
    const RunResult run = test::runShadowlabIn(
      { "reference", commandLinePlanarScene(), spelling, "3", "-r", "16x16", "-q", "--out", out }, temp.path());
    ASSERT_EQ(run.exitCode, 0) << run.describe();
    EXPECT_EQ(run.err, spelling == "--samples" ? renamedNote("--samples", "--reference-samples") : "")
      << run.describe();
    std::ifstream stats(temp.path() / out / "stats.json");
    EXPECT_EQ(nlohmann::json::parse(stats).at("samples").get<int>(), 3) << spelling;
  }

  // differential --samples: the note, then the check names the spelling typed (no scene is made for a bad value).
  const RunResult differential =
    test::runShadowlabIn({ "differential", "--samples", "0", "--out", "diff" }, temp.path());
  EXPECT_EQ(differential.exitCode, 1) << differential.describe();
  EXPECT_EQ(differential.err, renamedNote("--samples", "--reference-samples") +
      "shadowlab: error: --samples 0: must be in 1 .. 65536\n")
    << differential.describe();
  const RunResult differentialNew =
    test::runShadowlabIn({ "differential", "--reference-samples", "0", "--out", "diff" }, temp.path());
  EXPECT_EQ(differentialNew.exitCode, 1);
  EXPECT_EQ(differentialNew.err, "shadowlab: error: --reference-samples 0: must be in 1 .. 65536\n")
    << differentialNew.describe();
}

TEST(CommandLine, BothSpellingsOfOneOptionAreOneError)
{
  TempDir temp;
  for (const std::vector<std::string>& both : { std::vector<std::string>{ "-t", "hard", "--techniques", "pcf" },
         std::vector<std::string>{ "-t", "hard", "--samples", "4", "--reference-samples", "4" } })
  {
    const RunResult run = quietBench(temp, "both", both);
    EXPECT_EQ(run.exitCode, 1) << run.describe();
    EXPECT_EQ(run.errLines(), 1u) << run.describe();
    EXPECT_NE(run.err.find("given twice"), std::string::npos) << run.describe();
    EXPECT_FALSE(fs::exists(temp.path() / "both"));
  }
}

// The techniques `list` printed, in order: its text output's header lines ("name - title (paper)").
std::vector<std::string> listedTechniques(const std::string& out)
{
  std::vector<std::string> names;
  std::istringstream lines(out);
  for (std::string line; std::getline(lines, line);)
  {
    if (!line.empty() && line[0] != ' ' && line.find(" - ") != std::string::npos)
    {
      names.push_back(line.substr(0, line.find(" - ")));
    }
  }
  return names;
}

TEST(CommandLine, ListPrintsOnlyTheTechniquesNamed)
{
  TempDir temp;
  const RunResult all = test::runShadowlabIn({ "list" }, temp.path());
  ASSERT_EQ(all.exitCode, 0);
  std::vector<std::string> registry;
  for (const TechniqueDescriptor& technique : techniqueRegistry())
  {
    registry.push_back(technique.name);
  }
  EXPECT_EQ(listedTechniques(all.out), registry);

  const RunResult pcss = test::runShadowlabIn({ "list", "pcss" }, temp.path());
  ASSERT_EQ(pcss.exitCode, 0) << pcss.describe();
  EXPECT_EQ(listedTechniques(pcss.out), std::vector<std::string>{ "pcss" }) << pcss.out;
  // pcss's block is the same text as in the full list.
  const std::size_t start = all.out.find("pcss - ");
  ASSERT_NE(start, std::string::npos);
  EXPECT_EQ(all.out.substr(start, pcss.out.size()), pcss.out);

  // Names and comma lists, printed in registry order, each once.
  const RunResult several = test::runShadowlabIn({ "list", "vsm,hard", "pcf", "hard" }, temp.path());
  ASSERT_EQ(several.exitCode, 0) << several.describe();
  EXPECT_EQ(listedTechniques(several.out), (std::vector<std::string>{ "hard", "pcf", "vsm" }));
  const RunResult json = test::runShadowlabIn({ "list", "pcss", "--json" }, temp.path());
  ASSERT_EQ(json.exitCode, 0) << json.describe();
  const nlohmann::json parsed = nlohmann::json::parse(json.out);
  ASSERT_EQ(parsed.size(), 1u);
  EXPECT_EQ(parsed[0].at("name"), "pcss");
}

TEST(CommandLine, ListOfAnUnknownTechniqueIsOneLineNamingTheValidOnes)
{
  TempDir temp;
  for (const std::vector<std::string>& arguments :
    { std::vector<std::string>{ "list", "nosuch" }, std::vector<std::string>{ "list", "pcss,nosuch" } })
  {
    const RunResult run = test::runShadowlabIn(arguments, temp.path());
    EXPECT_EQ(run.exitCode, 1) << run.describe();
    EXPECT_EQ(run.errLines(), 1u) << run.describe();
    EXPECT_EQ(run.out, "") << run.describe();
    EXPECT_NE(run.err.find("nosuch"), std::string::npos) << run.describe();
    for (const TechniqueDescriptor& technique : techniqueRegistry())
    {
      EXPECT_NE(run.err.find(technique.name), std::string::npos) << technique.name << "\n" << run.describe();
    }
  }
}

TEST(CommandLine, ListStructuresNamesEachStructureWithItsTechniques)
{
  TempDir temp;
  const RunResult all = test::runShadowlabIn({ "list", "--structures", "--json" }, temp.path());
  ASSERT_EQ(all.exitCode, 0) << all.describe();
  const nlohmann::json structures = nlohmann::json::parse(all.out);
  ASSERT_EQ(structures.size(), lightSpaceStructureRegistry().size());
  for (std::size_t s = 0; s < structures.size(); ++s)
  {
    const LightSpaceStructure& structure = *lightSpaceStructureRegistry()[s];
    EXPECT_EQ(structures[s].at("name"), structure.name);
    std::vector<std::string> users;
    for (const TechniqueDescriptor& technique : techniqueRegistry())
    {
      if (std::count(technique.lightStructures.begin(), technique.lightStructures.end(), &structure) > 0)
      {
        users.push_back(technique.name);
      }
    }
    EXPECT_EQ(structures[s].at("techniques").get<std::vector<std::string>>(), users) << structure.name;
  }
  // With a technique named: only its structures, listing only it.
  const RunResult pcss = test::runShadowlabIn({ "list", "--structures", "pcss" }, temp.path());
  ASSERT_EQ(pcss.exitCode, 0) << pcss.describe();
  EXPECT_EQ(commandLineOccurrences(pcss.out, "  used by: "), findTechnique("pcss").lightStructures.size()) << pcss.out;
  EXPECT_EQ(commandLineOccurrences(pcss.out, "  used by: pcss\n"), findTechnique("pcss").lightStructures.size())
    << pcss.out;
}

TEST(CommandLine, LessonsListNamesEveryLessonAndWritesNothing)
{
  TempDir temp;
  const RunResult run = test::runShadowlabIn({ "lessons", "--list" }, temp.path());
  ASSERT_EQ(run.exitCode, 0) << run.describe();
  EXPECT_EQ(run.err, "");
  std::string expected;
  for (const Lesson& lesson : lessonRegistry())
  {
    expected += lesson.name + " - " + lesson.title + "\n";
  }
  EXPECT_EQ(run.out, expected);
  EXPECT_EQ(test::entriesOf(temp.path()), std::vector<std::string>{}) << "lessons --list wrote something";
}

TEST(CommandLine, DefaultOutputsAreNamedAfterTheirCommand)
{
  TempDir temp;
  const RunResult render =
    test::runShadowlabIn({ "render", commandLinePlanarScene(), "-t", "hard", "-r", "16x16", "-q" }, temp.path());
  ASSERT_EQ(render.exitCode, 0) << render.describe();
  const RunResult reference =
    test::runShadowlabIn({ "reference", commandLinePlanarScene(), "-n", "1", "-r", "16x16", "-q" }, temp.path());
  ASSERT_EQ(reference.exitCode, 0) << reference.describe();
  const RunResult compare = test::runShadowlabIn(
    { "compare", "shadowlab-render/buffers.vti", "shadowlab-reference/buffers.vti", "-q" }, temp.path());
  ASSERT_EQ(compare.exitCode, 0) << compare.describe();
  const RunResult montage = test::runShadowlabIn(
    { "montage", "shadowlab-render", "shadowlab-reference", "--buffer", "visibility", "-q" }, temp.path());
  ASSERT_EQ(montage.exitCode, 0) << montage.describe();
  EXPECT_EQ(test::entriesOf(temp.path()), (std::vector<std::string>{ "shadowlab-compare", "shadowlab-montage.png",
                                            "shadowlab-reference", "shadowlab-render" }));
  for (const std::string& dir : { "shadowlab-compare", "shadowlab-reference", "shadowlab-render" })
  {
    EXPECT_TRUE(fs::is_regular_file(temp.path() / dir / ".shadowlab-output")) << dir << " carries the marker";
  }
  // The old defaults are left alone: a directory named out is not the render's default any more.
  fs::create_directories(temp.path() / "out");
  test::writeFile(temp.path() / "out" / "notes.txt", "mine");
  ASSERT_EQ(test::runShadowlabIn({ "render", commandLinePlanarScene(), "-t", "hard", "-r", "16x16", "-q" }, temp.path())
              .exitCode,
    0);
  EXPECT_EQ(test::readFile(temp.path() / "out" / "notes.txt"), "mine");
  EXPECT_EQ(test::entriesOf(temp.path() / "out"), std::vector<std::string>{ "notes.txt" });
}

// The progress lines of core/Progress.h: the estimate, the lines with the time left, the total.
bool hasProgressLines(const std::string& err, const std::string& what)
{
  return err.find("shadowlab: " + what + ": ") != std::string::npos && err.find("expect about") != std::string::npos;
}

TEST(CommandLine, ProgressOnlyWhenAsked)
{
  TempDir temp;
  // bench, three configurations: with --progress, the estimate after the first, a line with the elapsed time and
  // the time left after the second, and the total; even with --quiet.
  const RunResult forced = quietBench(temp, "forced", { "-t", "hard,pcf,pcss", "--reference-samples", "4", "--progress" });
  ASSERT_EQ(forced.exitCode, 0) << forced.describe();
  EXPECT_TRUE(hasProgressLines(forced.err, "bench")) << forced.describe();
  EXPECT_TRUE(std::regex_search(forced.err,
    std::regex("shadowlab: bench: 3 configuration\\(s\\), expect about [0-9.]+ s on this machine \\(measured: 1 "
               "configuration in [0-9.]+ s\\)\n")))
    << forced.describe();
  EXPECT_TRUE(std::regex_search(
    forced.err, std::regex("shadowlab: bench: 2/3 configurations, [0-9.]+ s elapsed, about [0-9.]+ s left\n")))
    << forced.describe();
  EXPECT_TRUE(std::regex_search(forced.err, std::regex("shadowlab: bench: 3 configurations in [0-9.]+ s\n")))
    << forced.describe();
  EXPECT_EQ(forced.errLines(), 3u) << forced.describe();
  // Without it (stderr is a file here), none, quiet or not.
  const RunResult quiet = quietBench(temp, "quiet", { "-t", "hard,pcf,pcss", "--reference-samples", "4" });
  ASSERT_EQ(quiet.exitCode, 0) << quiet.describe();
  EXPECT_EQ(quiet.err, "") << quiet.describe();
  const RunResult chatty = test::runShadowlabIn({ "bench", commandLinePlanarScene(), "-t", "hard,pcf,pcss", "-r",
                                                  "16x16", "--repeat", "1", "--reference-samples", "4", "--cache",
                                                  "cache", "--out", "chatty" },
    temp.path());
  ASSERT_EQ(chatty.exitCode, 0) << chatty.describe();
  EXPECT_FALSE(hasProgressLines(chatty.err, "bench")) << chatty.describe();
  EXPECT_EQ(chatty.err.find("elapsed"), std::string::npos) << chatty.describe();

  // reference, per batch of rows: the estimate when a batch was reported before the last row (the tracing threads
  // may finish 16 rows before the first report), and the total in any case.
  const RunResult reference = test::runShadowlabIn(
    { "reference", commandLinePlanarScene(), "-n", "4", "-r", "16x16", "--out", "ref", "--progress" }, temp.path());
  ASSERT_EQ(reference.exitCode, 0) << reference.describe();
  EXPECT_TRUE(std::regex_search(reference.err, std::regex("shadowlab: reference: 16 rows in [0-9.]+ s\n")))
    << reference.describe();
  const RunResult referenceQuietly = test::runShadowlabIn(
    { "reference", commandLinePlanarScene(), "-n", "4", "-r", "16x16", "--out", "ref" }, temp.path());
  ASSERT_EQ(referenceQuietly.exitCode, 0) << referenceQuietly.describe();
  EXPECT_EQ(referenceQuietly.errLines(), 1u) << "only the summary line\n" << referenceQuietly.describe();
  EXPECT_FALSE(hasProgressLines(referenceQuietly.err, "reference")) << referenceQuietly.describe();
}

TEST(CommandLine, DifferentialProgressPerConfigurationWhenAsked)
{
  // Two seeds of hard's default choice on 16-pixel random scenes: two configurations.
  TempDir temp;
  const std::vector<std::string> arguments = { "differential", "--seeds", "1,2", "-t", "hard", "--choice", "default",
    "--max-side", "16", "--reference-samples", "4", "-q" };
  std::vector<std::string> forced = arguments;
  forced.insert(forced.end(), { "--out", "forced", "--progress" });
  const RunResult run = test::runShadowlabIn(forced, temp.path());
  ASSERT_EQ(run.exitCode, 0) << run.describe();
  EXPECT_TRUE(std::regex_search(run.err,
    std::regex("shadowlab: differential: 2 seed\\(s\\), 2 configuration\\(s\\), expect about [0-9.]+ s on this "
               "machine \\(measured: 1 configuration in [0-9.]+ s\\)\nshadowlab: differential: 2 configurations in "
               "[0-9.]+ s\n")))
    << run.describe();
  std::vector<std::string> plain = arguments;
  plain.insert(plain.end(), { "--out", "plain" });
  const RunResult quiet = test::runShadowlabIn(plain, temp.path());
  ASSERT_EQ(quiet.exitCode, 0) << quiet.describe();
  EXPECT_EQ(quiet.err.find("shadowlab: differential: 2 seed"), std::string::npos) << quiet.describe();
  EXPECT_EQ(quiet.err.find("elapsed"), std::string::npos) << quiet.describe();
}

TEST(CommandLine, LessonsProgressPerLessonWhenAsked)
{
  // The two quickest lessons, at 32x32 (about 4 s in all).
  TempDir temp;
  const std::vector<std::string> arguments = { "lessons", "--only", "pcf-fixed-kernel", "--only", "acne-and-bias",
    "-r", "32x32", "-q" };
  std::vector<std::string> forced = arguments;
  forced.insert(forced.end(), { "--out", "forced", "--progress" });
  const RunResult run = test::runShadowlabIn(forced, temp.path());
  ASSERT_EQ(run.exitCode, 0) << run.describe();
  EXPECT_TRUE(std::regex_search(run.err,
    std::regex("shadowlab: lessons: 2 lesson\\(s\\) at 32x32, expect about [0-9.]+ s on this machine \\(measured: "
               "1 lesson in [0-9.]+ s\\)\nshadowlab: lessons: 2 lessons in [0-9.]+ s\n")))
    << run.describe();
  std::vector<std::string> plain = arguments;
  plain.insert(plain.end(), { "--out", "plain" });
  const RunResult quiet = test::runShadowlabIn(plain, temp.path());
  ASSERT_EQ(quiet.exitCode, 0) << quiet.describe();
  EXPECT_EQ(quiet.err, "") << quiet.describe();
}

TEST(CommandLine, LessonsDefaultOutputIsNotTheSourceTree)
{
  // Without --out, the pages go to shadowlab-lessons in the current directory (the page footer's command says so).
  TempDir temp;
  const RunResult run =
    test::runShadowlabIn({ "lessons", "--only", "acne-and-bias", "-r", "32x32", "-q" }, temp.path());
  ASSERT_EQ(run.exitCode, 0) << run.describe();
  EXPECT_EQ(test::entriesOf(temp.path()), std::vector<std::string>{ "shadowlab-lessons" });
  EXPECT_TRUE(fs::is_regular_file(temp.path() / "shadowlab-lessons" / "acne-and-bias" / "README.md"));
  EXPECT_NE(test::readFile(temp.path() / "shadowlab-lessons" / "acne-and-bias" / "README.md")
              .find("shadowlab lessons --out shadowlab-lessons"),
    std::string::npos);
}

} // namespace
} // namespace sl
