// The output contract (src/io/OutputDirectory.h, docs/outputs.md), end to end through the
// executable: --out never destroys what shadowlab did not create, every write is checked, signals and killed
// runs leave no temporary directory behind, and every usage error is one line with exit 1. Case ids (D07, K22,
// ...) are those of the bad-input probe, a review of bad inputs that preceded these tests.
#include "io/ImageIO.h"
#include "pipeline/ShadowRenderer.h"
#include "support/CliRun.h"
#include "support/TempDir.h"
#include "support/TestSupport.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <sys/wait.h>
#include <filesystem>
#include <map>
#include <pwd.h>
#include <string>
#include <thread>
#include <unistd.h>
#include <vector>

namespace sl
{
namespace
{

namespace fs = std::filesystem;
using test::entriesOf;
using test::joined;
using test::readFile;
using test::RunResult;
using test::TempDir;
using test::writeFile;

// Small and fast: everything here is about files, not pixels.
const std::vector<std::string> kSmallRender = { "--technique", "hard", "--resolution", "24x24", "--set",
  "shadow_map_size=256" };

std::vector<std::string> renderArguments(const fs::path& scene, const std::string& out,
  const std::vector<std::string>& extra = {})
{
  std::vector<std::string> arguments{ "render", scene.string() };
  arguments.insert(arguments.end(), kSmallRender.begin(), kSmallRender.end());
  arguments.insert(arguments.end(), { "--out", out });
  arguments.insert(arguments.end(), extra.begin(), extra.end());
  return arguments;
}

// Every regular file under `dir` with its bytes: a directory's exact state, to compare before and after.
std::map<std::string, std::string> snapshot(const fs::path& dir)
{
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
  {
    const std::string relative = fs::relative(entry.path(), dir).string();
    files[relative] = entry.is_regular_file() ? readFile(entry.path()) : std::string("<dir>");
  }
  return files;
}

// A user's directory of their own files (not written by shadowlab).
void fillWithUserFiles(const fs::path& dir)
{
  fs::create_directories(dir / "notes");
  writeFile(dir / "thesis.tex", "\\documentclass{article} my only copy");
  writeFile(dir / "notes" / "shopping.txt", "buy milk");
}

// A copy of a dataset directory (scene.json, meshes) at `where`.
fs::path copyDataset(const std::string& name, const fs::path& where)
{
  fs::create_directories(where);
  fs::copy(test::datasetPath(name).parent_path(), where, fs::copy_options::recursive);
  return where / "scene.json";
}

void expectOneLineRefusal(const RunResult& run, const std::string& mention)
{
  EXPECT_EQ(run.exitCode, 1) << run.describe();
  EXPECT_EQ(run.errLines(), 1u) << run.describe();
  EXPECT_NE(run.err.find(mention), std::string::npos) << "stderr should mention '" << mention << "'\n"
                                                      << run.describe();
}

// ---- data loss (D07-D10, K22, H13) -------------------------------------------------------------------------

TEST(OutputSafety, UserDirectoryWithoutMarkerIsRefusedAndKeptByteForByte) // D07
{
  TempDir temp;
  const fs::path out = temp.path() / "shadowlab-render";
  fillWithUserFiles(out);
  const auto before = snapshot(out);
  // The default --out name, as a plain `shadowlab render scene.json` would use it.
  std::vector<std::string> arguments{ "render", test::datasetPath("planar-occluder").string() };
  arguments.insert(arguments.end(), kSmallRender.begin(), kSmallRender.end());
  const RunResult run = test::runShadowlabIn(arguments, temp.path());
  expectOneLineRefusal(run, "--force");
  EXPECT_EQ(snapshot(out), before);
  EXPECT_EQ(entriesOf(temp.path()), std::vector<std::string>{ "shadowlab-render" }) << joined(entriesOf(temp.path()));
}

TEST(OutputSafety, ForceReplacesAUserDirectoryAndTheResultCarriesTheMarker)
{
  TempDir temp;
  const fs::path out = temp.path() / "results";
  fillWithUserFiles(out);
  const RunResult run =
    test::runShadowlabIn(renderArguments(test::datasetPath("planar-occluder"), "results", { "--force" }), temp.path());
  ASSERT_EQ(run.exitCode, 0) << run.describe();
  EXPECT_FALSE(fs::exists(out / "thesis.tex"));
  EXPECT_TRUE(fs::is_regular_file(out / "image.png"));
  const nlohmann::json marker = nlohmann::json::parse(readFile(out / ".shadowlab-output"));
  EXPECT_EQ(marker.value("tool", ""), "shadowlab");
  EXPECT_EQ(marker.value("command", ""), "render");
  EXPECT_FALSE(marker.value("version", "").empty());

  // The marked result is replaced by the next run without --force; so is an empty directory.
  const RunResult again =
    test::runShadowlabIn(renderArguments(test::datasetPath("planar-occluder"), "results"), temp.path());
  EXPECT_EQ(again.exitCode, 0) << again.describe();
  fs::create_directories(temp.path() / "empty");
  const RunResult intoEmpty =
    test::runShadowlabIn(renderArguments(test::datasetPath("planar-occluder"), "empty"), temp.path());
  EXPECT_EQ(intoEmpty.exitCode, 0) << intoEmpty.describe();
  EXPECT_TRUE(fs::is_regular_file(temp.path() / "empty" / "stats.json"));
  EXPECT_EQ(entriesOf(temp.path()), (std::vector<std::string>{ "empty", "results" }))
    << joined(entriesOf(temp.path()));
}

TEST(OutputSafety, CurrentDirectoryItsAncestorsAndTheDatasetAreRefusedEvenWithForce) // D08, D09, D10
{
  TempDir temp;
  const fs::path project = temp.path() / "project";
  const fs::path scene = copyDataset("planar-occluder", project / "dataset");
  fs::create_directories(project / "sub");
  writeFile(project / "keep.txt", "mine");
  const auto before = snapshot(temp.path());
  struct Case
  {
    fs::path workDir;
    std::string out;
    std::string mention;
  };
  for (const Case& refused : { Case{ project, ".", "current directory" },               // D08
         Case{ project / "sub", "..", "holds the current directory" },                   // D09
         Case{ project / "sub", "../..", "holds the current directory" },
         Case{ project, "dataset", "an input of this command" },                        // D10
         Case{ project, "dataset/", "an input of this command" },
         Case{ project, "sub/../dataset", "an input of this command" },
         Case{ project, "/", "filesystem root" } })
  {
    for (const bool force : { false, true })
    {
      const RunResult run = test::runShadowlabIn(
        renderArguments(scene, refused.out, force ? std::vector<std::string>{ "--force" } : std::vector<std::string>{}),
        refused.workDir);
      expectOneLineRefusal(run, refused.mention);
      EXPECT_EQ(snapshot(temp.path()), before) << "-o " << refused.out << (force ? " --force" : "");
    }
  }
}

TEST(OutputSafety, HomeDirectoryIsRefusedEvenWithForce)
{
  TempDir temp;
  const fs::path home = temp.path() / "home";
  fillWithUserFiles(home);
  const auto before = snapshot(home);
  const RunResult run = test::runShadowlabIn(
    renderArguments(test::datasetPath("planar-occluder"), home.string(), { "--force" }), temp.path(),
    "export HOME=" + test::shellQuote(home.string()));
  expectOneLineRefusal(run, "home directory");
  EXPECT_EQ(snapshot(home), before);
}

TEST(OutputSafety, ThePasswordDatabaseHomeIsRefusedWithHomeUnset)
{
  // `env -u HOME shadowlab render ... -o ~ --force`: the shell expands ~ from the password database. The real
  // home is named here, so the run is fenced should the refusal ever regress: under a file size limit of 1 KiB
  // (room for the one-line error, SIGXFSZ ignored) writing buffers.vti into the temporary sibling fails, and the
  // run ends before anything could be replaced. tests/unit/OutputDirectoryTest.cpp checks the rule itself.
  const struct passwd* entry = ::getpwuid(::getuid());
  ASSERT_TRUE(entry && entry->pw_dir && *entry->pw_dir);
  const fs::path home = entry->pw_dir;
  ASSERT_TRUE(fs::is_directory(home)) << home;
  TempDir temp;
  const RunResult run = test::runShadowlabIn(
    renderArguments(test::datasetPath("planar-occluder"), home.string(), { "--force" }), temp.path(),
    "unset HOME; ulimit -f 1; trap '' XFSZ");
  expectOneLineRefusal(run, home == home.root_path() ? "filesystem root" : "home directory");
}

TEST(OutputSafety, DirectoryHoldingTheMeshIsRefusedEvenWithForce)
{
  TempDir temp;
  const fs::path scene = copyDataset("bunny", temp.path() / "scenes");
  // The mesh moves to its own directory, named from the scene by an absolute path.
  const fs::path meshes = temp.path() / "meshes";
  fs::create_directories(meshes);
  fs::rename(temp.path() / "scenes" / "bunny.ply", meshes / "bunny.ply");
  std::string text = readFile(scene);
  const std::string relative = "\"bunny.ply\"";
  ASSERT_NE(text.find(relative), std::string::npos);
  text.replace(text.find(relative), relative.size(), "\"" + (meshes / "bunny.ply").string() + "\"");
  writeFile(scene, text);
  const auto before = snapshot(meshes);
  const RunResult run = test::runShadowlabIn(renderArguments(scene, meshes.string(), { "--force" }), temp.path());
  expectOneLineRefusal(run, "bunny.ply");
  EXPECT_EQ(snapshot(meshes), before);
}

TEST(OutputSafety, CompareRefusesTheDirectoryHoldingItsInput) // K22
{
  TempDir temp;
  const fs::path render = temp.path() / "render";
  ASSERT_EQ(test::runShadowlabIn(renderArguments(test::datasetPath("planar-occluder"), "render"), temp.path()).exitCode, 0);
  const auto before = snapshot(render);
  const std::string buffers = (render / "buffers.vti").string();
  for (const bool force : { false, true })
  {
    std::vector<std::string> arguments{ "compare", buffers, buffers, "--out", "render" };
    if (force)
    {
      arguments.push_back("--force");
    }
    const RunResult run = test::runShadowlabIn(arguments, temp.path());
    expectOneLineRefusal(run, "an input of this command");
    EXPECT_EQ(snapshot(render), before);
  }
}

TEST(OutputSafety, BenchRefusesItsCacheAsOutput) // H13
{
  TempDir temp;
  const fs::path cache = temp.path() / "cache";
  fs::create_directories(cache / "0123456789abcdef");
  writeFile(cache / "0123456789abcdef" / "buffers.vti", "an earlier reference");
  const auto before = snapshot(cache);
  for (const std::string& out : { std::string("cache"), std::string("cache/inside") })
  {
    const RunResult run = test::runShadowlabIn({ "bench", test::datasetPath("planar-occluder").string(), "-t", "hard",
                                                 "-r", "16x16", "--reference-samples", "4", "--cache", "cache", "--out", out,
                                                 "--force" },
      temp.path());
    expectOneLineRefusal(run, "cache");
    EXPECT_EQ(snapshot(cache), before) << "--out " << out;
  }
  // A cache inside --out would be deleted with it.
  fs::create_directories(temp.path() / "out-bench" / "cache");
  const RunResult holds = test::runShadowlabIn({ "bench", test::datasetPath("planar-occluder").string(), "-t", "hard",
                                                 "-r", "16x16", "--reference-samples", "4", "--cache", "out-bench/cache",
                                                 "--out", "out-bench", "--force" },
    temp.path());
  expectOneLineRefusal(holds, "an input of this command");
}

TEST(OutputSafety, AFileParameterIsAnInputOfEveryCommandThatTakesSet)
{
  // ss08's budget_image (ParameterSpec::file) inside --out: refused naming it, with --force too; and inside an
  // earlier output, which --out would otherwise replace without --force.
  TempDir temp;
  const std::string scene = test::datasetPath("planar-occluder").string();
  const fs::path dir = temp.path() / "dir";
  fs::create_directories(dir);
  writePng(dir / "b.png", ImageU8(8, 8, 3, 10));
  writeFile(dir / "notes.txt", "mine");
  const auto before = snapshot(dir);
  const std::vector<std::string> budget = { "-t", "ss08", "-r", "16x16", "--set", "budget_map=image", "--set",
    "budget_image=" + (dir / "b.png").string() };
  const auto command = [&](const std::string& name, const std::string& out, bool force) {
    std::vector<std::string> arguments{ name, scene };
    arguments.insert(arguments.end(), budget.begin(), budget.end());
    if (name == "probe")
    {
      arguments.insert(arguments.end(), { "--pixel", "8,8" });
    }
    if (name == "bench")
    {
      arguments.insert(arguments.end(), { "--reference-samples", "4", "--repeat", "1", "--cache", "cache" });
    }
    arguments.insert(arguments.end(), { "--out", out });
    if (force)
    {
      arguments.push_back("--force");
    }
    return arguments;
  };
  for (const std::string& name : { "render", "probe", "bench" })
  {
    SCOPED_TRACE(name);
    expectOneLineRefusal(test::runShadowlabIn(command(name, dir.string(), true), temp.path()), "b.png");
    EXPECT_EQ(snapshot(dir), before);
  }
  // An earlier output holding the image.
  ASSERT_EQ(test::runShadowlabIn(renderArguments(test::datasetPath("planar-occluder"), "earlier"), temp.path()).exitCode, 0);
  const fs::path earlier = temp.path() / "earlier";
  writePng(earlier / "b.png", ImageU8(8, 8, 3, 10));
  const auto earlierBefore = snapshot(earlier);
  for (const std::string& name : { "render", "probe", "bench" })
  {
    SCOPED_TRACE(name + " into an earlier output");
    std::vector<std::string> arguments = command(name, "earlier", false);
    std::replace(arguments.begin(), arguments.end(), "budget_image=" + (dir / "b.png").string(),
      "budget_image=" + (earlier / "b.png").string());
    expectOneLineRefusal(test::runShadowlabIn(arguments, temp.path()), "b.png");
    EXPECT_EQ(snapshot(earlier), earlierBefore);
  }
}

TEST(OutputSafety, MontageRemovesThePartialFilesOfDeadRuns) // a Ctrl-C'd or killed montage
{
  TempDir temp;
  ASSERT_EQ(test::runShadowlabIn(renderArguments(test::datasetPath("planar-occluder"), "run"), temp.path()).exitCode, 0);
  const pid_t dead = ::fork();
  if (dead == 0)
  {
    ::_exit(0);
  }
  ASSERT_GT(dead, 0);
  ASSERT_EQ(::waitpid(dead, nullptr, 0), dead);
  const fs::path stale = temp.path() / (".m.png.shadowlab-partial-" + std::to_string(dead));
  const fs::path live = temp.path() / (".m.png.shadowlab-partial-" + std::to_string(::getpid()));
  const fs::path other = temp.path() / (".other.png.shadowlab-partial-" + std::to_string(dead));
  for (const fs::path& file : { stale, live, other })
  {
    writeFile(file, "half a png");
  }
  const RunResult run =
    test::runShadowlabIn({ "montage", "run", "--buffer", "visibility", "-q", "--out", "m.png" }, temp.path());
  ASSERT_EQ(run.exitCode, 0) << run.describe();
  EXPECT_FALSE(fs::exists(stale)) << "a dead run's partial file was left";
  EXPECT_TRUE(fs::exists(live)) << "a running process's partial file was removed";
  EXPECT_TRUE(fs::exists(other)) << "the partial file of another output was removed";
}

TEST(OutputSafety, BenchCountsAReferenceItCouldNotWriteAsAFailure)
{
  TempDir temp;
  const std::vector<std::string> arguments{ "bench", test::datasetPath("planar-occluder").string(), "-t", "hard", "-r",
    "16x16", "--reference-samples", "4", "--repeat", "1", "--cache", "cache", "--out", "out-bench" };
  ASSERT_EQ(test::runShadowlabIn(arguments, temp.path()).exitCode, 0);
  const std::vector<std::string> entries = entriesOf(temp.path() / "cache");
  ASSERT_EQ(entries.size(), 1u) << joined(entries);
  // The cache entry's path is taken by a plain file.
  const fs::path entry = temp.path() / "cache" / entries.front();
  fs::remove_all(entry);
  writeFile(entry, "in the way");
  const RunResult blocked = test::runShadowlabIn(arguments, temp.path());
  EXPECT_EQ(blocked.exitCode, 4) << blocked.describe();
  EXPECT_NE(blocked.err.find("cache/" + entries.front()), std::string::npos) << blocked.describe();
  EXPECT_EQ(blocked.err.find("--out cache"), std::string::npos) << "blames an --out the user did not give: "
                                                                << blocked.describe();
  EXPECT_EQ(blocked.err.find(" 0 failed ->"), std::string::npos) << blocked.describe();
  fs::remove(entry);
  // A file size limit (SIGXFSZ left at its default: shadowlab ignores it itself): the reference cannot be written.
  const RunResult limited = test::runShadowlabIn({ "bench", test::datasetPath("planar-occluder").string(), "-t",
                                                   "hard", "-r", "128x128", "--reference-samples", "4", "--repeat", "1",
                                                   "--cache", "cache", "--out", "out-limited" },
    temp.path(), "ulimit -f 24");
  EXPECT_NE(limited.exitCode, 0) << limited.describe();
  EXPECT_NE(limited.err.find("cache/"), std::string::npos) << limited.describe();
  EXPECT_NE(limited.err.find("cannot write"), std::string::npos) << limited.describe();
  EXPECT_EQ(limited.err.find("crashed"), std::string::npos) << limited.describe();
}

TEST(OutputSafety, RepeatedPointersEmptyListItemsAndOutOfRangeSeedsAreOneLineErrors)
{
  TempDir temp;
  const std::string scene = test::datasetPath("planar-occluder").string();
  struct Case
  {
    std::vector<std::string> arguments;
    std::string mention;
  };
  const std::vector<Case> cases = {
    { { "render", scene, "--scene-set", "/lights/0/size=1", "--scene-set", "/lights/0/size=2" }, "/lights/0/size" },
    { { "reference", scene, "--scene-set", "/lights/0/size=1", "--scene-set", "/lights/0/size=2" }, "/lights/0/size" },
    { { "bench", scene, "-t", "hard", "--scene-sweep", "/lights/0/size=1,2", "--scene-sweep", "/lights/0/size=3" },
      "/lights/0/size" },
    { { "bench", scene, "-t", "hard", "--scene-set", "/lights/0/size=1", "--scene-sweep", "/lights/0/size=3,4" },
      "/lights/0/size" },
    { { "bench", scene, "-t", "pcf", "--sweep", "kernel_texels=3,,9" }, "kernel_texels=3,,9" },
    { { "bench", scene, "-t", "pcf", "--sweep", "kernel_texels=3,9," }, "kernel_texels=3,9," },
    { { "bench", scene, "-t", "pcf," }, "pcf," },
    { { "bench", scene, "-t", "hard", "--scene-sweep", "/lights/0/size=1,,2" }, "/lights/0/size=1,,2" },
    { { "reference", scene, "--light-samples", "" }, "--light-samples" },
    { { "reference", scene, "--seed", "99999999999999999999999" }, "18446744073709551615" },
    { { "reference", scene, "--seed", "-1" }, "18446744073709551615" },
    { { "reference", scene, "--seed", "18446744073709551616" }, "--seed" },
  };
  for (const Case& refused : cases)
  {
    const RunResult run = test::runShadowlabIn(refused.arguments, temp.path());
    expectOneLineRefusal(run, refused.mention);
    EXPECT_LT(run.err.size(), 300u) << run.describe();
    EXPECT_EQ(entriesOf(temp.path()), std::vector<std::string>{}) << "output written: " << run.describe();
  }
}

// ---- paths that used to go wrong (D11, D12, D14) ------------------------------------------------------------

TEST(OutputSafety, EmptyLongAndSymlinkedOutPaths)
{
  TempDir temp;
  const RunResult empty = test::runShadowlabIn(renderArguments(test::datasetPath("planar-occluder"), ""), temp.path());
  expectOneLineRefusal(empty, "--out"); // D11: exit 1, not "internal error"

  const std::string longName(250, 'o'); // D14: the temporary sibling's name no longer grows with --out's
  const RunResult longOut =
    test::runShadowlabIn(renderArguments(test::datasetPath("planar-occluder"), longName), temp.path());
  EXPECT_EQ(longOut.exitCode, 0) << longOut.describe();
  EXPECT_TRUE(fs::is_regular_file(temp.path() / longName / "stats.json"));

  // D12: --out a link to an earlier output: the results go where the link points, and the link stays a link.
  const fs::path target = temp.path() / "target";
  ASSERT_EQ(test::runShadowlabIn(renderArguments(test::datasetPath("planar-occluder"), "target"), temp.path()).exitCode, 0);
  fs::create_directory_symlink(target, temp.path() / "link");
  const RunResult viaLink = test::runShadowlabIn(renderArguments(test::datasetPath("planar-occluder"), "link"), temp.path());
  EXPECT_EQ(viaLink.exitCode, 0) << viaLink.describe();
  EXPECT_TRUE(fs::is_symlink(temp.path() / "link"));
  EXPECT_TRUE(fs::is_regular_file(target / "stats.json"));
}

// ---- leftovers (X01-X08, H18, H19) ------------------------------------------------------------------------

TEST(OutputSafety, StaleTemporaryDirectoriesOfDeadRunsAreRemovedOthersKept) // X04, X08
{
  TempDir temp;
  // A PID that is not running: a child that has exited and been reaped.
  const pid_t dead = ::fork();
  if (dead == 0)
  {
    ::_exit(0);
  }
  ASSERT_GT(dead, 0);
  ASSERT_EQ(::waitpid(dead, nullptr, 0), dead);
  const fs::path stale = temp.path() / (".shadowlab-partial-" + std::to_string(dead) + "-0");
  const fs::path foreign = temp.path() / (".shadowlab-partial-" + std::to_string(dead) + "-1");
  const fs::path live = temp.path() / (".shadowlab-partial-" + std::to_string(::getpid()) + "-0");
  for (const fs::path& dir : { stale, foreign, live })
  {
    fs::create_directories(dir);
    writeFile(dir / "buffers.vti", "half written");
  }
  writeFile(stale / ".shadowlab-output", R"({"tool": "shadowlab", "command": "render"})");
  writeFile(live / ".shadowlab-output", R"({"tool": "shadowlab", "command": "render"})");
  const RunResult run = test::runShadowlabIn(renderArguments(test::datasetPath("planar-occluder"), "out"), temp.path());
  ASSERT_EQ(run.exitCode, 0) << run.describe();
  EXPECT_FALSE(fs::exists(stale)) << "a dead run's temporary directory was left";
  EXPECT_TRUE(fs::exists(foreign / "buffers.vti")) << "a directory without the marker is not shadowlab's to delete";
  EXPECT_TRUE(fs::exists(live / "buffers.vti")) << "a running process's temporary directory was deleted";
}

// Starts `arguments` in `workDir`, waits until a temporary output directory appears in `watchDir` (the write
// phase has begun), sends `signalNumber`, and returns how the process ended (128 + signal when it died of it).
int interruptDuringWrite(const std::vector<std::string>& arguments, const fs::path& workDir, const fs::path& watchDir,
  int signalNumber)
{
  const pid_t pid = ::fork();
  if (pid == 0)
  {
    if (::chdir(workDir.c_str()) != 0)
    {
      ::_exit(120);
    }
    std::vector<std::string> all{ SL_SHADOWLAB_EXE };
    all.insert(all.end(), arguments.begin(), arguments.end());
    std::vector<char*> argv;
    for (std::string& argument : all)
    {
      argv.push_back(argument.data());
    }
    argv.push_back(nullptr);
    // As a process started from a terminal: a shell's background job (a CI script's `&`) inherits SIGINT ignored,
    // and shadowlab rightly keeps an ignored signal ignored.
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
    ::freopen("/dev/null", "w", stderr);
    ::freopen("/dev/null", "w", stdout);
    ::execv(SL_SHADOWLAB_EXE, argv.data());
    ::_exit(121);
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  bool sent = false;
  while (!sent && std::chrono::steady_clock::now() < deadline)
  {
    std::error_code error;
    for (fs::directory_iterator it(watchDir, error), end; !error && it != end; it.increment(error))
    {
      if (it->path().filename().string().rfind(".shadowlab-partial-", 0) == 0)
      {
        ::kill(pid, signalNumber);
        sent = true;
        break;
      }
    }
    int status = 0;
    if (!sent && ::waitpid(pid, &status, WNOHANG) == pid)
    {
      ADD_FAILURE() << "the process ended before its write phase was seen";
      return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    }
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  if (!sent)
  {
    ::kill(pid, SIGKILL);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

TEST(OutputSafety, SigintAndSigtermDuringTheWritePhaseLeaveNoTemporaryDirectory) // X01, X02, X05, X07
{
  TempDir temp;
  ASSERT_EQ(test::runShadowlabIn(renderArguments(test::datasetPath("planar-occluder"), "out"), temp.path()).exitCode, 0);
  const auto before = snapshot(temp.path() / "out");
  for (const int signalNumber : { SIGINT, SIGTERM })
  {
    // Large enough that writing the heat maps takes a while.
    const int ended = interruptDuringWrite({ "render", test::datasetPath("planar-occluder").string(), "-t", "pcf",
                                             "-r", "384x384", "--set", "shadow_map_size=256", "--out", "out" },
      temp.path(), temp.path(), signalNumber);
    EXPECT_EQ(ended, 128 + signalNumber) << "the process should end with the signal";
    EXPECT_EQ(entriesOf(temp.path()), std::vector<std::string>{ "out" }) << joined(entriesOf(temp.path()));
    EXPECT_EQ(snapshot(temp.path() / "out"), before) << "the previous output changed";
  }
}

TEST(OutputSafety, SigtermDuringBenchEndsItsChildrenAndLeavesNoTemporaryDirectory) // H18, H19
{
  TempDir temp;
  fs::create_directories(temp.path() / "cache");
  // The signal reaches bench while its reference child writes into the cache (the child's temporary directory
  // is there) and bench's own temporary directory holds the logs: bench forwards it, and both clean up.
  const int ended = interruptDuringWrite({ "bench", test::datasetPath("planar-occluder").string(), "-t", "hard,pcf",
                                           "-r", "32x32", "--reference-samples", "4", "--repeat", "1", "--cache", "cache",
                                           "--out", "out-bench" },
    temp.path(), temp.path() / "cache", SIGTERM);
  EXPECT_EQ(ended, 128 + SIGTERM);
  // Children end with the signal too; give them a moment to finish their own clean-up.
  std::this_thread::sleep_for(std::chrono::seconds(2));
  EXPECT_EQ(entriesOf(temp.path()), std::vector<std::string>{ "cache" }) << joined(entriesOf(temp.path()));
  for (const std::string& name : entriesOf(temp.path() / "cache"))
  {
    EXPECT_EQ(name.rfind(".shadowlab-partial-", 0), std::string::npos) << "left in the cache: " << name;
  }
}

// ---- checked writes (D17) ------------------------------------------------------------------------------------

TEST(OutputSafety, AFailedWriteIsAnErrorAndKeepsThePreviousOutput) // D17
{
  TempDir temp;
  ASSERT_EQ(test::runShadowlabIn(renderArguments(test::datasetPath("planar-occluder"), "out"), temp.path()).exitCode, 0);
  const auto before = snapshot(temp.path() / "out");
  // A file size limit of 64 KiB with SIGXFSZ ignored: writes past it fail with EFBIG, like a full disk.
  const RunResult run = test::runShadowlabIn({ "render", test::datasetPath("planar-occluder").string(), "-t", "pcf",
                                               "-r", "256x256", "--set", "shadow_map_size=256", "--out", "out" },
    temp.path(), "ulimit -f 64; trap '' XFSZ");
  EXPECT_EQ(run.exitCode, 1) << run.describe();
  EXPECT_EQ(run.errLines(), 1u) << run.describe();
  EXPECT_NE(run.err.find("cannot write"), std::string::npos) << run.describe();
  EXPECT_NE(run.err.find("out/"), std::string::npos) << "the file is named under --out: " << run.describe();
  EXPECT_EQ(run.err.find(".shadowlab-partial"), std::string::npos) << "the temporary path leaked: " << run.describe();
  EXPECT_EQ(run.err.find("shadowlab: rendered"), std::string::npos) << "a success line after a failed write";
  EXPECT_EQ(snapshot(temp.path() / "out"), before) << "the previous output changed";
  EXPECT_EQ(entriesOf(temp.path()), std::vector<std::string>{ "out" }) << joined(entriesOf(temp.path()));
}

// ---- one-line errors with exit 1 (L29, P10, P19, P22-P26, F03, F06, S28-S30, H02, H03, H16) ------------------

TEST(OutputSafety, UsageErrorsAreOneLineWithExit1)
{
  TempDir temp;
  const std::string scene = test::datasetPath("planar-occluder").string();
  const std::vector<std::vector<std::string>> cases = {
    { "render", scene, "--light", "abc" },                     // L29
    { "render", scene, "--no-such-option" },                   // P22
    { "render" },                                              // P23: no scene
    { "render", scene, "extra-positional" },                   // P24
    {},                                                        // P25: no subcommand
    { "paint", scene },                                        // P26: unknown subcommand
    { "reference", scene, "--reference-samples", "99999999999" },        // F03
    { "reference", scene, "--seed", "-1" },                    // F06
    { "render", scene, "--set", "shadow_map_size=0x200" },     // P10: hexadecimal
    { "render", scene, "-t", "pcf", "--set", "kernel_texels=3", "--set", "kernel_texels=5" }, // P19
    { "render", scene, "--resolution", "0x0" },
    { "bench", scene, "-t", "hard,pcf", "--set", "kernal_texels=9" },   // H02: misspelt key
    { "bench", scene, "-t", "hard,pcf", "--sweep", "kernal_texels=1,3" }, // H03
    { "bench", scene, "-t", "hard", "-r", "0x0" },                       // H16
  };
  for (const std::vector<std::string>& arguments : cases)
  {
    const RunResult run = test::runShadowlabIn(arguments, temp.path());
    EXPECT_EQ(run.exitCode, 1) << run.describe();
    EXPECT_EQ(run.errLines(), 1u) << run.describe();
    EXPECT_EQ(entriesOf(temp.path()), std::vector<std::string>{}) << "output written: " << run.describe();
  }
}

TEST(OutputSafety, ControlCharactersInEchoedNamesAreEscaped) // S28-S30
{
  TempDir temp;
  const std::string name = "scene\n\x1b[31mred\x1b[0m.json";
  const RunResult run = test::runShadowlabIn({ "render", name }, temp.path());
  EXPECT_EQ(run.exitCode, 1) << run.describe();
  EXPECT_EQ(run.errLines(), 1u) << run.describe();
  EXPECT_EQ(run.err.find('\x1b'), std::string::npos) << "an escape sequence reached the terminal";
  EXPECT_NE(run.err.find("\\x1b[31mred"), std::string::npos) << run.describe();
}

TEST(OutputSafety, AFileNameThatIsNotUtf8StillGivesValidJson)
{
  TempDir temp;
  // Linux file names are any bytes; stats.json names the scene file.
  const fs::path scene = temp.path() / "scene-\xff\xfe.json";
  fs::copy_file(test::datasetPath("planar-occluder"), scene);
  const RunResult run = test::runShadowlabIn(renderArguments(scene, "out"), temp.path());
  ASSERT_EQ(run.exitCode, 0) << run.describe();
  const nlohmann::json stats = nlohmann::json::parse(readFile(temp.path() / "out" / "stats.json"));
  EXPECT_NE(stats["scene"].get<std::string>().find("scene-"), std::string::npos);
}

TEST(OutputSafety, BenchRecomputesAPoisonedCacheEntry) // H14
{
  TempDir temp;
  const std::vector<std::string> arguments{ "bench", test::datasetPath("planar-occluder").string(), "-t", "hard", "-r",
    "16x16", "--reference-samples", "4", "--repeat", "1", "--cache", "cache", "--out", "out-bench" };
  ASSERT_EQ(test::runShadowlabIn(arguments, temp.path()).exitCode, 0);
  const std::vector<std::string> entries = entriesOf(temp.path() / "cache");
  ASSERT_EQ(entries.size(), 1u) << joined(entries);
  const fs::path cached = temp.path() / "cache" / entries.front() / "buffers.vti";
  const std::string good = readFile(cached);
  for (const std::string& poison : { good.substr(0, good.size() / 2), std::string("not a vti file at all") })
  {
    writeFile(cached, poison);
    const RunResult run = test::runShadowlabIn(arguments, temp.path());
    EXPECT_EQ(run.exitCode, 0) << run.describe();
    EXPECT_NE(run.err.find("unusable"), std::string::npos) << run.describe();
    EXPECT_NO_THROW(readVti(cached)) << "the cache entry was not recomputed";
    const nlohmann::json bench = nlohmann::json::parse(readFile(temp.path() / "out-bench" / "bench.json"));
    EXPECT_TRUE(bench["configurations"][0]["result"].contains("error")) << "no error metrics against the reference";
  }
}

} // namespace
} // namespace sl
