// The output contract walked argument by argument from the CLI's own list (src/cli/PathOptions.h): every argument
// of every command's --help is in that list, and every argument that writes keeps the contract (docs/outputs.md,
// "Outputs and exit codes"): (a) an input inside the output is refused, even with --force; (b) the output inside an
// input directory is refused, even with --force; (c) an existing file or directory the command did not write is not
// replaced without --force, and is replaced with it only where the contract says so. Every run is tiny (16x16,
// technique hard); refusals leave what they refused byte for byte.
#include "cli/PathOptions.h"
#include "support/CliRun.h"
#include "support/TempDir.h"
#include "support/TestSupport.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace sl
{
namespace
{

namespace fs = std::filesystem;
using test::readFile;
using test::RunResult;
using test::TempDir;
using test::writeFile;

// Every regular file under `path` (or the file itself) with its bytes.
std::map<std::string, std::string> snapshot(const fs::path& path)
{
  std::map<std::string, std::string> files;
  if (fs::is_regular_file(path))
  {
    files["."] = readFile(path);
    return files;
  }
  for (const auto& entry : fs::recursive_directory_iterator(path))
  {
    files[fs::relative(entry.path(), path).string()] = entry.is_regular_file() ? readFile(entry.path()) : "<dir>";
  }
  return files;
}

// The long option (or positional) names of `command`'s --help that take a value; flags are left out.
std::set<std::string> valueArgumentsInHelp(const std::string& command)
{
  TempDir temp;
  const RunResult help = test::runShadowlabIn({ command, "--help" }, temp.path());
  EXPECT_EQ(help.exitCode, 0) << help.describe();
  std::set<std::string> names;
  std::istringstream lines(help.out);
  for (std::string line; std::getline(lines, line);)
  {
    // "  -o,--out TEXT [out]   Output directory ..." or "  scene TEXT REQUIRED   Scene file": an entry starts two
    // spaces in; deeper lines continue a description.
    if (line.size() < 3 || line.compare(0, 2, "  ") != 0 || line[2] == ' ')
    {
      continue;
    }
    std::istringstream words(line);
    std::string spelling;
    std::string type;
    words >> spelling >> type;
    // A value's type is upper case: TEXT, INT=0 (with its default), UINT:0 .. 2^64-1 (with a check); a flag's
    // description follows its name.
    const std::size_t typeEnd = std::min(type.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZ"), type.size());
    const bool takesValue =
      typeEnd >= 3 && (typeEnd == type.size() || std::string(":=[").find(type[typeEnd]) != std::string::npos);
    if (!takesValue)
    {
      continue;
    }
    std::string name = spelling;
    if (spelling[0] == '-')
    {
      std::istringstream spellings(spelling);
      for (std::string one; std::getline(spellings, one, ',');)
      {
        name = one.rfind("--", 0) == 0 ? one : name;
      }
    }
    names.insert(name);
  }
  return names;
}

TEST(PathArguments, EveryArgumentOfEveryCommandIsListed)
{
  // The commands: those --help shows, and the hidden bench-run.
  TempDir temp;
  const RunResult help = test::runShadowlabIn({ "--help" }, temp.path());
  std::set<std::string> commandsInHelp{ "bench-run" };
  bool inSubcommands = false;
  std::istringstream lines(help.out);
  for (std::string line; std::getline(lines, line);)
  {
    inSubcommands = inSubcommands || line.rfind("Subcommands:", 0) == 0;
    if (inSubcommands && line.size() > 2 && line.compare(0, 2, "  ") == 0 && line[2] != ' ')
    {
      commandsInHelp.insert(line.substr(2, line.find(' ', 2) - 2));
    }
  }
  std::set<std::string> commandsListed;
  std::map<std::string, std::set<std::string>> listed;
  for (const PathArgument& argument : kPathArguments)
  {
    EXPECT_TRUE(listed[argument.command].insert(argument.name).second) << argument.command << " " << argument.name;
  }
  for (const OtherArguments& others : kOtherArguments)
  {
    commandsListed.insert(others.command);
    std::istringstream names(others.names);
    for (std::string name; names >> name;)
    {
      EXPECT_TRUE(listed[others.command].insert(name).second)
        << others.command << " " << name << " is in both lists of PathOptions.h";
    }
  }
  EXPECT_EQ(commandsListed, commandsInHelp) << "a command is missing from kOtherArguments (PathOptions.h)";
  for (const std::string& command : commandsInHelp)
  {
    EXPECT_EQ(valueArgumentsInHelp(command), listed[command])
      << "`shadowlab " << command << " --help` and src/cli/PathOptions.h disagree: add the argument to "
      << "kPathArguments when it names a file or directory, else to kOtherArguments";
  }
}

// ---- the contract, per writing argument ----------------------------------------------------------------------

// What a command reads, made for one test under a directory of its own.
struct Inputs
{
  fs::path scene; // a copy of planar-occluder
  fs::path run;   // a render's output directory (compare, montage)
  fs::path cache; // bench's --cache
};

struct Writer
{
  // Makes the command's inputs under `where`.
  std::function<Inputs(const fs::path& where)> prepare;
  // The command line that writes `out`.
  std::function<std::vector<std::string>(const Inputs&, const std::string& out)> arguments;
  bool hasForce = true;
  // (a): an input that `out` holds when the inputs are made inside `out` (empty: none can be, e.g. lessons).
  bool inputsCanBeInside = true;
  // (b): an input directory (empty: the command reads files only).
  std::function<fs::path(const Inputs&)> inputDirectory;
  // (c): whether runs may complete here (false: only refusals are run, e.g. lessons); and the exit status of a run
  // the contract lets through (view exits 2 without a display, after its checks).
  bool completes = true;
  int passedExit = 0;
  std::string prelude;
  // (c) for a file output: a file the command itself would have written, which it may replace.
  std::function<void(const Inputs&, const fs::path& file)> writeOwnFile;  // (a) for a file output: the inputs it must never be.
  std::function<std::vector<fs::path>(const Inputs&)> inputsOf;
};

fs::path renderRun(const fs::path& scene, const fs::path& out)
{
  const RunResult run = test::runShadowlabIn({ "render", scene.string(), "-t", "hard", "-r", "16x16", "--set",
                                               "shadow_map_size=64", "-q", "--out", out.string() },
    out.parent_path());
  EXPECT_EQ(run.exitCode, 0) << run.describe();
  return out;
}

Inputs datasetCopy(const fs::path& where)
{
  fs::create_directories(where);
  fs::copy(test::datasetPath("planar-occluder").parent_path(), where, fs::copy_options::recursive);
  return { where / "scene.json", {}, where / "cache" };
}

Inputs datasetAndRun(const fs::path& where)
{
  Inputs inputs = datasetCopy(where);
  inputs.run = renderRun(inputs.scene, where / "run");
  return inputs;
}

std::vector<std::string> small(std::vector<std::string> arguments)
{
  arguments.insert(arguments.end(), { "-r", "16x16", "-q" });
  return arguments;
}

// One entry per writing argument of kPathArguments ("command option").
const std::map<std::string, Writer>& writers()
{
  static const std::map<std::string, Writer> table = [] {
    std::map<std::string, Writer> w;
    w["render --out"] = { datasetCopy, [](const Inputs& in, const std::string& out) {
                           return small({ "render", in.scene.string(), "-t", "hard", "--set", "shadow_map_size=64",
                             "--out", out });
                         } };
    w["probe --out"] = { datasetCopy, [](const Inputs& in, const std::string& out) {
                          return small({ "probe", in.scene.string(), "-t", "hard", "--set", "shadow_map_size=64",
                            "--pixel", "8,8", "--out", out });
                        } };
    w["reference --out"] = { datasetCopy, [](const Inputs& in, const std::string& out) {
                              return small({ "reference", in.scene.string(), "--reference-samples", "4", "--out", out });
                            } };
    w["bench --out"] = { datasetCopy,
      [](const Inputs& in, const std::string& out) {
        return small({ "bench", in.scene.string(), "-t", "hard", "--reference-samples", "4", "--repeat", "1", "--cache",
          in.cache.string(), "--out", out });
      },
      true, true,
      [](const Inputs& in) {
        fs::create_directories(in.cache);
        writeFile(in.cache / "0123456789abcdef", "a cache entry");
        return in.cache;
      } };
    w["bench --plan"] = { datasetCopy,
      [](const Inputs& in, const std::string& out) {
        return small({ "bench", in.scene.string(), "-t", "hard", "--reference-samples", "4", "--repeat", "1", "--cache",
          in.cache.string(), "--plan", out });
      },
      true, true,
      [](const Inputs& in) {
        fs::create_directories(in.cache);
        writeFile(in.cache / "0123456789abcdef", "a cache entry");
        return in.cache;
      } };
    // A reference of one tile (0/1) is its whole, merged alone.
    w["reference-merge --out"] = { [](const fs::path& where) {
                                    Inputs inputs = datasetCopy(where);
                                    inputs.run = where / "tile";
                                    EXPECT_EQ(test::runShadowlabInTempDir(small({ "reference", inputs.scene.string(),
                                                "--reference-samples", "4", "--tile", "0/1", "--out",
                                                inputs.run.string() })).exitCode, 0);
                                    return inputs;
                                  },
      [](const Inputs& in, const std::string& out) {
        return std::vector<std::string>{ "reference-merge", in.run.string(), "-q", "--out", out };
      },
      true, true, [](const Inputs& in) { return in.run; } };
    w["compare --out"] = { datasetAndRun, [](const Inputs& in, const std::string& out) {
                            const std::string vti = (in.run / "buffers.vti").string();
                            return std::vector<std::string>{ "compare", vti, vti, "-q", "--out", out };
                          } };
    w["lessons --out"] = { [](const fs::path&) { return Inputs{}; },
      [](const Inputs&, const std::string& out) {
        return small({ "lessons", "--only", "acne-and-bias", "--out", out });
      },
      true, false, [](const Inputs&) { return test::sourceDir() / "datasets"; }, false };
    w["differential --out"] = { [](const fs::path&) { return Inputs{}; },
      [](const Inputs&, const std::string& out) {
        return std::vector<std::string>{ "differential", "--seeds", "1", "-t", "hard", "--choice", "default",
          "--max-side", "16", "--reference-samples", "4", "-q", "--out", out };
      },
      true, false };
    w["montage --out"] = { datasetAndRun,
      [](const Inputs& in, const std::string& out) {
        return std::vector<std::string>{ "montage", in.run.string(), "--buffer", "visibility", "-q", "--out", out };
      },
      true, true, [](const Inputs& in) { return in.run; }, true, 0, "",
      [](const Inputs& in, const fs::path& file) {
        const RunResult run = test::runShadowlabIn(
          { "montage", in.run.string(), "--buffer", "visibility", "-q", "--out", file.string() }, file.parent_path());
        EXPECT_EQ(run.exitCode, 0) << run.describe();
      },
      [](const Inputs& in) { return std::vector<fs::path>{ in.run, in.run / "image.png" }; } };
    w["view --record"] = { datasetCopy,
      [](const Inputs& in, const std::string& out) {
        return std::vector<std::string>{ "view", in.scene.string(), "-t", "hard", "-r", "16x16", "--record", out };
      },
      true, true, nullptr, true, 2, "unset DISPLAY",
      [](const Inputs&, const fs::path& file) { writeFile(file, "# StreamVersion 1.1\nExposeEvent 0 0 0 0 0 0\n"); },
      [](const Inputs& in) { return std::vector<fs::path>{ in.scene }; } };
    return w;
  }();
  return table;
}

std::vector<std::string> withForce(std::vector<std::string> arguments, bool force)
{
  if (force)
  {
    arguments.push_back("--force");
  }
  return arguments;
}

void expectRefused(const RunResult& run, const std::string& mention)
{
  EXPECT_EQ(run.exitCode, 1) << run.describe();
  EXPECT_EQ(run.errLines(), 1u) << run.describe();
  EXPECT_NE(run.err.find(mention), std::string::npos) << "stderr should mention '" << mention << "'\n"
                                                      << run.describe();
}

void checkDirectoryWriter(const Writer& writer)
{
  TempDir temp;
  const fs::path work = temp.path();
  // (a) The inputs inside --out: refused even with --force, nothing touched.
  if (writer.inputsCanBeInside)
  {
    const fs::path holder = work / "holder";
    const Inputs inside = writer.prepare(holder / "inputs");
    const auto before = snapshot(holder);
    const RunResult run =
      test::runShadowlabIn(withForce(writer.arguments(inside, holder.string()), writer.hasForce), work, writer.prelude);
    SCOPED_TRACE("(a) an input inside the output");
    expectRefused(run, "an input");
    EXPECT_EQ(snapshot(holder), before);
  }
  const Inputs inputs = writer.prepare(work / "inputs");
  // (b) --out inside an input directory: refused even with --force.
  if (writer.inputDirectory)
  {
    const fs::path directory = writer.inputDirectory(inputs);
    const auto before = snapshot(directory);
    const fs::path out = directory / "never-written";
    const RunResult run =
      test::runShadowlabIn(withForce(writer.arguments(inputs, out.string()), writer.hasForce), work, writer.prelude);
    SCOPED_TRACE("(b) the output inside an input directory");
    expectRefused(run, "input directory");
    EXPECT_EQ(snapshot(directory), before);
    std::error_code ignored;
    fs::remove_all(out, ignored); // only should the refusal have failed
  }
  // (c) A directory of the user's: refused without --force; replaced with it; then, being ShadowLab's, replaced
  // without it.
  const fs::path user = work / "user";
  fs::create_directories(user / "notes");
  writeFile(user / "thesis.tex", "my only copy");
  const auto before = snapshot(user);
  {
    SCOPED_TRACE("(c) a directory shadowlab did not write, without --force");
    const RunResult run = test::runShadowlabIn(writer.arguments(inputs, user.string()), work, writer.prelude);
    expectRefused(run, "--force");
    EXPECT_EQ(snapshot(user), before);
  }
  if (writer.completes)
  {
    SCOPED_TRACE("(c) with --force, then again without");
    const RunResult forced =
      test::runShadowlabIn(withForce(writer.arguments(inputs, user.string()), true), work, writer.prelude);
    EXPECT_EQ(forced.exitCode, writer.passedExit) << forced.describe();
    EXPECT_TRUE(fs::is_regular_file(user / ".shadowlab-output"));
    EXPECT_FALSE(fs::exists(user / "thesis.tex"));
    const RunResult again = test::runShadowlabIn(writer.arguments(inputs, user.string()), work, writer.prelude);
    EXPECT_EQ(again.exitCode, writer.passedExit) << again.describe();
  }
}

void checkFileWriter(const Writer& writer)
{
  TempDir temp;
  const fs::path work = temp.path();
  const Inputs inputs = writer.prepare(work / "inputs");
  const auto inputsBefore = snapshot(work / "inputs");
  // (a) The output is an input: refused even with --force.
  for (const fs::path& input : writer.inputsOf(inputs))
  {
    SCOPED_TRACE("(a) the output is the input " + input.string());
    const RunResult run =
      test::runShadowlabIn(withForce(writer.arguments(inputs, input.string()), writer.hasForce), work, writer.prelude);
    EXPECT_EQ(run.exitCode, 1) << run.describe();
    EXPECT_EQ(run.errLines(), 1u) << run.describe();
  }
  // (b) Inside an input directory: refused.
  if (writer.inputDirectory)
  {
    SCOPED_TRACE("(b) the output inside an input directory");
    const fs::path out = writer.inputDirectory(inputs) / "never-written.png";
    const RunResult run =
      test::runShadowlabIn(withForce(writer.arguments(inputs, out.string()), writer.hasForce), work, writer.prelude);
    expectRefused(run, "input directory");
  }
  EXPECT_EQ(snapshot(work / "inputs"), inputsBefore);
  // (c) A file of the user's is kept without --force, and replaced only with it (where the command has it); a
  // file the command wrote is replaced.
  const fs::path user = work / "notes.png";
  writeFile(user, "my notes, not a picture");
  {
    SCOPED_TRACE("(c) a file shadowlab did not write");
    const RunResult run = test::runShadowlabIn(writer.arguments(inputs, user.string()), work, writer.prelude);
    EXPECT_EQ(run.exitCode, 1) << run.describe();
    EXPECT_EQ(run.errLines(), 1u) << run.describe();
    EXPECT_EQ(readFile(user), "my notes, not a picture");
  }
  if (writer.hasForce)
  {
    SCOPED_TRACE("(c) a file shadowlab did not write, with --force");
    const RunResult run = test::runShadowlabIn(withForce(writer.arguments(inputs, user.string()), true), work, writer.prelude);
    EXPECT_EQ(run.exitCode, writer.passedExit) << run.describe();
  }
  const fs::path own = work / "own.png";
  writer.writeOwnFile(inputs, own);
  {
    SCOPED_TRACE("(c) a file shadowlab wrote");
    const RunResult run = test::runShadowlabIn(writer.arguments(inputs, own.string()), work, writer.prelude);
    EXPECT_EQ(run.exitCode, writer.passedExit) << run.describe();
  }
  for (const std::string& name : test::entriesOf(work))
  {
    EXPECT_EQ(name.find(".shadowlab-partial"), std::string::npos) << "left behind: " << name;
  }
}

TEST(PathArguments, EveryWritingArgumentKeepsTheOutputContract)
{
  for (const PathArgument& argument : kPathArguments)
  {
    if (argument.role != PathRole::WritesDirectory && argument.role != PathRole::WritesFile)
    {
      continue;
    }
    const std::string key = std::string(argument.command) + " " + argument.name;
    SCOPED_TRACE(key);
    const auto found = writers().find(key);
    if (found == writers().end())
    {
      ADD_FAILURE() << key << " writes, but PathArgumentsTest.cpp's writers() has no entry to run it";
      continue;
    }
    if (argument.role == PathRole::WritesDirectory)
    {
      checkDirectoryWriter(found->second);
    }
    else
    {
      checkFileWriter(found->second);
    }
  }
}

} // namespace
} // namespace sl
